#!/usr/bin/python3
"""Reads localized.bag with ROS's python rosbag (independent of the C++ writer) and prints one
JSON object: message counts per topic, the map -> odom transforms on /tf, and the first and
last /localization poses. Usage: summarize_localized_bag.py BAG"""
import json
import sys

import rosbag

counts, map_odom, poses = {}, 0, []
with rosbag.Bag(sys.argv[1]) as bag:
    for topic, msg, t in bag.read_messages():
        counts[topic] = counts.get(topic, 0) + 1
        if topic == "/tf":
            map_odom += sum(1 for x in msg.transforms if x.header.frame_id == "map" and x.child_frame_id == "odom")
        elif topic == "/localization":
            p = msg.pose.pose.position
            poses.append({"stamp": msg.header.stamp.to_sec(), "frame_id": msg.header.frame_id, "xyz": [p.x, p.y, p.z],
                          "cov_xx": msg.pose.covariance[0], "cov_yawyaw": msg.pose.covariance[35]})
print(json.dumps({"counts": counts, "map_odom": map_odom, "poses": poses}))
