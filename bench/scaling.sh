#!/usr/bin/env bash
# Cost of the soft-sphere DEM against the number of particles: fluidem on settled beds of 10^4,
# 10^5 and 10^6 spheres (bench/cases/bed10k.toml, bed100k.toml, bed1m.toml: the beds of
# ../shared/bench/dem, the largest being bed100k repeated ten times along y), with 1 and 2 threads
# (pinned to cores 0 and 0-1). Reported per run: particle-steps per second, nanoseconds per
# particle-step, relative to the smallest bed, the neighbour-list pair and wall entries per
# particle and the nanoseconds per list entry (the work per particle differs between the beds:
# the 10^4 bed is only 2.5 diameters deep, so a particle has fewer partners and more wall
# entries), fluidem's own bytes per particle and the peak RSS. The run's wall time includes its
# output (the first and last frame and a checkpoint: ~2 s of ~12 s at 10^6, where the run has
# only 100 steps), so the cost per particle-step is also given for the steps alone (the wall
# time less the log's output time).
#
# usage: bench/scaling.sh [SIZE ...]     SIZE: 10k, 100k, 1m (default: all three)
# env:   FLUIDEM  fluidem binary (default: build/fluidem; built in Release if missing)
#        WORK     work folder (default: ${TMPDIR:-/tmp}/fluidem-scaling): beds, logs, results.csv
#        DEM      the peer benchmark folder (default: ../shared/bench/dem next to the repository)
#        THREADS  thread counts (default: "1 2")
# The step counts are the cases' own (2000, 500, 100 steps); about 3 minutes in all.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
WORK=${WORK:-${TMPDIR:-/tmp}/fluidem-scaling}
read -r -a THREADS <<<"${THREADS:-1 2}"
SIZES=("$@")
[ ${#SIZES[@]} -gt 0 ] || SIZES=(10k 100k 1m)
# shellcheck source=bench/bench_lib.sh
source "$ROOT/bench/bench_lib.sh"
mkdir -p "$WORK"
ensure_fluidem

CSV=$WORK/results.csv
HEADER="date,commit,threads,N,steps,seconds,particle_steps_per_s,ns_per_particle_step,pairs_per_particle,peak_rss_mb,bytes_per_particle,walls_per_particle,ns_per_list_entry,output_seconds,ns_per_particle_step_without_output"
if [ -f "$CSV" ] && [ "$(head -1 "$CSV")" != "$HEADER" ]; then
  mv "$CSV" "$CSV.old" # an earlier version's columns
  echo "scaling.sh: $CSV had other columns: kept as $CSV.old" >&2
fi
[ -f "$CSV" ] || echo "$HEADER" >"$CSV"
ROWS=()
declare -A BASE=() BASE_STEPS=()
for n in "${SIZES[@]}"; do
  data=$(bed_data "$n" "$WORK")
  for t in "${THREADS[@]}"; do
    echo "== fluidem, bed$n, $t thread(s)" >&2
    log=$WORK/fluidem_${n}_t$t.log
    read -r np steps secs rate bpp rss < <(run_fluidem "$log" "$t" "$ROOT/bench/cases/bed$n.toml" \
      --set "insert[0].file=$data" --out "$WORK/fluidem_${n}_t$t")
    pairs=$(sed -nE 's/^neighbour pairs +([0-9.]+) and wall entries.*/\1/p' "$log")
    walls=$(sed -nE 's/^neighbour pairs .* and wall entries +([0-9.]+) per particle.*/\1/p' "$log")
    ns=$(awk -v r="$rate" -v t="$t" 'BEGIN {printf "%.1f", 1e9 / r}')
    ns_entry=$(awk -v ns="$ns" -v p="${pairs:-0}" -v w="${walls:-0}" \
      'BEGIN {printf "%.1f", (p + w > 0) ? ns / (p + w) : 0}')
    # The log's "time in contacts ..., output X s" line: the steps alone take the rest.
    out=$(sed -nE 's/^time in contacts .*, output ([0-9.]+) s.*/\1/p' "$log")
    [ -n "$out" ] || die "no output time in $log"
    ns_steps=$(awk -v s="$secs" -v o="$out" -v n="$np" -v k="$steps" \
      'BEGIN {printf "%.1f", (s - o) * 1e9 / (n * k)}')
    [ -n "${BASE[$t]:-}" ] || BASE[$t]=$ns BASE_STEPS[$t]=$ns_steps
    rel=$(awk -v a="$ns" -v b="${BASE[$t]}" 'BEGIN {printf "%.2f", a / b}')
    rel_steps=$(awk -v a="$ns_steps" -v b="${BASE_STEPS[$t]}" 'BEGIN {printf "%.2f", a / b}')
    echo "$STAMP,$COMMIT,$t,$np,$steps,$secs,$rate,$ns,${pairs:-},$rss,$bpp,${walls:-},$ns_entry,$out,$ns_steps" >>"$CSV"
    ROWS+=("| $np | $t | $steps | $rate | $ns | $rel | $out | $ns_steps | $rel_steps | ${pairs:--} | ${walls:--} | $ns_entry | $bpp | $rss |")
    echo "N=$np threads=$t: $rate particle-steps/s, $ns ns per particle-step (x$rel of the smallest)" >&2
  done
done

echo
echo "commit $COMMIT, $STAMP, $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "| N | threads | steps | particle-steps/s | ns per particle-step | vs smallest N | output s | ns per particle-step without output | vs smallest N | pair entries per particle | wall entries per particle | ns per list entry | bytes/particle (own count) | peak RSS MB |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${ROWS[@]}"
echo "(all rows appended to $CSV)"
