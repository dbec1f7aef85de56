#!/usr/bin/env bash
# mapping_test.sh SEMCHAIN_ROS SOURCE_DIR WORK [RATE]: the node's mapping mode end to end.
# Plays the fixture's mapping run of two_similar_rooms (WORK/mapping.bag, no images) at RATE
# (default 2) into semchain_ros _mode:=mapping _out:=WORK/live_map
# (tests/ros/mapping_checker.py: objects on /semchain/objects before the bag ends, then
# /semchain/save_map), scores the saved semantic.json against the world (precision and recall
# >= 0.97, tests/ros/score_semantic.py), then localizes the room A trial bag on that map in the
# default mode (node_test.sh: the last /amcl_pose within 0.25 m and 10°).
set -euo pipefail
node="$1"
source_dir="$2"
work="$3"
rate="${4:-2}"
name=mapping
out="$work/live_map"
rm -rf "$out"
(
  source "$source_dir/tests/ros/ros_env.sh"
  ros_start "$name"
  node_args=(_mode:=mapping _out:="$out")
  ros_check "$name" "$source_dir/tests/ros/mapping_checker.py" --bag "$work/mapping.bag" \
    --rate "$rate"
)
echo "saved map: $(ls "$out" | tr '\n' ' ')"
/usr/bin/python3 "$source_dir/tests/ros/score_semantic.py" "$out/semantic.json" \
  "$source_dir/worlds/two_similar_rooms.yaml"
SEMCHAIN_MAP="$out" bash "$source_dir/tests/ros/node_test.sh" "$node" "$source_dir" "$work" \
  live_map_lookalike "$work/room_a.bag" semantic-scanmatch
