#!/usr/bin/python3
"""Reads a ROS 1 bag with ROS's own python rosbag (independent of the C++ reader under test:
it decompresses lz4 chunks with roslz4's python binding and bz2 chunks with python's bz2) and
prints one JSON object: per topic, the message count and a SHA-256 of every message's receive
time and serialized bytes, in order; and the compression of each chunk, as the bag's records
say.

Usage: bag_digest.py BAG
"""
import hashlib
import json
import sys

import rosbag


def main(path):
    topics = {}
    with rosbag.Bag(path) as bag:
        for topic, raw, t in bag.read_messages(raw=True):
            entry = topics.setdefault(topic, {"messages": 0, "sha256": hashlib.sha256()})
            entry["messages"] += 1
            entry["sha256"].update(("%d.%09d" % (t.secs, t.nsecs)).encode())
            entry["sha256"].update(raw[1])
        chunks = sorted({c.compression for c in bag._chunk_headers.values()})
    out = {t: {"messages": e["messages"], "sha256": e["sha256"].hexdigest()} for t, e in topics.items()}
    print(json.dumps({"topics": out, "chunk_compressions": chunks}, sort_keys=True))


if __name__ == "__main__":
    main(sys.argv[1])
