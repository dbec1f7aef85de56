#!/usr/bin/env bash
# node_test.sh SEMCHAIN_ROS SOURCE_DIR WORK NAME BAG METHOD [ARGS...]: starts its own roscore on
# a free port (simulated time), runs semchain_ros on WORK/map (or $SEMCHAIN_MAP) with METHOD,
# plays BAG into it through tests/ros/node_checker.py (which scores the last /amcl_pose against
# the bag's truth), stops the node cleanly and prints its CPU and latency figures
# (WORK/NAME_stats.json); then checks that the /amcl_pose messages the checker received are
# those the node says it published (tests/ros/check_pose_counts.py). ARGS of the form
# _name:=value go to the node, the others to the checker.
set -euo pipefail
node="$1"
source_dir="$2"
work="$3"
name="$4"
bag="$5"
method="$6"
shift 6
source "$source_dir/tests/ros/ros_env.sh"
ros_start "$name"

node_args=(_map:="${SEMCHAIN_MAP:-$work/map}" _method:="$method")
checker_args=()
for arg in "$@"; do
  if [[ "$arg" == _*:=* ]]; then node_args+=("$arg"); else checker_args+=("$arg"); fi
done
ros_check "$name" "$source_dir/tests/ros/node_checker.py" --bag "$bag" "${checker_args[@]}"
/usr/bin/python3 "$source_dir/tests/ros/check_pose_counts.py" "$work/${name}_result.json" \
  "$work/${name}_stats.json"
