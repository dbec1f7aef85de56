#!/usr/bin/env bash
# mode_test.sh SEMCHAIN_ROS SOURCE_DIR WORK: ~mode and the command line's parameters. On a roscore
# of its own: (1) a mapping run started with _mode:=mapping _out:=... _seed:=3 beside a ~particles
# set with rosparam says its mode and where it came from on its start-up line and, stopped
# cleanly, deletes ~mode, ~out and ~seed but leaves ~particles; (2) a ~mode mapping left on the
# parameter server and a command line giving _map:= stop the node with an error naming ~mode; (3)
# the same ~mode with _mode:=localization given runs the localization mode.
set -euo pipefail
node="$1"
source_dir="$2"
work="$3"
source "$source_dir/tests/ros/ros_env.sh"
ros_start mode
log="$ROS_LOG_DIR/mode_node.out"
fail() {
  echo "FAIL: $*"
  cat "$log"
  exit 1
}
params() { rosparam list 2>/dev/null | grep '^/semchain_ros/' | sort | tr '\n' ' '; }
# Runs the node with ARGS until its start-up line is in the log (or it exits), then stops it.
run_node() {
  "$node" "$@" >"$log" 2>&1 &
  local pid=$!
  for _ in $(seq 1 100); do
    grep -q -E "semchain_ros: (mapping|localization) \(~mode|FATAL" "$log" && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  kill -INT "$pid" 2>/dev/null || true
  local status=0
  wait "$pid" || status=$?
  return "$status"
}

rosparam set /semchain_ros/particles 20
run_node _mode:=mapping _out:="$work/mode_map" _seed:=3 _save_on_shutdown:=false \
  _min_detection_score:=0.6 _frame_queue_size:=30 || fail "the mapping run did not exit cleanly"
grep -q "semchain_ros: mapping (~mode: command line), out $work/mode_map" "$log" ||
  fail "no start-up line saying the mode and where it came from"
grep -q "particles 20," "$log" || fail "the start-up line does not give ~particles"
grep -q "min_detection_score 0.6," "$log" || fail "the start-up line does not give ~min_detection_score"
grep -q "frame_queue_size 30," "$log" || fail "the start-up line does not give ~frame_queue_size"
[ "$(params)" = "/semchain_ros/particles " ] ||
  fail "parameters left after the run: $(params) (expected only ~particles)"
echo "ok: the command line's ~mode, ~out, ~seed deleted at exit, ~particles kept"

if run_node _mode:=mapping _out:="$work/mode_map" _min_detection_score:=1.5; then
  fail "~min_detection_score 1.5 did not stop the node"
fi
grep -q "parameter ~min_detection_score: must be in \[0, 1\]" "$log" ||
  fail "no error naming ~min_detection_score"
echo "ok: ~min_detection_score is on the start-up line and checked"

if run_node _mode:=mapping _out:="$work/mode_map" _frame_queue_size:=0; then
  fail "~frame_queue_size 0 did not stop the node"
fi
grep -q "parameter ~frame_queue_size: must be >= 1" "$log" || fail "no error naming ~frame_queue_size"
echo "ok: ~frame_queue_size is on the start-up line and checked"

rosparam set /semchain_ros/mode mapping
if run_node _map:="$work/map"; then fail "a stale ~mode mapping with _map:= did not stop the node"; fi
grep -q "parameter ~mode: 'mapping' is on the parameter server" "$log" ||
  fail "no error naming the stale ~mode"
echo "ok: a stale ~mode under a localization command line is refused"

run_node _mode:=localization _map:="$work/map" || fail "the localization run did not exit cleanly"
grep -q "semchain_ros: localization (~mode: command line), method semantic-scanmatch" "$log" ||
  fail "_mode:=localization did not run the localization mode"
[ "$(params)" = "/semchain_ros/particles " ] ||
  fail "parameters left after the run: $(params) (the stale ~mode was overwritten by the command line's, which is deleted)"
echo "ok: _mode:=localization overrides it"
