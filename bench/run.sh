#!/usr/bin/env bash
# The benchmark of graftal: `make bench`, or directly
#
#   bench/run.sh [BUILD_DIR]        (default: build)
#
# Runs graftal (BUILD_DIR/graftal, already built in Release) and the npm package
# `lindenmayer` side by side on the L-systems in bench/lsystems/, plus a memcpy probe for
# the memory-bandwidth floor, and prints one table (bench/report.py) that it also writes
# into docs/performance.md between <!-- bench:begin --> and <!-- bench:end -->.
# Never part of `make test`. See bench/README.md.
#
# Settings (environment variables):
#   BENCH_RUNS=5              graftal runs per row (fewer for slow rows: see BENCH_BUDGET)
#   BENCH_BUDGET=15           stop repeating a graftal row once its runs took this many s
#   BENCH_PEER_RUNS=3         lindenmayer runs per row (repeated only while under 20 s)
#   BENCH_PEER_TIMEOUT=120    seconds lindenmayer gets per row before "timeout"
#   BENCH_STREAM_TIMEOUT=150  seconds the streamed Koch n=11 render gets
#   BENCH_PEER=1              0: skip lindenmayer (and its npm install)
#   BENCH_DOC=docs/performance.md   where the table goes ("" for nowhere)
#   CPFG=DEST/bin/cpfg        also run cpfg 6.6 side by side (bench/versus_cpfg.py): the
#                             models of bench/cpfg/ in three modes, runs alternating;
#                             ../shared/cpfg-anchor/ says how to build cpfg from vlab's
#                             sources outside the repository
#   BENCH_CPFG_RUNS=3         runs per program and mode in the cpfg comparison; with CPFG
#                             the row `startup` (bench/startup_versus_cpfg.py) also runs:
#                             every command on small models, 15 runs each, interleaved
#   BENCH_ROWS="honda23 pcond22"    run only these rows (keys as in bench/report.py, and
#                             mesh3d: the 3D turtle and mesher, python: the Python module,
#                             printed, not in the table);
#                             the table then lists only them. Default: every row.
#
# Results (JSON per row, the table, the PNG) go to BUILD_DIR/bench/results/.
# lindenmayer is installed with npm into bench/.peers/ (git-ignored), never committed.

