# Sourced by the node tests: ros_start NAME starts a roscore of their own on a free port (ROS
# logs under $work/ros_home_NAME, simulated time) and stops it, and whatever the test added to
# pids, when the test exits. Needs $work.
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
  pids+=($!)
  for _ in $(seq 1 100); do
    rosparam list >/dev/null 2>&1 && break
    sleep 0.2
  done
  rosparam set /use_sim_time true
}
