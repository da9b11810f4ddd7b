#!/usr/bin/python3
"""Damages a bag of `bimloc simulate` the ways issue 29 found recordings passing in silence,
with ROS's own python rosbag (independent of the C++ reader under test). Message classes come
from the definitions stored in the bag.

Usage: garble_bag.py IN OUT MODE
  nan        every point's x, y, z NaN            inf       every point at +inf
  far        every point scaled to 1e30 m          origin    every point at (0, 0, 0)
  height0    height = 0, the data block kept whole
  overlap    x, y, z declared FLOAT64 at 0, 4, 8 in the 22-byte point (the fields overlap)
  bigendian  is_bigendian = 1 on the little-endian data
  halfnan    the even-numbered clouds all NaN; the others untouched
  someout    in every cloud, every 10th point at 150 m (beyond the VLP-16's 100 m) and every
             10th (another) at 0.1 m (below its 0.4 m)
  odomnan    every 10th /odom sample with a NaN position
  odomzeroq  every 10th /odom sample with a zero quaternion
  odomjump   one /odom sample (the 100th) moved 5 m along x
"""
import math
import sys

import numpy
import rosbag

XYZ = numpy.dtype({"names": ["x", "y", "z"], "formats": ["<f4"] * 3, "offsets": [0, 4, 8], "itemsize": 22})


def points(msg):
    return numpy.frombuffer(bytearray(msg.data), dtype=XYZ, count=msg.width * msg.height).copy()


def set_points(msg, p):
    data = bytearray(msg.data)
    view = numpy.frombuffer(data, dtype=XYZ, count=msg.width * msg.height)
    view.setflags(write=True)
    view[:] = p
    msg.data = bytes(data)


def cloud(msg, mode, index):
    p = points(msg)
    if mode == "nan" or (mode == "halfnan" and index % 2 == 0):
        for a in "xyz":
            p[a] = numpy.nan
    elif mode == "inf":
        for a in "xyz":
            p[a] = numpy.inf
    elif mode == "far":
        r = numpy.sqrt(p["x"].astype("f8") ** 2 + p["y"] ** 2 + p["z"] ** 2)
        for a in "xyz":
            p[a] = (p[a] / r * 1e30).astype("f4")
    elif mode == "origin":
        for a in "xyz":
            p[a] = 0.0
    elif mode == "someout":
        r = numpy.sqrt(p["x"].astype("f8") ** 2 + p["y"] ** 2 + p["z"] ** 2)
        for start, distance in ((0, 150.0), (5, 0.1)):
            sel = slice(start, None, 10)
            for a in "xyz":
                p[a][sel] = (p[a][sel] / r[sel] * distance).astype("f4")
    if mode in ("nan", "inf", "far", "origin", "halfnan", "someout"):
        set_points(msg, p)
    elif mode == "height0":
        msg.height = 0
    elif mode == "overlap":
        for f in msg.fields:
            if f.name in "xyz":
                f.datatype = 8
    elif mode == "bigendian":
        msg.is_bigendian = True


def main():
    source, target, mode = sys.argv[1:4]
    clouds = odoms = 0
    with rosbag.Bag(source) as inp, rosbag.Bag(target, "w") as out:
        for topic, msg, t in inp.read_messages():
            if topic == "/velodyne_points":
                cloud(msg, mode, clouds)
                clouds += 1
            elif topic == "/odom":
                if mode == "odomnan" and odoms % 10 == 0:
                    msg.pose.pose.position.x = math.nan
                elif mode == "odomzeroq" and odoms % 10 == 0:
                    o = msg.pose.pose.orientation
                    o.x = o.y = o.z = o.w = 0.0
                elif mode == "odomjump" and odoms == 100:
                    msg.pose.pose.position.x += 5.0
                odoms += 1
            out.write(topic, msg, t)
    print(clouds, odoms)


if __name__ == "__main__":
    main()
