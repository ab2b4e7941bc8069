#!/usr/bin/env bash
# Whole-run benchmark of the event-driven hard-sphere engine: collisions processed per second of
# wall time, from the line fluidem prints at the end of `fluidem run`
#   "N collisions, X collisions per second of wall time"
# (the whole time loop: collisions, neighbour lists every DT, kicks, outputs; setup excluded).
# One thread (the engine is serial), pinned to core 0 when taskset is there.
#
#  (a) pouring: cases/hoomans96/pouring_hard.toml as it is (500 discs, 2-D, DT = 1e-4 s, 0.5 s);
#      if that file does not exist, cases/hoomans96/pouring_soft.toml with
#      --set simulation.engine=hard_sphere --set simulation.time_step=1e-4 and end_time 0.3 s.
#  (b) dense granular gas, bench/cases/hs_gas_{1k,10k,100k}.toml: N = 10^3, 10^4, 10^5 spheres
#      (10^3, 22^3, 46^3 on a simple cubic lattice at solid fraction 0.30, written here as LAMMPS
#      data files), e = 0.9, mu = 0, periodic, 0.02 s (~20 collisions per particle). Small
#      systems are repeated with other velocity seeds (1k: 100 runs, 10k: 10, 100k: 1) so that
#      every size processes ~10^6 collisions; the rate is sum(collisions) / sum(loop wall time).
#      Reported: wall time per collision against N, and its growth against log N (an event queue
#      costs O(log N) per event; everything else should be O(1)).
#  (c) flow-step sweep at N = 10^4: DT from 2.5e-5 to 8e-4 s (the neighbour lists are rebuilt
#      and every particle rescheduled once per DT, so the cost per collision depends on DT).
#  (d) bubble: the Tsuji bed with the bubble at an orifice, cases/hoomans96/bubble_orifice.toml
#      (2400 hard spheres coupled to the gas, ~3 million collisions per simulated second), for
#      BUBBLE_END s (default 1) on 1 and 2 threads (BUBBLE_THREADS); reported: wall time per
#      simulated second and its split from the run log's time lines: the engine ("time in the
#      collision engine", hard_->advance), the gas solver and coupling, and the rest (outputs,
#      setup of steps).
#      One thread is pinned to core 0; two threads are not pinned.
#
# usage: bench/hardsphere.sh [PART ...]     PART: pouring, gas, sweep, bubble (default: all four)
#        bench/hardsphere.sh --data N FILE  write the N^3 lattice of the gas cases to FILE
# env:   FLUIDEM  fluidem binary (default: build/fluidem; built in Release if missing)
#        WORK     work folder (default: ${TMPDIR:-/tmp}/fluidem-bench-hs): data, logs, results.csv
#        REPEATS  repeats of the 1k,10k,100k gas runs (default: "100 10 1")
#        THREADS  OpenMP threads of parts (a)-(c) (default 1, pinned to core 0; more: not pinned)
#        BUBBLE_END      simulated seconds of the bubble runs (default 1.0)
#        BUBBLE_THREADS  thread counts of the bubble runs (default "1 2")
#        COMMIT   label of the rows (default: the checkout's commit; set it when FLUIDEM is another
#                 build, e.g. a baseline)
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
WORK=${WORK:-${TMPDIR:-/tmp}/fluidem-bench-hs}
FLUIDEM=${FLUIDEM:-$ROOT/build/fluidem}
read -r -a REPEATS <<<"${REPEATS:-100 10 1}"

die() { echo "hardsphere.sh: $*" >&2; exit 1; }

