# Sourced by the node tests: ros_start NAME starts a roscore of their own on a free port (ROS
# logs under $work/ros_home_NAME, simulated time) and stops it, and whatever the test added to
# pids, when the test exits; ros_check NAME CHECKER.py [ARGS...] runs the node ("$node" with the
# array node_args and _stats_file:=$work/NAME_stats.json) and the checker against it, stops the
# node cleanly and prints the checker's JSON, the node's log and stats; returns the checker's
# status. Needs $work.
export PATH="/usr/bin:$PATH"  # ROS's tools and Python modules are Debian's
pids=()
ros_cleanup() {
  for pid in "${pids[@]}"; do kill -INT "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
}
ros_start() {
  local port
  port=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
  export ROS_MASTER_URI="http://127.0.0.1:$port"
  export ROS_HOSTNAME=127.0.0.1
  export ROS_HOME="$work/ros_home_$1"
  export ROS_LOG_DIR="$ROS_HOME/log"
  mkdir -p "$ROS_LOG_DIR"
  trap ros_cleanup EXIT
  roscore -p "$port" >"$ROS_LOG_DIR/roscore.out" 2>&1 &
  local roscore_pid=$!
  pids+=("$roscore_pid")
  # Up once its parameter server answers, however long a loaded machine takes (ctest's timeout
  # bounds the wait); a roscore that exited (the port taken meanwhile) is an error.
  until rosparam list >/dev/null 2>&1; do
    if ! kill -0 "$roscore_pid" 2>/dev/null; then
      echo "FAIL: roscore exited: $(tail -n 3 "$ROS_LOG_DIR/roscore.out")"
      return 1
    fi
    sleep 0.2
  done
  rosparam set /use_sim_time true
}

ros_check() {
  local name="$1" checker="$2" status stats="$work/${1}_stats.json"
  shift 2
  rm -f "$stats"
  "$node" "${node_args[@]}" _stats_file:="$stats" >"$ROS_LOG_DIR/semchain_ros.out" 2>&1 &
  local node_pid=$!
  set +e
  /usr/bin/python3 "$checker" "$@" >"$work/${name}_result.json"
  status=$?
  set -e
  kill -INT "$node_pid"
  wait "$node_pid" || true
  cat "$work/${name}_result.json"
  echo "node log:"; grep -E "semchain_ros" "$ROS_LOG_DIR/semchain_ros.out" | tail -n 12 || true
  if [ -s "$stats" ]; then echo "node stats:"; cat "$stats"; fi
  return "$status"
}
