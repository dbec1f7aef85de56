#!/usr/bin/python3
"""Copies a mapping bag and adds the bad input a live robot can produce.

- /semchain/detections: a frame stamped before the first scan (no pose yet), a frame older than
  the one before it (out of time order) and a frame with a detection of a class the map does not
  know ('fridge');
- /scan: a scan older than the one before it.
The node must warn about each, keep mapping and save a correct map.
"""
import argparse
import copy
import json

import rosbag
import rospy
from std_msgs.msg import String


def detections(frame: str, stamp: float, class_name: str) -> String:
    record = {"frame": frame, "stamp": stamp, "detections": [
        {"class": class_name, "class_id": 0, "score": 0.9, "box": [100, 100, 140, 160],
         "depth_m": 2.0}]}
    return String(data=json.dumps(record))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("bag")
    parser.add_argument("out")
    args = parser.parse_args()
    with rosbag.Bag(args.bag) as bag, rosbag.Bag(args.out, "w") as out:
        start = bag.get_start_time()
        scans = 0
        previous_scan = None
        early_added = late_added = False
        # The connection headers keep /tf_static latched when the copy is played.
        for topic, message, t, header in bag.read_messages(return_connection_header=True):
            if topic == "/semchain/detections" and t.to_sec() < start + 1.0:
                continue  # the first frames make way for the one below (they see nothing)
            out.write(topic, message, t, connection_header=header)
            if topic == "/camera/color/camera_info" and t.to_sec() >= start + 0.5 \
                    and not early_added:
                early_added = True
                # Stamped half a second before the first scan, played a tenth of a second after
                # the second camera_info (so that the node knows the camera): the node's first
                # frame, and it has no pose.
                out.write("/semchain/detections",
                          detections("bad/before_first_scan", start - 0.5, "cabinet"),
                          t + rospy.Duration(0.1))
            if topic == "/scan":
                scans += 1
                if scans == 400 and previous_scan is not None:
                    # The previous scan again, after a newer one: out of time order.
                    out.write("/scan", previous_scan, t, connection_header=header)
                previous_scan = copy.deepcopy(message)
            if topic == "/semchain/detections" and t.to_sec() >= start + 40.0 and not late_added:
                late_added = True
                # Ten seconds older than the frame just played: out of time order.
                out.write("/semchain/detections",
                          detections("bad/out_of_order", t.to_sec() - 10.0, "cabinet"),
                          t + rospy.Duration(0.01))
                # A class the map does not know.
                out.write("/semchain/detections",
                          detections("bad/unknown_class", t.to_sec() + 0.02, "fridge"),
                          t + rospy.Duration(0.02))


if __name__ == "__main__":
    main()
