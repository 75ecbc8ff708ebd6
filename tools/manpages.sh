#!/bin/sh
# The man pages, made from the commands' own --help text (the one source: a page cannot say
# other than the command): refray(1) from `refray --help`, refray-COMMAND(1) for every command
# that `refray --help` lists (so a new command gets its page without a change here), and the
# separate programs refray-raster, refray-verify and refray-view.
#   tools/manpages.sh BUILD OUTDIR
# Each page: NAME (the command table's summary), SYNOPSIS (the usage lines), DESCRIPTION (the
# rest of the help, kept as printed: its columns are aligned by hand, which man's filling would
# undo), SEE ALSO. Not help2man: it wants GNU-style option lists and one program per page.
set -eu
build=$1 out=$2
version=$("$build/refray" --version | sed -n '1s/^refray //p')
mkdir -p "$out"

# the commands refray --help lists: "  NAME  summary" lines after "commands:"
commands() {
    "$build/refray" --help | awk '/^[Cc]ommands:/ { on = 1; next } on && /^$/ { exit }
                                   on && /^  [a-z]/ { print $1 }'
}
summary() {
    "$build/refray" --help | awk -v c="$1" '/^[Cc]ommands:/ { on = 1; next } on && /^$/ { exit }
        on && $1 == c { sub(/^  [^ ]+ +/, ""); print; exit }'
}

# page NAME SUMMARY SEE_ALSO COMMAND...: the page of NAME from COMMAND --help (stdout or stderr)
page() {
    name=$1 summary=$2 see=$3
    shift 3
    "$@" --help 2>&1 | awk -v name="$name" -v summary="$summary" -v version="$version" -v see="$see" '
        # roff: a backslash is \e; a line starting with . or '"'"' would be a request
        function esc(s) { gsub(/\\/, "\\e", s); gsub(/-/, "\\-", s); if (s ~ /^[.'"'"']/) s = "\\&" s; return s }
        BEGIN {
            up = toupper(name)
            printf ".TH %s 1 \"\" \"refray %s\" \"refray manual\"\n", up, version
            printf ".SH NAME\n%s \\- %s\n", esc(name), esc(summary)
        }
        # the usage block: from "usage: ..." on, with the lines that continue it (indented "["
        # or the program name again); the lines before it (a title) and after it are the
        # description
        function describe() { if (!desc) { print ".SH DESCRIPTION\n.nf"; printf "%s", pre; desc = 1 } }
        state == 0 && tolower($0) ~ /^usage: / { sub(/^[Uu]sage: +/, ""); print ".SH SYNOPSIS\n.nf"; print esc($0); state = 1; next }
        state == 0 { if ($0 != "" || pre != "") pre = pre esc($0) "\n"; next }
        state == 1 && ($0 ~ /^ +\[/ || $0 ~ /^ +refray/) { sub(/^       /, ""); print esc($0); next }
        state == 1 { print ".fi"; state = 2; if ($0 == "") next }
        # a label line of the help ("options:", "commands:", "keys:") becomes a subsection
        /^[A-Za-z][A-Za-z ]*:$/ { describe(); sub(/:$/, ""); printf ".fi\n.SS %s\n.nf\n", toupper(esc($0)); next }
        { describe(); print esc($0) }
        END {
            if (state == 1) print ".fi"
            if (state == 0 || desc) { describe(); print ".fi" }
            if (see != "") printf ".SH SEE ALSO\n%s\n", see
        }' > "$out/$name.1"
}

see_all="refray(1)"
pages="refray(1)"
for c in $(commands); do
    pages="$pages, refray-$c(1)"
done
for b in refray-raster refray-verify refray-view; do
    pages="$pages, $b(1)"
done

page refray "$("$build/refray" --help | sed -n '1s/^refray [^,]*, //p')" "$(echo "$pages" | sed 's/^refray(1), //')" "$build/refray"
for c in $(commands); do
    page "refray-$c" "$(summary "$c")" "$see_all" "$build/refray" "$c"
done
page refray-raster "the OpenGL comparator: rasterizes a scene with the tracer's local shading" "$see_all" "$build/refray-raster"
page refray-verify "the CGAL verifier: the tracer's intersections against exact predicates" "$see_all" "$build/refray-verify"
page refray-view "a window on a scene: the tracer's image refining, the rasterization, their difference" "$see_all" "$build/refray-view"
