#!/usr/bin/env bash
# Whole-run benchmark: fluidem on the settled beds of ../shared/bench/dem (10^4 and 10^5 spheres,
# Hertz with tangential history, dt = 1e-5 s), one thread, pinned to core 0; and, when LIGGGHTS is
# installed (or can be: apt-get install -y liggghts), LIGGGHTS on the identical bed in the same
# run (its in.bench.lig, model hertz), so that the two are compared side by side as a ratio.
#
# usage: bench/dem_bed.sh [SIZE ...]        SIZE: 10k, 100k (default: both)
# env:   FLUIDEM  fluidem binary (default: build/fluidem; built in Release if missing)
#        WORK     work folder (default: ${TMPDIR:-/tmp}/fluidem-bench): gunzipped beds, logs,
#                 results.csv
#        DEM      the peer benchmark folder (default: ../shared/bench/dem next to the repository)
#        NWARM    LIGGGHTS warm-up steps before the timed run (default: 100)
#        NO_LIGGGHTS=1  skip LIGGGHTS
# The step counts are the cases' own (bench/cases/bed10k.toml: 2000, bed100k.toml: 500);
# LIGGGHTS runs the same number of timed steps. fluidem's rate is its own "particle-steps/s"
# (the whole time loop, outputs included); LIGGGHTS' is atoms x steps / "Loop time" of the timed
# run. Peak RSS from /usr/bin/time -v.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
DEM=${DEM:-$(cd "$ROOT/.." && pwd)/shared/bench/dem}
WORK=${WORK:-${TMPDIR:-/tmp}/fluidem-bench}
FLUIDEM=${FLUIDEM:-$ROOT/build/fluidem}
NWARM=${NWARM:-100}
SIZES=("$@")
[ ${#SIZES[@]} -gt 0 ] || SIZES=(10k 100k)

die() { echo "dem_bed.sh: $*" >&2; exit 1; }
[ -d "$DEM" ] || die "no peer benchmark folder $DEM (set DEM=...)"
mkdir -p "$WORK"

# Tools: /usr/bin/time (package `time`), taskset (util-linux) for pinning.
if [ ! -x /usr/bin/time ]; then
  echo "installing /usr/bin/time (package time)" >&2
  apt-get install -y time >/dev/null 2>&1 || die "/usr/bin/time is missing (apt-get install -y time)"
fi
PIN=()
if command -v taskset >/dev/null 2>&1; then PIN=(taskset -c 0); fi

if [ ! -x "$FLUIDEM" ]; then
  echo "building fluidem (Release) in $ROOT/build" >&2
  cmake -S "$ROOT" -B "$ROOT/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$ROOT/build" -j"$(nproc)" --target fluidem >/dev/null
  FLUIDEM=$ROOT/build/fluidem
fi

LIGGGHTS=""
if [ "${NO_LIGGGHTS:-0}" != 1 ]; then
  if ! command -v liggghts >/dev/null 2>&1; then
    echo "LIGGGHTS not found: trying apt-get install -y liggghts" >&2
    apt-get install -y liggghts >/dev/null 2>&1 || true
  fi
  if command -v liggghts >/dev/null 2>&1; then LIGGGHTS=$(command -v liggghts); fi
  [ -n "$LIGGGHTS" ] || echo "LIGGGHTS is not available: fluidem only" >&2
fi

rss_mb() { awk '/Maximum resident set size/ {printf "%.1f", $NF / 1024}' "$1"; }

CSV=$WORK/results.csv
[ -f "$CSV" ] || echo "date,commit,code,N,steps,seconds,particle_steps_per_s,peak_rss_mb,bytes_per_particle" >"$CSV"
COMMIT=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)
STAMP=$(date -u +%Y-%m-%dT%H:%M:%SZ)
SUMMARY=()

for n in "${SIZES[@]}"; do
  case_file=$ROOT/bench/cases/bed$n.toml
  gz=$DEM/bed$n.data.gz
  [ -f "$case_file" ] || die "no case $case_file"
  [ -f "$gz" ] || die "no bed $gz"
  data=$WORK/bed$n.data
  [ "$data" -nt "$gz" ] || gunzip -c "$gz" >"$data"

  # --- fluidem ---
  log=$WORK/fluidem_$n.log
  echo "== fluidem, N = $n ($case_file)" >&2
  /usr/bin/time -v "${PIN[@]}" "$FLUIDEM" run "$case_file" --threads 1 \
    --set "insert[0].file=$data" --out "$WORK/fluidem_$n" >"$log" 2>"$WORK/fluidem_$n.time" ||
    { cat "$log" "$WORK/fluidem_$n.time" >&2; die "fluidem failed on bed$n"; }
  done_line=$(grep '^done:' "$log")
  steps=$(echo "$done_line" | awk '{print $2}')
  secs=$(echo "$done_line" | awk '{print $5}')
  f_rate=$(echo "$done_line" | sed -E 's/.* ([0-9.e+]+) particle-steps\/s.*/\1/')
  bpp=$(sed -nE 's/^memory ([0-9]+) bytes per particle.*/\1/p' "$log")
  natoms=$(awk '/^particles / {print $2}' "$log")
  f_rss=$(rss_mb "$WORK/fluidem_$n.time")
  echo "$STAMP,$COMMIT,fluidem,$natoms,$steps,$secs,$f_rate,$f_rss,$bpp" >>"$CSV"
  echo "fluidem   N=$natoms steps=$steps loop=${secs}s  $f_rate particle-steps/s  peak RSS $f_rss MB  $bpp bytes/particle" >&2
  grep -E '^(time in contacts|memory)' "$log" >&2

  # --- LIGGGHTS on the identical bed ---
  if [ -n "$LIGGGHTS" ]; then
    echo "== LIGGGHTS hertz, N = $n, $NWARM warm-up + $steps timed steps" >&2
    (
      cd "$WORK"
      cp -f "$DEM"/model_*.lig .
      /usr/bin/time -v "${PIN[@]}" "$LIGGGHTS" -in "$DEM/in.bench.lig" -var model hertz \
        -var data "$data" -var nsteps "$steps" -var nwarm "$NWARM" -log "liggghts_$n.log" \
        >"liggghts_$n.out" 2>"liggghts_$n.time"
    ) || { tail -20 "$WORK/liggghts_$n.out" >&2; die "LIGGGHTS failed on bed$n"; }
    lt=$(grep 'Loop time of' "$WORK/liggghts_$n.log" | tail -1)
    l_secs=$(echo "$lt" | awk '{print $4}')
    l_atoms=$(echo "$lt" | awk '{for (i = 1; i <= NF; i++) if ($i == "with") print $(i + 1)}')
    l_rate=$(awk -v a="$l_atoms" -v s="$steps" -v t="$l_secs" 'BEGIN {printf "%.4g", a * s / t}')
    l_rss=$(rss_mb "$WORK/liggghts_$n.time")
    ratio=$(awk -v f="$f_rate" -v l="$l_rate" 'BEGIN {printf "%.2f", f / l}')
    echo "$STAMP,$COMMIT,liggghts-hertz,$l_atoms,$steps,$l_secs,$l_rate,$l_rss," >>"$CSV"
    echo "LIGGGHTS  N=$l_atoms steps=$steps loop=${l_secs}s  $l_rate particle-steps/s  peak RSS $l_rss MB" >&2
    echo "ratio fluidem/LIGGGHTS (particle-steps/s): $ratio" >&2
    SUMMARY+=("| $n | $steps | $f_rate | $l_rate | $ratio | $f_rss | $l_rss | $bpp |")
  else
    SUMMARY+=("| $n | $steps | $f_rate | - | - | $f_rss | - | $bpp |")
  fi
done

echo
echo "commit $COMMIT, $STAMP, $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), one thread pinned to core 0"
echo "| N | steps | fluidem particle-steps/s | LIGGGHTS particle-steps/s | ratio fluidem/LIGGGHTS | fluidem peak RSS MB | LIGGGHTS peak RSS MB | fluidem bytes/particle |"
echo "|---|---|---|---|---|---|---|---|"
printf '%s\n' "${SUMMARY[@]}"
echo "(all rows appended to $CSV)"
