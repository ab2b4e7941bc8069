#!/usr/bin/env bash
# Side-by-side whole-run benchmark of the soft-sphere DEM: fluidem, LAMMPS (GRANULAR,
# gran/hertz/history) and LIGGGHTS (hertz with tangential history) on the identical settled beds of
# ../shared/bench/dem (10^4 and 10^5 spheres of 4 mm, 2700 kg/m3, box 0.15 x (0.01 or 0.10) x 0.6 m
# with frictional walls, Hertz E = 1e7 Pa, nu = 0.25, e = 0.9, mu = 0.3, dt = 1e-5 s, skin 1 mm,
# gravity -z), in one go, so that the ratios are taken minutes apart on the same machine.
# The peers install from Debian when missing (apt-get install -y lammps liggghts).
#
# fluidem runs with 1 thread (pinned to core 0) and with 2 threads (cores 0-1); the peers with one
# core (pinned to core 0). fluidem's rate is its own "particle-steps/s" (the whole time loop from
# the settled bed, output included; set-up and the first neighbour build excluded); the peers'
# is atoms x steps / "Loop time" of the timed run after NWARM warm-up steps. Peak RSS from
# /usr/bin/time -v; fluidem also reports its own count of bytes per particle (particle store,
# neighbour list with contact history, contact scratch arrays).
#
# usage: bench/compare_dem.sh [SIZE ...]     SIZE: 10k, 100k (default: both)
# env:   FLUIDEM  fluidem binary (default: build/fluidem; built in Release if missing)
#        WORK     work folder (default: ${TMPDIR:-/tmp}/fluidem-compare-dem): beds, logs, results.csv
#        DEM      the peer benchmark folder (default: ../shared/bench/dem next to the repository)
#        THREADS  fluidem thread counts (default: "1 2")
#        PEERS    which peers (default: "lammps liggghts"; empty: fluidem only)
#        NWARM    peer warm-up steps before the timed run (default: 100)
#        CORE1    1 (default with two or more cores and taskset): each round also runs fluidem on one
#                 thread pinned to core 1, and two threads are compared with the one-thread run on
#                 either core, the faster one and their mean. This VM's host at times runs one core
#                 25-35% slower than the other, for minutes, and which one changes (bench/RESULTS.md);
#                 against the slow core two threads look better than they are, against the fast
#                 one worse than the machine allows. 0: core 0 only.
#        REPEAT   rounds per size (default: 1): each round runs fluidem and the peers once, one
#                 after the other; the table gives each code's median rate and the median of the
#                 rounds' own ratios (with their range), taken on a machine whose speed drifts
#                 (a shared VM: +-15% within minutes) from runs seconds apart
# The step counts are the cases' own (bench/cases/bed10k.toml: 2000, bed100k.toml: 500); the
# peers run the same number of timed steps.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
WORK=${WORK:-${TMPDIR:-/tmp}/fluidem-compare-dem}
read -r -a THREADS <<<"${THREADS:-1 2}"
read -r -a PEERS <<<"${PEERS-lammps liggghts}"
NWARM=${NWARM:-100}
REPEAT=${REPEAT:-1}
CORE1=${CORE1:-1}
[ "$(nproc)" -ge 2 ] && command -v taskset >/dev/null 2>&1 || CORE1=0
SIZES=("$@")
[ ${#SIZES[@]} -gt 0 ] || SIZES=(10k 100k)
# shellcheck source=bench/bench_lib.sh
source "$ROOT/bench/bench_lib.sh"
[ -d "$DEM" ] || die "no peer benchmark folder $DEM (set DEM=...)"
mkdir -p "$WORK"
ensure_fluidem

declare -A PEER_BIN
for pr in "${PEERS[@]}"; do
  case $pr in
  lammps) PEER_BIN[$pr]=$(peer lmp lammps) ;;
  liggghts) PEER_BIN[$pr]=$(peer liggghts liggghts) ;;
  *) die "unknown peer $pr (lammps, liggghts)" ;;
  esac
  [ -n "${PEER_BIN[$pr]}" ] || echo "$pr is not available: left out" >&2
done

