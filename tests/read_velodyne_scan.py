#!/usr/bin/python3
"""Reads the velodyne_msgs/VelodyneScan messages of a ROS1 bag with ROS's own python rosbag
(the independent reader of the C++ tests); the message class comes from the definition the
bag stores. Prints one JSON object: the connection's type and MD5 sum, the message count,
packets per message, the header stamps and frame, and the first packet's stamp and bytes.
Usage: read_velodyne_scan.py BAG TOPIC
"""
import json
import sys

import rosbag


def main(path, topic):
    out = {"messages": 0, "packets": [], "stamps": [], "frames": []}
    with rosbag.Bag(path) as bag:
        for c in bag._get_connections([topic]):
            out["type"], out["md5sum"] = c.datatype, c.md5sum
        for _, msg, _ in bag.read_messages(topics=[topic]):
            if out["messages"] == 0:
                p = msg.packets[0]
                out["first_packet_stamp"] = p.stamp.secs + 1e-9 * p.stamp.nsecs
                out["first_packet_hex"] = bytes(p.data).hex()
            out["messages"] += 1
            out["packets"].append(len(msg.packets))
            out["stamps"].append(msg.header.stamp.secs + 1e-9 * msg.header.stamp.nsecs)
            out["frames"].append(msg.header.frame_id)
    print(json.dumps(out))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
