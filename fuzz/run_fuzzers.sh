#!/bin/sh
# Runs each fuzz target of a `make fuzz` build for a set time, one after the other:
#   fuzz/run_fuzzers.sh BUILD_DIR SECONDS TARGET...
# Seeds: fuzz/corpus/<target> and fuzz/regressions/<target>. New corpus entries go to
# BUILD_DIR/corpus/<target>, findings (crash-*, timeout-*, oom-*) to BUILD_DIR/findings/<target>,
# each run's log to BUILD_DIR/logs/<target>.log and one line per run to BUILD_DIR/fuzz-summary.txt.
# FUZZ_NICE (default 19) is the niceness; FUZZ_JOBS (default 1) the parallel fuzzing processes.
# libFuzzer runs in fork mode and carries on after a finding, so that a known bug does not
# end the run.
set -eu

if [ $# -lt 3 ]; then
    echo "usage: $0 BUILD_DIR SECONDS TARGET..." >&2
    exit 2
fi
build=$1
seconds=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
nice_level=${FUZZ_NICE:-19}
jobs=${FUZZ_JOBS:-1}

# Inputs and limits per target: the .l texts of the examples are under 4 KB, surface files
# under 8 KB, view and data files (fuzz_data_files.cpp) under 4 KB. The derive target
# bounds its own derivation time (fuzz_api.hpp); -timeout is the limit for one input, past
# which libFuzzer records a timeout finding.
options_for() {
    case $1 in
        parse) echo "-max_len=4096 -timeout=10 -rss_limit_mb=1024 -dict=$here/dict/lsystem.dict" ;;
        derive) echo "-max_len=4096 -timeout=20 -rss_limit_mb=1536 -dict=$here/dict/lsystem.dict" ;;
        surface) echo "-max_len=8192 -timeout=10 -rss_limit_mb=1024 -dict=$here/dict/surface.dict" ;;
        expression) echo "-max_len=1024 -timeout=10 -rss_limit_mb=1024 -dict=$here/dict/lsystem.dict" ;;
        data_files) echo "-max_len=4096 -timeout=10 -rss_limit_mb=1024 -dict=$here/dict/view.dict" ;;
        # A flags byte, four sizes and 16 doubles: longer inputs add nothing.
        camera) echo "-max_len=256 -timeout=10 -rss_limit_mb=1024" ;;
        # A route byte and a JSON body, or a whole HTTP request (fuzz_studio.cpp).
        studio) echo "-max_len=8192 -timeout=30 -rss_limit_mb=2048 -dict=$here/dict/studio.dict" ;;
        *) echo "unknown fuzz target '$1' (parse, derive, surface, expression, data_files, camera, studio)" >&2; exit 2 ;;
    esac
}

export ASAN_OPTIONS="${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
summary="$build/fuzz-summary.txt"
mkdir -p "$build/logs"

for target in "$@"; do
    exe="$build/fuzz/graftal_fuzz_$target"
    [ -x "$exe" ] || { echo "$exe is missing: run make fuzz" >&2; exit 2; }
    options=$(options_for "$target")
    corpus="$build/corpus/$target"
    findings="$build/findings/$target"
    log="$build/logs/$target.log"
    mkdir -p "$corpus" "$findings"
    seeds="$here/corpus/$target"
    [ -d "$here/regressions/$target" ] && seeds="$seeds $here/regressions/$target"
    echo "fuzzing $target for ${seconds}s (log: $log)"
    before=$(ls "$findings" | wc -l)
    start=$(date +%s)
    # shellcheck disable=SC2086
    nice -n "$nice_level" "$exe" $options -max_total_time="$seconds" -fork="$jobs" \
        -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 -print_final_stats=1 \
        -artifact_prefix="$findings/" "$corpus" $seeds > "$log" 2>&1 || true
    elapsed=$(($(date +%s) - start))
    # Fork mode's progress lines: "#EXECS: cov: C ft: F corp: K exec/s E oom/timeout/crash:
    # O/T/C time: Ss job: J dft_time: D"; the last one has the run's totals.
    last=$(grep -E '^#[0-9]+: cov:' "$log" | tail -1 || true)
    found=$(($(ls "$findings" | wc -l) - before))
    echo "$(date -u +%Y-%m-%dT%H:%MZ) $target ${elapsed}s new-findings=$found | $last" |
        tee -a "$summary"
done
