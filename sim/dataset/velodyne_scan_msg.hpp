// velodyne_msgs/VelodyneScan and VelodynePacket (ROS 1, ros-drivers/velodyne), which Debian
// does not package: the two structs with the traits rosbag needs to write and read them. The
// MD5 sums are genmsg's for the definitions below (checked by a test against Python rosbag,
// which rebuilds the classes from the definitions a bag stores). Only for bag_reader.cpp and
// bag_writer.cpp: rosbag stays inside sim/dataset.
#pragma once

#include <boost/array.hpp>
#include <ros/message_traits.h>
#include <ros/serialization.h>
#include <ros/time.h>
#include <std_msgs/Header.h>

#include <cstdint>
#include <vector>

namespace velodyne_msgs {

struct VelodynePacket {
  ros::Time stamp;
  boost::array<std::uint8_t, 1206> data{};
};

struct VelodyneScan {
  std_msgs::Header header;
  std::vector<VelodynePacket> packets;
};

}  // namespace velodyne_msgs

namespace ros {
namespace message_traits {

template <>
struct MD5Sum<velodyne_msgs::VelodynePacket> {
  static const char* value() { return "ae4f90a23256f44e82baa08dd45c3456"; }
  static const char* value(const velodyne_msgs::VelodynePacket&) { return value(); }
};
template <>
struct DataType<velodyne_msgs::VelodynePacket> {
  static const char* value() { return "velodyne_msgs/VelodynePacket"; }
  static const char* value(const velodyne_msgs::VelodynePacket&) { return value(); }
};
template <>
struct Definition<velodyne_msgs::VelodynePacket> {
  static const char* value() {
    return "# Raw Velodyne LIDAR packet.\n"
           "\n"
           "time stamp              # packet timestamp\n"
           "uint8[1206] data        # packet contents\n";
  }
  static const char* value(const velodyne_msgs::VelodynePacket&) { return value(); }
};

template <>
struct MD5Sum<velodyne_msgs::VelodyneScan> {
  static const char* value() { return "50804fc9533a0e579e6322c04ae70566"; }
  static const char* value(const velodyne_msgs::VelodyneScan&) { return value(); }
};
template <>
struct DataType<velodyne_msgs::VelodyneScan> {
  static const char* value() { return "velodyne_msgs/VelodyneScan"; }
  static const char* value(const velodyne_msgs::VelodyneScan&) { return value(); }
};
template <>
struct HasHeader<velodyne_msgs::VelodyneScan> : TrueType {};
template <>
struct Definition<velodyne_msgs::VelodyneScan> {
  // As genmsg writes it: the message, then each type it uses after a line of '='.
  static const char* value() {
    return "# Velodyne LIDAR scan packets.\n"
           "\n"
           "Header           header         # standard ROS message header\n"
           "VelodynePacket[] packets        # vector of raw packets\n"
           "\n"
           "================================================================================\n"
           "MSG: std_msgs/Header\n"
           "# Standard metadata for higher-level stamped data types.\n"
           "# This is generally used to communicate timestamped data \n"
           "# in a particular coordinate frame.\n"
           "# \n"
           "# sequence ID: consecutively increasing ID \n"
           "uint32 seq\n"
           "#Two-integer timestamp that is expressed as:\n"
           "# * stamp.sec: seconds (stamp_secs) since epoch (in Python the variable is called 'secs')\n"
           "# * stamp.nsec: nanoseconds since stamp_secs (in Python the variable is called 'nsecs')\n"
           "# time-handling sugar is provided by the client library\n"
           "time stamp\n"
           "#Frame this data is associated with\n"
           "string frame_id\n"
           "\n"
           "================================================================================\n"
           "MSG: velodyne_msgs/VelodynePacket\n"
           "# Raw Velodyne LIDAR packet.\n"
           "\n"
           "time stamp              # packet timestamp\n"
           "uint8[1206] data        # packet contents\n";
  }
  static const char* value(const velodyne_msgs::VelodyneScan&) { return value(); }
};

}  // namespace message_traits

namespace serialization {

template <>
struct Serializer<velodyne_msgs::VelodynePacket> {
  template <typename Stream, typename T>
  inline static void allInOne(Stream& stream, T m) {
    stream.next(m.stamp);
    stream.next(m.data);
  }
  ROS_DECLARE_ALLINONE_SERIALIZER
};

template <>
struct Serializer<velodyne_msgs::VelodyneScan> {
  template <typename Stream, typename T>
  inline static void allInOne(Stream& stream, T m) {
    stream.next(m.header);
    stream.next(m.packets);
  }
  ROS_DECLARE_ALLINONE_SERIALIZER
};

}  // namespace serialization
}  // namespace ros
