#!/usr/bin/python3
"""The steps of tools/node_track.sh: tracking with the ROS node, scored against a map's trajectory.

  node_track.py prepare --map MAP --out OUT   checks MAP (map.yaml, trajectory.txt), gives the
      node a map folder (MAP itself when it has semantic.json, else OUT/node_map: MAP's map with
      an empty semantic map) and prints the node's arguments, one a line: _map:=..., and the
      trajectory's first pose as _initial_pose_x/y/a with _initial_cov_xx/yy/aa (σ 0.05 m, 0.03
      rad, as `semchain bench track` starts its trackers).
  node_track.py record --bag BAG --poses FILE [--rate R]   plays BAG into the running node
      (tests/ros/play_bag.py: simulated clock, paused while the node is more than 2 s of bag
      time behind the newest scan sent) and writes every /amcl_pose it publishes to FILE;
      prints a one-line JSON summary.
  node_track.py score --bag BAG --map MAP --poses FILE --stats STATS --out OUT   matches each pose
      to the trajectory's pose of the same scan by stamp, writes OUT/node_track.json and
      OUT/node_track.md and prints the JSON.

Stamps: the trajectory holds the log's stamps. `semchain bag export` writes them as they are, plus
the whole seconds of /semchain/run_info's stamp_offset_s (non-zero only for a log starting at 0),
and moves a scan stamped less than 1 ms after the one before to 1 ms after it; both are applied
to the trajectory's stamps here. A bag imported by `semchain bag import` (bench track --bag) has
the bag's own stamps and no run info: offset 0.
"""
import argparse
import bisect
import json
import math
import os
import shutil
import sys
import threading
import time
from typing import Dict, List, Optional, Tuple

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "ros"))

INITIAL_SIGMA_M = 0.05
INITIAL_SIGMA_RAD = 0.03
# bag export's least gap between consecutive scans (src/ros/bag_export.cc, kMinScanGapSeconds).
MIN_SCAN_GAP_S = 1e-3
# A pose belongs to a trajectory entry whose bag stamp is this close (scans are >= 1 ms apart).
MATCH_TOLERANCE_S = 1e-4
# `semchain bench track`'s target (apps/track_report.h).
TARGET = {"median_m": 0.05, "median_deg": 1.0, "max_m": 0.20, "max_deg": 5.0}


def fail(message: str) -> None:
    print(f"node_track: {message}", file=sys.stderr)
    sys.exit(2)


