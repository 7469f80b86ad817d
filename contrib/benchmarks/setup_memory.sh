#!/usr/bin/env bash
# The memory of a `talus` run on ranks set up by region against one set up
# with the whole model on every rank (issue 24). The scene is the settling
# cubes of benchmark_rigid_ranks (n x n x (n + 1) unit cubes, the lowest
# layer fixed), run for a few steps by `mpirun -np P talus` twice: with
# TALUS_SETUP=whole and with TALUS_SETUP=region (the default). Prints each
# run's wall time (set-up included) and last "Time =" line (the time after
# the set-up, and the largest rank's peak resident memory over the run) and checks that the two runs print the same summary and write the
# same history, byte for byte.
#
# Usage: contrib/benchmarks/setup_memory.sh [talus executable] [n] [P] [steps]
#   (defaults: build/talus, 60, 2, 2)
set -euo pipefail
talus=${1:-build/talus}
n=${2:-60}
ranks=${3:-2}
steps=${4:-2}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 TALUS_PROGRESS_SECONDS=0
export TALUS_HISTORY_DIGITS=17
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/cubes.prm" <<PRM
subsection Model
  set Brick min = 0, 0, 0
  set Brick max = $n, $n, $((n + 1))
  set Default group = cubes
end
subsection Joint set 1
  set Dip = 0
  set Dip direction = 0
  set Spacing = 1
end
subsection Joint set 2
  set Dip = 90
  set Dip direction = 0
  set Spacing = 1
end
subsection Joint set 3
  set Dip = 90
  set Dip direction = 90
  set Spacing = 1
end
subsection Group 1
  set Name = floor
  set Corner min = -1, -1, -1
  set Corner max = $((n + 1)), $((n + 1)), 1
end
subsection Solver
  set Steps = $steps
  set Target ratio = 0
  set Fixed groups = floor
  set History interval = 1
end
subsection Output
  set Directory = $work/out
  set Base name = cubes
  set Write VTU = false
end
PRM
echo "# $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "# settling cubes n = $n ($((n * n * (n + 1))) blocks), $ranks ranks, $steps steps"
for setup in whole region; do
  begin=$(date +%s.%N)
  TALUS_SETUP=$setup mpirun --oversubscribe -np "$ranks" "$talus" "$work/cubes.prm" > "$work/$setup.out" 2> "$work/$setup.err" ||
    { echo "$setup: talus failed:" >&2; cat "$work/$setup.err" >&2; exit 1; }
  end=$(date +%s.%N)
  # (The "Time =" line counts from the run's start, after the set-up.)
  echo "$setup: mpirun took $(awk -v a="$begin" -v b="$end" 'BEGIN { printf "%.1f", b - a }') s; $(grep '^   Time = ' "$work/$setup.out" | tail -1 | sed 's/^ *//')"
  grep -v '^   Time = ' "$work/$setup.out" > "$work/$setup.summary"
  cp "$work/out/cubes_history.csv" "$work/$setup.csv"
done
cmp -s "$work/whole.summary" "$work/region.summary" && echo "summaries: identical" ||
  { echo "summaries differ:"; diff "$work/whole.summary" "$work/region.summary" | head; exit 1; }
cmp -s "$work/whole.csv" "$work/region.csv" && echo "histories: identical" ||
  { echo "histories differ"; exit 1; }
