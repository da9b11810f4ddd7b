// What a user of the installed library writes: read a plan, build a bimloc::Localizer, feed it
// one lidar turn. The turn is synthetic: the walls of the plan's first room seen from its centre
// (a box room for a rectangular footprint), points every 5 cm along each wall, 0.1 m to 2.5 m
// above the floor, in the lidar frame. Prints one line the install test checks.
#include <bimloc/bim/ifc_reader.hpp>
#include <bimloc/localizer.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <exception>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer PLAN.ifc\n");
    return 2;
  }
  try {
    bimloc::bim::ExtractOptions options;
    options.build_meshes = false;  // the localizer's methods here need walls and rooms only
    const bimloc::bim::Building building = bimloc::bim::readIfc(argv[1], options);
    const bimloc::bim::Storey* storey = nullptr;
    for (const auto& s : building.storeys)
      if (!s.rooms.empty() && !s.walls.empty()) {
        storey = &s;
        break;
      }
    if (storey == nullptr) {
      std::fprintf(stderr, "consumer: no storey with rooms and walls in %s\n", argv[1]);
      return 1;
    }
    const bimloc::bim::Room& room = storey->rooms.front();

    const double lidar_height_m = 0.5;
    Eigen::Isometry3d T_base_lidar = Eigen::Isometry3d::Identity();
    T_base_lidar.translation().z() = lidar_height_m;
    const Eigen::Vector3d lidar_in_map(room.centre.x(), room.centre.y(), room.floor_z + lidar_height_m);

    std::vector<Eigen::Vector3f> points;
    const auto& polygon = room.footprint;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const Eigen::Vector2d a = polygon[i], b = polygon[(i + 1) % polygon.size()];
      const int steps = static_cast<int>(std::ceil((b - a).norm() / 0.05));
      for (int k = 0; k < steps; ++k)
        for (double z = 0.1; z <= 2.5; z += 0.05) {
          const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(k) / steps);
          points.emplace_back((Eigen::Vector3d(p.x(), p.y(), room.floor_z + z) - lidar_in_map).cast<float>());
        }
    }

    bimloc::LocalizerConfig config;
    config.storey = storey->name;
    config.seed = 1;
    bimloc::Localizer localizer(building, T_base_lidar, config);
    const bimloc::LocalizationResult r = localizer.step(0.0, Eigen::Isometry3d::Identity(), points);
    std::printf("bimloc consumer: plan=%zu storeys room=%s points=%zu state=%s used_points=%d walls_observed=%d\n",
                building.storeys.size(), room.name.c_str(), points.size(), bimloc::toString(r.state),
                r.used_points ? 1 : 0, r.walls_observed);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
