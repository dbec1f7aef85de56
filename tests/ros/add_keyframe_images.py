#!/usr/bin/python3
"""Copies a mapping bag played with /semchain/detections and adds the colour images of some of
its frames on /camera/color/image_raw, stamped as their detection records, so that the mapping
mode keeps them as keyframe images; one more image matches no record. With --check, compares a
saved map folder's keyframes with the run's images instead.
"""
import argparse
import json
import os
import sys

import cv2
import numpy as np
import rosbag
import rospy
from sensor_msgs.msg import Image
from std_msgs.msg import Header


def image_message(rgb: np.ndarray, stamp: float) -> Image:
    header = Header(stamp=rospy.Time.from_sec(stamp), frame_id="camera_color_optical_frame")
    height, width = rgb.shape[:2]
    return Image(header=header, height=height, width=width, encoding="rgb8", is_bigendian=0,
                 step=3 * width, data=rgb.tobytes())


def read_rgb(path: str) -> np.ndarray:
    bgr = cv2.imread(path, cv2.IMREAD_COLOR)
    if bgr is None:
        sys.exit(f"FAIL: cannot read {path}")
    return cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)


def add_images(bag_path: str, out_path: str, run: str, count: int) -> None:
    added = 0
    with rosbag.Bag(bag_path) as bag, rosbag.Bag(out_path, "w") as out:
        for topic, message, t, header in bag.read_messages(return_connection_header=True):
            out.write(topic, message, t, connection_header=header)
            if topic != "/semchain/detections" or added >= count:
                continue
            record = json.loads(message.data)
            frame = record.get("frame", "")
            if not record.get("detections") or not frame.startswith("frames/"):
                continue
            rgb = read_rgb(os.path.join(run, frame + ".png"))
            # The image after its record (the node pairs them in either order).
            out.write("/camera/color/image_raw", image_message(rgb, record["stamp"]),
                      t + rospy.Duration(0.001))
            added += 1
            if added == 1:  # an image of no frame: must not become anyone's keyframe image
                out.write("/camera/color/image_raw",
                          image_message(255 - rgb, record["stamp"] + 0.25),
                          t + rospy.Duration(0.002))
    print(f"added {added} keyframe images")


def check(map_dir: str, run: str, count: int) -> None:
    with open(os.path.join(map_dir, "keyframes.json")) as f:
        keyframes = json.load(f)
    if keyframes["run"] != ".":
        sys.exit(f"FAIL: keyframes.json run is {keyframes['run']!r}, expected '.'")
    frames = [k["frame"] for k in keyframes["keyframes"]]
    if not 1 <= len(frames) <= count:
        sys.exit(f"FAIL: {len(frames)} keyframes with images, expected 1..{count}")
    for frame in frames:
        saved = read_rgb(os.path.join(map_dir, frame + ".png"))
        original = read_rgb(os.path.join(run, frame + ".png"))
        if saved.shape != original.shape or np.any(saved != original):
            sys.exit(f"FAIL: {frame}: the saved image is not the frame's image")
    print(f"ok: {len(frames)} keyframes, each with its own frame's image in the map folder")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--run", required=True, help="the run the bag was exported from")
    parser.add_argument("--count", type=int, default=5)
    parser.add_argument("--bag")
    parser.add_argument("--out")
    parser.add_argument("--check", help="a saved map folder")
    args = parser.parse_args()
    if args.check:
        check(args.check, args.run, args.count)
    else:
        add_images(args.bag, args.out, args.run, args.count)


if __name__ == "__main__":
    main()
