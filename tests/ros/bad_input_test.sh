#!/usr/bin/env bash
# bad_input_test.sh SEMCHAIN_ROS SOURCE_DIR WORK: the mapping mode fed bad input (a frame
# before the first scan, frames and scans out of time order, an unknown class; made by
# tests/ros/bad_inputs.py from the fixture's mapping bag). The node must warn about each, keep
# mapping, save on /semchain/save_map, and the saved map must still match the world (precision
# and recall >= 0.97) with no object of the unknown class. The bag also carries the colour images
# of five frames (tests/ros/add_keyframe_images.py): the saved folder must hold them as its
# keyframes' images ("run": "."), each the image of its own frame.
set -euo pipefail
node="$1"
source_dir="$2"
work="$3"
name=bad_input
out="$work/bad_input_map"
/usr/bin/python3 "$source_dir/tests/ros/bad_inputs.py" "$work/mapping.bag" "$work/bad_only.bag"
/usr/bin/python3 "$source_dir/tests/ros/add_keyframe_images.py" --run "$work/mapping" \
  --bag "$work/bad_only.bag" --out "$work/bad_input.bag"
rm -rf "$out"
(
  source "$source_dir/tests/ros/ros_env.sh"
  ros_start "$name"
  node_args=(_mode:=mapping _out:="$out")
  ros_check "$name" "$source_dir/tests/ros/mapping_checker.py" --bag "$work/bad_input.bag" \
    --rate 2
  log="$ROS_LOG_DIR/semchain_ros.out"
  for expected in "frame bad/before_first_scan at .* comes before the first scan: no pose" \
    "frame bad/out_of_order at .* out of time order, skipped" \
    "detection of unknown class 'fridge'" \
    "scan at .* is older than the last one .*out of time order, skipped"; do
    if ! grep -q -E "$expected" "$log"; then
      echo "FAIL: no warning matching '$expected' in the node's log"
      exit 1
    fi
    echo "ok: warned: $expected"
  done
)
if grep -q fridge "$out/semantic.json"; then
  echo "FAIL: the saved map has an object of the unknown class"
  exit 1
fi
/usr/bin/python3 "$source_dir/tests/ros/score_semantic.py" "$out/semantic.json" \
  "$source_dir/worlds/two_similar_rooms.yaml"
/usr/bin/python3 "$source_dir/tests/ros/add_keyframe_images.py" --run "$work/mapping" \
  --check "$out"
