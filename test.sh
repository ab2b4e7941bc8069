#!/usr/bin/env bash
# Install what is missing, build fluidem with its tests, run the tests (labels unit, regression);
# then the unit tests under ASan + UBSan (tools/ci-sanitizers.sh, build-asan) and 30 s of fuzzing
# of the case reader on every core (tools/ci-fuzz.sh, build-fuzz). FLUIDEM_QUICK=1 skips those two.
set -euo pipefail
cd "$(dirname "$0")"
tools/install-deps.sh
# The cores, not the OpenMP threads: GNU nproc honours OMP_NUM_THREADS (exported below), which
# made ctest and the sanitizer build run one job at a time (CI took 33 min instead of ~22).
cores=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)
export FLUIDEM_JOBS=${FLUIDEM_JOBS:-$cores}
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$FLUIDEM_JOBS"
# ctest runs nproc tests at once: each on one OpenMP thread unless it sets more itself (the
# thread-independence tests do), so that the cores are not oversubscribed (an OpenMP barrier then
# waits for a descheduled thread: a coupled test took 227 s beside another instead of 43 s alone).
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
ctest --test-dir build --output-on-failure -j"$FLUIDEM_JOBS" -L "unit|regression" "$@"
if [ "${FLUIDEM_QUICK:-0}" != 1 ]; then
  tools/ci-sanitizers.sh
  tools/ci-fuzz.sh
fi
