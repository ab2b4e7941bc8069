#!/usr/bin/env bash
# OpenFOAM DPMFoam against fluidem on the Tsuji/Hoomans bed, in one go, same machine, same core:
#  - DPMFoam (Debian package `openfoam`, v1912) on ../shared/bench/dpmfoam-tsuji (copied to
#    $WORK/dpmfoam first): settling 0 .. 0.24 s without gas (not timed), then fluidisation at
#    2.6 m/s superficial for SIM simulated seconds (timed: the ClockTime of the solver's log
#    between its first and its last flow step, so start-up and case reading are excluded);
#  - fluidem on the like-for-like of bench/tsuji.sh soft_3d (3-D box 4 x 150 x 500 mm, one gas
#    cell deep, 15 x 25 cells, uniform 2.6 m/s, Hertz E = 1e7 Pa, e = 0.9, mu = 0.3, DT = 1e-4 s)
#    from the settled packing cases/hoomans96/tsuji_bed.data for SIM simulated seconds (timed:
#    the `done:` line of `fluidem run`, set-up excluded), one thread, twice: at fluidem's
#    automatic particle step (1/50 of the contact duration) and at DEM_DT (default 2e-5 s, the
#    sub-step DPMFoam takes on this case).
# Two ways to share the machine (ALONGSIDE):
#  - 1 (the default with two cores): fluidem runs again and again on core 0 while DPMFoam's timed
#    run goes on on core 1, the two fluidem runs (auto, matched) in turn; only the fluidem runs
#    that end before DPMFoam does count, and each time step's figure is the median of its runs
#    (min and max printed). Both codes see the same state of the host (this machine's speed
#    drifts by 15-30% within minutes: bench/RESULTS.md) with the other core busy, as the peers'
#    reference figures in ../shared/bench/README.md were measured.
#  - 0: one after the other, each pinned to core 1 (the other core idle): DPMFoam, then fluidem
#    once per time step (the figures of the sessions before 2026-12-03 22:00 UTC).
# Prints the wall seconds per simulated second of both, their ratio, and the mean pressure drop
# over the interval relative to the bed weight per area W/A (a check that both beds are
# fluidised; over a short interval the start-up transient dominates it).
#
# usage: bench/compare_dpmfoam.sh
# env:   SIM      simulated seconds of fluidisation timed (default 0.05)
#        FLUIDEM  binary (default build/fluidem)
#        CASE     the DPMFoam case (default /work/shared/bench/dpmfoam-tsuji)
#        WORK     work folder (default ${TMPDIR:-/tmp}/fluidem-compare-dpmfoam)
#        DEM_DT   fluidem's particle step for the matched run (default 2e-5 s)
#        REUSE_SETTLED=1  keep a settled DPMFoam case already in $WORK (skips the settling)
#        ALONGSIDE  1: fluidem repeated beside DPMFoam's run (default with two cores); 0: after it
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
FLUIDEM=${FLUIDEM:-$ROOT/build/fluidem}
SIM=${SIM:-0.05}
CASE=${CASE:-/work/shared/bench/dpmfoam-tsuji}
WORK=${WORK:-${TMPDIR:-/tmp}/fluidem-compare-dpmfoam}
PY=/usr/bin/python3
export WM_PROJECT_DIR=/usr/share/openfoam FOAM_ETC=/usr/share/openfoam/etc
[[ -x $FLUIDEM ]] || { echo "compare_dpmfoam.sh: no $FLUIDEM" >&2; exit 1; }
command -v DPMFoam >/dev/null || { echo "compare_dpmfoam.sh: no DPMFoam (apt-get install openfoam)" >&2; exit 1; }
[[ -d $CASE ]] || { echo "compare_dpmfoam.sh: no case $CASE" >&2; exit 1; }
pin=() fl_pin=()
two_cores=0
if command -v taskset >/dev/null && [[ $(nproc) -ge 2 ]]; then two_cores=1; fi
ALONGSIDE=${ALONGSIDE:-$two_cores}
[[ $ALONGSIDE == 0 || $ALONGSIDE == 1 ]] || { echo "compare_dpmfoam.sh: ALONGSIDE must be 0 or 1" >&2; exit 2; }
if [[ $ALONGSIDE == 1 && $two_cores == 0 ]]; then
  echo "compare_dpmfoam.sh: ALONGSIDE=1 needs two cores and taskset" >&2
  exit 2
