"""Plays a bag into the nodes under test without losing any of its messages.

`rosbag play` starts publishing 0.2 s after it advertises its topics; a subscriber on a loaded
machine may connect later than that and miss what the bag says first (the bad-input test's frame
before the first scan is its first detection message). So the bag is played with
--wait-for-subscribers, limited to the topics somebody subscribes to: the others (the truth, the
run's metadata, odometry the node reads from /tf) would make rosbag wait forever, and nobody would
read them anyway.

`rosbag play` also keeps its pace whatever the node does: a node on a loaded machine that falls
further behind than its subscriber queues hold (the mapping node's: 20 s of scans) loses the oldest
messages without a word, and a test that counts on every message fails (a loaded CI run lost half
the mapping bag's scans, and with them the bad-input test's out-of-order frame). With a
NodeProgress the player is paused whenever the node is more than a few seconds of bag time behind
and resumed when it has caught up (its ~pause_playback service), so the node sees every message
however slow the machine is.
"""
import subprocess
import sys
import threading
import time
from typing import List, Optional

import rosbag
import rosgraph
import rospy
from rosgraph_msgs.msg import Clock
from std_srvs.srv import SetBool
from tf2_msgs.msg import TFMessage

PLAYER_NAME = "semchain_test_player"


class NodeProgress:
    """How far into the bag the node under test has got, on the bag's clock.

    The node's transform parent → child (the mapping node sends map → odom for every scan it takes
    in, stamped with the scan's stamp) against /clock. Create it after rospy.init_node and before
    play(), so that its subscriptions count as listeners.
    """

    def __init__(self, parent: str = "map", child: str = "odom") -> None:
        self._parent, self._child = parent, child
        self._condition = threading.Condition()
        self._taken_in: Optional[float] = None  # the latest stamp of parent → child
        self._clock: Optional[float] = None
        rospy.Subscriber("/tf", TFMessage, self._on_tf, queue_size=1000)
        rospy.Subscriber("/clock", Clock, self._on_clock, queue_size=10)

    def _on_tf(self, message: TFMessage) -> None:
        for transform in message.transforms:
            if (transform.header.frame_id.lstrip("/") == self._parent
                    and transform.child_frame_id.lstrip("/") == self._child):
                with self._condition:
                    stamp = transform.header.stamp.to_sec()
                    self._taken_in = max(stamp, self._taken_in or stamp)
                    self._condition.notify_all()

    def _on_clock(self, message: Clock) -> None:
        with self._condition:
            self._clock = message.clock.to_sec()
            self._condition.notify_all()

    def lag(self, bag_start: float, poll: float) -> Optional[float]:
        """Bag seconds the node is behind the player (None before the clock runs), after waiting
        up to 'poll' seconds for news."""
        with self._condition:
            self._condition.wait(poll)
            if self._clock is None:
                return None
            return self._clock - max(bag_start, self._taken_in or bag_start)

    def wait_until(self, stamp: float, stalled_seconds: float = 60.0) -> bool:
        """Waits until the node has taken in the input stamped 'stamp'; False when it makes no
        progress for 'stalled_seconds' (it stopped taking input: a failure, not a slow node)."""
        with self._condition:
            last, since = self._taken_in, time.monotonic()
            while self._taken_in is None or self._taken_in < stamp:
                if self._taken_in != last:
                    last, since = self._taken_in, time.monotonic()
                elif time.monotonic() - since > stalled_seconds:
                    return False
                self._condition.wait(1.0)
            return True


def subscribed_topics(bag_path: str, caller_id: str) -> List[str]:
    """The bag's topics that have at least one subscriber registered with the master."""
    _, subscribers, _ = rosgraph.Master(caller_id).getSystemState()
    listened = {topic for topic, nodes in subscribers if nodes}
    with rosbag.Bag(bag_path) as bag:
        topics = bag.get_type_and_topic_info().topics.keys()
    return sorted(topic for topic in topics if topic in listened)


def last_stamp(bag_path: str, topic: str) -> float:
    """The newest header stamp among the bag's messages on 'topic'."""
    with rosbag.Bag(bag_path) as bag:
        return max(message.header.stamp.to_sec()
                   for _, message, _ in bag.read_messages(topics=[topic]))


def _pace(process: subprocess.Popen, progress: NodeProgress, bag_start: float,
          max_lag: float) -> None:
    """Pauses the player while the node is more than 'max_lag' bag seconds behind, until it is
    within half that; returns when the player has ended."""
    pause = rospy.ServiceProxy(f"/{PLAYER_NAME}/pause_playback", SetBool)
    paused = False
    pauses = 0
    while process.poll() is None:
        lag = progress.lag(bag_start, poll=0.05)
        if lag is None:
            continue
        want = lag > (max_lag / 2 if paused else max_lag)
        if want == paused:
            continue
        try:
            pause(want)
            paused = want
            pauses += int(want)
        except (rospy.ServiceException, rospy.ROSException):
            pass  # not advertised yet, or the player has just ended: the loop looks again
    # stderr: the checkers' stdout is their JSON result.
    print(f"play_bag: the player waited {pauses} times for the node (more than {max_lag:g} s of "
          "bag time behind)", file=sys.stderr)


def play(bag_path: str, rate: float, caller_id: str, progress: Optional[NodeProgress] = None,
         max_lag: float = 2.0) -> int:
    """Plays the bag with a simulated clock; returns rosbag's exit status. With 'progress', the
    player waits whenever the node falls more than 'max_lag' bag seconds behind."""
    topics = subscribed_topics(bag_path, caller_id)
    if not topics:
        raise RuntimeError(f"{bag_path}: none of its topics has a subscriber")
    # --topics takes every argument after it: the node name goes before.
    command = ["rosbag", "play", "--clock", "-q", "-r", str(rate), "--wait-for-subscribers",
               bag_path, f"__name:={PLAYER_NAME}", "--topics", *topics]
    # rosbag play talks on stdout; the checkers' stdout is their JSON result.
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL)
    if progress is not None:
        with rosbag.Bag(bag_path) as bag:
            bag_start = bag.get_start_time()
        _pace(process, progress, bag_start, max_lag)
    return process.wait()
