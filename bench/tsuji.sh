#!/usr/bin/env bash
# Whole-run benchmark of the coupled DPM on the Tsuji bed [Hoomans96 Table 2]: 2400 spheres of
# 4 mm, 15 x 25 gas cells, DT = 1e-4 s, started from the settled packing
# cases/hoomans96/tsuji_bed.data, one thread (pinned to core 1 when taskset is there, like the
# peers in ../shared/bench). Reported: wall seconds per simulated second (the "done:" line of
# `fluidem run`, set-up excluded) and the split gas+coupling / particles.
#
#  hard_2d   cases/hoomans96/tsuji_setup.toml as shipped (hard spheres, 2-D, orifice 2.6 m/s
#            over 1.8 m/s background), END s.
#  soft_2d   cases/hoomans96/tsuji_setup_soft.toml as shipped (Hertz-Mindlin, E = 1e7 Pa).
#  soft_3d   the like-for-like of ../shared/bench/dpmfoam-tsuji (OpenFOAM DPMFoam: 3-D box
#            4 x 150 x 500 mm, one cell deep, uniform 2.6 m/s superficial, Hertz E = 1e7 Pa,
#            e = 0.9, mu = 0.3): tsuji_setup_soft.toml with simulation.dimension = 3 and a
#            uniform 2.6 m/s inflow. DPMFoam measured 1036 s of wall time per simulated second
#            on this machine (../shared/bench/README.md); the ratio is printed.
#  hard_3d   the same 3-D bed with the hard-sphere engine.
#
# usage: bench/tsuji.sh [PART ...]   PART: hard_2d soft_2d soft_3d hard_3d (default: all)
# env:   FLUIDEM  binary (default build/fluidem)   END  simulated seconds (default 1.0)
#        WORK     folder for the outputs (default ${TMPDIR:-/tmp}/fluidem-bench-tsuji)
#        DEM_DT   particle time step of the soft parts (default: the case's, auto = 1/50 of
#                 the contact duration; 2e-5 is DPMFoam's own sub-step on this bed)
#        THREADS  OpenMP threads (default 1, pinned to core 1; 2: both cores, not pinned)
# Also printed: the mean pressure drop over 0.2 s .. END relative to the bed weight per area
# W/A = 3550 Pa (a check that the physics did not change with a speed-up).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
FLUIDEM=${FLUIDEM:-$ROOT/build/fluidem}
END=${END:-1.0}
WORK=${WORK:-${TMPDIR:-/tmp}/fluidem-bench-tsuji}
DPMFOAM_S_PER_S=1036
[[ -x $FLUIDEM ]] || { echo "tsuji.sh: no $FLUIDEM (build it: cmake --build build --target fluidem)" >&2; exit 1; }
mkdir -p "$WORK"
THREADS=${THREADS:-1}
pin=()
if [[ $THREADS == 1 ]] && command -v taskset >/dev/null && [[ $(nproc) -ge 2 ]]; then pin=(taskset -c 1); fi
parts=("$@")
[[ ${#parts[@]} -gt 0 ]] || parts=(hard_2d soft_2d soft_3d hard_3d)
C=$ROOT/cases/hoomans96
printf "%-8s %10s %12s %12s %14s %8s %9s\n" case "sim s" "wall s" "wall/sim" "vs DPMFoam" "gas+cpl" "dp/(W/A)"
for part in "${parts[@]}"; do
  common=(--set simulation.end_time="$END" --set output.frame_interval=0.1 --threads "$THREADS" --force)
  case $part in
    hard_2d) args=("$C/tsuji_setup.toml") ;;
    soft_2d) args=("$C/tsuji_setup_soft.toml") ;;
    soft_3d) args=("$C/tsuji_setup_soft.toml" --set simulation.dimension=3 --set gas.boundary.bottom.velocity=2.6) ;;
    hard_3d) args=("$C/tsuji_setup.toml" --set simulation.dimension=3 --set gas.boundary.bottom.velocity=2.6) ;;
    *) echo "tsuji.sh: unknown part $part" >&2; exit 1 ;;
  esac
  if [[ -n ${DEM_DT:-} && $part == soft_* ]]; then args+=(--set simulation.time_step="$DEM_DT"); fi
  log=$WORK/$part.log
  "${pin[@]}" "$FLUIDEM" run "${args[@]}" "${common[@]}" --out "$WORK/$part" >"$log" 2>&1 || {
    echo "tsuji.sh: $part failed, see $log" >&2; tail -3 "$log" >&2; continue; }
  wall=$(sed -n 's/^done: .* in \([0-9.]*\) s wall.*/\1/p' "$log")
  gas=$(awk '/^time in / { for (i = 1; i < NF; i++) if ($i == "solver" || $i == "coupling") g += $(i + 1) }
    END { if (g != "") print g }' "$log")
  # Mean pressure drop over t >= 0.2 s (the whole run if it is shorter) / (W/A).
  dpw=$(awk -F, -v e="$END" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "pressure_drop") c = i; next }
    c && $1 > 0 && ($1 >= 0.2 || e <= 0.2) { s += $c; n++ } END { printf "%.3f", n ? s / n / 3550.4 : 0 }' \
    "$WORK/$part/series.csv")
  awk -v p="$part" -v e="$END" -v w="$wall" -v g="${gas:-0}" -v f="$DPMFOAM_S_PER_S" -v dp="$dpw" 'BEGIN {
    printf "%-8s %10.3f %12.1f %12.1f %13.1fx %7.0f%% %9s\n", p, e, w, w / e, f / (w / e), 100 * g / w, dp }'
done