fi
if [[ $two_cores == 1 ]]; then pin=(taskset -c 1) fl_pin=(taskset -c 1); fi
[[ $ALONGSIDE == 1 ]] && fl_pin=(taskset -c 0)
mkdir -p "$WORK"
D=$WORK/dpmfoam
T0=0.24 # end of the settling phase (a write time of the case)
T1=$(awk -v a=$T0 -v b="$SIM" 'BEGIN { printf "%.6g", a + b }')

echo "== $(date -u '+%F %T') UTC, $(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "== fluidem $(cd "$ROOT" && git rev-parse --short HEAD 2>/dev/null || echo '?'), DPMFoam: $(dpkg-query -W -f='${Version}' openfoam 2>/dev/null || echo '?')"

# --- DPMFoam: settle (not timed) ---
if [[ ${REUSE_SETTLED:-0} == 1 && -d $D/$T0 ]]; then
  echo "== DPMFoam: reusing the settled case in $D"
  rm -rf "$D/postProcessing"
  for t in "$D"/[0-9]*; do # the time folders written after the settling
    if awk -v t="$(basename "$t")" -v t0=$T0 'BEGIN { exit !(t + 0 > t0 + 0) }'; then rm -rf "$t"; fi
  done
  cp "$D/settled.U.air" "$D/$T0/U.air"
else
  rm -rf "$D"
  cp -r "$CASE" "$D"
  chmod -R u+w "$D"
  (cd "$D" && $PY mkPositions.py >/dev/null && blockMesh >log.blockMesh 2>&1)
  sed -i "s/^endTime .*/endTime         $T0;/" "$D/system/controlDict"
  echo "== DPMFoam: settling 0 .. $T0 s (not timed) ..."
  (cd "$D" && "${pin[@]}" DPMFoam >log.settle 2>&1)
  cp "$D/$T0/U.air" "$D/settled.U.air"
fi

# --- DPMFoam: fluidise, timed ---
sed -i 's/inletVelocity   uniform (0 0 0)/inletVelocity   uniform (0 0 2.6)/' "$D/$T0/U.air"
sed -i "s/^endTime .*/endTime         $T1;/" "$D/system/controlDict"
# --- fluidem: the soft_3d like-for-like, timed, at two particle time steps ---
# "auto": fluidem's default, 1/50 of the Hertz contact duration (6.7e-6 s, 15 sub-steps per flow
# step); DEM_DT (default 2e-5 s, 5 sub-steps): the resolution DPMFoam itself uses on this case
# (collisionResolutionSteps 12: its particle sub-step was 1.4-2.5e-5 s, ../shared/bench/README.md).
C=$ROOT/cases/hoomans96
DEM_DT=${DEM_DT:-2e-5}
fluidem_run() { # TAG DT: wall seconds and mean pressure drop into fl_wall[TAG], fl_dp[TAG]
  local tag=$1 dt=$2
  [[ $ALONGSIDE == 1 ]] ||
    echo "== fluidem ($tag, particle dt $dt): 0 .. $SIM s of fluidisation from the settled packing ..."
  "${fl_pin[@]}" "$FLUIDEM" run "$C/tsuji_setup_soft.toml" --set simulation.dimension=3 \
    --set gas.boundary.bottom.velocity=2.6 --set simulation.end_time="$SIM" \
    --set simulation.time_step="$dt" --set output.frame_interval=0.1 --threads 1 \
    --out "$WORK/fluidem_$tag" --force >"$WORK/fluidem_$tag.log" 2>&1
  fl_wall[$tag]=$(sed -n 's/^done: .* in \([0-9.]*\) s wall.*/\1/p' "$WORK/fluidem_$tag.log")
  fl_dp[$tag]=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "pressure_drop") c = i; next }
    c && $1 > 0 { s += $c; n++ } END { printf "%.1f", n ? s / n : 0 }' "$WORK/fluidem_$tag/series.csv")
}
declare -A fl_wall=() fl_dp=() fl_runs=() fl_min=() fl_max=()
echo "== DPMFoam: fluidising $T0 .. $T1 s ..."
if [[ $ALONGSIDE == 1 ]]; then
  (cd "$D" && "${pin[@]}" DPMFoam >log.fluidise 2>&1) &
  dpm_pid=$!
  trap 'kill $dpm_pid 2>/dev/null || true' EXIT
  echo "== fluidem beside it on core 0, 0 .. $SIM s from the settled packing, auto and $DEM_DT in turn ..."
  declare -A walls=()
  while kill -0 "$dpm_pid" 2>/dev/null; do
    for tag in matched auto; do
      fluidem_run "$tag" "$([[ $tag == auto ]] && echo auto || echo "$DEM_DT")"
      kill -0 "$dpm_pid" 2>/dev/null || break 2 # ended after DPMFoam: not counted
      walls[$tag]+="${fl_wall[$tag]} "
      fl_runs[$tag]=$((${fl_runs[$tag]:-0} + 1))
    done
  done
  wait "$dpm_pid"
  trap - EXIT
  for tag in auto matched; do
    [[ -n ${walls[$tag]:-} ]] || { echo "compare_dpmfoam.sh: no fluidem $tag run ended before DPMFoam (raise SIM)" >&2; exit 1; }
    read -r fl_wall[$tag] fl_min[$tag] fl_max[$tag] < <(echo "${walls[$tag]}" | tr ' ' '\n' | sed '/^$/d' | sort -g |
      awk '{ v[NR] = $1 } END { printf "%s %s %s\n", NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2, v[1], v[NR] }')
  done
