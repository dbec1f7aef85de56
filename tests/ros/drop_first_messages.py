#!/usr/bin/python3
"""Copies a bag without the first N messages of one topic.

drop_first_messages.py IN.bag OUT.bag TOPIC N: a camera whose camera_info reaches the node after
its first images (each topic comes on a connection of its own, so a node may see them in either
order) is made certain by leaving out the first N /camera/color/camera_info messages.
"""
import sys

import rosbag


def main() -> int:
    source, target, topic, count = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
    dropped = 0
    with rosbag.Bag(source) as bag_in, rosbag.Bag(target, "w") as bag_out:
        for name, message, stamp in bag_in.read_messages(raw=True):
            if name == topic and dropped < count:
                dropped += 1
                continue
            bag_out.write(name, message, stamp, raw=True)
    if dropped < count:
        print(f"{source}: only {dropped} messages on {topic}, not {count}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
