#!/usr/bin/env bash
# Whole-run benchmark of the coupled step (issue 38): where a coupled run's time goes, per
# simulated second, split into the particle engine, the gas solver, the coupling and the output,
# for three beds run one thread each (pinned to core 1 when taskset is there):
#
#  demo      cases/hoomans96/bubble_orifice.toml (the README's demo: 2400 hard spheres, 2-D,
#            15 x 25 cells, DT = 1e-4 s), END_DEMO s (default 0.2).
#  tsuji     cases/hoomans96/tsuji_setup_soft.toml (2400 Hertz-Mindlin spheres, 2-D, 15 x 25
#            cells), END_TSUJI s (default 0.2).
#  velocity  cases/deen07/velocity_ideal.toml (25,000 hard spheres, 3-D, 20 x 1 x 36 cells),
#            END_VELOCITY s (default 0.02).
#
# usage: bench/coupled.sh [BASE]   BASE: another fluidem binary (e.g. an older commit's, built in
#        a worktree) run on the same beds right after each of ours; the ratios ours / BASE are
#        printed per part (< 1: faster).
# env:   FLUIDEM  binary (default build/fluidem)   WORK  outputs (default /tmp/fluidem-bench-coupled)
#        PARTS    which beds (default "demo tsuji velocity")
# Printed per bed and binary: wall seconds per simulated second, and of it the particle engine
# (contacts, integration and lists; the event-driven engine's collisions), the gas solver (of
# which the pressure solve), the coupling (porosity, interpolation, drag, deposition) and the
# output, all from the run's own timers (the "done:" and "time in" lines of `fluidem run`).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
FLUIDEM=${FLUIDEM:-$ROOT/build/fluidem}
BASE=${1:-}
WORK=${WORK:-${TMPDIR:-/tmp}/fluidem-bench-coupled}
PARTS=${PARTS:-demo tsuji velocity}
[[ -x $FLUIDEM ]] || { echo "coupled.sh: no $FLUIDEM (cmake --build build --target fluidem)" >&2; exit 1; }
[[ -z $BASE || -x $BASE ]] || { echo "coupled.sh: no executable $BASE" >&2; exit 1; }
mkdir -p "$WORK"
pin=()
if command -v taskset >/dev/null && [[ $(nproc) -ge 2 ]]; then pin=(taskset -c 1); fi

case_of() {
  case $1 in
  demo) echo "$ROOT/cases/hoomans96/bubble_orifice.toml ${END_DEMO:-0.2}" ;;
  tsuji) echo "$ROOT/cases/hoomans96/tsuji_setup_soft.toml ${END_TSUJI:-0.2}" ;;
  velocity) echo "$ROOT/cases/deen07/velocity_ideal.toml ${END_VELOCITY:-0.02}" ;;
  *) echo "coupled.sh: unknown bed $1 (demo, tsuji, velocity)" >&2; exit 1 ;;
  esac
}

# run BINARY LABEL BED: prints "wall engine gas pressure coupling output" per simulated second.
run() {
  local bin=$1 label=$2 bed=$3 toml end out log
  read -r toml end <<<"$(case_of "$bed")"
  out=$WORK/$bed-$label
  log=$WORK/$bed-$label.log
  rm -rf "$out"
  OMP_NUM_THREADS=1 "${pin[@]}" "$bin" run "$toml" --out "$out" -t 1 \
    --set simulation.end_time="$end" --set output.checkpoint_interval=1000 >"$log" 2>&1 ||
    { echo "coupled.sh: $bin failed on $bed (see $log)" >&2; exit 1; }
  /usr/bin/python3 - "$log" "$end" <<'EOF'
import re, sys
text = open(sys.argv[1]).read()
end = float(sys.argv[2])
def num(pattern):
    m = re.search(pattern, text)
    return float(m.group(1)) if m else 0.0
wall = num(r"done: \d+ steps in ([0-9.eE+-]+) s wall")
engine = num(r"time in the collision engine ([0-9.eE+-]+) s")
if not engine:
    engine = sum(num(p) for p in (r"time in contacts ([0-9.eE+-]+) s", r"integration ([0-9.eE+-]+) s",
                                  r"neighbour lists ([0-9.eE+-]+) s"))
values = [wall, engine, num(r"gas solver ([0-9.eE+-]+) s"), num(r"pressure solve ([0-9.eE+-]+) s"),
          num(r"coupling ([0-9.eE+-]+) s"), num(r"output ([0-9.eE+-]+) s")]
print(" ".join(f"{v / end:.4g}" for v in values))
EOF
}

printf "%-9s %-6s %10s %10s %10s %10s %10s %10s\n" bed binary "wall/sim" engine gas "(pressure)" coupling output
for bed in $PARTS; do
  read -r w e g p c o <<<"$(run "$FLUIDEM" ours "$bed")"
  printf "%-9s %-6s %10s %10s %10s %10s %10s %10s\n" "$bed" ours "$w" "$e" "$g" "($p)" "$c" "$o"
  if [[ -n $BASE ]]; then
    read -r bw be bg bp bc bo <<<"$(run "$BASE" base "$bed")"
    printf "%-9s %-6s %10s %10s %10s %10s %10s %10s\n" "$bed" base "$bw" "$be" "$bg" "($bp)" "$bc" "$bo"
    /usr/bin/python3 -c "
import sys
a = [float(x) for x in sys.argv[1:7]]; b = [float(x) for x in sys.argv[7:13]]
r = ['%.3f' % (x / y) if y else '-' for x, y in zip(a, b)]
print('%-9s %-6s %10s %10s %10s %10s %10s %10s' % ('', 'ratio', r[0], r[1], r[2], '(' + r[3] + ')', r[4], r[5]))
" "$w" "$e" "$g" "$p" "$c" "$o" "$bw" "$be" "$bg" "$bp" "$bc" "$bo"
  fi
done
echo "seconds of wall time per simulated second, one thread; $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo '?') ours${BASE:+, base $BASE}"
