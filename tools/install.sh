#!/bin/sh
# make install / make uninstall (and the install test, which calls it directly with a temporary
# prefix, so that it needs no second make run with the build's flags).
#   tools/install.sh install BUILD DESTDIR PREFIX LIBDIR
#   tools/install.sh uninstall DESTDIR PREFIX LIBDIR
# install copies the commands, the static and shared library, the headers, refray.pc (written
# here with the real prefix), the man pages, the bash completion and refray.mk, and lists every
# file and link it made in PREFIX/share/refray/installed-files; uninstall removes exactly those
# (and then the list and the folders it left empty), whatever the source tree holds by then.
# Environment: RF_VERSION (the library's version), RF_PKGS (the pkg-config modules the library
# links against: its Requires.private).
set -eu

mode=$1
shift
if [ "$mode" = install ]; then
    build=$1
    shift
fi
destdir=$1 prefix=$2 libdir=$3
root=$destdir$prefix
list=$root/share/refray/installed-files

# ldconfig's cache, so that programs find librefray.so.0 without LD_LIBRARY_PATH: only as root,
# installing for real (no DESTDIR), into a folder the cache covers (/etc/ld.so.conf names it, as
# Debian's does /usr/local/lib); /usr/lib is searched without the cache, a private prefix never
refresh_ld_cache() {
    if [ -z "$destdir" ] && [ "$(id -u)" = 0 ] && command -v ldconfig >/dev/null 2>&1 &&
        cat /etc/ld.so.conf /etc/ld.so.conf.d/*.conf 2>/dev/null | grep -qx "$libdir"; then
        ldconfig && echo "ran ldconfig ($libdir is in its cache)"
    fi
}

# put FILE MODE DIR [NAME]: copies FILE into DIR (under DESTDIR) and records it
put() {
    install -d "$destdir$3"
    install -m "$2" "$1" "$destdir$3/${4:-$(basename "$1")}"
    echo "$3/${4:-$(basename "$1")}" >> "$list.tmp"
}
# link TARGET DIR NAME: a symbolic link DIR/NAME -> TARGET, recorded
link() {
    ln -sf "$1" "$destdir$2/$3"
    echo "$2/$3" >> "$list.tmp"
}

case $mode in
install)
    install -d "$root/share/refray"
    : > "$list.tmp"
    for b in refray refray-raster refray-verify refray-view; do
        put "$build/$b" 755 "$prefix/bin"
    done
    put "$build/librefray.a" 644 "$libdir"
    soname=librefray.so.${RF_VERSION%%.*}
    put "$build/librefray.so.$RF_VERSION" 755 "$libdir"
    link "librefray.so.$RF_VERSION" "$libdir" "$soname"
    link "$soname" "$libdir" librefray.so
    for h in include/refray/*.h; do
        put "$h" 644 "$prefix/include/refray"
    done
    # pkg-config: Requires.private and Libs.private serve `pkg-config --static` (librefray.a)
    install -d "$destdir$libdir/pkgconfig"
    cat > "$build/refray.pc" <<EOF
prefix=$prefix
libdir=$libdir
includedir=\${prefix}/include

Name: refray
Description: reference ray tracer for computer-graphics teaching: formulas, scenes, renderer
Version: $RF_VERSION
Requires.private: $RF_PKGS
Cflags: -I\${includedir}
Libs: -L\${libdir} -lrefray
Libs.private: -lm -pthread
EOF
    put "$build/refray.pc" 644 "$libdir/pkgconfig"
    for m in "$build"/man/*.1; do
        put "$m" 644 "$prefix/share/man/man1"
    done
    # bash-completion loads completions/NAME when NAME is first completed: one script, a link
    # for each of the other commands
    put "$build/completion/refray" 644 "$prefix/share/bash-completion/completions"
    for b in refray-raster refray-verify refray-view; do
        link refray "$prefix/share/bash-completion/completions" "$b"
    done
    put tools/refray.mk 644 "$prefix/share/refray"
    echo "$prefix/share/refray/installed-files" >> "$list.tmp"
    mv "$list.tmp" "$list"
    echo "installed $(wc -l < "$list") files under $root (list: $list)"
    refresh_ld_cache
    ;;
uninstall)
    if [ ! -f "$list" ]; then
        echo "refray: nothing to uninstall: $list does not exist" >&2
        exit 1
    fi
    n=0
    while IFS= read -r f; do
        rm -f "$destdir$f"
        n=$((n + 1))
        # folders refray made and left empty go too (never the prefix's own bin, lib, ...)
        d=$(dirname "$f")
        case $d in
        */include/refray | */share/refray) rmdir "$destdir$d" 2>/dev/null || true ;;
        esac
    done < "$list"
    echo "removed $n files under $root"
    refresh_ld_cache
    ;;
*)
    echo "usage: tools/install.sh install BUILD DESTDIR PREFIX LIBDIR | uninstall DESTDIR PREFIX LIBDIR" >&2
    exit 2
    ;;
esac