set -uo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(dirname "$here")
build=${1:-build}
case $build in /*) ;; *) build="$PWD/$build" ;; esac

RUNS=${BENCH_RUNS:-5}
BUDGET=${BENCH_BUDGET:-15}
PEER_RUNS=${BENCH_PEER_RUNS:-3}
PEER_TIMEOUT=${BENCH_PEER_TIMEOUT:-120}
STREAM_TIMEOUT=${BENCH_STREAM_TIMEOUT:-150}
PEER=${BENCH_PEER:-1}
DOC=${BENCH_DOC-$root/docs/performance.md}
PEER_VERSION=1.5.4
ONLY=${BENCH_ROWS:-}
# Whether row KEY is to be run (every row unless BENCH_ROWS lists some).
wanted() { [ -z "$ONLY" ] || [[ " $ONLY " == *" $1 "* ]]; }

graftal="$build/graftal"
results="$build/bench/results"
ls_dir="$here/lsystems"
peers="$here/.peers"

say() { printf '%s\n' "$*" >&2; }
die() { say "bench: $*"; exit 1; }

[ -x "$graftal" ] || die "no graftal at $graftal (build it first: make build, or cmake --build $build)"
command -v python3 >/dev/null || die "python3 is needed for the measurements and the table"
command -v g++ >/dev/null || die "g++ is needed for the memcpy probe"

rm -rf "$results"
mkdir -p "$results"
start=$(date +%s)

measure() {  # measure OUT RUNS BUDGET TIMEOUT CMD...
    local out=$1 runs=$2 budget=$3 timeout=$4
    shift 4
    python3 "$here/report.py" measure --out "$results/$out.json" --runs "$runs" \
        --budget "$budget" --timeout "$timeout" -- "$@"
}

# ---- what this graftal can do ------------------------------------------------------------
quiet=()
if "$graftal" stats --help 2>/dev/null | grep -a -q -- '--quiet'; then quiet=(--quiet); fi
have_stream=0
if "$graftal" render --help 2>/dev/null | grep -a -q -- '--stream'; then have_stream=1; fi

# ---- the peer ----------------------------------------------------------------------------
peer_ok=0
peer_reason=""
if [ -n "$ONLY" ] && ! wanted koch8 && ! wanted abop16 && ! wanted hogeweg70 &&
    ! wanted honda23 && ! wanted interp8; then
    PEER=0  # none of the selected rows has a peer
fi
if [ "$PEER" = 1 ]; then
    if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
        peer_reason="not available (node/npm not installed)"
    else
        if [ ! -f "$peers/node_modules/lindenmayer/package.json" ]; then
            say "bench: installing lindenmayer@$PEER_VERSION with npm into bench/.peers/"
            mkdir -p "$peers"
            npm install --prefix "$peers" --no-audit --no-fund --silent \
                "lindenmayer@$PEER_VERSION" >/dev/null 2>"$results/npm.log" ||
                peer_reason="not available (npm install failed: see $results/npm.log)"
        fi
        [ -z "$peer_reason" ] && [ -f "$peers/node_modules/lindenmayer/package.json" ] && peer_ok=1
        [ $peer_ok = 1 ] || peer_reason=${peer_reason:-"not available (npm install failed)"}
    fi
else
    peer_reason="skipped (BENCH_PEER=0)"
fi

# ---- environment -------------------------------------------------------------------------
commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
git -C "$root" diff --quiet HEAD 2>/dev/null || commit="$commit + uncommitted changes"
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
python3 - "$results/env.json" <<EOF
import json, os, platform, subprocess, sys, time
def sh(c):
    try: return subprocess.run(c, shell=True, capture_output=True, text=True).stdout.strip()
    except Exception: return ""
mem = sh("awk '/MemTotal/ {printf \"%.0f GiB\", \$2/1048576}' /proc/meminfo")
cpu = sh("lscpu | sed -n 's/^Model name: *//p' | head -1") or platform.processor()
json.dump({
  "date": time.strftime("%Y-%m-%d %H:%M %Z"), "cpu": cpu, "cores": os.cpu_count(),
  "memory": mem, "load_before": "$load_before", "graftal_commit": "$commit",
  "build_dir": os.path.relpath("$build", "$root"),
  "graftal_flags": "stats ${quiet[*]:-(no --quiet)}; render --stream $([ $have_stream = 1 ] && echo available || echo 'not available')",
  "node": sh("node --version"),
  "peer_version": "$PEER_VERSION" if $peer_ok else "$peer_reason",
}, open(sys.argv[1], "w"), indent=1)
EOF

# ---- 6. the bandwidth floor --------------------------------------------------------------
if wanted memcpy; then
    say "bench: memcpy probe"
    g++ -O2 -std=c++17 -o "$build/bench/memcpy_probe" "$here/memcpy_probe.cpp" ||
        die "cannot build bench/memcpy_probe.cpp"
    # Koch island n = 8: 124,630,747 modules, 1 byte each.
    measure memcpy 1 0 120 "$build/bench/memcpy_probe" 124630747 7
fi

# ---- graftal -----------------------------------------------------------------------------
# row key | file | n | extra stats options (the in-process timing takes the same precision)
rows=(
    "koch8|koch-island.l|8|"
    "abop16|abop-1.24d.l|16|"
    "hogeweg70|hogeweg-1.31a.l|70|"
    "honda23|honda-2.6a.l|23|"
    "honda23d|honda-2.6a.l|23|--precision double"
    "pcond22|param-conditions.l|22|"
    "pctx20|param-context.l|20|"
    "pblocks20|param-blocks.l|20|"
)
selected=()
for r in "${rows[@]}"; do
    IFS='|' read -r key file n extra <<<"$r"
    wanted "$key" && selected+=("$r")
done
for r in "${selected[@]}"; do
    IFS='|' read -r key file n extra <<<"$r"
    say "bench: graftal $file n=$n $extra"
    # shellcheck disable=SC2086  # extra is one option and its value, or nothing
    measure "$key.graftal" "$RUNS" "$BUDGET" 600 \
        "$graftal" stats "$ls_dir/$file" -n "$n" --no-geometry "${quiet[@]}" $extra
