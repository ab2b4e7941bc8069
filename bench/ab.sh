#!/usr/bin/env bash
# A/B comparison of two fluidem binaries on a settled benchmark bed (../shared/bench/dem), in
# alternated short runs: A, B, A, B, ... each pinned to core 0 (two threads: cores 0-1). On a
# shared machine whose speed drifts by +-15% within minutes (bench/RESULTS.md, 2026-12-03), only
# runs seconds apart compare: the verdict is the median of the pairs' own ratios B/A and the
# number of pairs in which B was faster; the single rates are printed for the record.
# With 8 pairs of bed100k or 12-16 of bed10k the paired median resolved about +-3-4% here:
# a change smaller than that needs more pairs or a quieter machine.
#
# usage: bench/ab.sh BINARY_A BINARY_B [PAIRS]     PAIRS: default 12
# env:   SIZE     10k or 100k (default: 10k)
#        STEPS    time steps per run (default: 500 for 10k, 200 for 100k; dt = 1e-5 s)
#        THREADS  fluidem threads (default: 1)
#        WORK     work folder (default: ${TMPDIR:-/tmp}/fluidem-ab): the bed and the runs' output
#        DEM      the peer benchmark folder (default: ../shared/bench/dem next to the repository)
# The runs' results are not compared: check bitwise identity (series.csv, particles.h5) apart.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
[ $# -ge 2 ] || { sed -n '2,17p' "$0" >&2; exit 2; }
A=$1 B=$2 PAIRS=${3:-12}
SIZE=${SIZE:-10k}
THREADS=${THREADS:-1}
WORK=${WORK:-${TMPDIR:-/tmp}/fluidem-ab}
case $SIZE in
10k) STEPS=${STEPS:-500} ;;
100k) STEPS=${STEPS:-200} ;;
*) echo "ab.sh: SIZE must be 10k or 100k" >&2; exit 2 ;;
esac
[[ $PAIRS =~ ^[1-9][0-9]*$ ]] || { echo "ab.sh: PAIRS must be a positive integer" >&2; exit 2; }
for bin in "$A" "$B"; do
  [ -x "$bin" ] || { echo "ab.sh: $bin is not an executable" >&2; exit 2; }
done
# shellcheck source=bench/bench_lib.sh
source "$ROOT/bench/bench_lib.sh"
mkdir -p "$WORK"
data=$(bed_data "$SIZE" "$WORK")
end=$(awk -v s="$STEPS" 'BEGIN { printf "%.10g", s * 1e-5 }')

# rate BINARY TAG: particle-steps per second of one run (bench_lib.sh's run_fluidem: pinned, its
# own "done:" line)
rate() {
  local r
  # (run_fluidem prints: particles, steps, seconds, rate, bytes per particle, peak RSS)
  read -r _ _ _ r _ _ < <(FLUIDEM=$1 run_fluidem "$WORK/run_$2.log" "$THREADS" \
    "$ROOT/bench/cases/bed$SIZE.toml" --set "insert[0].file=$data" \
    --set "simulation.end_time=$end" --set "output.frame_interval=$end" --out "$WORK/run_$2")
  echo "$r"
}

echo "A: $A"
echo "B: $B"
echo "bed$SIZE, $STEPS steps, $THREADS thread(s), $PAIRS alternated pairs, $STAMP"
for ((k = 1; k <= PAIRS; k++)); do
  ra=$(rate "$A" a) rb=$(rate "$B" b)
  echo "pair $k: A $ra B $rb"
done | tee "$WORK/pairs.txt"
/usr/bin/python3 - "$WORK/pairs.txt" <<'EOF'
import statistics as st
import sys

a, b = [], []
for line in open(sys.argv[1]):
    f = line.split()
    a.append(float(f[3]) / 1e6)
    b.append(float(f[5]) / 1e6)
ratios = [y / x for x, y in zip(a, b)]
for name, v in (("A", a), ("B", b)):
    print(f"{name}: median {st.median(v):.3f} M particle-steps/s (min {min(v):.3f}, max {max(v):.3f})")
wins = sum(r > 1 for r in ratios)
print(f"B/A paired: median {st.median(ratios):.4f}, mean {st.mean(ratios):.4f}, "
      f"B faster in {wins} of {len(ratios)} pairs")
EOF
