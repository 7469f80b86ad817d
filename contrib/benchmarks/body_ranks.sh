#!/usr/bin/env bash
# Strong scaling of a scene run from its parameter file (issue 24): a
# deformable body alone, an elastic block 8 x 4 x 4 m on rollers settling
# under gravity (statics, density scaling), run by `talus` on one rank and
# by `mpirun -np 2 talus` (the body split by its gridpoints). Each is run
# for S1 and S2 steps; the difference of the two "Time =" totals is the
# cost of S2 - S1 steps of the whole loop (zones, the per-step reductions,
# history rows every 100 steps), without the meshing and the set-up, which
# every rank does whole. Prints zone-cycles per second and the speed-up.
#
# Then, when benchmark_core_ceiling is built beside talus (cmake --build
# build --target benchmark_core_ceiling), it prints this machine's own
# two-rank ceiling in the same run (core_ceiling.cc): arithmetic held in
# cache, and memory streamed beyond the last-level cache.
#
# Usage: contrib/benchmarks/body_ranks.sh [talus executable] [edge length, m] [brick|cube]
#   (defaults: build/talus, 0.1 m: 640,000 zones, brick; "cube": a 10 m
#   cube instead, at 0.17 m the mesh of benchmark_zone_ranks 59)
set -euo pipefail
talus=${1:-build/talus}
edge=${2:-0.1}
case ${3:-brick} in
  brick) lx=8 ly=4 lz=4 ;;
  cube) lx=10 ly=10 lz=10 ;;
  *) echo "$0: third argument '$3': allowed: brick or cube" >&2; exit 2 ;;
esac
s1=50
s2=1050
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 TALUS_PROGRESS_SECONDS=0
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene() # steps
{
  cat <<PRM
subsection Model
  set Brick min = 0, 0, 0
  set Brick max = $lx, $ly, $lz
end
subsection Deformable
  set Groups          = rock
  set Edge length     = $edge
  set Young's modulus = 1e10
  set Poisson's ratio = 0.25
end
subsection Boundary 1
  set Corner min = -1, -1, -0.01
  set Corner max = $((lx + 1)), $((ly + 1)), 0.01
  set Held components = z
end
subsection Boundary 2
  set Corner min = -0.01, -1, -1
  set Corner max = 0.01, $((ly + 1)), $((lz + 1))
  set Held components = x
end
subsection Boundary 3
  set Corner min = $((lx - 1)).99, -1, -1
  set Corner max = $lx.01, $((ly + 1)), $((lz + 1))
  set Held components = x
end
subsection Solver
  set Steps            = $1
  set Target ratio     = 0
  set History interval = 100
  set History points   = $((lx / 2)), $((ly / 2)), $lz
end
subsection Output
  set Directory = $work/out
  set Write VTU = false
end
PRM
}
seconds() # launcher... : the total of the run's last "Time =" line
{
  "$@" | awk '/^   Time = / { t = $3 } /^Zones:/ { z = $2 } END { print t, z }'
}
scene $s1 > "$work/s1.prm"
scene $s2 > "$work/s2.prm"
read -r serial1 zones < <(seconds "$talus" "$work/s1.prm")
read -r serial2 _ < <(seconds "$talus" "$work/s2.prm")
read -r split1 _ < <(seconds mpirun -np 2 "$talus" "$work/s1.prm")
read -r split2 _ < <(seconds mpirun -np 2 "$talus" "$work/s2.prm")
steps=$((s2 - s1))
awk -v z="$zones" -v n="$steps" -v a="$serial1" -v b="$serial2" -v c="$split1" -v d="$split2" \
  -v cpu="$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')" 'BEGIN {
  one = z * n / (b - a); two = z * n / (d - c)
  printf "CPU: %s; %s\n", cpu, strftime("%Y-%m-%d %H:%M UTC", systime(), 1)
  printf "body: %d zones, %d steps timed (the runs of %d and %d steps)\n", z, n, '"$s1"', '"$s2"'
  printf "one rank:  %.3f s, %.3g zone-cycles/s\n", b - a, one
  printf "2 ranks:   %.3f s, %.3g zone-cycles/s\n", d - c, two
  printf "speed-up:  %.2f\n", two / one
}'
ceiling="$(dirname "$talus")/contrib/benchmarks/benchmark_core_ceiling"
if [ -x "$ceiling" ]; then
  mpirun -np 2 "$ceiling" 10 | sed -n 's/^\(arithmetic\|memory\)/machine\x27s ceiling, \1/p'
else
  echo "(the machine's ceiling: build benchmark_core_ceiling beside $talus)"
fi
