#!/usr/bin/env bash
# Install what is missing, build fluidem with its tests, run the tests (labels unit, regression).
set -euo pipefail
cd "$(dirname "$0")"
tools/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)" -L "unit|regression" "$@"
