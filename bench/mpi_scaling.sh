#!/usr/bin/env bash
# Strong scaling of the rank-independent soft-sphere engine over MPI ranks (docs/parallel.md),
# and the cost of its determinism: the settled beds of ../shared/bench/dem (bench/cases/bed10k.toml,
# bed100k.toml; 2000 or 500 steps of Hertz with tangential history) and the coupled bed
# bed100k_gas.toml (bed100k with air through it: 500 steps, 50 flow steps) run
#   - by the single-process engine on one thread (pinned to core 0): the reference speed;
#   - by the rank-independent engine on one process, one thread: its price against that;
#   - by mpirun on 2 and 4 ranks of one thread each (4 ranks oversubscribe this machine's two
#     cores: reported as such).
# Per run: particle-steps per second (the log's, over the steps and their output), the parallel
# efficiency against the one-process rank-independent run, the imbalance (the slowest rank's
# contact time over the mean) and what a rank sends per step (bytes and messages, the log's
# "exchange" line: ghosts every step, migration and new ghosts at list builds), which
# bench/RESULTS.md uses for the projection to more ranks.
#
# usage: bench/mpi_scaling.sh [CASE ...]     CASE: 10k, 100k, 100k_gas (default: all three)
# env:   FLUIDEM, WORK (default: ${TMPDIR:-/tmp}/fluidem-mpi), DEM as in bench_lib.sh
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
WORK=${WORK:-${TMPDIR:-/tmp}/fluidem-mpi}
SIZES=("$@")
[ ${#SIZES[@]} -gt 0 ] || SIZES=(10k 100k 100k_gas)
# shellcheck source=bench/bench_lib.sh
source "$ROOT/bench/bench_lib.sh"
mkdir -p "$WORK"
ensure_fluidem
command -v mpirun >/dev/null || die "mpirun is missing (apt-get install -y openmpi-bin)"
MPIRUN=(mpirun --oversubscribe --allow-run-as-root --mca btl self,vader)

CSV=$WORK/results.csv
HEADER="date,commit,N,engine,ranks,threads_per_rank,oversubscribed,seconds,particle_steps_per_s,efficiency,imbalance,bytes_per_rank_step,messages_per_rank_step"
[ -f "$CSV" ] || echo "$HEADER" >"$CSV"

rate_of() { sed -nE 's/^done: .* ([0-9.e+]+) particle-steps\/s$/\1/p' "$1"; }
secs_of() { sed -nE 's/^done: [0-9]+ steps in ([0-9.]+) s wall.*/\1/p' "$1"; }
imb_of() { sed -nE 's/.*imbalance ([0-9.]+) .*/\1/p' "$1"; }
bytes_of() { sed -nE 's/^exchange: ([0-9.e+]+) bytes and ([0-9.e+]+) messages per rank and step.*/\1/p' "$1"; }
msgs_of() { sed -nE 's/^exchange: ([0-9.e+]+) bytes and ([0-9.e+]+) messages per rank and step.*/\2/p' "$1"; }

for n in "${SIZES[@]}"; do
  data=$(bed_data "${n%_gas}" "$WORK")
  common=("$ROOT/bench/cases/bed$n.toml" --set "insert[0].file=$data" -t 1 --force)
  echo "== bed$n: single-process engine, 1 thread" >&2
  "${PIN1[@]}" "$FLUIDEM" run "${common[@]}" --out "$WORK/fast_$n" >"$WORK/fast_$n.log" 2>&1
  fast=$(rate_of "$WORK/fast_$n.log")
  echo "$STAMP,$COMMIT,$n,single-process,1,1,no,$(secs_of "$WORK/fast_$n.log"),$fast,,,," >>"$CSV"
  ri1=""
  for p in 1 2 4; do
    echo "== bed$n: rank-independent engine, $p rank(s)" >&2
    log=$WORK/ri_${n}_$p.log
    if [ "$p" = 1 ]; then
      "${PIN1[@]}" "$FLUIDEM" run "${common[@]}" --out "$WORK/ri_${n}_$p" \
        --set parallel.rank_independent=true >"$log" 2>&1
    else
      "${MPIRUN[@]}" -n "$p" "$FLUIDEM" run "${common[@]}" --out "$WORK/ri_${n}_$p" >"$log" 2>&1
    fi
    rate=$(rate_of "$log")
    [ -n "$rate" ] || die "no rate in $log"
    [ -n "$ri1" ] || ri1=$rate
    eff=$(awk -v r="$rate" -v b="$ri1" -v p="$p" 'BEGIN {printf "%.2f", r / (p * b)}')
    over=$([ "$p" -gt "$(nproc)" ] && echo yes || echo no)
    echo "$STAMP,$COMMIT,$n,rank-independent,$p,1,$over,$(secs_of "$log"),$rate,$eff,$(imb_of "$log"),$(bytes_of "$log"),$(msgs_of "$log")" >>"$CSV"
  done
  printf "bed%s: single-process %s particle-steps/s; rank-independent on one process %s (%.2fx slower)\n" \
    "$n" "$fast" "$ri1" "$(awk -v a="$fast" -v b="$ri1" 'BEGIN {print a / b}')"
done
echo "results: $CSV"
column -s, -t <"$CSV" | tail -n 12