done
# The derivation alone, timed inside one process (first run, then warm runs).
if [ ${#selected[@]} = 0 ]; then
    :
elif cmake --build "$build" --target graftal_derive_timing >"$results/derive_timing.log" 2>&1; then
    for r in "${selected[@]}"; do
        IFS='|' read -r key file n extra <<<"$r"
        precision=single
        [ "$extra" = "--precision double" ] && precision=double
        say "bench: graftal $file n=$n in process ($precision)"
        measure "$key.inproc" 1 0 600 "$build/graftal_derive_timing" "$ls_dir/$file" "$n" 5 \
            "$precision"
    done
else
    say "bench: cannot build graftal_derive_timing (see $results/derive_timing.log)"
fi
if wanted interp8; then
    say "bench: graftal koch-island.l n=8 with the 2D turtle"
    measure interp8.graftal "$RUNS" "$BUDGET" 600 \
        "$graftal" stats "$ls_dir/koch-island.l" -n 8 "${quiet[@]}"
fi

# The 3D turtle and the mesher in one process on a 1,048,575-segment tree (not in the table).
if wanted mesh3d; then
    if cmake --build "$build" --target graftal_mesh_timing >"$results/mesh_timing.log" 2>&1; then
        say "bench: graftal 3D turtle + mesh, honda-monopodial-tree.l n=20 (in process)"
        "$build/graftal_mesh_timing" "$root/examples/honda-monopodial-tree.l" 20 3 \
            >"$results/mesh3d.json" && python3 -c 'import json,sys; m=json.load(open(sys.argv[1]))
print("bench: 3D turtle %.3f s + mesh %.3f s for %d segments: %.1f M segments/s, peak %d MiB"
      % (m["turtle_s"], m["mesh_s"], m["segments"], m["segments_per_s"] / 1e6, m["peak_mib"]))' \
            "$results/mesh3d.json" >&2
    else
        say "bench: cannot build graftal_mesh_timing (see $results/mesh_timing.log)"
    fi
fi

# The Python module (docs/python.md; not in the table): Honda n=20 derived from Python against
# the command, the parameters read through NumPy without a copy, a 100-point sweep on two
# Dask workers against one process.
if wanted python && [ -d "$build/python/graftal" ]; then
    say "bench: the Python module (bench/python_bench.py)"
    /usr/bin/python3 "$here/python_bench.py" "$build" >&2 || say "bench: the Python bench failed"
fi

# Map L-systems (docs/maps.md): Fig 5.2's layer at n=17, 131,072 cells, derived and
# relaxed (every step settled, the outline grown) on one thread and on two.
for t in 1 2; do
    wanted "map17t$t" || continue
    say "bench: graftal map L-system fig5.2 n=17 relaxed, $t thread(s)"
    measure "map17t$t.graftal" "$RUNS" "$BUDGET" 600 \
        "$graftal" stats "$root/examples/fig5.2-cell-layer.l" -n 17 --map-geometry relaxed \
        --threads "$t"
done

# ---- lindenmayer -------------------------------------------------------------------------
peer_rows=("koch8|koch|8" "abop16|abop124d|16" "hogeweg70|hogeweg|70" "honda23|honda|23"
           "interp8|koch|8|--interpret")
for r in "${peer_rows[@]}"; do
    IFS='|' read -r key system n flag <<<"$r"
    wanted "$key" || continue
    if [ $peer_ok != 1 ]; then
        echo "$peer_reason" >"$results/$key.peer.unavailable"
        continue
    fi
    say "bench: lindenmayer $system n=$n ${flag:-} (up to ${PEER_TIMEOUT} s)"
    measure "$key.peer" "$PEER_RUNS" 20 "$PEER_TIMEOUT" \
        node --max-old-space-size=16000 "$here/lindenmayer_run.mjs" "$system" "$n" ${flag:+"$flag"}
done
# Koch n=11 has 6.4e10 modules: past the 2^29 - 24 characters a V8 string can hold.
echo "n/a (JS strings stop at 2^29 − 24 symbols)" >"$results/stream11.peer.unavailable"

echo "no map L-systems" >"$results/map17t1.peer.unavailable"
echo "no map L-systems" >"$results/map17t2.peer.unavailable"
# The parametric rows beyond Honda's are not written for the peer.
for key in honda23d pcond22 pctx20 pblocks20; do
    echo "not written for the peer" >"$results/$key.peer.unavailable"
done

# ---- 7. streamed Koch n=11 to PNG --------------------------------------------------------
if ! wanted stream11; then
    :
elif [ $have_stream = 1 ]; then
    say "bench: graftal render koch-island.l -n 11 --stream (up to ${STREAM_TIMEOUT} s)"
    png="$results/koch-n11.png"
    measure stream11.graftal 1 0 "$STREAM_TIMEOUT" \
        "$graftal" render "$ls_dir/koch-island.l" -n 11 --stream -o "$png" "${quiet[@]}"
    if grep -q '"rc": 0' "$results/stream11.graftal.json" && [ ! -s "$png" ]; then
        echo "failed: no PNG written" >"$results/stream11.graftal.unavailable"
    fi
else
    echo "not available (graftal render has no --stream)" >"$results/stream11.graftal.unavailable"
fi

# ---- 8. a big 3D plant ray traced --------------------------------------------------------
# Honda's monopodial tree at n = 20: 1,048,575 segments to an 800x800 ray-traced PNG (mesh,
# curves, Embree's BVH, the pixels); the peak RSS is the whole process's.
if wanted render3d; then
    say "bench: graftal render honda-monopodial-tree.l -n 20 (ray traced, 800x800)"
    measure render3d.graftal "$RUNS" "$BUDGET" 600 \
        "$graftal" render "$root/examples/honda-monopodial-tree.l" -n 20 --size 800x800 \
        -o "$results/honda-monopodial-n20.png"
    echo "not written for the peer" >"$results/render3d.peer.unavailable"
fi

# ---- cpfg side by side -------------------------------------------------------------------
# The same files (bench/cpfg/) read by both programs, string to a file, derivation, and
# derivation + turtle; its own table, between the cpfg:begin/cpfg:end markers of the doc.
if [ -n "${CPFG:-}" ]; then
    say "bench: cpfg side by side ($CPFG)"
    cpfg_rows=()
    for key in koch8 abop16 hogeweg70 honda23; do wanted "$key" && cpfg_rows+=("$key"); done
    if [ ${#cpfg_rows[@]} -gt 0 ]; then
        partial=()
        [ -n "$ONLY" ] && partial=(--rows "${cpfg_rows[*]}")
        python3 "$here/versus_cpfg.py" --graftal "$graftal" --cpfg "$CPFG" \
            --results "$results" --runs "${BENCH_CPFG_RUNS:-3}" "${partial[@]}" \
            ${DOC:+--doc "$DOC"} >/dev/null || say "bench: the cpfg comparison failed"
    fi
    # Start-up: every command on small models (the book's Fibonacci words, Koch n = 3).
    if wanted startup; then
        say "bench: start-up on small models, graftal and cpfg interleaved"
        python3 "$here/startup_versus_cpfg.py" --graftal "$graftal" --cpfg "$CPFG" \
            --results "$results" ${DOC:+--doc "$DOC"} >/dev/null ||
            say "bench: the start-up comparison failed"
    fi
fi

# ---- the table ---------------------------------------------------------------------------
load_after=$(cut -d' ' -f1-3 /proc/loadavg)
python3 - "$results/env.json" "$load_after" "$(( $(date +%s) - start ))" <<'EOF'
import json, sys
p = sys.argv[1]
env = json.load(open(p))
env["load_after"] = sys.argv[2]
env["bench_seconds"] = int(sys.argv[3])
json.dump(env, open(p, "w"), indent=1)
EOF
say ""
say "bench: done in $(( $(date +%s) - start )) s; results in $results"
echo
python3 "$here/report.py" report --results "$results" --json "$results/summary.json" \
    ${ONLY:+--only "$ONLY"} ${DOC:+--doc "$DOC"}
if [ -f "$results/versus-cpfg.md" ]; then
    echo
    echo "graftal and cpfg 6.6 side by side (bench/versus_cpfg.py):"
    cat "$results/versus-cpfg.md"
fi
if [ -f "$results/startup.md" ]; then
    echo
    echo "Start-up on small models (bench/startup_versus_cpfg.py):"
    cat "$results/startup.md"
fi
