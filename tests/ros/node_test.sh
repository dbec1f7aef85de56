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

stats="$work/${name}_stats.json"
rm -f "$stats"
"$node" _map:="${SEMCHAIN_MAP:-$work/map}" _method:="$method" _stats_file:="$stats" \
  >"$ROS_LOG_DIR/semchain_ros.out" 2>&1 &
node_pid=$!
set +e
/usr/bin/python3 "$source_dir/tests/ros/node_checker.py" --bag "$bag" "$@" >"$work/${name}_result.json"
checker=$?
set -e
kill -INT "$node_pid"
wait "$node_pid" || true
cat "$work/${name}_result.json"
echo "node log:"; grep -E "semchain_ros" "$ROS_LOG_DIR/semchain_ros.out" | tail -n 8 || true
[ -s "$stats" ] && { echo "node stats:"; cat "$stats"; }
exit "$checker"
