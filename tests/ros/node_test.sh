#!/usr/bin/env bash
# node_test.sh SEMCHAIN_ROS SOURCE_DIR WORK NAME BAG METHOD [CHECKER ARGS...]: starts its own
# roscore on a free port (simulated time), runs semchain_ros on WORK/map with METHOD, plays BAG
# into it through tests/ros/node_checker.py (which scores the last /amcl_pose against the bag's
# truth), stops the node cleanly and prints its CPU and latency figures (WORK/NAME_stats.json).
set -euo pipefail
node="$1"
source_dir="$2"
work="$3"
name="$4"
bag="$5"
method="$6"
shift 6
export PATH="/usr/bin:$PATH"  # ROS's tools and Python modules are Debian's
port=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI="http://127.0.0.1:$port"
export ROS_HOSTNAME=127.0.0.1
export ROS_HOME="$work/ros_home_$name"
export ROS_LOG_DIR="$ROS_HOME/log"
mkdir -p "$ROS_LOG_DIR"
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill -INT "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
}
trap cleanup EXIT

roscore -p "$port" >"$ROS_LOG_DIR/roscore.out" 2>&1 &
pids+=($!)
for _ in $(seq 1 100); do
  rosparam list >/dev/null 2>&1 && break
  sleep 0.2
done
rosparam set /use_sim_time true

stats="$work/${name}_stats.json"
rm -f "$stats"
"$node" _map:="$work/map" _method:="$method" _stats_file:="$stats" \
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
