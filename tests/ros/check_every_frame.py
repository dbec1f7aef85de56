#!/usr/bin/python3
"""Checks that the mapping mode handled every scan and every camera frame of a bag.

check_every_frame.py BAG STATS.json: STATS is the node's ~stats_file. Every /scan message must
have gone into SLAM (none dropped for want of tf, none rejected as out of time order) and every
colour image on /camera/color/image_raw must have been detected and mapped (frames_mapped), none
skipped. Exits 1 when not.
"""
import json
import sys

import rosbag


def main() -> int:
    with rosbag.Bag(sys.argv[1]) as bag:
        topics = bag.get_type_and_topic_info().topics
        scans = topics["/scan"].message_count
        images = topics["/camera/color/image_raw"].message_count
    with open(sys.argv[2], encoding="utf-8") as file:
        stats = json.load(file)
    detected = stats["detector_ms_per_frame"]
    print(f"bag: {scans} scans, {images} colour images; node: {stats['scans']} scans "
          f"({stats['dropped_scans']} dropped, {stats['rejected_scans']} rejected), "
          f"{stats['frames_detected']} frames detected, {stats['frames_mapped']} mapped, "
          f"{stats['frames_skipped']} skipped, {stats['frames_without_camera']} without a camera, "
          f"detector median {detected['median'] if detected else None} ms")
    problems = []
    if stats["scans"] != scans or stats["dropped_scans"] or stats["rejected_scans"]:
        problems.append("not every scan went into SLAM")
    if stats["frames_mapped"] != images or stats["frames_skipped"]:
        problems.append("not every frame was mapped")
    for problem in problems:
        print(f"FAIL: {problem}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