CSV=$WORK/results.csv
[ -f "$CSV" ] || echo "date,commit,code,threads,N,steps,seconds,particle_steps_per_s,peak_rss_mb,bytes_per_particle" >"$CSV"
ROWS=() TWO_OVER_ONE=()

# peer_run NAME N STEPS DATA: one peer run on core 0; prints "rate rss".
peer_run() {
  local name=$1 n=$2 steps=$3 data=$4 log=$WORK/${1}_$2.log
  local exe=() model
  case $name in
  lammps) exe=("${PEER_BIN[lammps]}" -in "$DEM/in.bench.lmp") model=hertzhist ;;
  liggghts) exe=("${PEER_BIN[liggghts]}" -in "$DEM/in.bench.lig") model=hertz ;;
  esac
  (
    cd "$WORK"
    cp -f "$DEM"/model_*.lig .
    /usr/bin/time -v "${PIN1[@]}" "${exe[@]}" -var model "$model" -var data "$data" \
      -var nsteps "$steps" -var nwarm "$NWARM" -log "$log" >"$log.out" 2>"$log.time"
  ) || { tail -20 "$log.out" >&2; die "$name failed on bed$n (log $log)"; }
  local lt secs atoms
  lt=$(grep 'Loop time of' "$log" | tail -1)
  secs=$(echo "$lt" | awk '{print $4}')
  atoms=$(echo "$lt" | awk '{for (i = 1; i <= NF; i++) if ($i == "with") print $(i + 1)}')
  echo "$(awk -v a="$atoms" -v s="$steps" -v t="$secs" 'BEGIN {printf "%.4g", a * s / t}') $(rss_mb "$log.time") $secs"
}

# median of the numbers given; "median (min-max)" with more than one; "-" with none (no
# reference run for a ratio)
stats() {
  [ $# -gt 0 ] || { echo -; return; }
  printf '%s\n' "$@" | sort -g | awk '{v[NR] = $1} END {
    m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
    if (NR == 1) printf "%.4g", m; else printf "%.4g (%.4g-%.4g)", m, v[1], v[NR]}'
}

