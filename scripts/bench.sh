#!/usr/bin/env bash
# Builds the benchmark programs (release preset) and runs them: load, build, intersect and frame
# with --summary (their runs, then a table of medians and ratios). Each program also writes its
# runs as Google Benchmark JSON to build/release/bench/<program>.json; for intersect and frame,
# scripts/perf_tables.py then prints the tables of docs/performance.md from them (to put them
# in the page: python3 scripts/perf_tables.py --write docs/performance.md
# build/release/bench/intersect.json build/release/bench/frame.json).
# With arguments, those programs only: bash scripts/bench.sh intersect png. About 10 minutes for
# the four.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
shared="$(cd .. && pwd)/shared"
[ -d "$shared/models" ] && export RAYLANE_MODEL_PATH="$shared/models:$shared/textures${RAYLANE_MODEL_PATH:+:$RAYLANE_MODEL_PATH}"
programs=("$@")
[ ${#programs[@]} -gt 0 ] || programs=(load build intersect frame)
targets=()
for p in "${programs[@]}"; do targets+=("bench_$p"); done
cmake --preset release >/dev/null
cmake --build --preset release --target "${targets[@]}"
for p in "${programs[@]}"; do
    case "$p" in
        build) args=(--benchmark_filter=BM_BuildMedian/dragon --benchmark_repetitions=10
                     --benchmark_enable_random_interleaving=true --benchmark_min_time=0.3) ;;
        intersect) args=(--benchmark_repetitions=3 --benchmark_min_time=0.3
                         --benchmark_filter=dragon) ;;
        frame) args=(--benchmark_repetitions=3 --benchmark_min_time=1) ;;
        *) args=(--benchmark_repetitions=3 --benchmark_min_time=0.5) ;;
    esac
    case "$p" in load | build | intersect | frame) args+=(--summary) ;; esac
    args+=(--benchmark_out="build/release/bench/$p.json" --benchmark_out_format=json)
    echo "== bench_$p ${args[*]}"
    "./build/release/bench/bench_$p" "${args[@]}"
done
tables=()
for p in "${programs[@]}"; do
    case "$p" in intersect | frame) tables+=("build/release/bench/$p.json") ;; esac
done
if [ ${#tables[@]} -gt 0 ]; then
    echo "== docs/performance.md's tables (scripts/perf_tables.py ${tables[*]})"
    python3 scripts/perf_tables.py "${tables[@]}"
fi
