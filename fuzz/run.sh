#!/bin/sh
# refray fuzzing: `make fuzz` (fuzz/README.md). Builds the libFuzzer targets with clang into
# FUZZ_BUILD (default build-fuzz), makes the seed corpora, runs each target for FUZZ_SECONDS
# (default 60) seconds, FUZZ_JOBS (default 2) at a time, and prints one line per target:
# executions, coverage (edges and features), corpus size and the crashes found (each saved as
# FUZZ_BUILD/artifacts/<target>/crash-*, leak-*, timeout-* or oom-*). A target that crashes is
# restarted for the rest of its time, so one bug does not hide the next.
# Exit status: 0 when nothing new was found (or clang's libFuzzer is missing: then it prints the
# apt-get line and does nothing), 1 when some target found something, 2 when the build failed.
# The reproducers under tests/data/fuzz/ that still fail are listed, not counted (make test
# fails on them).
#   FUZZ_TARGETS="nff rf"   a subset (default: nff rf obj mtl exr png formula)
#   FUZZ_SECONDS=10         CI's short round
set -u
cd "$(dirname "$0")/.."
SECS=${FUZZ_SECONDS:-60}
TARGETS=${FUZZ_TARGETS:-nff rf obj mtl exr png formula}
JOBS=${FUZZ_JOBS:-2}
B=${FUZZ_BUILD:-build-fuzz}
MAKE=${MAKE:-make}
APT="apt-get install clang-14 libclang-rt-14-dev"

CC=${FUZZ_CC:-$(command -v clang-14 || command -v clang || true)}
mkdir -p "$B"
if [ -n "$CC" ]; then
    printf '#include <stdint.h>\n#include <stddef.h>\nint LLVMFuzzerTestOneInput(const uint8_t *d, size_t n) { (void)d; (void)n; return 0; }\n' > "$B/probe.c"
    "$CC" -fsanitize=fuzzer,address,undefined "$B/probe.c" -o "$B/probe" > "$B/probe.log" 2>&1 || CC=""
fi
if [ -z "$CC" ]; then
    echo "refray fuzz: clang with libFuzzer is missing; to fuzz, run this once, then make fuzz again:" >&2
    echo "  sudo $APT" >&2
    exit 0
fi

# a make of its own (not the caller's jobserver or command-line variables)
env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL $MAKE --no-print-directory -f fuzz/fuzz.mk -j"$JOBS" FUZZ_CC="$CC" FUZZ_BUILD="$B" FUZZ_TARGETS="$TARGETS" || exit 2
sh fuzz/seed.sh "$B" || exit 2

# per target: the largest input libFuzzer makes (bytes)
max_len() {
    case $1 in
        exr | png) echo 65536 ;;
        formula) echo 8192 ;;
        *) echo 16384 ;;
    esac
}

# fuzz one target for SECS seconds (restarting after each finding); writes $B/stats/<t>
run_target() {
    t=$1
    corpus=$B/corpus/$t
    art=$B/artifacts/$t
    log=$B/logs/$t.log
    # the sandboxes (fuzz_main.h) go here: a crashed process leaves its own behind
    tmp=$(cd "$B" && pwd)/tmp/$t
    mkdir -p "$corpus" "$art" "$B/logs" "$B/stats" "$tmp"
    : > "$log"
    start=$(date +%s)
    execs=0
    rounds=0
    while :; do
        left=$((start + SECS - $(date +%s)))
        [ "$left" -ge 1 ] && [ "$rounds" -lt 50 ] || break
        rounds=$((rounds + 1))
        # -malloc_limit_mb: the largest image refray takes (2^28 RGBA float pixels) is one 4 GiB
        # calloc that a header may legitimately ask for; the memory actually touched stays
        # under -rss_limit_mb
        TMPDIR=$tmp RF_FUZZ_SCENES=scenes "$B/fuzz-$t" -max_total_time="$left" -timeout=10 -rss_limit_mb=2048 \
            -malloc_limit_mb=4608 \
            -max_len="$(max_len "$t")" -dict="fuzz/dict/$t.dict" -artifact_prefix="$art/" \
            -print_final_stats=1 "$corpus" "$B/seeds/$t" > "$log.round" 2>&1
        rc=$?
        cat "$log.round" >> "$log"
        n=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log.round" | tail -n 1)
        execs=$((execs + ${n:-0}))
        [ "$rc" = 0 ] && break
    done
    rm -f "$log.round"
    rm -rf "$tmp"
    cov=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$log" | tail -n 1)
    found=$(grep -c 'Test unit written to' "$log")
    secs=$(($(date +%s) - start))
    printf '%-8s %5ss %10s execs %7s/s  %-22s corpus %5s  found %s\n' "$t" "$secs" "$execs" \
        "$((execs / (secs > 0 ? secs : 1)))" "${cov:-cov: ?}" "$(ls "$corpus" | wc -l)" "$found" > "$B/stats/$t"
}

echo "refray fuzz: $TARGETS, ${SECS} s each, $JOBS at a time (logs: $B/logs, corpora: $B/corpus)"
rm -f "$B"/stats/*
i=0
for j in $(seq 1 "$JOBS"); do
    list=""
    k=0
    for t in $TARGETS; do
        [ $((k % JOBS + 1)) = "$j" ] && list="$list $t"
        k=$((k + 1))
    done
    [ -n "$list" ] && (for t in $list; do run_target "$t"; done) &
    i=$((i + 1))
done
wait

status=0
for t in $TARGETS; do
    cat "$B/stats/$t"
    f=$(sed -n 's/.*found //p' "$B/stats/$t")
    [ "${f:-0}" = 0 ] || status=1
done
if [ -s "$B/seeds/open.txt" ]; then
    echo "refray fuzz: kept reproducers (tests/data/fuzz) that still fail here, left out of the seeds:"
    sed 's/^/  /' "$B/seeds/open.txt"
fi
if [ "$status" = 1 ]; then
    # each finding in full enough to rebuild it elsewhere (CI keeps only the log's tail):
    # the sanitizer's summary, refray's first frames and the input itself, base64
    for t in $TARGETS; do
        log=$B/logs/$t.log
        for a in $(sed -n 's/.*Test unit written to //p' "$log" | head -n 3); do
            echo "refray fuzz: $t finding $(basename "$a"):"
            # the round (from libFuzzer's "INFO: Seed:") that wrote this artifact
            awk -v a="$a" '/^INFO: Seed:/ {n = 0} {l[++n] = $0}
                 index($0, "Test unit written to " a) {
                     k = 0; f = 0
                     for (i = 1; i <= n; i++) {
                         if (l[i] ~ /^(SUMMARY|==[0-9]+==ERROR)|runtime error|ERROR: libFuzzer/ && k < 3) { print "  " l[i]; k++ }
                         if (l[i] ~ /^ *#[0-9]+ .* in rf/ && f < 6) { print "  " l[i]; f++ }
                     }
                     exit
                 }' "$log"
            if [ -f "$a" ] && [ "$(wc -c < "$a")" -le 4096 ]; then
                echo "  the input, base64 (base64 -d > FILE):"
                base64 -w 100 "$a" | sed 's/^/  /'
            fi
        done
    done
    echo "refray fuzz: findings in $B/artifacts/<target>/ (reproduce: $B/fuzz-<target> FILE;" \
         "minimise: $B/fuzz-<target> -minimize_crash=1 -runs=10000 FILE)" >&2
fi
exit $status
