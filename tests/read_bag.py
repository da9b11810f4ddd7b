#!/usr/bin/python3
"""Reads a bimloc dataset bag with ROS's own python rosbag (the independent reader of the
C++ tests) and prints one JSON object: topics, types, counts, frames, the PointCloud2
layout and first point, the first odometry / ground-truth messages and the tf pairs.

Run with Debian's /usr/bin/python3 (python3-rosbag); message classes come from the
definitions stored in the bag, so no ROS message package is needed.
Usage: read_bag.py BAG
"""
import json
import struct
import sys

import rosbag


def stamp(t):
    return "%d.%09d" % (t.secs, t.nsecs)


def vec3(v):
    return [v.x, v.y, v.z]


def quat(q):
    return [q.x, q.y, q.z, q.w]


def odometry(msg):
    return {
        "frame_id": msg.header.frame_id,
        "child_frame_id": msg.child_frame_id,
        "seq": msg.header.seq,
        "stamp": stamp(msg.header.stamp),
        "position": vec3(msg.pose.pose.position),
        "orientation": quat(msg.pose.pose.orientation),
        "linear": vec3(msg.twist.twist.linear),
        "angular": vec3(msg.twist.twist.angular),
        "pose_covariance_diagonal": [msg.pose.covariance[i * 7] for i in range(6)],
        "twist_covariance_diagonal": [msg.twist.covariance[i * 7] for i in range(6)],
    }


def first_point(cloud):
    # Unpacked by offset, not by a fixed struct: the layout is what the fields say.
    offsets = {f.name: (f.offset, f.datatype) for f in cloud.fields}
    codes = {7: "<f", 4: "<H"}  # sensor_msgs/PointField FLOAT32, UINT16
    point = {}
    for name, (offset, datatype) in offsets.items():
        point[name] = struct.unpack_from(codes[datatype], bytes(cloud.data), offset)[0]
    return point


def main(path):
    out = {"topics": {}, "tf": {}}
    with rosbag.Bag(path) as bag:
        info = bag.get_type_and_topic_info()
        for topic, t in info.topics.items():
            out["topics"][topic] = {"type": t.msg_type, "count": t.message_count, "frame_ids": [],
                                    "child_frame_ids": [], "in_order": True, "stamps_match": True}
        last = {}
        for topic, msg, t in bag.read_messages():
            entry = out["topics"][topic]
            if topic in last and t <= last[topic]:
                entry["in_order"] = False
            last[topic] = t
            entry.setdefault("first_stamp", stamp(t))
            entry["last_stamp"] = stamp(t)
            if hasattr(msg, "header"):
                entry["stamps_match"] = entry["stamps_match"] and msg.header.stamp == t
                if msg.header.frame_id not in entry["frame_ids"]:
                    entry["frame_ids"].append(msg.header.frame_id)
            if hasattr(msg, "child_frame_id") and msg.child_frame_id not in entry["child_frame_ids"]:
                entry["child_frame_ids"].append(msg.child_frame_id)
            if msg._type == "sensor_msgs/PointCloud2":
                cloud = out.setdefault("cloud", {
                    "fields": [{"name": f.name, "offset": f.offset, "datatype": f.datatype, "count": f.count}
                               for f in msg.fields],
                    "point_step": msg.point_step, "height": msg.height, "row_step": msg.row_step,
                    "is_dense": bool(msg.is_dense), "is_bigendian": bool(msg.is_bigendian),
                    "first_point": first_point(msg), "widths": [], "data_sizes": [], "seqs": []})
                cloud["widths"].append(msg.width)
                cloud["data_sizes"].append(len(msg.data))
                cloud["seqs"].append(msg.header.seq)
            elif msg._type == "nav_msgs/Odometry":
                out.setdefault("first_" + topic.strip("/"), odometry(msg))
            elif msg._type == "tf2_msgs/TFMessage":
                for tf in msg.transforms:
                    key = tf.header.frame_id + " -> " + tf.child_frame_id
                    pair = out["tf"].setdefault(key, {"count": 0, "translation": vec3(tf.transform.translation),
                                                      "rotation": quat(tf.transform.rotation)})
                    pair["count"] += 1
                    entry["stamps_match"] = entry["stamps_match"] and tf.header.stamp == t
    json.dump(out, sys.stdout, sort_keys=True)
    sys.stdout.write("\n")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: read_bag.py BAG")
    main(sys.argv[1])
