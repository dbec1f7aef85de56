#!/usr/bin/env bash
# mapping_test.sh SEMCHAIN_ROS SOURCE_DIR WORK [RATE]: the node's mapping mode end to end, fed
# bad input along the way. Plays the fixture's mapping run of two_similar_rooms (WORK/mapping.bag,
# no images) with bad messages spliced in (tests/ros/bad_inputs.py: a frame before the first
# scan, frames and scans out of time order, an unknown class) and the colour images of five
# frames (tests/ros/add_keyframe_images.py) at RATE (default 2) into semchain_ros _mode:=mapping
# _out:=WORK/live_map (tests/ros/mapping_checker.py: objects on /semchain/objects before the bag
# ends, then /semchain/save_map). The node must warn about each bad message and keep mapping;
# the saved semantic.json must match the world (precision and recall >= 0.97,
# tests/ros/score_semantic.py) with no object of the unknown class, and the saved folder's
# keyframes (one to five, "run": ".") must each carry its own frame's image, from those five.
# Then the room A trial bag is localized on that map in the default mode (node_test.sh: the last
# /amcl_pose within 0.25 m and 10°). One bag play for both: each play is 80 s of a CI run.
set -euo pipefail
node="$1"
source_dir="$2"
work="$3"
rate="${4:-2}"
name=mapping
out="$work/live_map"
/usr/bin/python3 "$source_dir/tests/ros/bad_inputs.py" "$work/mapping.bag" "$work/bad_only.bag"
/usr/bin/python3 "$source_dir/tests/ros/add_keyframe_images.py" --run "$work/mapping" \
  --bag "$work/bad_only.bag" --out "$work/bad_input.bag"
rm -rf "$out"
(
  source "$source_dir/tests/ros/ros_env.sh"
  ros_start "$name"
  node_args=(_mode:=mapping _out:="$out")
  ros_check "$name" "$source_dir/tests/ros/mapping_checker.py" --bag "$work/bad_input.bag" \
    --rate "$rate"
  log="$ROS_LOG_DIR/semchain_ros.out"
  for expected in "frame bad/before_first_scan at .* comes before the first scan: no pose" \
    "frame bad/out_of_order at .* out of time order, skipped" \
    "detection of unknown class 'fridge'" \
    "scan at .* is not newer than the last one .*out of time order, skipped"; do
    if ! grep -q -E "$expected" "$log"; then
      echo "FAIL: no warning matching '$expected' in the node's log"
      exit 1
    fi
    echo "ok: warned: $expected"
  done
)
echo "saved map: $(ls "$out" | tr '\n' ' ')"
if grep -q fridge "$out/semantic.json"; then
  echo "FAIL: the saved map has an object of the unknown class"
  exit 1
fi
/usr/bin/python3 "$source_dir/tests/ros/score_semantic.py" "$out/semantic.json" \
  "$source_dir/worlds/two_similar_rooms.yaml"
/usr/bin/python3 "$source_dir/tests/ros/add_keyframe_images.py" --run "$work/mapping" \
  --check "$out"
SEMCHAIN_MAP="$out" bash "$source_dir/tests/ros/node_test.sh" "$node" "$source_dir" "$work" \
  live_map_lookalike "$work/room_a.bag" semantic-scanmatch
