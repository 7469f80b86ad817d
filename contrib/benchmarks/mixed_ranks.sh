#!/usr/bin/env bash
# Strong scaling of a scene of deformable blocks among rigid ones (issue 24),
# run from its parameter file by `talus` on one rank and by `mpirun -np 2
# talus` (the model split by its blocks, each deformable block's zones on
# its owner). The scene is run without VTU output and with 'Target ratio =
# 0', for S1 and S2 steps (TALUS_MAX_STEPS); the difference of the two
# "Time =" totals is the cost of S2 - S1 steps of the whole loop, without
# the meshing (every rank meshes every deformable block) and the set-up.
# Prints block-steps and zone-cycles per second and the speed-up.
#
# Usage: contrib/benchmarks/mixed_ranks.sh [talus executable] [scene.prm] [S1] [S2]
#   (defaults: build/talus, parameters/cavern_in_jointed_rock.prm: 949
#   blocks, 46,915 zones in 83 deformable blocks; 100 and 1100 steps)
set -euo pipefail
talus=${1:-build/talus}
prm=${2:-parameters/cavern_in_jointed_rock.prm}
s1=${3:-100}
s2=${4:-1100}
[ -f "$prm" ] || { echo "$0: '$prm': no such parameter file" >&2; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 TALUS_PROGRESS_SECONDS=0
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The scene as given, but no VTU frames, no stop at a ratio, output here;
# an 'include' is read from the scene's own folder.
sed -e 's/^\( *set Target ratio *=\).*/\1 0/' \
    -e "s#^\( *set Directory *=\).*#\1 $work/out#" \
    -e 's/^\( *subsection Output\)$/\1\n  set Write VTU = false/' "$prm" > "$(dirname "$prm")/.mixed_ranks_scene.prm"
scene="$(dirname "$prm")/.mixed_ranks_scene.prm"
trap 'rm -rf "$work" "$scene"' EXIT
seconds() # steps launcher... : the total of the run's last "Time =" line, blocks, zones
{
  local steps=$1
  shift
  TALUS_MAX_STEPS=$steps "$@" | awk '/^   Time = / { t = $3 } /^Blocks:/ { b = $2 }
    /^Zones:/ { z = $2 } END { print t, b, z }'
}
read -r serial1 blocks zones < <(seconds "$s1" "$talus" "$scene")
read -r serial2 _ _ < <(seconds "$s2" "$talus" "$scene")
read -r split1 _ _ < <(seconds "$s1" mpirun -np 2 "$talus" "$scene")
read -r split2 _ _ < <(seconds "$s2" mpirun -np 2 "$talus" "$scene")
awk -v nb="$blocks" -v z="$zones" -v n="$((s2 - s1))" -v a="$serial1" -v b="$serial2" \
  -v c="$split1" -v d="$split2" -v scene="$prm" \
  -v cpu="$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')" 'BEGIN {
  printf "CPU: %s; %s\n", cpu, strftime("%Y-%m-%d %H:%M UTC", systime(), 1)
  printf "%s: %d blocks, %d zones, %d steps timed\n", scene, nb, z, n
  printf "one rank:  %.3f s, %.3g block-steps/s, %.3g zone-cycles/s\n", b - a, nb * n / (b - a), z * n / (b - a)
  printf "2 ranks:   %.3f s, %.3g block-steps/s, %.3g zone-cycles/s\n", d - c, nb * n / (d - c), z * n / (d - c)
  printf "speed-up:  %.2f\n", (b - a) / (d - c)
}'
