#!/usr/bin/env bash
# node_test.sh SEMCHAIN_ROS SOURCE_DIR WORK NAME BAG METHOD [CHECKER ARGS...]: starts its own
# roscore on a free port (simulated time), runs semchain_ros on WORK/map (or $SEMCHAIN_MAP) with
# METHOD, plays BAG into it through tests/ros/node_checker.py (which scores the last /amcl_pose
# against the bag's truth), stops the node cleanly and prints its CPU and latency figures
# (WORK/NAME_stats.json).
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
ros_check "$name" "$source_dir/tests/ros/node_checker.py" --bag "$bag" "$@"
