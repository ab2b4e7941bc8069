#!/usr/bin/env bash
# The cost of the non-contact forces (docs/noncontact.md) on the settled bed10k of
# ../shared/bench/dem (10000 spheres of 4 mm, Hertz with history, dt = 1e-5 s): the same run
# without them and with each of van der Waals, electrostatics and liquid bridges, then all three;
# one thread pinned to core 0. Prints the rate, the time in the contact loop and the time in the
# non-contact forces per particle-step (fluidem's own timing, its "time in ..." line).
# The step is forced at 1e-5 s (van der Waals at h0 = 0.4 nm would ask for a shorter one): the
# work per step is what is measured.
#
# usage: bench/noncontact.sh            env: STEPS (default 500), WORK, FLUIDEM, DEM
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
STEPS=${STEPS:-500}
WORK=${WORK:-${TMPDIR:-/tmp}/fluidem-noncontact}
# shellcheck source=bench/bench_lib.sh
source "$ROOT/bench/bench_lib.sh"
ensure_fluidem
mkdir -p "$WORK"
data=$(bed_data 10k "$WORK")
end=$(awk -v s="$STEPS" 'BEGIN { printf "%.10g", s * 1e-5 }')
vdw=(--set van_der_waals.hamaker=1e-19 --set van_der_waals.min_separation=4e-10
  --set van_der_waals.range=4e-4 --set van_der_waals.wall_hamaker=1e-19)
charge=(--set "insert[0].charge=1e-11" --set electrostatics.cutoff=0.012)
bridge=(--set "species[0].liquid_fraction=1e-3" --set liquid_bridge.surface_tension=0.0728
  --set liquid_bridge.viscosity=1e-3 --set liquid_bridge.min_gap=1e-6)

echo "bed10k, $STEPS steps, 1 thread, $(git -C "$ROOT" rev-parse --short HEAD), $STAMP"
printf "%-16s %12s %14s %16s\n" forces "M p-steps/s" "contacts us/ps" "non-contact us/ps"
run() {
  local name=$1
  shift
  local log=$WORK/$name.log
  run_fluidem "$log" 1 "$ROOT/bench/cases/bed10k.toml" --set "insert[0].file=$data" \
    --set "simulation.end_time=$end" --set "output.frame_interval=$end" \
    --set simulation.force_time_step=true "$@" --out "$WORK/$name" >/dev/null
  awk -v name="$name" -v n=10000 -v steps="$STEPS" '
    /^done:/ { rate = $(NF - 1) }
    /^time in contacts/ {
      c = $4; nc = 0
      for (k = 1; k <= NF; k++) if ($k == "non-contact") nc = $(k + 2)
    }
    END { ps = n * steps; printf "%-16s %12.3f %14.3f %16.3f\n", name, rate / 1e6, c / ps * 1e6, nc / ps * 1e6 }
  ' "$log"
}
run none
run van_der_waals "${vdw[@]}"
run electrostatics "${charge[@]}"
run liquid_bridge "${bridge[@]}"
run all "${vdw[@]}" "${charge[@]}" "${bridge[@]}"
