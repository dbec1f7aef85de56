"""Plays a bag into the nodes under test without losing its first messages.

`rosbag play` starts publishing 0.2 s after it advertises its topics; a subscriber on a loaded
machine may connect later than that and miss what the bag says first (the bad-input test's frame
before the first scan is its first detection message). So the bag is played with
--wait-for-subscribers, limited to the topics somebody subscribes to: the others (the truth, the
run's metadata, odometry the node reads from /tf) would make rosbag wait forever, and nobody would
read them anyway.
"""
import subprocess
from typing import List

import rosbag
import rosgraph


def subscribed_topics(bag_path: str, caller_id: str) -> List[str]:
    """The bag's topics that have at least one subscriber registered with the master."""
    _, subscribers, _ = rosgraph.Master(caller_id).getSystemState()
    listened = {topic for topic, nodes in subscribers if nodes}
    with rosbag.Bag(bag_path) as bag:
        topics = bag.get_type_and_topic_info().topics.keys()
    return sorted(topic for topic in topics if topic in listened)


def play(bag_path: str, rate: float, caller_id: str) -> int:
    """Plays the bag with a simulated clock; returns rosbag's exit status."""
    topics = subscribed_topics(bag_path, caller_id)
    if not topics:
        raise RuntimeError(f"{bag_path}: none of its topics has a subscriber")
    command = ["rosbag", "play", "--clock", "-q", "-r", str(rate), "--wait-for-subscribers",
               bag_path, "--topics", *topics]
    # rosbag play talks on stdout; the checkers' stdout is their JSON result.
    return subprocess.run(command, stdout=subprocess.DEVNULL, check=False).returncode
