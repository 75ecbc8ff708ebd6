#!/bin/sh
# make install / make uninstall (and the install test, which calls it directly with a temporary
# prefix, so that it needs no second make run with the build's flags).
#   tools/install.sh install BUILD DESTDIR PREFIX LIBDIR
#   tools/install.sh uninstall DESTDIR PREFIX LIBDIR
# install copies the commands, the static and shared library, the headers, refray.pc (written
# here with the real prefix), the man pages, the bash completion and refray.mk, and lists every
# file, link and folder it made in PREFIX/share/refray/installed-files (a folder with a trailing
# /); uninstall removes exactly those (a folder only when nothing else is in it by then),
# whatever the source tree holds by then.
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

# missing DIR: the folders on the way to DIR (under DESTDIR) that do not exist yet, outermost
# first, each with a trailing / (how the list tells a folder from a file)
missing() {
    m= d=$1
    while [ -n "$d" ] && [ "$d" != / ] && [ ! -d "$destdir$d" ]; do
        m="$d/
$m"
        d=$(dirname "$d")
    done
    printf '%s' "$m"
}
# folder DIR: makes DIR (under DESTDIR) and records the folders it made, so that uninstall
# removes those and no other
folder() {
    m=$(missing "$1")
    install -d "$destdir$1"
    [ -z "$m" ] || echo "$m" >> "$list.tmp"
}
# put FILE MODE DIR [NAME]: copies FILE into DIR (under DESTDIR) and records it
put() {
    folder "$3"
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
    rm -f "$list.tmp" # one that a run stopped half-way left
    folder "$prefix/share/refray" # the list's own folder: its first lines
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
    folder "$libdir/pkgconfig"
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
    echo "installed $(grep -vc '/$' "$list") files under $root (list: $list)"
    refresh_ld_cache
    ;;
uninstall)
    if [ ! -f "$list" ]; then
        echo "refray: nothing to uninstall: $list does not exist" >&2
        exit 1
    fi
    # the folders install made, innermost first (read now: the list is among the files removed)
    folders=$(grep '/$' "$list" | sed -n '1!G;h;$p')
    n=0
    while IFS= read -r f; do
        case $f in
        */) continue ;; # a folder: below, once its files are gone
        esac
        rm -f "$destdir$f"
        n=$((n + 1))
        # refray's own folders go when empty (a list from before folders were recorded)
        d=$(dirname "$f")
        case $d in
        */include/refray | */share/refray) rmdir "$destdir$d" 2>/dev/null || true ;;
        esac
    done < "$list"
    # then those folders; one that holds something else by now stays
    printf '%s\n' "$folders" | while IFS= read -r d; do
        [ -z "$d" ] || rmdir "$destdir$d" 2>/dev/null || true
    done
    echo "removed $n files under $root"
    refresh_ld_cache
    ;;
*)
    echo "usage: tools/install.sh install BUILD DESTDIR PREFIX LIBDIR | uninstall DESTDIR PREFIX LIBDIR" >&2
    exit 2
    ;;
esac
