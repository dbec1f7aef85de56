#!/usr/bin/env bash
# Tracking with the ROS node on a map, scored scan by scan against the map's trajectory: the
# figures of `semchain bench track` from semchain_ros itself. See --help.
set -euo pipefail

usage() {
  cat <<'EOF'
Usage: tools/node_track.sh --bag BAG --map MAPDIR --out OUT [--method M] [--rate R]
                           [--node SEMCHAIN_ROS] [--node-arg _name:=value]...

Plays BAG into semchain_ros in localization mode on MAPDIR, started from the first pose of
MAPDIR/trajectory.txt (the node's ~initial_pose_x/y/a, σ 0.05 m and 0.03 rad, as bench track), with
~publish_pose_every_scan; scores every /amcl_pose against the trajectory's pose of the same scan
(by stamp) and reports median, p95 and max error in metres and degrees, the scans scored and the
node's CPU and latency per scan (its ~stats_file).

  --bag BAG        the bag: one `semchain bench track --bag` mapped, or `semchain bag export LOG`
                   of the log bench track --log mapped
  --map MAPDIR     map.yaml and trajectory.txt with one pose per scan (bench track's OUT/map)
  --out OUT        output folder: node_track.json, node_track.md, node_track.log (the node's log
                   and stats), node_poses.json (every pose received), the ROS logs
  --method M       the node's ~method (default scanmatch-global)
  --rate R         rosbag play rate (default 1); the player pauses while the node is more than
                   2 s of bag time behind
  --node PATH      semchain_ros (default: build/src/ros/semchain_ros of this checkout)
  --node-arg A     one more node parameter, e.g. --node-arg _laser_max_beams:=120 (repeatable)

Needs ROS 1 (roscore, rosbag); runs a roscore of its own on a free port with simulated time.
Prints OUT/node_track.json. Exit status 0 when poses were scored, 1 when none, 2 on bad usage.
EOF
}

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bag="" map="" out="" method="scanmatch-global" rate=1 node="$root/build/src/ros/semchain_ros"
extra=()
die() { echo "node_track: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --bag|--map|--out|--method|--rate|--node|--node-arg)
      [ $# -ge 2 ] || die "$1 needs a value"
      case "$1" in
        --bag) bag="$2" ;; --map) map="$2" ;; --out) out="$2" ;; --method) method="$2" ;;
        --rate) rate="$2" ;; --node) node="$2" ;; --node-arg) extra+=("$2") ;;
      esac
      shift 2 ;;
    *) usage >&2; die "unknown argument '$1'" ;;
  esac
done
if [ -z "$bag" ] || [ -z "$map" ] || [ -z "$out" ]; then
  usage >&2
  die "--bag, --map and --out are required"
fi
[ -f "$bag" ] || die "$bag: no such bag"
[ -d "$map" ] || die "$map: no such map folder"
[ -x "$node" ] || die "$node: no semchain_ros there (build it, or give --node)"
[[ "$rate" =~ ^[0-9]*\.?[0-9]+$ ]] || die "--rate: expected a positive number, got '$rate'"
for arg in "${extra[@]}"; do
  [[ "$arg" == _*:=* ]] || die "--node-arg: expected _name:=value, got '$arg'"
done
command -v roscore >/dev/null || die "roscore not found (ROS 1 is needed)"

mkdir -p "$out"
out="$(cd "$out" && pwd)"
bag="$(cd "$(dirname "$bag")" && pwd)/$(basename "$bag")"
map="$(cd "$map" && pwd)"
tool="$root/tools/node_track.py"
mapfile -t prepared < <(/usr/bin/python3 "$tool" prepare --map "$map" --out "$out") || exit 2
[ "${#prepared[@]}" -gt 0 ] || exit 2

# ros_env.sh: ros_start (a private roscore, use_sim_time) and ros_check (runs "$node" with
# node_args and _stats_file:=$work/NAME_stats.json beside the recorder, then stops it cleanly).
export work="$out"
poses="$out/node_poses.json"
stats="$out/node_track_stats.json"
rm -f "$poses" "$stats" "$out/node_track.json" "$out/node_track.md"
# shellcheck source=tests/ros/ros_env.sh
source "$root/tests/ros/ros_env.sh"
ros_start node_track >&2
node_args=("${prepared[@]}" _method:="$method" _publish_pose_every_scan:=true "${extra[@]}")
echo "node_track: $node ${node_args[*]}" >&2
echo "node_track: playing $bag at rate $rate" >&2
status=0
ros_check node_track "$tool" record --bag "$bag" --rate "$rate" --poses "$poses" \
  >"$out/node_track.log" 2>&1 || status=$?
if [ ! -s "$poses" ]; then
  cat "$out/node_track.log" >&2
  die "no poses recorded (status $status; the node's log: $ROS_LOG_DIR/semchain_ros.out)"
fi
/usr/bin/python3 "$tool" score --bag "$bag" --map "$map" --poses "$poses" --stats "$stats" \
  --out "$out" --method "$method"
