#!/usr/bin/python3
"""Plays a bag into a running semchain_ros node and scores its last /amcl_pose against the truth.

The bag carries /semchain/truth (geometry_msgs/PoseStamped in the map frame), as `semchain bag
export` writes it. With --kidnap-at T the checker calls /global_localization once the bag's clock
has passed T seconds after its start (the bag jumps the robot there). Prints one JSON object and
exits 1 when the last pose is not within the tolerances.
"""
import argparse
import json
import math
import sys
import threading
import time

import play_bag
import rosbag
import rospy
from geometry_msgs.msg import PoseStamped, PoseWithCovarianceStamped
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty


def yaw(q) -> float:
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def angle_difference(a: float, b: float) -> float:
    return abs(math.atan2(math.sin(a - b), math.cos(a - b)))


class Recorder:
    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.poses: list = []  # (stamp, x, y, theta)
        self.truth: list = []

    def on_pose(self, message: PoseWithCovarianceStamped) -> None:
        p = message.pose.pose
        with self.lock:
            self.poses.append((message.header.stamp.to_sec(), p.position.x, p.position.y,
                               yaw(p.orientation)))

    def on_truth(self, message: PoseStamped) -> None:
        p = message.pose
        with self.lock:
            self.truth.append((message.header.stamp.to_sec(), p.position.x, p.position.y,
                               yaw(p.orientation)))


def truth_at(truth: list, stamp: float):
    return min(truth, key=lambda t: abs(t[0] - stamp))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--bag", required=True)
    parser.add_argument("--rate", type=float, default=1.0, help="rosbag play rate")
    parser.add_argument("--tolerance-m", type=float, default=0.25)
    parser.add_argument("--tolerance-deg", type=float, default=10.0)
    parser.add_argument("--kidnap-at", type=float, default=None,
                        help="bag seconds after its start at which to call /global_localization")
    parser.add_argument("--kidnap-at-file", default=None,
                        help="a file holding --kidnap-at (splice_bags.py prints it)")
    parser.add_argument("--timeout", type=float, default=60.0, help="wait for the node, seconds")
    args = parser.parse_args()
    if args.kidnap_at_file:
        with open(args.kidnap_at_file, encoding="utf-8") as file:
            args.kidnap_at = float(file.read().strip())

    with rosbag.Bag(args.bag) as bag:
        bag_start = bag.get_start_time()
    rospy.init_node("semchain_node_checker", anonymous=True)
    recorder = Recorder()
    rospy.Subscriber("/amcl_pose", PoseWithCovarianceStamped, recorder.on_pose, queue_size=100)
    rospy.Subscriber("/semchain/truth", PoseStamped, recorder.on_truth, queue_size=100)
    rospy.wait_for_service("/global_localization", timeout=args.timeout)
    global_localization = rospy.ServiceProxy("/global_localization", Empty)

    kidnap_called = threading.Event()
    pose_count_at_kidnap = [0]  # poses received before the call

    def on_clock(message: Clock) -> None:
        if args.kidnap_at is None or kidnap_called.is_set():
            return
        if message.clock.to_sec() >= bag_start + args.kidnap_at:
            kidnap_called.set()
            with recorder.lock:
                pose_count_at_kidnap[0] = len(recorder.poses)
            threading.Thread(target=global_localization).start()

    rospy.Subscriber("/clock", Clock, on_clock, queue_size=10)
    play_exit = play_bag.play(args.bag, args.rate, rospy.get_name())
    # The last scans' poses are still on their way.
    time.sleep(1.0)

    result = {"bag": args.bag, "rosbag_play_exit": play_exit}
    with recorder.lock:
        poses = list(recorder.poses)
        truth = list(recorder.truth)
    result["poses"] = len(poses)
    result["truth_poses"] = len(truth)
    if args.kidnap_at is not None:
        result["kidnap_called"] = kidnap_called.is_set()
        result["poses_before_kidnap"] = pose_count_at_kidnap[0]
    ok = play_exit == 0 and poses and truth
    if poses and truth:
        stamp, x, y, theta = poses[-1]
        t = truth_at(truth, stamp)
        error_m = math.hypot(x - t[1], y - t[2])
        error_deg = math.degrees(angle_difference(theta, t[3]))
        result.update({"last_pose": [x, y, theta], "truth": list(t[1:]), "error_m": error_m,
                       "error_deg": error_deg, "stamp_gap_s": abs(stamp - t[0])})
        ok = ok and error_m <= args.tolerance_m and error_deg <= args.tolerance_deg
        if args.kidnap_at is not None:
            # Before the kidnap the node had found the robot in the first place as well.
            before = poses[:pose_count_at_kidnap[0]]
            ok = ok and kidnap_called.is_set() and bool(before)
            if before:
                stamp, x, y, theta = before[-1]
                t = truth_at(truth, stamp)
                result["error_before_kidnap_m"] = math.hypot(x - t[1], y - t[2])
                result["error_before_kidnap_deg"] = math.degrees(angle_difference(theta, t[3]))
                ok = ok and result["error_before_kidnap_m"] <= args.tolerance_m and \
                    result["error_before_kidnap_deg"] <= args.tolerance_deg
    result["success"] = bool(ok)
    print(json.dumps(result, indent=2))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
