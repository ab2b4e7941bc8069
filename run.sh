#!/usr/bin/env bash
# Install what is missing, build fluidem in Release, run the demo case and draw its picture.
set -euo pipefail
cd "$(dirname "$0")"
tools/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DFLUIDEM_BUILD_TESTS=OFF -DFLUIDEM_BUILD_BENCH=OFF >/dev/null
cmake --build build -j"$(nproc)" --target fluidem
# Demo: a bubble at a single orifice [Hoomans96 §5.3.1], 2400 hard spheres, jet of 10 u_mf.
out=out/bubble_orifice
./build/fluidem run cases/hoomans96/bubble_orifice.toml --out "$out" "$@"
/usr/bin/python3 python/fluidem_plot.py "$out" --out "$out/snapshot.png"
echo
echo "results:  $out/particles.h5 and $out/fields.h5 (open $out/particles.xmf and"
echo "          $out/fields.xmf in ParaView), $out/series.csv, $out/probes.csv"
echo "picture:  $out/snapshot.png"
