# Shared shell functions of the whole-run benchmarks (sourced by compare_dem.sh and scaling.sh).
# Expects ROOT (the repository) to be set; sets FLUIDEM, DEM, PIN1/PIN2 and the helpers below.

die() { echo "$(basename "$0"): $*" >&2; exit 1; }

DEM=${DEM:-$(cd "$ROOT/.." && pwd)/shared/bench/dem}
FLUIDEM=${FLUIDEM:-$ROOT/build/fluidem}
COMMIT=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)
STAMP=$(date -u +%Y-%m-%dT%H:%M:%SZ)

# /usr/bin/time (package `time`) for the peak RSS; taskset pins one thread to core 0, two to 0-1.
if [ ! -x /usr/bin/time ]; then
  echo "installing /usr/bin/time (package time)" >&2
  apt-get install -y time >/dev/null 2>&1 || die "/usr/bin/time is missing (apt-get install -y time)"
fi
PIN1=() PIN2=()
if command -v taskset >/dev/null 2>&1; then PIN1=(taskset -c 0) PIN2=(taskset -c 0,1); fi

ensure_fluidem() {
  [ -x "$FLUIDEM" ] && return 0
  echo "building fluidem (Release) in $ROOT/build" >&2
  cmake -S "$ROOT" -B "$ROOT/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$ROOT/build" -j"$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)" --target fluidem >/dev/null
  FLUIDEM=$ROOT/build/fluidem
}

# peer BINARY PACKAGE: the peer's binary path, installed with apt-get if missing; empty if not.
peer() {
  if ! command -v "$1" >/dev/null 2>&1; then
    echo "$1 not found: trying apt-get install -y $2" >&2
    apt-get install -y "$2" >/dev/null 2>&1 || true
  fi
  command -v "$1" 2>/dev/null || true
}

rss_mb() { awk '/Maximum resident set size/ {printf "%.1f", $NF / 1024}' "$1"; }

# bed_data TAG WORK: the settled bed TAG (10k, 100k: ../shared/bench/dem; 1m: bed100k repeated
# ten times along y, 0.15 x 1.0 x 0.6 m, the copies touching where the y walls were) unpacked
# into WORK; prints the file name.
bed_data() {
  local tag=$1 work=$2 out=$2/bed$1.data
  case $tag in
  10k | 100k)
    local gz=$DEM/bed$tag.data.gz
    [ -f "$gz" ] || die "no bed $gz"
    [ "$out" -nt "$gz" ] || gunzip -c "$gz" >"$out"
    ;;
  1m)
    if [ ! -s "$out" ]; then
      local src
      src=$(bed_data 100k "$work")
      awk 'BEGIN {atoms = 0}
        /^Atoms/ {mode = 1; next}
        /^Velocities/ {mode = 2}
        mode == 0 && / atoms$/ {n = $1; next}
        mode == 0 && / ylo yhi$/ {ylen = $2 - $1; next}
        mode == 1 && NF >= 7 {line[++atoms] = $0}
        END {
          printf "LAMMPS data file: bed100k repeated 10x along y (bench/bench_lib.sh)\n\n"
          printf "%d atoms\n1 atom types\n\n", 10 * n
          printf "0 0.15 xlo xhi\n0 %.17g ylo yhi\n0 0.6 zlo zhi\n\nAtoms # sphere\n\n", 10 * ylen
          id = 0
          for (c = 0; c < 10; c++)
            for (k = 1; k <= atoms; k++) {
              split(line[k], f, " ")
              printf "%d 1 %s %s %s %.17g %s\n", ++id, f[3], f[4], f[5], f[6] + c * ylen, f[7]
            }
        }' "$src" >"$out"
    fi
    ;;
  *) die "unknown bed $tag (10k, 100k, 1m)" ;;
  esac
  echo "$out"
}

# run_fluidem LOG THREADS CASE [ARGS...]: one fluidem run under /usr/bin/time; prints
# "particles steps loop_seconds rate bytes_per_particle peak_rss_mb".
run_fluidem() {
  local log=$1 threads=$2
  shift 2
  local pin=("${PIN1[@]}")
  [ "$threads" -gt 1 ] && pin=("${PIN2[@]}")
  /usr/bin/time -v "${pin[@]}" "$FLUIDEM" run "$@" --threads "$threads" --force >"$log" 2>"$log.time" ||
    { tail -5 "$log" "$log.time" >&2; die "fluidem failed (log $log)"; }
  local done_line
  done_line=$(grep '^done:' "$log")
  echo "$(awk '/^particles / {print $2}' "$log") $(echo "$done_line" | awk '{print $2, $5}')" \
    "$(echo "$done_line" | sed -E 's/.* ([0-9.e+]+) particle-steps\/s.*/\1/')" \
    "$(sed -nE 's/^memory ([0-9]+) bytes per particle.*/\1/p' "$log")" "$(rss_mb "$log.time")"
}
