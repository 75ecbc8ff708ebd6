#!/bin/sh
# refray fuzzing: the seed corpora, made afresh from the repository's files.
#   sh fuzz/seed.sh BUILD_DIR      -> BUILD_DIR/seeds/<target>/ for every target
# nff: scenes/spd/*.nff and the gears (gunzipped), each cut to its first 12 KB at a line end
# (libFuzzer mutates inputs of at most -max_len bytes); rf: scenes/*.rf and the docs' broken
# example; obj, mtl: scenes/*.obj, *.mtl; exr: tests/data/golden/*.exr and the tiny images of
# BUILD_DIR/mkseeds (every compression, HALF/FLOAT, Y/RGB/RGBA); png: mkseeds' PNGs (refray's
# writer and libpng's other colour types, bit depths, interlacing), the smaller docs/img
# pictures and the PPM, JPEG, HDR and corrupt files of tests/data (read by signature too);
# formula: up to three cases per id from tests/data/formula_cases_*.jsonl, one per file, and
# tests/data/docs/cases.jsonl whole. The kept reproducers (tests/data/fuzz/<target>/)
# are seeds too, once they no longer crash the target.
set -eu
B=${1:?usage: seed.sh BUILD_DIR}
S=$B/seeds
LIMIT=12000
rm -rf "$S"
for t in nff rf obj mtl exr png formula; do mkdir -p "$S/$t"; done

# a text file, cut at a line end to at most LIMIT bytes
cut_copy() {
    if [ "$(wc -c < "$1")" -gt "$LIMIT" ]; then
        head -c "$LIMIT" "$1" | sed '$d' > "$2"
    else
        cp "$1" "$2"
    fi
}

for f in scenes/spd/*.nff; do cut_copy "$f" "$S/nff/$(basename "$f")"; done
if [ -f scenes/spd/gears.nff.gz ]; then
    gzip -dc scenes/spd/gears.nff.gz > "$S/nff/gears.full"
    cut_copy "$S/nff/gears.full" "$S/nff/gears.nff"
    rm -f "$S/nff/gears.full"
fi
for f in scenes/*.rf scenes/bench/*.rf tests/data/docs/*.rf; do
    [ -f "$f" ] && cut_copy "$f" "$S/rf/$(echo "$f" | tr / _)"
done
for f in scenes/*.obj; do cut_copy "$f" "$S/obj/$(basename "$f")"; done
for f in scenes/*.mtl; do cp "$f" "$S/mtl/"; done

for f in tests/data/golden/*.exr; do [ -f "$f" ] && cp "$f" "$S/exr/"; done
"$B/mkseeds" "$S/exr" "$S/png"
for f in docs/img/*.png; do
    [ -f "$f" ] && [ "$(wc -c < "$f")" -le 65536 ] && cp "$f" "$S/png/"
done
# the other formats rf_image_read dispatches to by signature (refray grade's students' files:
# PPM, JPEG, HDR, and the corrupt samples of each format, tests/data/corrupt)
for f in tests/data/docs/*.ppm tests/data/docs/*.jpg tests/data/docs/*.hdr tests/data/corrupt/*; do
    [ -f "$f" ] && [ "$(wc -c < "$f")" -le 65536 ] && cp "$f" "$S/png/$(echo "$f" | tr / _)"
done

n=0
for f in tests/data/formula_cases_*.jsonl; do
    [ -f "$f" ] || continue
    awk -v dir="$S/formula" -v base="$(basename "$f" .jsonl)" '
        match($0, /"id": *"[^"]*"/) {
            id = substr($0, RSTART, RLENGTH); sub(/"id": *"/, "", id); sub(/"$/, "", id)
            if (seen[id]++ < 3) { out = sprintf("%s/%s_%04d", dir, base, NR); print > out; close(out) }
        }' "$f"
done
[ -f tests/data/docs/cases.jsonl ] && cp tests/data/docs/cases.jsonl "$S/formula/docs_cases.jsonl"

# the kept reproducers: what once broke a reader stays in its corpus, once it is fixed (libFuzzer
# stops at a seed that still crashes); the others are listed in $S/open.txt
: > "$S/open.txt"
mkdir -p "$B/tmp"
for t in nff rf obj mtl exr png formula; do
    [ -d "tests/data/fuzz/$t" ] || continue
    for f in "tests/data/fuzz/$t"/*; do
        [ -f "$f" ] || continue
        if [ ! -x "$B/fuzz-$t" ] ||
           TMPDIR=$B/tmp RF_FUZZ_SCENES=scenes "$B/fuzz-$t" -timeout=10 -rss_limit_mb=2048 "$f" > /dev/null 2>&1; then
            cp "$f" "$S/$t/regress_$(basename "$f")"
        else
            echo "$f" >> "$S/open.txt"
        fi
    done
done
rm -rf "$B"/tmp/refray-fuzz-* # the sandboxes of the reproducers that crashed
for t in nff rf obj mtl exr png formula; do
    n=$(ls "$S/$t" | wc -l)
    printf '%s %s\n' "$t" "$n"
done > "$S/count.txt"
