#!/usr/bin/python3
"""Plays a mapping bag into semchain_ros in mapping mode, then asks it to save the map.

Records when /semchain/objects first carries objects (on the bag's clock) and how many /map
messages came, calls /semchain/save_map after the bag ends and prints one JSON object; exits 1
when no object appeared before the bag's end (unless --objects-optional) or the save failed.
"""
import argparse
import json
import sys
import threading
import time

import play_bag
import rosbag
import rospy
from nav_msgs.msg import OccupancyGrid
from std_srvs.srv import Trigger
from visualization_msgs.msg import MarkerArray


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--bag", required=True)
    parser.add_argument("--rate", type=float, default=1.0, help="rosbag play rate")
    parser.add_argument("--timeout", type=float, default=60.0, help="wait for the node, seconds")
    parser.add_argument("--objects-optional", action="store_true",
                        help="succeed without objects on /semchain/objects")
    args = parser.parse_args()

    with rosbag.Bag(args.bag) as bag:
        bag_start, bag_end = bag.get_start_time(), bag.get_end_time()
    rospy.init_node("semchain_mapping_checker", anonymous=True)
    lock = threading.Lock()
    seen = {"first_objects_stamp": None, "max_objects": 0, "maps": 0}

    def on_objects(message: MarkerArray) -> None:
        objects = [m for m in message.markers if m.ns == "objects" and m.action == m.ADD]
        with lock:
            seen["max_objects"] = max(seen["max_objects"], len(objects))
            if objects and seen["first_objects_stamp"] is None:
                seen["first_objects_stamp"] = rospy.Time.now().to_sec()

    def on_map(_: OccupancyGrid) -> None:
        with lock:
            seen["maps"] += 1

    rospy.Subscriber("/semchain/objects", MarkerArray, on_objects, queue_size=10)
    rospy.Subscriber("/map", OccupancyGrid, on_map, queue_size=10)
    # The player waits for the node whenever it falls behind, so that no message is lost on a
    # loaded machine; the map is saved once the node has taken in the bag's last scan.
    progress = play_bag.NodeProgress()
    rospy.wait_for_service("/semchain/save_map", timeout=args.timeout)
    save_map = rospy.ServiceProxy("/semchain/save_map", Trigger)
    wall_start = time.monotonic()
    play_exit = play_bag.play(args.bag, args.rate, rospy.get_name(), progress=progress)
    play_seconds = time.monotonic() - wall_start
    if not progress.wait_until(play_bag.last_stamp(args.bag, "/scan")):
        print(json.dumps({"bag": args.bag, "rosbag_play_exit": play_exit, "success": False,
                          "error": "the node stopped taking in scans before the bag's last"}))
        return 1
    save_start = time.monotonic()
    saved = save_map()
    save_seconds = time.monotonic() - save_start
    with lock:
        result = dict(seen)
    result.update({"bag": args.bag, "rosbag_play_exit": play_exit,
                   "bag_seconds": bag_end - bag_start, "play_wall_seconds": play_seconds,
                   "save_success": saved.success, "save_message": saved.message,
                   "save_wall_seconds": save_seconds})
    first = result["first_objects_stamp"]
    result["objects_before_end_s"] = None if first is None else bag_end - first
    objects_in_time = first is not None and first < bag_end
    ok = play_exit == 0 and saved.success and (objects_in_time or args.objects_optional)
    result["success"] = bool(ok)
    print(json.dumps(result, indent=2))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
