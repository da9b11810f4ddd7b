#!/usr/bin/python3
"""Rewrites a bag of `bimloc simulate` the way other robots record theirs, with ROS's own
python rosbag (independent of the C++ reader under test). Message classes come from the
definitions stored in the bag, so no ROS message package is needed.

Usage: rewrite_bag.py IN OUT MODE
  rename    /velodyne_points -> /lidar/points (frame lidar_link), /odom -> /legs/odom,
            tf frames odom -> odom_legs, base_link -> body; the mount body -> lidar_link
            goes to /tf_static once (as robot_state_publisher latches it)
  reorder   the clouds' fields in another order and width: time FLOAT64 first, ring, z,
            intensity, y FLOAT64, x, with padding; the same points
  footprint no /odom; /tf odom -> base_footprint, and base_footprint -> base_link 0.3 m up
            on /tf_static (as a legged robot's state publisher gives them)
  otherclock /odom stamped 100000 s later (another clock), nothing else changed
  noodom    no /odom and no odom -> base_link on /tf (the mount stays)
  ouster    the clouds in ouster-ros' layout: x y z (padded to 16), intensity, t UINT32 ns
            relative to the stamp, ring UINT8; point_step 48
  hesai     the clouds in HesaiLidar_ROS_2.0's layout: x y z intensity, timestamp FLOAT64
            absolute seconds, ring UINT16; point_step 32
  notime    the clouds with x y z intensity only: no per-point time
"""
import copy
import sys

import numpy
import rosbag

FRAMES = {"odom": "odom_legs", "base_link": "body", "velodyne": "lidar_link"}


def rename(inp, out):
    static_written = False
    for topic, msg, t in inp.read_messages():
        if topic == "/velodyne_points":
            msg.header.frame_id = FRAMES["velodyne"]
            out.write("/lidar/points", msg, t)
        elif topic == "/odom":
            msg.header.frame_id = FRAMES["odom"]
            msg.child_frame_id = FRAMES["base_link"]
            out.write("/legs/odom", msg, t)
        elif topic == "/tf":
            moving = [x for x in msg.transforms if x.header.frame_id == "odom"]
            fixed = [x for x in msg.transforms if x.header.frame_id != "odom"]
            for x in msg.transforms:
                x.header.frame_id = FRAMES[x.header.frame_id]
                x.child_frame_id = FRAMES[x.child_frame_id]
            if fixed and not static_written:
                static = copy.deepcopy(msg)
                static.transforms = fixed
                out.write("/tf_static", static, t)
                static_written = True
            msg.transforms = moving
            out.write("/tf", msg, t)
        else:
            out.write(topic, msg, t)


# sensor_msgs/PointField datatypes: FLOAT32 7, FLOAT64 8, UINT16 4.
NUMPY = {7: "<f4", 8: "<f8", 4: "<u2"}
NEW_LAYOUT = [("time", 8), ("ring", 4), ("z", 7), ("intensity", 7), ("y", 8), ("x", 7)]


def reorder(inp, out):
    for topic, msg, t in inp.read_messages():
        if topic == "/velodyne_points":
            old = numpy.dtype({"names": [f.name for f in msg.fields], "formats": [NUMPY[f.datatype] for f in msg.fields],
                               "offsets": [f.offset for f in msg.fields], "itemsize": msg.point_step})
            points = numpy.frombuffer(bytes(msg.data), dtype=old, count=msg.width)
            offsets, offset = [], 0
            for name, datatype in NEW_LAYOUT:
                offsets.append(offset)
                offset += numpy.dtype(NUMPY[datatype]).itemsize + 1  # a padding byte after each field
            new = numpy.dtype({"names": [n for n, _ in NEW_LAYOUT], "formats": [NUMPY[d] for _, d in NEW_LAYOUT],
                               "offsets": offsets, "itemsize": offset + 3})
            packed = numpy.zeros(msg.width, dtype=new)
            for name, _ in NEW_LAYOUT:
                packed[name] = points[name]
            field_class = type(msg.fields[0])
            msg.fields = [field_class(name=n, offset=o, datatype=d, count=1) for (n, d), o in zip(NEW_LAYOUT, offsets)]
            msg.point_step = new.itemsize
            msg.row_step = new.itemsize * msg.width
            msg.data = packed.tobytes()
        out.write(topic, msg, t)


