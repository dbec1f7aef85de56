#!/usr/bin/env bash
# pixels_test.sh SEMCHAIN_ROS SEMCHAIN SOURCE_DIR WORK [RATE]: the mapping mode from pixels. The
# fixture's room A trial exported with its colour and depth images (WORK/room_a_images.bag) is
# played at RATE (default 2) into semchain_ros _mode:=mapping _detector:=models/detector.onnx
# (tests/ros/mapping_checker.py, then /semchain/save_map). The detector runs on a thread of its
# own: every scan of the bag must be processed (none dropped or rejected) and every frame
# detected and mapped, none skipped as out of time order (tests/ros/check_every_frame.py). The
# first two frames' camera_info is left out of the bag: their frames wait for the camera (a node
# may see a camera's first images before its camera_info, which comes on a connection of its
# own) and are mapped once the third frame's camera_info has come. The
# trial's world is built of textured prisms, which the default model, trained on the classes'
# shapes, rarely takes for furniture (docs/results.md, "From pixels"), so no object is required.
set -euo pipefail
node="$1"
semchain="$2"
source_dir="$3"
work="$4"
rate="${5:-2}"
name=pixels
bag="$work/room_a_images.bag"
"$semchain" bag export "$work/room_a" --out "$work/room_a_images_full.bag" >/dev/null
/usr/bin/python3 "$source_dir/tests/ros/drop_first_messages.py" "$work/room_a_images_full.bag" \
  "$bag" /camera/color/camera_info 2
rm -rf "$work/pixels_map"
source "$source_dir/tests/ros/ros_env.sh"
ros_start "$name"
node_args=(_mode:=mapping _out:="$work/pixels_map" _detector:="$source_dir/models/detector.onnx")
ros_check "$name" "$source_dir/tests/ros/mapping_checker.py" --bag "$bag" --rate "$rate" \
  --objects-optional
/usr/bin/python3 "$source_dir/tests/ros/check_every_frame.py" "$bag" "$work/${name}_stats.json"
