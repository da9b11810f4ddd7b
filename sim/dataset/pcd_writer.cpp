#include "sim/dataset/pcd_writer.hpp"

#include "sim/dataset/velodyne_points.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace bimloc::sim {

std::string pcdHeader(std::size_t point_count) {
  std::string fields, sizes, types, counts;
  for (const PointFieldLayout& f : velodynePointFields()) {
    fields += std::string(" ") + f.name;
    sizes += " " + std::to_string(f.size_bytes);
    types += f.type == PointFieldType::kFloat32 ? " F" : " U";
    counts += " 1";
  }
  const std::string n = std::to_string(point_count);
  // An unorganised cloud (HEIGHT 1) as the driver publishes it; the points are in the
  // sensor frame, hence the identity viewpoint.
  return "# .PCD v0.7 - Point Cloud Data file format\n"
         "VERSION 0.7\n"
         "FIELDS" + fields + "\n"
         "SIZE" + sizes + "\n"
         "TYPE" + types + "\n"
         "COUNT" + counts + "\n"
         "WIDTH " + n + "\n"
         "HEIGHT 1\n"
         "VIEWPOINT 0 0 0 1 0 0 0\n"
         "POINTS " + n + "\n"
         "DATA binary\n";
}

void writePcd(const std::string& path, const std::vector<LidarPoint>& points) {
  // A plain write, not writeFileAtomically: the file sits in the staging directory, which
  // becomes visible only as a whole, and an fsync per turn would dominate the run time.
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(path + ": cannot create: " + std::strerror(errno));
  const std::string header = pcdHeader(points.size());
  const std::vector<std::uint8_t> data = packVelodynePoints(points);
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  out.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
  out.close();
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace bimloc::sim