# Other drivers' layouts (name, datatype, offset) and how their time is made from the
# Velodyne time (seconds relative to the header stamp).
LAYOUTS = {
    "ouster": ([("x", 7, 0), ("y", 7, 4), ("z", 7, 8), ("intensity", 7, 16), ("t", 6, 20), ("ring", 2, 26)], 48,
               lambda rel, stamp: numpy.round(rel * 1e9).astype("<u4")),
    "hesai": ([("x", 7, 0), ("y", 7, 4), ("z", 7, 8), ("intensity", 7, 12), ("timestamp", 8, 16), ("ring", 4, 24)], 32,
              lambda rel, stamp: stamp + rel.astype("<f8")),
    "notime": ([("x", 7, 0), ("y", 7, 4), ("z", 7, 8), ("intensity", 7, 12)], 16, None),
}
NUMPY.update({6: "<u4", 2: "u1"})


def layout(mode):
    def rewrite(inp, out):
        fields, step, timing = LAYOUTS[mode]
        for topic, msg, t in inp.read_messages():
            if topic == "/velodyne_points":
                old = numpy.dtype({"names": [f.name for f in msg.fields], "formats": [NUMPY[f.datatype] for f in msg.fields],
                                   "offsets": [f.offset for f in msg.fields], "itemsize": msg.point_step})
                points = numpy.frombuffer(bytes(msg.data), dtype=old, count=msg.width)
                new = numpy.dtype({"names": [n for n, _, _ in fields], "formats": [NUMPY[d] for _, d, _ in fields],
                                   "offsets": [o for _, _, o in fields], "itemsize": step})
                packed = numpy.zeros(msg.width, dtype=new)
                stamp = msg.header.stamp.secs + 1e-9 * msg.header.stamp.nsecs
                for name, _, _ in fields:
                    if name in ("t", "timestamp"):
                        packed[name] = timing(points["time"], stamp)
                    else:
                        packed[name] = points[name]
                field_class = type(msg.fields[0])
                msg.fields = [field_class(name=n, offset=o, datatype=d, count=1) for n, d, o in fields]
                msg.point_step = step
                msg.row_step = step * msg.width
                msg.data = packed.tobytes()
            out.write(topic, msg, t)
    return rewrite


def footprint(inp, out):
    static_written = False
    for topic, msg, t in inp.read_messages():
        if topic == "/odom":
            continue
        if topic == "/tf":
            for x in msg.transforms:
                if x.header.frame_id == "odom":  # odom <- footprint = odom <- base * (footprint <- base)^-1
                    x.child_frame_id = "base_footprint"
                    q = x.transform.rotation
                    # base_link is 0.3 m above the footprint, same orientation: shift by R * (0, 0, -0.3)
                    r13 = 2 * (q.x * q.z + q.w * q.y)
                    r23 = 2 * (q.y * q.z - q.w * q.x)
                    r33 = 1 - 2 * (q.x * q.x + q.y * q.y)
                    x.transform.translation.x -= 0.3 * r13
                    x.transform.translation.y -= 0.3 * r23
                    x.transform.translation.z -= 0.3 * r33
            if not static_written:
                static = copy.deepcopy(msg)
                edge = static.transforms[0]
                edge.header.frame_id, edge.child_frame_id = "base_footprint", "base_link"
                edge.transform.translation.x = edge.transform.translation.y = 0.0
                edge.transform.translation.z = 0.3
                edge.transform.rotation.x = edge.transform.rotation.y = edge.transform.rotation.z = 0.0
                edge.transform.rotation.w = 1.0
                static.transforms = [edge]
                out.write("/tf_static", static, t)
                static_written = True
        out.write(topic, msg, t)


def otherclock(inp, out):
    for topic, msg, t in inp.read_messages():
        if topic == "/odom":
            msg.header.stamp.secs += 100000
        out.write(topic, msg, t)


def noodom(inp, out):
    for topic, msg, t in inp.read_messages():
        if topic == "/odom":
            continue
        if topic == "/tf":
            msg.transforms = [x for x in msg.transforms if x.header.frame_id != "odom"]
        out.write(topic, msg, t)


def main():
    source, target, mode = sys.argv[1:4]
    with rosbag.Bag(source) as inp, rosbag.Bag(target, "w") as out:
        {"rename": rename, "reorder": reorder, "footprint": footprint, "otherclock": otherclock,
         "noodom": noodom, "ouster": layout("ouster"), "hesai": layout("hesai"),
         "notime": layout("notime")}[mode](inp, out)


if __name__ == "__main__":
    main()
