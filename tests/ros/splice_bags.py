#!/usr/bin/python3
"""Splices two bags of `semchain bag export` into one in which the robot is kidnapped.

The second bag's messages follow the first's after a gap; its odometry (tf odom → base_link and
/odom) continues from where the first's ended, as it would when a robot is carried away: the
wheels did not turn, so odometry does not see the jump. /semchain/truth jumps. Static transforms
and latched topics are taken from the first bag. Prints the kidnap time, in seconds after the
spliced bag's start.
"""
import argparse
import json
import math

import rosbag
import rospy

STATIC_TOPICS = {"/tf_static", "/semchain/run_info"}


def planar(translation, rotation):
    yaw = math.atan2(2.0 * (rotation.w * rotation.z + rotation.x * rotation.y),
                     1.0 - 2.0 * (rotation.y * rotation.y + rotation.z * rotation.z))
    return translation.x, translation.y, yaw


def compose(a, b):
    ax, ay, at = a
    bx, by, bt = b
    return (ax + math.cos(at) * bx - math.sin(at) * by,
            ay + math.sin(at) * bx + math.cos(at) * by, at + bt)


def inverse(a):
    x, y, t = a
    return (-math.cos(t) * x - math.sin(t) * y, math.sin(t) * x - math.cos(t) * y, -t)


def set_planar(translation, rotation, pose):
    translation.x, translation.y = pose[0], pose[1]
    rotation.x = rotation.y = 0.0
    rotation.z, rotation.w = math.sin(pose[2] / 2.0), math.cos(pose[2] / 2.0)


def odometry_poses(bag, odom_frame, base_frame):
    poses = []
    for _, message, _ in bag.read_messages(topics=["/tf"]):
        for t in message.transforms:
            if t.header.frame_id == odom_frame and t.child_frame_id == base_frame:
                poses.append(planar(t.transform.translation, t.transform.rotation))
    return poses


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("first")
    parser.add_argument("second")
    parser.add_argument("--out", required=True)
    parser.add_argument("--gap", type=float, default=1.0, help="seconds between the two")
    parser.add_argument("--odom-frame", default="odom")
    parser.add_argument("--base-frame", default="base_link")
    args = parser.parse_args()

    with rosbag.Bag(args.first) as first, rosbag.Bag(args.second) as second, \
            rosbag.Bag(args.out, "w") as out:
        first_odometry = odometry_poses(first, args.odom_frame, args.base_frame)
        second_odometry = odometry_poses(second, args.odom_frame, args.base_frame)
        # odometry of the second bag, seen from the first's last pose on.
        rebase = compose(first_odometry[-1], inverse(second_odometry[0]))
        shift = rospy.Duration.from_sec(first.get_end_time() + args.gap - second.get_start_time())
        kidnap_at = first.get_end_time() + args.gap / 2.0 - first.get_start_time()
        # Connection headers carry 'latching': /tf_static must stay latched, or a node that
        # connects after rosbag play published it never gets the robot's frames.
        for topic, message, stamp, header in first.read_messages(return_connection_header=True):
            out.write(topic, message, stamp, connection_header=header)
        for topic, message, stamp, header in second.read_messages(return_connection_header=True):
            if topic in STATIC_TOPICS:
                continue
            if topic == "/tf":
                for t in message.transforms:
                    t.header.stamp += shift
                    if t.header.frame_id == args.odom_frame and t.child_frame_id == args.base_frame:
                        pose = compose(rebase, planar(t.transform.translation, t.transform.rotation))
                        set_planar(t.transform.translation, t.transform.rotation, pose)
            elif topic == "/odom":
                message.header.stamp += shift
                p = message.pose.pose
                set_planar(p.position, p.orientation,
                           compose(rebase, planar(p.position, p.orientation)))
            elif topic == "/semchain/detections":
                record = json.loads(message.data)
                record["stamp"] += shift.to_sec()
                message.data = json.dumps(record)
            elif hasattr(message, "header"):
                message.header.stamp += shift
            out.write(topic, message, stamp + shift, connection_header=header)
    print(f"{kidnap_at:.3f}")


if __name__ == "__main__":
    main()
