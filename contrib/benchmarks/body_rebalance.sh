#!/usr/bin/env bash
# A deformable body alone on ranks, split again after an excavation
# (issue 24), against the same run whose split stays the first one. The
# scene is tests/parallel/body_excavation_01 (a 6 x 2 x 5 m body, pressed
# and made stiffer, then its upper left third excavated, all of it in the
# lower rank's half on 2 ranks) read from a finer mesh of the same box
# (contrib/meshes/kuhn_box_msh.py: cubes of 1/c m, six tetrahedra each:
# 360 c^3 zones), with `steps` steps after the excavation and 50 in each
# other stage. Runs `mpirun -np P talus` with TALUS_REBALANCE_THRESHOLD=0 (never
# split again) and with the default (1.15), prints each run's last "Time ="
# line and the split's line, and checks that both print the same summary
# and write the same history, byte for byte.
#
# Usage: contrib/benchmarks/body_rebalance.sh [talus executable] [cubes per metre] [P] [steps]
#   (defaults: build/talus, 10 (360,000 zones), 2, 500)
set -euo pipefail
talus=$(realpath "${1:-build/talus}")
per_metre=${2:-10}
ranks=${3:-2}
steps=${4:-500}
here=$(cd "$(dirname "$0")/../.." && pwd)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 TALUS_PROGRESS_SECONDS=0
export TALUS_HISTORY_DIGITS=17
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 "$here/contrib/meshes/kuhn_box_msh.py" 6 2 5 $((6 * per_metre)) $((2 * per_metre)) \
  $((5 * per_metre)) > "$work/box.msh"
sed -e 's/box_6x2x5_kuhn.msh/box.msh/' \
  -e 's/^  set Steps            = 400/  set Steps            = 50/' \
  -e 's/^  set History interval = 50/  set History interval = 10/' \
  -e 's/^  set Base name = body/&\n  set Write VTU = false/' \
  "$here/tests/parallel/body_excavation_01.prm" > "$work/body.prm"
sed -e 's/^  set Steps = 300/  set Steps = 50/' \
  -e 's/^  set Name = excavate the upper left part/&\n  set Steps = '"$steps"'/' \
  "$here/tests/parallel/body_excavation_scene.prm" > "$work/body_excavation_scene.prm"
echo "CPU: $(lscpu | sed -n 's/^Model name: *//p' | head -1); $(date -u '+%Y-%m-%d %H:%M UTC')"
for threshold in 0 1.15; do
  (cd "$work" && rm -rf output_body_excavation &&
    TALUS_REBALANCE_THRESHOLD=$threshold mpirun -np "$ranks" --oversubscribe "$talus" body.prm \
      > "run_$threshold.out" 2> "run_$threshold.err" || test $? -eq 4)
  cp "$work/output_body_excavation/body_history.csv" "$work/history_$threshold.csv"
  echo "TALUS_REBALANCE_THRESHOLD=$threshold: $(grep '^Zones:' "$work/run_$threshold.out" | cut -c15-45)"
  grep '^   Time = ' "$work/run_$threshold.out" | sed 's/^ */  /'
done
diff <(grep -v '^   Time = ' "$work/run_0.out") <(grep -v '^   Time = ' "$work/run_1.15.out") > /dev/null &&
  echo "summaries: identical" || echo "summaries: DIFFER"
cmp -s "$work/history_0.csv" "$work/history_1.15.csv" && echo "histories: identical" ||
  echo "histories: differ (sums over the ranks in another order; the tests compare them to 1e-12)"
