#!/usr/bin/env bash
# What a rebalance of the ranks' regions (RankBalance, issue 24) buys when
# a stage makes their work uneven. The scene (default
# contrib/benchmarks/rebalance_wall.prm: 6,000 blocks, stage 1 settles 300
# steps, stage 2 excavates the left half and settles 1,500 more) is run by
# `talus` on one rank and by `mpirun -np 2 talus` with the rebalance (the
# default) and without (TALUS_REBALANCE_THRESHOLD=0), each with its last
# stage's steps (the scene's one line 'set Steps = 1500') set to A and to B;
# the difference of the two "Time =" totals is the cost of B - A steps of
# that stage (the rebalance and its migration come at the stage's first
# step, in both runs, so their cost cancels). Every split run's history must
# be the serial run's byte for byte (checked here). Prints the times, the
# speed-ups and the ranks' line on their work.
#
# Usage: contrib/benchmarks/rebalance_ranks.sh [talus executable] [scene.prm] [A] [B]
#   (defaults: build/talus, contrib/benchmarks/rebalance_wall.prm, 50, 1500)
set -euo pipefail
talus=${1:-build/talus}
prm=${2:-contrib/benchmarks/rebalance_wall.prm}
s1=${3:-50}
s2=${4:-1500}
[ -f "$prm" ] || { echo "$0: '$prm': no such parameter file" >&2; exit 2; }
grep -q '^ *set Steps = 1500$' "$prm" || { echo "$0: '$prm' has no line 'set Steps = 1500'" >&2; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 TALUS_PROGRESS_SECONDS=0
export TALUS_HISTORY_DIGITS=17
work=$(mktemp -d)
scene="$(dirname "$prm")/.rebalance_ranks_scene.prm"
trap 'rm -rf "$work" "$scene"' EXIT
run() # steps name launcher... : prints the run's last "Time =" total; keeps its history
{
  local steps=$1 name=$2
  shift 2
  sed -e "s#^\( *set Directory *=\).*#\1 $work/out#" \
      -e "s#^\( *set Steps = \)1500\$#\1$steps#" "$prm" > "$scene"
  "$@" "$scene" 2> "$work/$name.err" |
    awk '/^   Time = / { t = $3 } END { print t }'
  cp "$work"/out/*_history.csv "$work/$name.csv"
}
serial1=$(run "$s1" serial1 "$talus")
serial2=$(run "$s2" serial2 "$talus")
on1=$(run "$s1" on1 mpirun -np 2 "$talus")
on2=$(run "$s2" on2 mpirun -np 2 "$talus")
off1=$(TALUS_REBALANCE_THRESHOLD=0 run "$s1" off1 mpirun -np 2 "$talus")
off2=$(TALUS_REBALANCE_THRESHOLD=0 run "$s2" off2 mpirun -np 2 "$talus")
for r in on2 off2; do
  cmp -s "$work/serial2.csv" "$work/$r.csv" || { echo "$0: the $r history differs from the serial run's" >&2; exit 1; }
done
awk -v n="$((s2 - s1))" -v a="$serial1" -v b="$serial2" -v c="$on1" -v d="$on2" \
  -v e="$off1" -v f="$off2" -v scene="$prm" \
  -v cpu="$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')" 'BEGIN {
  printf "CPU: %s; %s\n", cpu, strftime("%Y-%m-%d %H:%M UTC", systime(), 1)
  printf "%s: %d steps timed\n", scene, n
  printf "one rank:                %.3f s\n", b - a
  printf "2 ranks, rebalance:      %.3f s, speed-up %.2f\n", d - c, (b - a) / (d - c)
  printf "2 ranks, no rebalance:   %.3f s, speed-up %.2f\n", f - e, (b - a) / (f - e)
  printf "rebalance over none:     %.2f\n", (f - e) / (d - c)
}'
echo "histories of both split runs: the serial run's byte for byte"
grep -h "migration events" "$work/on2.err" | sed 's/^/with rebalance:    /'
grep -h "migration events" "$work/off2.err" | sed 's/^/without rebalance: /'