else
  (cd "$D" && "${pin[@]}" DPMFoam >log.fluidise 2>&1)
fi
read -r dpm_steps dpm_sim dpm_wall < <(awk '
  /^Time = / { t = $3; n++ }
  /ClockTime = / { c = $(NF - 1); if (n == 1) { t0 = t; c0 = c } t1 = t; c1 = c }
  END { printf "%d %.6g %.6g\n", n, t1 - t0, c1 - c0 }' "$D/log.fluidise")
# Pressure drop: rho_g (p_bottom - p_top) (kinematic p in DPMFoam), mean over the interval.
dpm_dp=$($PY - "$D" "$T0" <<'PYEOF'
import glob, sys
d, t0 = sys.argv[1], float(sys.argv[2])
def read(name):
    out = {}
    for f in glob.glob(d + "/postProcessing/%s/*/surfaceFieldValue.dat" % name):
        for line in open(f):
            if line.startswith("#") or not line.strip(): continue
            t, v = line.split()[:2]
            out[round(float(t), 7)] = float(v)
    return out
pb, pt = read("pBottom"), read("pTop")
v = [1.2 * (pb[t] - pt[t]) for t in sorted(set(pb) & set(pt)) if t > t0]
print("%.1f" % (sum(v) / len(v)) if v else "nan")
PYEOF
)

if [[ $ALONGSIDE == 0 ]]; then
  fluidem_run auto auto
  fluidem_run matched "$DEM_DT"
fi

# Bed weight per area: 2400 spheres of 4 mm, 2700 kg/m3, over 0.15 m x 4 mm.
WA=$(awk 'BEGIN { printf "%.1f", 2400 * 2700 * 3.14159265358979 / 6 * 0.004^3 * 9.81 / (0.15 * 0.004) }')
echo
printf "%-22s %10s %10s %14s %12s %9s %9s\n" code "sim s" "wall s" "wall s/sim s" "mean dp Pa" "dp/(W/A)" "ratio"
awk -v s="$dpm_sim" -v w="$dpm_wall" -v dp="$dpm_dp" -v wa="$WA" 'BEGIN {
  printf "%-22s %10.4f %10.1f %14.1f %12.1f %9.3f %9s\n", "DPMFoam", s, w, w / s, dp, dp / wa, "1" }'
for tag in auto matched; do
  label="fluidem dt=auto"
  [[ $tag == matched ]] && label="fluidem dt=$DEM_DT"
  awk -v l="$label" -v s="$SIM" -v w="${fl_wall[$tag]}" -v dp="${fl_dp[$tag]}" -v wa="$WA" \
    -v a="$dpm_wall" -v as="$dpm_sim" 'BEGIN {
    printf "%-22s %10.4f %10.1f %14.1f %12.1f %9.3f %8.1fx\n", l, s, w, w / s, dp, dp / wa, (a / as) / (w / s) }'
done
echo "ratio: DPMFoam's wall per simulated second over fluidem's"
if [[ $ALONGSIDE == 1 ]]; then
  for tag in auto matched; do
    awk -v t="$tag" -v n="${fl_runs[$tag]}" -v s="$SIM" -v lo="${fl_min[$tag]}" -v hi="${fl_max[$tag]}" \
      -v a="$dpm_wall" -v as="$dpm_sim" 'BEGIN {
      printf "fluidem %s: median of %d runs beside DPMFoam; wall %.3f .. %.3f s (ratio %.1fx .. %.1fx)\n",
        t, n, lo, hi, (a / as) / (hi / s), (a / as) / (lo / s) }'
  done
fi
echo "(DPMFoam: $dpm_steps flow steps timed; logs in $WORK)"