# Lattice spacing of solid fraction 0.30 for d = 4 mm: d (pi / (6 * 0.3))^(1/3), m; the cases'
# boxes are n such spacings wide.
SPACING=0.00481599226276091
write_lattice() { # n file
  awk -v n="$1" -v a="$SPACING" 'BEGIN {
    printf "LAMMPS data file: %d^3 simple cubic lattice, spacing %.17g m (bench/hardsphere.sh)\n\n", n, a
    printf "%d atoms\n1 atom types\n\n", n * n * n
    printf "0 %.17g xlo xhi\n0 %.17g ylo yhi\n0 %.17g zlo zhi\n\nAtoms # sphere\n\n", n * a, n * a, n * a
    id = 0
    for (k = 0; k < n; k++) for (j = 0; j < n; j++) for (i = 0; i < n; i++)
      printf "%d 1 0.004 2700 %.17g %.17g %.17g\n", ++id, (i + 0.5) * a, (j + 0.5) * a, (k + 0.5) * a
  }' >"$2"
}
if [ "${1:-}" = "--data" ]; then
  [ $# -eq 3 ] || die "usage: bench/hardsphere.sh --data N FILE"
  write_lattice "$2" "$3"
  exit 0
fi

PARTS=("$@")
[ ${#PARTS[@]} -gt 0 ] || PARTS=(pouring gas sweep bubble)
want() { local p; for p in "${PARTS[@]}"; do [ "$p" = "$1" ] && return 0; done; return 1; }

mkdir -p "$WORK"
THREADS=${THREADS:-1}
PIN=()
if [ "$THREADS" = 1 ] && command -v taskset >/dev/null 2>&1; then PIN=(taskset -c 0); fi
if [ ! -x "$FLUIDEM" ]; then
  echo "building fluidem (Release) in $ROOT/build" >&2
  cmake -S "$ROOT" -B "$ROOT/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$ROOT/build" -j"$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)" --target fluidem >/dev/null
  FLUIDEM=$ROOT/build/fluidem
fi

CSV=$WORK/results.csv
[ -f "$CSV" ] || echo "date,commit,case,N,dt,runs,collisions,loop_seconds,collisions_per_s,ns_per_collision,bytes_per_particle" >"$CSV"
COMMIT=${COMMIT:-$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)}
STAMP=$(date -u +%Y-%m-%dT%H:%M:%SZ)

# run LOG ARGS...: one fluidem run; prints "collisions loop_seconds bytes_per_particle".
run() {
  local log=$1
  shift
  "${PIN[@]}" "$FLUIDEM" run "$@" --threads "$THREADS" --force >"$log" 2>&1 || { tail -5 "$log" >&2; die "fluidem failed (log $log)"; }
  local coll secs bpp
  coll=$(awk '/ collisions, .* collisions per second of wall time/ {print $1}' "$log")
  secs=$(awk '/^done:/ {print $5}' "$log")
  bpp=$(sed -nE 's/^memory ([0-9]+) bytes per particle.*/\1/p' "$log")
  if [ -z "$coll" ] || [ -z "$secs" ]; then die "no collision count in $log"; fi
  echo "$coll $secs $bpp"
}
# record CASE N DT RUNS COLLISIONS SECONDS BPP: appends to the CSV, prints "rate ns_per_collision".
record() {
  local rate ns
  rate=$(awk -v c="$5" -v s="$6" 'BEGIN {printf "%.4g", c / s}')
  ns=$(awk -v c="$5" -v s="$6" 'BEGIN {printf "%.4g", 1e9 * s / c}')
  echo "$STAMP,$COMMIT,$1,$2,$3,$4,$5,$6,$rate,$ns,$7" >>"$CSV"
  echo "$rate $ns"
}
fmt_rate() { awk -v r="$1" 'BEGIN {if (r >= 1e6) printf "%.2f M", r / 1e6; else printf "%.0f k", r / 1e3}'; }

OUT=()

# --- (d) the Tsuji bubble bed, coupled: wall time per simulated second and its split ---
BUBBLE_END=${BUBBLE_END:-1.0}
read -r -a BUBBLE_THREADS <<<"${BUBBLE_THREADS:-1 2}"
if want bubble; then
  BUBBLE=()
  for th in "${BUBBLE_THREADS[@]}"; do
    echo "== (d) bubble_orifice, $BUBBLE_END s, $th thread(s)" >&2
    log=$WORK/bubble_t$th.log
    pin=()
    [ "$th" = 1 ] && command -v taskset >/dev/null 2>&1 && pin=(taskset -c 0)
    "${pin[@]}" "$FLUIDEM" run "$ROOT/cases/hoomans96/bubble_orifice.toml" --out "$WORK/bubble_t$th" \
      --force --threads "$th" --set "simulation.end_time=$BUBBLE_END" >"$log" 2>&1 ||
      { tail -5 "$log" >&2; die "fluidem failed (log $log)"; }
    read -r wall engine gas coll < <(awk '
      /^done:/ {w = $5}
      /^time in the collision engine/ {e = $6
        for (i = 1; i < NF; i++) { if ($i == "solver") g += $(i + 1); if ($i == "coupling") g += $(i + 1) } }
      / collisions, .* collisions per second of wall time/ {c = $1}
      END {print w, e, g, c}' "$log")
    [ -n "$wall" ] && [ -n "$engine" ] && [ -n "$gas" ] || die "no time lines in $log"
    row=$(awk -v w="$wall" -v e="$engine" -v g="$gas" -v t="$BUBBLE_END" -v c="$coll" -v th="$th" 'BEGIN {
      printf "| %d | %.1f | %.2f | %.2f | %.2f | %.2f | %.0f |", th, c / t / 1e3, w / t, e / t, g / t, (w - e - g) / t, c / e }')
    echo "$STAMP,$COMMIT,bubble_orifice_t$th,2400,1e-4,1,$coll,$wall,engine=$engine,gas=$gas," >>"$CSV"
    echo "threads=$th: wall $wall s, engine $engine s, gas+coupling $gas s, $coll collisions over $BUBBLE_END s" >&2
    BUBBLE+=("$row")
  done
fi

# --- (a) pouring ---
if want pouring; then
  if [ -f "$ROOT/cases/hoomans96/pouring_hard.toml" ]; then
    pour=("$ROOT/cases/hoomans96/pouring_hard.toml")
    pour_name=pouring_hard
  else
    pour=("$ROOT/cases/hoomans96/pouring_soft.toml" --set simulation.engine=hard_sphere
      --set simulation.time_step=1e-4 --set simulation.end_time=0.3)
    pour_name=pouring_soft+hard_sphere
  fi
  echo "== (a) $pour_name" >&2
  read -r coll secs bpp < <(run "$WORK/pouring.log" "${pour[@]}" --out "$WORK/pouring")
  read -r rate ns < <(record "$pour_name" 500 1e-4 1 "$coll" "$secs" "$bpp")
  drift=$(sed -nE 's/.*energy balance drift ([^ ]+) .*/\1/p' "$WORK/pouring.log")
  echo "pouring: $coll collisions in ${secs} s: $rate collisions/s, $ns ns per collision, energy drift $drift" >&2
  OUT+=("(a) $pour_name, 500 discs: $coll collisions in $secs s of loop wall time: **$(fmt_rate "$rate") collisions/s** ($ns ns per collision); energy balance drift $drift; $bpp bytes per particle")
fi

# --- (b) dense gas against N ---
declare -A LATTICE=([1k]=10 [10k]=22 [100k]=46)
gas_runs() { # size dt runs -> "collisions seconds bpp N"
  local size=$1 dt=$2 runs=$3 n=${LATTICE[$1]}
  local data=$WORK/hs_gas_$size.data
  [ -s "$data" ] || write_lattice "$n" "$data"
  local tc=0 ts=0 bpp="" c s b r
  for ((r = 1; r <= runs; r++)); do
    read -r c s b < <(run "$WORK/hs_gas_${size}_dt${dt}.log" "$ROOT/bench/cases/hs_gas_$size.toml" \
      --set "insert[0].file=$data" --set "insert[0].seed=$r" --set "simulation.time_step=$dt" \
      --out "$WORK/hs_gas_$size")
    tc=$((tc + c))
    ts=$(awk -v a="$ts" -v b="$s" 'BEGIN {printf "%.3f", a + b}')
    bpp=$b
  done
  echo "$tc $ts $bpp $((n * n * n))"
}
if want gas; then
  GAS=()
  ns_1k=""
  i=0
  for size in 1k 10k 100k; do
    runs=${REPEATS[$i]:-1}
    i=$((i + 1))
    echo "== (b) hs_gas_$size, $runs run(s)" >&2
    read -r coll secs bpp n < <(gas_runs "$size" 1e-4 "$runs")
    read -r rate ns < <(record "hs_gas_$size" "$n" 1e-4 "$runs" "$coll" "$secs" "$bpp")
    [ -n "$ns_1k" ] || { ns_1k=$ns; n_1k=$n; }
    rel=$(awk -v a="$ns" -v b="$ns_1k" 'BEGIN {printf "%.2f", a / b}')
    logrel=$(awk -v n="$n" -v m="$n_1k" 'BEGIN {printf "%.2f", log(n) / log(m)}')
    echo "N=$n: $coll collisions in $secs s: $rate collisions/s, $ns ns per collision (x$rel of N=$n_1k; log N ratio $logrel)" >&2
    GAS+=("| $n | $runs | $coll | $secs | $(fmt_rate "$rate") | $ns | $rel | $logrel | $bpp |")
  done
  # The verdict: cost per collision from the smallest to the largest N against ln N.
  VERDICT=$(awk -v r="$rel" -v l="$logrel" 'BEGIN {
    printf "cost per collision grew x%s from N = 10^3 to 10^5; ln N grew x%s: %s", r, l,
      (r <= l ? "no faster than log N" : "FASTER than log N") }')
  echo "$VERDICT" >&2
fi

# --- (c) flow-step sweep at N = 10^4 ---
if want sweep; then
  SWEEP=()
  for dt in 2.5e-5 5e-5 1e-4 2e-4 4e-4 8e-4; do
    echo "== (c) hs_gas_10k, DT = $dt" >&2
    read -r coll secs bpp n < <(gas_runs 10k "$dt" 1)
    read -r rate ns < <(record hs_gas_10k "$n" "$dt" 1 "$coll" "$secs" "$bpp")
    echo "DT=$dt: $coll collisions in $secs s: $rate collisions/s, $ns ns per collision" >&2
    SWEEP+=("| $dt | $coll | $secs | $(fmt_rate "$rate") | $ns | $bpp |")
  done
fi

echo
echo "commit $COMMIT, $STAMP, $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $THREADS thread(s)${PIN:+ pinned to core 0}; load: $(uptime | sed 's/.*load average/load average/')"
for l in "${OUT[@]}"; do echo "$l"; done
if want gas; then
  echo
  echo "(b) dense gas, solid fraction 0.30, e = 0.9, mu = 0, periodic, DT = 1e-4 s, 0.02 s per run"
  echo "| N | runs | collisions | loop wall s | collisions/s | ns per collision | cost / cost(1k) | ln N / ln 1000 | bytes/particle |"
  echo "|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${GAS[@]}"
  echo "$VERDICT"
fi
if want sweep; then
  echo
  echo "(c) N = 10648, one run of 0.02 s per flow step DT"
  echo "| DT (s) | collisions | loop wall s | collisions/s | ns per collision | bytes/particle |"
  echo "|---|---|---|---|---|---|"
  printf '%s\n' "${SWEEP[@]}"
fi
if want bubble; then
  echo
  echo "(d) bubble_orifice (2400 hard spheres + gas), $BUBBLE_END s; seconds of wall time per simulated second"
  echo "| threads | k collisions / sim. s | wall | engine | gas solver and coupling | rest | collisions per engine second |"
  echo "|---|---|---|---|---|---|---|"
  printf '%s\n' "${BUBBLE[@]}"
fi
echo "(all rows appended to $CSV)"
