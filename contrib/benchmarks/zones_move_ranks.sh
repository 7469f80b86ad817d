#!/bin/bash
# The cost of moving a deformable block's zones between MPI ranks (issue 24):
# the cube of tests/parallel/pushed_deformable_crossing_01, meshed finer
# (edge length $1 m, default 0.05: 40,000 zones) and pushed harder (1e6 Pa,
# some 380 m/s^2) so that it crosses from the first rank's region to the
# second's within a few thousand steps. Runs it on one rank and on 2, and
# prints the zones, the steps, each run's wall time, and on 2 ranks the
# wall time of the zones' new split (rank 0's, from the summary's line
# 'Time = T s to split the zones again') against the time of one step.
#
# Usage: contrib/benchmarks/zones_move_ranks.sh [edge length] [talus binary]
set -euo pipefail
edge=${1:-0.05}
talus=${2:-$(dirname "$0")/../../build/talus}
talus=$(realpath "$talus")
here=$(realpath "$(dirname "$0")/../..")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/tests/scenes" "$work/tests/parallel"
cp "$here/tests/scenes/pushed_deformable_cube.prm" "$work/tests/scenes/"
sed -i 's/set Pressure = 1e5/set Pressure = 1e6/; s/set End time = 0.5/set End time = 0.12/; s/set Steps = 20000/set Steps = 200000/' \
  "$work/tests/scenes/pushed_deformable_cube.prm"
cat > "$work/tests/parallel/cube.prm" <<EOF
include ../scenes/pushed_deformable_cube.prm
subsection Deformable
  set Groups          = cube
  set Edge length     = $edge
  set Young's modulus = 1e9
  set Poisson's ratio = 0.25
end
subsection Output
  set Directory = out
  set Write VTU = false
end
EOF
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "$work/tests/parallel"
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), $(nproc) cores; $(date -u '+%Y-%m-%d %H:%M UTC')"
run() {
  local start end
  start=$(date +%s.%N)
  "$@" > run.out 2> run.err
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }'
}
one=$(run "$talus" cube.prm)
two=$(run mpirun -np 2 "$talus" cube.prm)
zones=$(grep -m1 '^Zones:' run.out | awk '{print $2}')
steps=$(grep '^Steps:' run.out | awk '{print $2}')
moved=$(grep -o 'the zones split again at [0-9]* of the events' run.err || true)
split=$(grep 'to split the zones again' run.out | awk '{print $3}' || true)
echo "cube: $zones zones, $steps steps (edge length $edge m)"
echo "one rank: $one s; 2 ranks: $two s (speed-up $(awk -v a="$one" -v b="$two" 'BEGIN { printf "%.2f", a / b }'))"
echo "2 ranks: $moved, in $split s (rank 0's wall time)"
if [ -n "$split" ] && [ -n "$steps" ]; then
  echo "the new split over one step on 2 ranks: $(awk -v s="$split" -v t="$two" -v n="$steps" 'BEGIN { printf "%.1f", s / (t / n) }') steps"
fi