def read_trajectory(path: str) -> List[Tuple[float, float, float, float]]:
    """trajectory.txt: '# timestamp x y theta' then one pose per scan."""
    poses = []
    with open(path, encoding="utf-8") as file:
        for number, line in enumerate(file, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            fields = line.split()
            if len(fields) != 4:
                fail(f"{path}:{number}: expected 'timestamp x y theta'")
            poses.append(tuple(float(f) for f in fields))
    if not poses:
        fail(f"{path}: no poses")
    return poses


def map_image(map_yaml: str) -> str:
    """The image file map.yaml names, as written there (relative to map.yaml's folder unless
    absolute)."""
    with open(map_yaml, encoding="utf-8") as file:
        for line in file:
            key, _, value = line.partition(":")
            if key.strip() == "image":
                return value.strip().strip("'\"")
    fail(f"{map_yaml}: no 'image:'")
    return ""


def prepare(args: argparse.Namespace) -> int:
    map_yaml = os.path.join(args.map, "map.yaml")
    trajectory_path = os.path.join(args.map, "trajectory.txt")
    for path in (map_yaml, trajectory_path):
        if not os.path.isfile(path):
            fail(f"{path}: no such file (--map needs map.yaml and trajectory.txt, as `semchain "
                 "bench track` writes to OUT/map)")
    named = map_image(map_yaml)
    image = os.path.join(args.map, named)  # an absolute 'named' stays as it is
    if not os.path.isfile(image):
        fail(f"{image}: no such file (named by {map_yaml})")
    node_map = os.path.abspath(args.map)
    if not os.path.isfile(os.path.join(args.map, "semantic.json")):
        # The node reads a map folder with its semantic map; a laser-only map gets an empty one
        # (bench track localizes on an empty semantic map too).
        node_map = os.path.abspath(os.path.join(args.out, "node_map"))
        os.makedirs(node_map, exist_ok=True)
        shutil.copyfile(map_yaml, os.path.join(node_map, "map.yaml"))
        if not os.path.isabs(named):
            target = os.path.join(node_map, named)
            os.makedirs(os.path.dirname(target), exist_ok=True)
            shutil.copyfile(image, target)
        with open(os.path.join(node_map, "semantic.json"), "w", encoding="utf-8") as file:
            json.dump({"version": 1, "classes": [], "objects": [], "chains": [],
                       "neighbours": []}, file)
            file.write("\n")
    _, x, y, theta = read_trajectory(trajectory_path)[0]
    print(f"_map:={node_map}")
    print(f"_initial_pose_x:={x:.9f}")
    print(f"_initial_pose_y:={y:.9f}")
    print(f"_initial_pose_a:={theta:.9f}")
    print(f"_initial_cov_xx:={INITIAL_SIGMA_M ** 2:.9f}")
    print(f"_initial_cov_yy:={INITIAL_SIGMA_M ** 2:.9f}")
    print(f"_initial_cov_aa:={INITIAL_SIGMA_RAD ** 2:.9f}")
    return 0


def yaw(q) -> float:
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def scan_progress():
    """A play_bag.NodeProgress whose lag is counted from the newest scan the player has sent, not
    from /clock: in a gap between a log's scans longer than the player's max_lag (aces: 3 s) the
    clock runs on while the node has nothing left to take in, and a lag against the clock would
    pause the player there for good."""
    import play_bag
    import rospy
    from sensor_msgs.msg import LaserScan

    class ScanProgress(play_bag.NodeProgress):
        def __init__(self) -> None:
            super().__init__()
            self._newest_scan: Optional[float] = None
            rospy.Subscriber("/scan", LaserScan, self._on_scan, queue_size=1000)

        def _on_scan(self, message: LaserScan) -> None:
            with self._condition:
                self._newest_scan = message.header.stamp.to_sec()
                self._condition.notify_all()

        def lag(self, bag_start: float, poll: float) -> Optional[float]:
            with self._condition:
                self._condition.wait(poll)
                if self._newest_scan is None:
                    return None
                return self._newest_scan - max(bag_start, self._taken_in or bag_start)

    return ScanProgress()


def record(args: argparse.Namespace) -> int:
    import play_bag
    import rospy
    from geometry_msgs.msg import PoseWithCovarianceStamped

    lock = threading.Condition()
    poses: List[List[float]] = []  # [stamp_ns, x, y, theta]

    def on_pose(message: PoseWithCovarianceStamped) -> None:
        p = message.pose.pose
        with lock:
            poses.append([message.header.stamp.to_nsec(), p.position.x, p.position.y,
                          yaw(p.orientation)])
            lock.notify_all()

    rospy.init_node("semchain_node_track", anonymous=True)
    rospy.Subscriber("/amcl_pose", PoseWithCovarianceStamped, on_pose, queue_size=100000)
    progress = scan_progress()
    # The node advertises /global_localization last, once its subscriptions are registered.
    rospy.wait_for_service("/global_localization", timeout=args.timeout)
    started = time.monotonic()
    play_exit = play_bag.play(args.bag, args.rate, rospy.get_name(), progress)
    play_seconds = time.monotonic() - started
    # The last scans' poses are still on their way: wait for the last scan's, or until none has
    # come for 'settle' seconds (the node may have dropped it).
    last_ns = round(play_bag.last_stamp(args.bag, "/scan") * 1e9)
    with lock:
        count, since = len(poses), time.monotonic()
        while not (poses and poses[-1][0] >= last_ns - 1000):
            if len(poses) != count:
                count, since = len(poses), time.monotonic()
            elif time.monotonic() - since > args.settle:
                break
            lock.wait(0.2)
        recorded = list(poses)
    with open(args.poses, "w", encoding="utf-8") as file:
        json.dump({"bag": args.bag, "rate": args.rate, "rosbag_play_exit": play_exit,
                   "play_wall_s": play_seconds, "poses": recorded}, file)
    print(json.dumps({"poses": len(recorded), "rosbag_play_exit": play_exit,
                      "play_wall_s": round(play_seconds, 1)}))
    return 0 if play_exit == 0 and recorded else 1


def bag_scans(bag_path: str) -> Tuple[List[int], int]:
    """The bag's /scan header stamps (ns, in bag order) and its run info's stamp offset (s)."""
    import rosbag

    stamps, offset = [], 0
    with rosbag.Bag(bag_path) as bag:
        for topic, message, _ in bag.read_messages(topics=["/scan", "/semchain/run_info"]):
            if topic == "/scan":
                stamps.append(message.header.stamp.to_nsec())
            else:
                offset = int(json.loads(message.data).get("stamp_offset_s", 0))
    return stamps, offset


def percentile(values: List[float], p: float) -> Optional[float]:
    """As eval::Percentile: the value at rank ceil(p/100 n)."""
    if not values:
        return None
    ordered = sorted(values)
    n = len(ordered)
    return ordered[min(max(int(math.ceil(p / 100.0 * n)), 1), n) - 1]


def angle_difference(a: float, b: float) -> float:
    return abs(math.atan2(math.sin(a - b), math.cos(a - b)))


def score(args: argparse.Namespace) -> int:
    trajectory = read_trajectory(os.path.join(args.map, "trajectory.txt"))
    with open(args.poses, encoding="utf-8") as file:
        recording = json.load(file)
    stats: Dict = {}
    if os.path.isfile(args.stats):
        with open(args.stats, encoding="utf-8") as file:
            stats = json.load(file)
    scan_stamps, offset = bag_scans(args.bag)

    # The bag stamp of each trajectory pose, as bag export writes a log's scans.
    expected: List[float] = []
    restamped = 0
    for stamp, *_ in trajectory:
        if expected and stamp < expected[-1] + MIN_SCAN_GAP_S:
            stamp = expected[-1] + MIN_SCAN_GAP_S
            restamped += 1
        expected.append(stamp)
    expected = [s + offset for s in expected]

    def match(stamp_s: float) -> Optional[int]:
        i = bisect.bisect_left(expected, stamp_s)
        best = min((j for j in (i - 1, i) if 0 <= j < len(expected)),
                   key=lambda j: abs(expected[j] - stamp_s))
        return best if abs(expected[best] - stamp_s) <= MATCH_TOLERANCE_S else None

    bag_in_trajectory = sum(match(ns * 1e-9) is not None for ns in scan_stamps)
    errors_m, errors_deg, rows = [], [], []
    unmatched, repeated = 0, 0
    seen = set()
    for stamp_ns, x, y, theta in recording["poses"]:
        i = match(stamp_ns * 1e-9)
        if i is None:
            unmatched += 1
            continue
        if i in seen:
            repeated += 1  # a second pose for a scan already scored
            continue
        seen.add(i)
        _, rx, ry, rtheta = trajectory[i]
        error_m = math.hypot(x - rx, y - ry)
        error_deg = math.degrees(angle_difference(theta, rtheta))
        errors_m.append(error_m)
        errors_deg.append(error_deg)
        rows.append((i, error_m, error_deg))

    def rounded(value: Optional[float], digits: int) -> Optional[float]:
        return None if value is None else round(value, digits)

    figures = {
        "median_m": rounded(percentile(errors_m, 50), 4),
        "p95_m": rounded(percentile(errors_m, 95), 4),
        "max_m": rounded(percentile(errors_m, 100), 4),
        "median_deg": rounded(percentile(errors_deg, 50), 3),
        "p95_deg": rounded(percentile(errors_deg, 95), 3),
        "max_deg": rounded(percentile(errors_deg, 100), 3),
    }
    within = bool(errors_m) and percentile(errors_m, 50) <= TARGET["median_m"] and \
        percentile(errors_deg, 50) <= TARGET["median_deg"] and \
        max(errors_m) <= TARGET["max_m"] and max(errors_deg) <= TARGET["max_deg"]
    worst = sorted(rows, key=lambda r: -r[1])[:3]
    first_scored = min(seen) if seen else None
    result = {
        "bag": os.path.abspath(args.bag),
        "map": os.path.abspath(args.map),
        "method": args.method,
        "rate": recording.get("rate"),
        "stamps": {"bag_stamp_offset_s": offset, "trajectory_stamps_moved_by_export": restamped,
                   "bag_scans": len(scan_stamps), "bag_scans_in_trajectory": bag_in_trajectory},
        "trajectory_poses": len(trajectory),
        "poses_received": len(recording["poses"]),
        "poses_without_trajectory_pose": unmatched,
        "repeated_poses": repeated,
        "scans_scored": len(errors_m),
        "first_scored_trajectory_index": first_scored,
        **figures,
        "target": TARGET,
        "within_target": within,
        "worst_scans": [{"index": i, "stamp": trajectory[i][0], "error_m": round(m, 4),
                         "error_deg": round(d, 3)} for i, m, d in worst],
        "rosbag_play_exit": recording.get("rosbag_play_exit"),
        "play_wall_s": rounded(recording.get("play_wall_s"), 1),
    }
    if stats:
        result["node"] = {key: stats.get(key) for key in (
            "scans", "dropped_scans", "rescued_scans", "scans_with_pose", "poses_published", "state",
            "latency_ms", "pose_latency_ms", "processing_ms", "tf_wait_ms", "cpu_ms_per_scan")}
        # Poses the node published that never arrived (its /amcl_pose queue holds 2: a recorder
        # starved of CPU at a high --rate loses some).
        if stats.get("poses_published") is not None:
            result["poses_not_received"] = stats["poses_published"] - len(recording["poses"])
    else:
        result["node"] = None
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "node_track.json"), "w", encoding="utf-8") as file:
        json.dump(result, file, indent=2)
        file.write("\n")
    with open(os.path.join(args.out, "node_track.md"), "w", encoding="utf-8") as file:
        file.write(markdown(result))
    print(json.dumps(result, indent=2))
    return 0 if errors_m else 1


