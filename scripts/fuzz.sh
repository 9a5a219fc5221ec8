#!/usr/bin/env bash
# Fuzzing: builds the fuzz preset (clang, libFuzzer + ASan + UBSan) and runs every
# tests/fuzz/fuzz_<name> program, starting from a copy of tests/fuzz/corpus/<name>/ after
# replaying tests/fuzz/regressions/<name>/.
#
#   scripts/fuzz.sh [SECONDS_PER_TARGET]   explore: a random seed, SECONDS each (default 30)
#   scripts/fuzz.sh ci                     repeatable: seed 1 and a fixed number of inputs per
#                                          target (about 20 s each here), what .ci/run runs
#
# The ci mode gives the same inputs on every run, so a commit's CI result does not depend on
# luck; exploring with random seeds (and longer) is how new findings are made, and each one
# goes into regressions/ where every run replays it.
#
# Exits 1 on any finding (crash, sanitizer report, leak, timeout, out-of-memory, an exception
# other than InputError, bad data returned by a reader) and prints the path of the saved input;
# reproduce it with build/fuzz/tests/fuzz/fuzz_<name> <file>. The repository is not modified.
# Environment: FUZZ_CXX (compiler, default the preset's clang++-14), FUZZ_JOBS (build jobs),
# FUZZ_WORK (where corpora, logs and findings go; default a new temporary folder, kept).
set -euo pipefail
mode="${1:-30}"
if [ "$mode" = ci ]; then
    seconds=""
elif [[ "$mode" =~ ^[0-9]+$ ]]; then
    seconds="$mode"
else
    echo "usage: $0 [SECONDS_PER_TARGET | ci]" >&2
    exit 2
fi
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
bash scripts/setup.sh

configure=(--preset fuzz)
[ -n "${FUZZ_CXX:-}" ] && configure+=("-DCMAKE_CXX_COMPILER=$FUZZ_CXX")
cmake "${configure[@]}" >/dev/null
cmake --build --preset fuzz -j "${FUZZ_JOBS:-$(nproc)}"
bin="$root/build/fuzz/tests/fuzz"

work="${FUZZ_WORK:-$(mktemp -d "${TMPDIR:-/tmp}/raylane-fuzz.XXXXXX")}"
mkdir -p "$work"
echo "fuzz: working folder $work" >&2

# Largest input per kind: scenes and meshes are small text files, binary PLY and images bigger.
max_len_for() {
    case "$1" in
        scene) echo 16384 ;;
        obj) echo 8192 ;;
        ply) echo 8192 ;;
        image) echo 32768 ;;
        exr) echo 8192 ;;
        api) echo 1024 ;;
        *) echo 8192 ;;
    esac
}

# Inputs per target in ci mode: counts sized so that each target takes about 20 s on a 2-vCPU
# machine (a reader's rate differs by an order of magnitude between targets, and exr's first
# inputs are its slowest). Longer runs: scripts/fuzz.sh SECONDS.
runs_for() {
    case "$1" in
        scene) echo 150000 ;;
        obj) echo 600000 ;;
        ply) echo 500000 ;;
        image) echo 100000 ;;
        exr) echo 10000 ;;
        api) echo 300000 ;;
        *) echo 200000 ;;
    esac
}

# Sanitizer defaults are built in (tests/fuzz/sanitizer_options.cpp).
unset RAYLANE_MODEL_PATH

status=0
report() {  # report NAME LOG: prints the finding and the saved inputs
    echo "fuzz: FINDING in $1 (log: $2)" >&2
    grep -E '^==[0-9]+==ERROR|^SUMMARY|runtime error|^==fuzz==|uncaught exception|terminate called|ALARM|out-of-memory|deadly signal' "$2" | head -n 8 >&2 || true
    grep -o 'Test unit written to .*' "$2" | sed 's/^Test unit written to /fuzz: input saved as /' >&2 || true
    status=1
}

shopt -s nullglob
programs=("$bin"/fuzz_*)
[ ${#programs[@]} -gt 0 ] || { echo "fuzz: no programs in $bin" >&2; exit 1; }
for program in "${programs[@]}"; do
    [ -x "$program" ] || continue
    name="${program##*/fuzz_}"
    flags=(-max_len="$(max_len_for "$name")" -timeout=10 -rss_limit_mb=2048
        -artifact_prefix="$work/$name-" -print_final_stats=1)
    dict="$root/tests/fuzz/dict/$name.dict"
    [ -f "$dict" ] && flags+=(-dict="$dict")

    regressions=("$root/tests/fuzz/regressions/$name"/*)
    [ ${#regressions[@]} -gt 0 ] && echo "== fuzz_$name: ${#regressions[@]} regression inputs" >&2
    for input in "${regressions[@]}"; do
        log="$work/$name-regression-${input##*/}.log"
        if ! "$program" "${flags[@]}" "$input" >"$log" 2>&1; then
            report "fuzz_$name, regression input $input" "$log"
        fi
    done

    if [ -n "$seconds" ]; then
        budget=(-max_total_time="$seconds")
        echo "== fuzz_$name: ${seconds} s, random seed" >&2
    else
        budget=(-runs="$(runs_for "$name")" -seed=1)
        echo "== fuzz_$name: ${budget[0]#-runs=} inputs, seed 1" >&2
    fi
    corpus="$work/corpus-$name"
    mkdir -p "$corpus"
    [ -d "$root/tests/fuzz/corpus/$name" ] && cp -r "$root/tests/fuzz/corpus/$name/." "$corpus/"
    log="$work/$name.log"
    if "$program" "${flags[@]}" "${budget[@]}" "$corpus" >"$log" 2>&1; then
        grep -E '^stat::number_of_executed_units|^stat::average_exec_per_sec|^#[0-9]+ +DONE' "$log" \
            | tr '\n' ' ' >&2 || true
        echo >&2
    else
        report "fuzz_$name" "$log"
    fi
done
[ $status -eq 0 ] && echo "fuzz: no findings" >&2
exit $status
