#!/usr/bin/env bash
# Fuzz the case-file reader (fuzz/case_reader_fuzz.cpp) with libFuzzer + ASan + UBSan: one
# fuzzer per core (each its own random seed and corpus folder, started from the same seeds), for
# FUZZ_SECONDS of wall time (default 30: 60 s of fuzzing in 30 s of CI on its two cores;
# libFuzzer's -fork mode made a third as many runs here, restarting its jobs). Builds
# build-fuzz (clang, -DFLUIDEM_FUZZ=ON, only the fuzz target).
# Seed corpus: the shipped cases, copied into a temporary folder; dictionary fuzz/toml.dict.
# Exits non-zero on any finding (crash, sanitizer report, hang > 10 s, > 2 GB, an exception other
# than InputError, a failed round trip) and prints the path of the input that caused it.
# Extra arguments go to the fuzzer (e.g. -jobs=2 -workers=2).
set -euo pipefail
cd "$(dirname "$0")/.."
# Parallel jobs: the cores (nproc alone would follow OMP_NUM_THREADS, which test.sh sets to 1).
jobs=${FLUIDEM_JOBS:-$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)}
root=$PWD
seconds=${FUZZ_SECONDS:-30}
build=build-fuzz

cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DFLUIDEM_FUZZ=ON \
  -DFLUIDEM_BUILD_TESTS=OFF -DFLUIDEM_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j"$jobs" --target case_reader_fuzz

work=$(mktemp -d "${TMPDIR:-/tmp}/fluidem-fuzz.XXXXXX")
mkdir -p "$work/corpus" "$work/artifacts"
i=0
for f in cases/*/*.toml bench/cases/*.toml; do
  cp "$f" "$work/corpus/seed-$i-$(basename "$f")"
  i=$((i + 1))
done
# The reader only checks that an insert file is a readable file: empty stand-ins in the fuzzer's folder let
# the seeds with placement = "file" get past [[insert]] to [gas] and [coupling].
for name in $(sed -n 's/^ *file *= *"\([A-Za-z0-9_.-]*\)".*/\1/p' cases/*/*.toml bench/cases/*.toml |
  sort -u); do
  : >"$work/$name"
done
# Earlier findings (now regression tests) seed the search too.
for f in tests/data/fuzz/*.toml; do
  [ -e "$f" ] && cp "$f" "$work/corpus/"
done

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:symbolize=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export ASAN_SYMBOLIZER_PATH=${ASAN_SYMBOLIZER_PATH:-$(command -v llvm-symbolizer-14 || command -v llvm-symbolizer || true)}

echo "fuzzing the case reader for ${seconds} s with $jobs fuzzers (corpus and findings in $work)"
status=0
pids=()
for j in $(seq 1 "$jobs"); do
  cp -r "$work/corpus" "$work/corpus-$j"
  # Run from the work folder (no case files in it): a fuzzed insert file path resolves there.
  (cd "$work" && exec "$root/$build/fuzz/case_reader_fuzz" -seed="$j" -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=2048 -max_len=65536 -dict="$root/fuzz/toml.dict" \
    -artifact_prefix="$work/artifacts/" -print_final_stats=1 "$@" "corpus-$j" \
    >"$work/fuzz-$j.log" 2>&1) &
  pids+=($!)
done
for p in "${pids[@]}"; do
  wait "$p" || status=$?
done
for j in $(seq 1 "$jobs"); do
  echo "--- fuzzer $j ($work/fuzz-$j.log)"
  grep -v "NEW_FUNC" "$work/fuzz-$j.log" | tail -n 12
done
shopt -s nullglob
artifacts=("$work"/artifacts/*)
if [ "$status" -ne 0 ] || [ ${#artifacts[@]} -gt 0 ]; then
  echo "FUZZ FINDING (fuzzer exit $status); full logs: $work/fuzz-*.log" >&2
  for a in "${artifacts[@]}"; do
    echo "  crashing input: $a" >&2
    echo "  reproduce: $build/fuzz/case_reader_fuzz $a" >&2
  done
  exit 1
fi
echo "no findings; corpora in $work/corpus-*"
