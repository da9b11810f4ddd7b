#include "sim/ros2/schemas.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace bimloc::sim::ros2 {
namespace {

// The .msg texts (comments and constants left out), as ROS 2 Humble defines them.
const std::map<std::string, std::string>& definitions() {
  static const std::map<std::string, std::string> d = {
      {"builtin_interfaces/msg/Time", "int32 sec\nuint32 nanosec\n"},
      {"builtin_interfaces/msg/Duration", "int32 sec\nuint32 nanosec\n"},
      {"std_msgs/msg/Header", "builtin_interfaces/Time stamp\nstring frame_id\n"},
      {"std_msgs/msg/ColorRGBA", "float32 r\nfloat32 g\nfloat32 b\nfloat32 a\n"},
      {"geometry_msgs/msg/Point", "float64 x\nfloat64 y\nfloat64 z\n"},
      {"geometry_msgs/msg/Vector3", "float64 x\nfloat64 y\nfloat64 z\n"},
      {"geometry_msgs/msg/Quaternion", "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n"},
      {"geometry_msgs/msg/Pose", "Point position\nQuaternion orientation\n"},
      {"geometry_msgs/msg/PoseWithCovariance", "Pose pose\nfloat64[36] covariance\n"},
      {"geometry_msgs/msg/Twist", "Vector3 linear\nVector3 angular\n"},
      {"geometry_msgs/msg/TwistWithCovariance", "Twist twist\nfloat64[36] covariance\n"},
      {"geometry_msgs/msg/Transform", "Vector3 translation\nQuaternion rotation\n"},
      {"geometry_msgs/msg/TransformStamped", "std_msgs/Header header\nstring child_frame_id\nTransform transform\n"},
      {"geometry_msgs/msg/PoseStamped", "std_msgs/Header header\nPose pose\n"},
      {"geometry_msgs/msg/PoseWithCovarianceStamped", "std_msgs/Header header\nPoseWithCovariance pose\n"},
      {"nav_msgs/msg/Odometry",
       "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
       "geometry_msgs/TwistWithCovariance twist\n"},
      {"tf2_msgs/msg/TFMessage", "geometry_msgs/TransformStamped[] transforms\n"},
      {"sensor_msgs/msg/PointField",
       "uint8 INT8 = 1\nuint8 UINT8 = 2\nuint8 INT16 = 3\nuint8 UINT16 = 4\nuint8 INT32 = 5\nuint8 UINT32 = 6\n"
       "uint8 FLOAT32 = 7\nuint8 FLOAT64 = 8\nstring name\nuint32 offset\nuint8 datatype\nuint32 count\n"},
      {"sensor_msgs/msg/PointCloud2",
       "std_msgs/Header header\nuint32 height\nuint32 width\nPointField[] fields\nbool is_bigendian\nuint32 point_step\n"
       "uint32 row_step\nuint8[] data\nbool is_dense\n"},
      {"visualization_msgs/msg/Marker",
       "int32 ARROW=0\nint32 CUBE=1\nint32 SPHERE=2\nint32 CYLINDER=3\nint32 LINE_STRIP=4\nint32 LINE_LIST=5\n"
       "int32 CUBE_LIST=6\nint32 SPHERE_LIST=7\nint32 POINTS=8\nint32 TEXT_VIEW_FACING=9\nint32 MESH_RESOURCE=10\n"
       "int32 TRIANGLE_LIST=11\nint32 ADD=0\nint32 MODIFY=0\nint32 DELETE=2\nint32 DELETEALL=3\n"
       "std_msgs/Header header\nstring ns\nint32 id\nint32 type\nint32 action\ngeometry_msgs/Pose pose\n"
       "geometry_msgs/Vector3 scale\nstd_msgs/ColorRGBA color\nbuiltin_interfaces/Duration lifetime\nbool frame_locked\n"
       "geometry_msgs/Point[] points\nstd_msgs/ColorRGBA[] colors\nstring text\nstring mesh_resource\n"
       "bool mesh_use_embedded_materials\n"},
      {"visualization_msgs/msg/MarkerArray", "Marker[] markers\n"},
      // ros-drivers/velodyne's messages (velodyne_msgs), for `simulate --packets`.
      {"velodyne_msgs/msg/VelodynePacket", "builtin_interfaces/Time stamp\nuint8[1206] data\n"},
      {"velodyne_msgs/msg/VelodyneScan", "std_msgs/Header header\nVelodynePacket[] packets\n"},
  };
  return d;
}

const std::set<std::string> kPrimitives = {"bool",  "byte",   "char",   "int8",    "uint8",   "int16",  "uint16", "int32",
                                           "uint32", "int64", "uint64", "float32", "float64", "string", "wstring"};

// "pkg/msg/Type" of a field's type as written in `package`'s .msg ("Pose", "std_msgs/Header").
std::string fullName(std::string type, const std::string& package) {
  const auto bracket = type.find('[');
  if (bracket != std::string::npos) type.erase(bracket);
  if (kPrimitives.count(type)) return "";
  const auto slash = type.find('/');
  if (slash == std::string::npos) return package + "/msg/" + type;
  return type.substr(0, slash) + "/msg/" + type.substr(slash + 1);
}

std::vector<std::string> dependencies(const std::string& type) {
  std::vector<std::string> out;
  const std::string package = type.substr(0, type.find('/'));
  std::istringstream lines(definitions().at(type));
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string field_type, name;
    words >> field_type >> name;
    if (field_type.empty() || line.find('=') != std::string::npos) continue;  // constants
    const std::string dep = fullName(field_type, package);
    if (!dep.empty()) out.push_back(dep);
  }
  return out;
}

}  // namespace

std::string ros2msgDefinition(const std::string& type) {
  if (!definitions().count(type)) throw std::invalid_argument("no ros2msg definition of " + type);
  std::string text = definitions().at(type);
  // Depth first, each type once, in the order of first use (as rosbag2's message definition cache).
  std::vector<std::string> order;
  std::set<std::string> seen{type};
  std::vector<std::string> stack = dependencies(type);
  std::reverse(stack.begin(), stack.end());
  while (!stack.empty()) {
    const std::string t = stack.back();
    stack.pop_back();
    if (!seen.insert(t).second) continue;
    order.push_back(t);
    auto deps = dependencies(t);
    std::reverse(deps.begin(), deps.end());
    stack.insert(stack.end(), deps.begin(), deps.end());
  }
  // "MSG: std_msgs/Header": the name as the fields spell it (rosbag2's Humble MCAP plugin and
  // @foxglove/rosmsg resolve a field's type against it letter for letter).
  for (const auto& t : order) {
    std::string name = t;
    name.erase(name.find("/msg/"), 4);
    text += std::string(80, '=') + "\nMSG: " + name + "\n" + definitions().at(t);
  }
  return text;
}

}  // namespace bimloc::sim::ros2
