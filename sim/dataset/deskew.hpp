// Motion de-skew of a lidar turn: a spinning lidar on a moving robot measures each point from
// where the sensor was at that point's firing, so a turn taken while walking or turning is
// bent. With the per-point `time` of the Velodyne driver and the odometry over the turn,
// every point is moved into the sensor frame at one reference instant (the turn's middle, the
// stamp the localizer is given), as LIO-SAM's deskewPoint does with its IMU/odometry.
#pragma once

#include "sim/dataset/dataset_reader.hpp"
#include "sim/lidar/lidar_scan.hpp"

#include <Eigen/Geometry>
#include <vector>

namespace bimloc::sim {

// odom <- base_link at t, interpolated between the two samples around t (linear in
// translation, slerp in rotation); the first or last sample outside their span.
// `samples` sorted by stamp, not empty.
Eigen::Isometry3d interpolatePose(const std::vector<StampedPose>& samples, double t);

// Moves each point, measured at stamp_s + time_s[i] in the lidar frame of that instant, into
// the lidar frame at reference_s: p' = (T_odom_lidar(ref))^-1 T_odom_lidar(t_i) p, with
// T_odom_lidar(t) = T_odom_base(t) T_base_lidar. `time_s` has one value per point.
// With cycle_s > 0, the points of one firing cycle (times in [c cycle_s, (c + 1) cycle_s),
// c an integer) are moved with the pose at the cycle's start, c cycle_s: one interpolated pose
// per cycle instead of per firing (see deskewedTurn).
void deskew(std::vector<Eigen::Vector3f>& points, const std::vector<double>& time_s, double stamp_s, double reference_s,
            const std::vector<StampedPose>& odometry, const Eigen::Isometry3d& T_base_lidar, double cycle_s = 0.0);

// A simulated turn's x, y, z (the bench's loop), de-skewed with its per-point `time` into the
// lidar frame at reference_s; `odometry`: the base's readings over the turn (never the truth).
// As the turn is cast when `odometry` is empty.
// With cycle_s > 0 (the bench's VLP-16: kVlp16CyclePeriod_s), one pose per firing cycle, the
// pose at the cycle's start: the simulator casts each cycle from the base's pose at that
// instant (vlp16.cpp), so the cycle's 16 firings (34.6 us) share the motion they are undone
// by. Per firing, the de-skew interpolated 16 poses a cycle that differ by at most the odometry's
// motion over 34.6 us (35 urad at 1 rad/s: 0.35 mm at 10 m), at a sixteenth of the cost.
std::vector<Eigen::Vector3f> deskewedTurn(const LidarScan& scan, const std::vector<StampedPose>& odometry, double reference_s,
                                          const Eigen::Isometry3d& T_base_lidar, double cycle_s = 0.0);

}  // namespace bimloc::sim