for n in "${SIZES[@]}"; do
  case_file=$ROOT/bench/cases/bed$n.toml
  [ -f "$case_file" ] || die "no case $case_file"
  data=$(bed_data "$n" "$WORK")
  declare -A RATES=() RATIOS=() RSS=() BPP=()
  keys=()
  for t in "${THREADS[@]}"; do keys+=("fluidem_$t"); done
  for pr in "${PEERS[@]}"; do [ -n "${PEER_BIN[$pr]}" ] && keys+=("$pr"); done
  for ((round = 1; round <= REPEAT; round++)); do
    declare -A RATE=()
    for t in "${THREADS[@]}"; do
      echo "== fluidem, bed$n, $t thread(s) (round $round of $REPEAT)" >&2
      read -r np steps secs rate bpp rss < <(run_fluidem "$WORK/fluidem_${n}_t$t.log" "$t" "$case_file" \
        --set "insert[0].file=$data" --out "$WORK/fluidem_${n}_t$t")
      grep -E '^(time in|memory)' "$WORK/fluidem_${n}_t$t.log" >&2
      echo "$STAMP,$COMMIT,fluidem,$t,$np,$steps,$secs,$rate,$rss,$bpp" >>"$CSV"
      RATE[fluidem_$t]=$rate RSS[fluidem_$t]=$rss BPP[fluidem_$t]=$bpp
    done
    if [ "$CORE1" = 1 ] && [ -n "${RATE[fluidem_1]:-}" ] && [ -n "${RATE[fluidem_2]:-}" ]; then
      echo "== fluidem, bed$n, 1 thread on core 1 (round $round of $REPEAT)" >&2
      pin0=("${PIN1[@]}")
      PIN1=(taskset -c 1)
      read -r _ _ _ rate _ _ < <(run_fluidem "$WORK/fluidem_${n}_t1_core1.log" 1 "$case_file" \
        --set "insert[0].file=$data" --out "$WORK/fluidem_${n}_t1_core1")
      PIN1=("${pin0[@]}")
      echo "$STAMP,$COMMIT,fluidem_core1,1,$np,$steps,,$rate,," >>"$CSV"
      RATE[fluidem_core1]=$rate
    fi
    for pr in "${PEERS[@]}"; do
      [ -n "${PEER_BIN[$pr]}" ] || continue
      echo "== $pr, bed$n, 1 core, $NWARM warm-up + $steps timed steps (round $round of $REPEAT)" >&2
      read -r rate rss secs < <(peer_run "$pr" "$n" "$steps" "$data")
      echo "$STAMP,$COMMIT,$pr,1,$np,$steps,$secs,$rate,$rss," >>"$CSV"
      RATE[$pr]=$rate RSS[$pr]=$rss BPP[$pr]=-
    done
    # This round's ratios against LAMMPS (or, without it, the one-thread fluidem run).
    ref=${RATE[lammps]:-${RATE[fluidem_1]:-}}
    for key in "${keys[@]}"; do
      RATES[$key]+=" ${RATE[$key]}"
      [ -n "$ref" ] && RATIOS[$key]+=" $(awk -v a="${RATE[$key]}" -v b="$ref" 'BEGIN {printf "%.4f", a / b}')"
    done
    if [ -n "${RATE[fluidem_1]:-}" ] && [ -n "${RATE[fluidem_2]:-}" ]; then
      RATIOS[two_over_one]+=" $(awk -v a="${RATE[fluidem_2]}" -v b="${RATE[fluidem_1]}" 'BEGIN {printf "%.4f", a / b}')"
    fi
    if [ -n "${RATE[fluidem_core1]:-}" ]; then
      read -r r1 rf rm < <(awk -v a="${RATE[fluidem_2]}" -v c0="${RATE[fluidem_1]}" -v c1="${RATE[fluidem_core1]}" \
        'BEGIN {printf "%.4f %.4f %.4f\n", a / c1, a / (c0 > c1 ? c0 : c1), 2 * a / (c0 + c1)}')
      RATIOS[two_over_core1]+=" $r1" RATIOS[two_over_faster]+=" $rf" RATIOS[two_over_mean]+=" $rm"
      RATIOS[core1_over_core0]+=" $(awk -v a="${RATE[fluidem_core1]}" -v b="${RATE[fluidem_1]}" 'BEGIN {printf "%.4f", a / b}')"
    fi
    unset RATE
  done
  for key in "${keys[@]}"; do
    code=${key%%_*}
    t=1
    [[ $key == fluidem_* ]] && t=${key#fluidem_}
    # shellcheck disable=SC2086
    ROWS+=("| $n | $code | $t | $(stats ${RATES[$key]}) | $(stats ${RATIOS[$key]:-}) | ${RSS[$key]} | ${BPP[$key]} |")
  done
  # shellcheck disable=SC2086
  if [ -n "${RATIOS[two_over_one]:-}" ]; then
    line="bed$n: fluidem 2 threads / 1 thread on core 0 = $(stats ${RATIOS[two_over_one]})"
    [ -n "${RATIOS[two_over_core1]:-}" ] && line+="; on core 1 = $(stats ${RATIOS[two_over_core1]}); on the faster core = $(stats ${RATIOS[two_over_faster]}); on their mean = $(stats ${RATIOS[two_over_mean]}) (core 1 / core 0 one-thread speed $(stats ${RATIOS[core1_over_core0]}))"
    echo "$line" >&2
    TWO_OVER_ONE+=("$line")
  fi
  unset RATES RATIOS RSS BPP
done

echo
echo "commit $COMMIT, $STAMP, $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "rounds per size: $REPEAT (with more than one: median (min-max) over the rounds; ratios per round)"
echo "| N | code | threads | particle-steps/s | ratio to LAMMPS (1 core) | peak RSS MB | bytes/particle (own count) |"
echo "|---|---|---|---|---|---|---|"
printf '%s\n' "${ROWS[@]}"
[ ${#TWO_OVER_ONE[@]} -eq 0 ] || printf '%s\n' "${TWO_OVER_ONE[@]}"
echo "(all rows appended to $CSV)"
