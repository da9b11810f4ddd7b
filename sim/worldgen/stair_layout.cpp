#include "sim/worldgen/stair_layout.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::worldgen {
namespace {

constexpr double kStairTol_m = 1e-9;

std::vector<Eigen::Vector2d> wellRectangle(const StairWell& w, double u0, double u1, double v0, double v1) {
  const auto at = [&](double u, double v) -> Eigen::Vector2d { return w.origin + w.inward * u + w.across * v; };
  std::vector<Eigen::Vector2d> out = {at(u0, v0), at(u1, v0), at(u1, v1), at(u0, v1)};
  double twice = 0.0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto& a = out[i];
    const auto& b = out[(i + 1) % out.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  if (twice < 0) std::reverse(out.begin(), out.end());
  return out;
}

}  // namespace

int risersPerFlight(double storey_height_m, const StairDimensions& d) {
  return static_cast<int>(std::ceil(storey_height_m / (2 * d.max_riser_m) - kStairTol_m));
}

double stairwellDepth(double storey_height_m, double flight_width_m, const StairDimensions& d) {
  return d.floor_landing_m + (risersPerFlight(storey_height_m, d) - 1) * d.going_m + flight_width_m;
}

std::optional<FittedStair> fitHalfTurnStair(const StairWell& well, double storey_height_m, bool first_on_low_side,
                                            const std::string& name, const StairDimensions& d) {
  const double flight_width = std::min(d.max_flight_width_m, (well.width_m - d.eye_m) / 2);
  if (flight_width < d.min_flight_width_m - kStairTol_m) return std::nullopt;
  const int n = risersPerFlight(storey_height_m, d);
  const double riser = storey_height_m / (2 * n);
  const double run = (n - 1) * d.going_m;
  const double u_top = well.depth_m - flight_width;  // the half landing's front edge
  const double u_start = u_top - run;                // the first flight's first riser
  if (u_start < d.floor_landing_m - kStairTol_m) return std::nullopt;
  const double v_low = flight_width / 2, v_high = well.width_m - flight_width / 2;
  const auto at = [&](double u, double v) -> Eigen::Vector2d { return well.origin + well.inward * u + well.across * v; };

  FittedStair out;
  out.stair.name = name;
  StairFlightSpec up;
  up.name = name + " flight 1";
  up.start = at(u_start, first_on_low_side ? v_low : v_high);
  up.direction = well.inward;
  up.z_m = 0.0;
  up.width_m = flight_width;
  up.risers = n;
  up.riser_m = riser;
  up.going_m = d.going_m;
  StairFlightSpec back = up;
  back.name = name + " flight 2";
  back.start = at(u_top, first_on_low_side ? v_high : v_low);
  back.direction = -well.inward;
  back.z_m = n * riser;
  out.stair.flights = {up, back};
  LandingSpec landing;
  landing.name = name + " landing";
  landing.outline = wellRectangle(well, u_top, well.depth_m, 0.0, well.width_m);
  landing.top_z_m = n * riser;
  landing.thickness_m = d.landing_thickness_m;
  out.stair.landings = {landing};
  out.void_outline = wellRectangle(well, u_start, well.depth_m, 0.0, well.width_m);
  return out;
}

}  // namespace bimloc::worldgen
