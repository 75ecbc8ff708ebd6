#!/bin/sh
# The bash completion of refray and its programs, made from their --help text (as the man pages,
# tools/manpages.sh): the commands `refray --help` lists, each command's options as its help
# names them (-o, --png, ...), and the values of an option written as --opt a|b|c.
#   tools/completion.sh BUILD > completion/refray
set -eu
build=$1

commands=$("$build/refray" --help | awk '/^[Cc]ommands:/ { on = 1; next } on && /^$/ { exit }
                                         on && /^  [a-z]/ { print $1 }' | tr '\n' ' ')

# options HELP-COMMAND...: the option names in the usage lines and the option list (lines that
# start with an option), not those that prose mentions ("for refray diff --stat")
options() {
    "$@" --help 2>&1 |
        awk 'tolower($0) ~ /^ *usage: / { u = 1; print; next }
             u && ($0 ~ /^ +\[/ || $0 ~ /^ +refray/) { print; next }
             { u = 0 } /^ +-/' |
        grep -oE '(^|[][ ,|(])(--[A-Za-z][A-Za-z0-9-]*|-[A-Za-z]{1,2}([][ ,|)=]|$))' |
        sed -E 's/^[][ ,|(]//; s/[][ ,|)=]$//' | sort -u | tr '\n' ' '
}
# values HELP-COMMAND...: "--opt) words=...;;" case arms for the options whose values the help
# names: "--opt a|b|c", or an option line "--opt NAME  [what: ]a, b or c[ (...)]"
values() {
    "$@" --help 2>&1 |
        sed -nE 's/^ +(-[A-Za-z], )?(--[a-z0-9-]+) [A-Z][A-Z0-9.]* +([a-z ]+: )?([a-z0-9-]+(, [a-z0-9-]+)* or [a-z0-9-]+)( \(.*)?$/\2 \4/p
                 s/.*(--[a-z][a-z0-9-]*)[ =]([a-z0-9]+(\|[a-z0-9-]+)+).*/\1 \2/p' |
        sed -E 's/, | or /|/g' | sort -u -k1,1 |
        while read -r opt vals; do
            printf '            %s) words="%s" ;;\n' "$opt" "$(echo "$vals" | tr '|' ' ')"
        done
}
# arm NAME HELP-COMMAND...: the case arm of one command
arm() {
    name=$1
    shift
    printf '    %s)\n        opts="%s"\n        case $prev in\n%s\n        esac ;;\n' \
        "$name" "$(options "$@")" "$(values "$@")"
}

# the formula ids, as `refray formula list` names them (refray formula <TAB>)
formulas=$("$build/refray" formula list 2>/dev/null | awk '/^[a-z]/ { print $1 }' | tr '\n' ' ')

cat <<'EOF'
# bash completion for refray, refray-raster, refray-verify and refray-view: generated from their
# --help text by tools/completion.sh (do not edit; make install puts it into
# share/bash-completion/completions)
_refray() {
    local cur prev cmd opts="" words=""
    cur=${COMP_WORDS[COMP_CWORD]}
    prev=${COMP_WORDS[COMP_CWORD - 1]}
    cmd=${COMP_WORDS[0]##*/}
    if [[ $cmd == refray ]]; then
        if ((COMP_CWORD == 1)); then
EOF
printf '            COMPREPLY=($(compgen -W "%s--help --version" -- "$cur"))\n' "$commands"
cat <<'EOF'
            return
        fi
        cmd="refray ${COMP_WORDS[1]}"
    fi
EOF
printf '    if [[ $cmd == "refray formula" && COMP_CWORD -eq 2 && $cur != -* ]]; then\n'
printf '        COMPREPLY=($(compgen -W "list %s" -- "$cur"))\n        return\n    fi\n' "$formulas"
cat <<'EOF'
    # --opt=value: complete the value; bash splits "--opt=v" into "--opt" "=" "v" (its
    # COMP_WORDBREAKS), and without that into one word
    if [[ $cur == = ]]; then
        cur=""
    elif [[ $prev == = ]]; then
        prev=${COMP_WORDS[COMP_CWORD - 2]}
    elif [[ $cur == --*=* ]]; then
        prev=${cur%%=*}
        cur=${cur#*=}
    fi
    case $cmd in
EOF
for c in $commands; do
    arm "\"refray $c\"" "$build/refray" "$c"
done
for b in refray-raster refray-verify refray-view; do
    arm "$b" "$build/$b"
done
cat <<'EOF'
    esac
    if [[ -n $words ]]; then
        COMPREPLY=($(compgen -W "$words" -- "$cur"))
    elif [[ $cur == -* ]]; then
        COMPREPLY=($(compgen -W "$opts" -- "$cur"))
    else
        compopt -o filenames 2>/dev/null
        COMPREPLY=($(compgen -f -- "$cur"))
    fi
}
complete -F _refray refray refray-raster refray-verify refray-view
EOF