def markdown(r: Dict) -> str:
    def cell(value, digits: int) -> str:
        return "–" if value is None else f"{value:.{digits}f}"

    node = r.get("node") or {}
    latency = node.get("latency_ms") or {}
    cpu = node.get("cpu_ms_per_scan") or {}
    lines = [
        "# semchain_ros tracking",
        "",
        f"bag `{r['bag']}` at rate {r['rate']}, map `{r['map']}`, method {r['method']}; every "
        "/amcl_pose scored against the map trajectory's pose of the same scan.",
        "",
        "| scans scored | median (m) | p95 (m) | max (m) | median (°) | p95 (°) | max (°) | "
        "latency median (ms) | latency p95 (ms) | CPU per scan median (ms) | within target |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
        f"| {r['scans_scored']} of {r['trajectory_poses']} | {cell(r['median_m'], 3)} | "
        f"{cell(r['p95_m'], 3)} | {cell(r['max_m'], 3)} | {cell(r['median_deg'], 2)} | "
        f"{cell(r['p95_deg'], 2)} | {cell(r['max_deg'], 2)} | {cell(latency.get('median'), 2)} | "
        f"{cell(latency.get('p95'), 2)} | {cell(cpu.get('median'), 2)} | "
        f"{'yes' if r['within_target'] else 'no'} |",
        "",
    ]
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    steps = parser.add_subparsers(dest="step", required=True)
    p = steps.add_parser("prepare")
    p.add_argument("--map", required=True)
    p.add_argument("--out", required=True)
    p.set_defaults(run=prepare)
    p = steps.add_parser("record")
    p.add_argument("--bag", required=True)
    p.add_argument("--poses", required=True)
    p.add_argument("--rate", type=float, default=1.0)
    p.add_argument("--timeout", type=float, default=120.0, help="wait for the node, seconds")
    p.add_argument("--settle", type=float, default=10.0,
                   help="after the bag: wait this long without a pose for the last one")
    p.set_defaults(run=record)
    p = steps.add_parser("score")
    p.add_argument("--bag", required=True)
    p.add_argument("--map", required=True)
    p.add_argument("--poses", required=True)
    p.add_argument("--stats", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--method", default="")
    p.set_defaults(run=score)
    args = parser.parse_args()
    return args.run(args)


if __name__ == "__main__":
    sys.exit(main())
