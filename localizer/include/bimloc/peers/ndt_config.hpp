// An HDL-style NDT localizer (hdl_localization + hdl_global_localization) as the paper's
// second baseline. Defaults from ../shared/reference.md, "Baselines", and the two packages'
// own configs (hdl_global_localization config/bbs_config.yaml, hdl_localization's launch file).
#pragma once

namespace bimloc::peers {

struct NdtConfig {
  // The map: points sampled from the storey mesh (every element, floor and ceiling).
  double map_spacing_m = 0.1;  // spacing of the samples on each triangle

  // Tracking: pcl::NormalDistributionsTransform, scan to map, odometry predicts.
  double ndt_resolution_m = 1.0;  // hdl_localization ndt_resolution; PCL's default
  double ndt_step_size_m = 0.1;   // PCL's default (More-Thuente line search, max step)
  int ndt_max_iterations = 35;    // PCL's default
  // hdl_localization's transformation epsilon (0.01); PCL 1.13 compares it with the squared
  // translation of the last step, so we pass its square: the last step moved < this.
  double ndt_epsilon_m = 0.01;
  double downsample_m = 0.1;      // hdl_localization downsample_resolution (voxel grid)
  // Then at most this many of them (every k-th, in the voxel grid's order): our departure from
  // hdl_localization, for the bench's 10x real time on one core; NDT's 1 m cells stay well
  // filled (a turn indoors keeps ~10k points after the voxel grid).
  int ndt_max_points = 3000;
  double max_range_m = 15.0;      // scan points beyond this are dropped (hdl_global_localization bbs/max_range)
  // Registration gates (as AMCL's update_min_d / update_min_a): a turn is registered only when
  // the odometry moved or turned this much since the last registered one (a VLP-16 turn is
  // ~29k points at 10 Hz; between gates odometry carries the pose).
  double update_min_d_m = 0.2;
  double update_min_a_rad = 0.1745329;  // 10 deg
  // Fitness = mean squared distance of the scan's points to their nearest map point, over the
  // points within fitness_max_distance_m (PCL's getFitnessScore with a max range), and the
  // share of the points that are within it.
  double fitness_max_distance_m = 1.0;
  double max_fitness_m2 = 0.02;      // a registration is good below this ...
  double min_inlier_fraction = 0.6;  // ... with at least this share of points matched
  int lost_after_bad_scans = 5;      // this many bad registrations in a row: global search again

  // Global localization: branch-and-bound over a 2D grid pyramid (hdl_global_localization BBS).
  double grid_resolution_m = 0.5;  // bbs/map_resolution
  int pyramid_levels = 6;          // bbs/map_pyramid_level
  // The slice of the scan, relative to the lidar (bbs/scan_min_z, bbs/scan_max_z); the map's
  // slice is the same band at the lidar's height above the floor (hdl's map_min_z/map_max_z
  // 2.0/2.4 m is that band for its car-mounted lidar): base_height_m + the mount's z.
  double scan_min_z_m = -0.2;
  double scan_max_z_m = 0.2;
  double base_height_m = 0.5;  // base_link above the floor (Spot standing; the simulator's body_height_m)
  // The scan slice the search matches: the slices of the registered turns of the last
  // global_window_m of travel, stitched by odometry (one turn of a 2D band is a single room's
  // outline, and rooms look alike); the search runs every global_period_s while searching.
  double global_window_m = 3.0;
  double global_period_s = 1.0;
  int min_scan_cells = 20;  // fewer scan cells in the window: no search (hdl: 32 points)
  // The search's own criterion: the share of scan cells that hit occupied map cells at the
  // best pose, and its margin over the best distinct pose (> distinct_m or > distinct_deg
  // away), as a share of the scan cells. Then the NDT fitness from that pose decides.
  double min_hit_fraction = 0.7;
  // 0.2: at 0.1 a start in R105 of the default world converged on a twin place (measured).
  double min_margin_fraction = 0.2;
  double distinct_m = 1.0;
  double distinct_deg = 20.0;
};

}  // namespace bimloc::peers
