// The free space of one level of a storey, split into regions at the doorways.
#include "room_raster.hpp"

#include <bimloc/bim/room_inference.hpp>

#include <cmath>

namespace bimloc::bim::detail {

Segmentation segmentFreeSpace(const std::vector<Polygon2>& obstacles, const RoomInferenceConfig& config) {
  Segmentation out;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  for (const auto& polygon : obstacles)
    for (const auto& p : polygon)
      if (p.allFinite()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (!(lo.x() <= hi.x())) return out;

  // The raster covers the walls and a margin wider than the rolling disk (see outside), so that the
  // outside reaches around the building.
  Raster& raster = out.raster;
  raster.cell_m = config.cell_m;
  const auto fit = [&] {
    const double margin = 0.5 * config.envelope_gap_m + 4.0 * raster.cell_m;
    raster.origin = lo - Eigen::Vector2d::Constant(margin);
    raster.width = int(std::ceil((hi.x() - lo.x() + 2 * margin) / raster.cell_m));
    raster.height = int(std::ceil((hi.y() - lo.y() + 2 * margin) / raster.cell_m));
  };
  fit();
  while (raster.size() > config.max_cells) {
    raster.cell_m *= std::sqrt(double(raster.size()) / double(config.max_cells)) * 1.01;
    fit();
    out.coarsened = true;
  }
  const double cell = raster.cell_m;

  Mask walls(raster.size(), 0);
  for (const auto& polygon : obstacles) fillPolygon(raster, polygon, walls);
  // Walls that don't quite meet: gaps up to max_gap_m closed.
  const Mask closed = closing(raster, walls, 0.5 * config.max_gap_m / cell);
  Mask free(raster.size());
  for (std::size_t k = 0; k < free.size(); ++k) free[k] = !closed[k];
  // Clearance: from a free cell's centre to the nearest wall cell's centre, so a passage of
  // width w has clearance about w / 2 + half a cell at its middle.
  out.clearance_d2 = squaredDistance(raster, closed);
  const auto& d2 = out.clearance_d2;

  // Outside: where a disk of diameter envelope_gap_m rolling in from the border reaches. It
  // does not pass a gap narrower than that (entrances modelled as a gap, windows of a curtain
  // wall at the probe height, a split-level's stair opening): the building's inside is closed.
  const double envelope_r = 0.5 * config.envelope_gap_m / cell;
  Mask fits(raster.size());
  for (std::size_t k = 0; k < fits.size(); ++k) fits[k] = d2[k] > (envelope_r + 0.5) * (envelope_r + 0.5);
  const auto to_centres = squaredDistance(raster, reachedFromBorder(raster, fits));
  Mask exterior(raster.size());
  for (std::size_t k = 0; k < exterior.size(); ++k) exterior[k] = free[k] && to_centres[k] <= envelope_r * envelope_r;
  // The outside's marker keeps off the walls by half the disk: near a gap, the watershed, not
  // the disk's edge, puts the boundary, at the gap's narrowest line.
  const double marker_r = 0.5 * envelope_r;

  // Seeds: inside, and farther from every wall than half a door: a doorway separates them.
  Labels& labels = out.labels;
  labels.assign(raster.size(), 0);
  Mask seeds(raster.size(), 0);
  const double door = 0.5 * config.door_width_m / cell + 0.5;
  for (std::size_t k = 0; k < labels.size(); ++k) {
    if (exterior[k] && to_centres[k] <= marker_r * marker_r) labels[k] = kExteriorLabel;
    seeds[k] = free[k] && !exterior[k] && d2[k] > door * door;
  }
  std::int32_t next = labelComponents(raster, seeds, labels, kExteriorLabel + 1);
  // Every seed, and the exterior, grows back into the free space; basins meet at doorways.
  watershed(raster, free, d2, labels);
  // Enclosed pockets no seed reached (closets narrower than a door) are regions of their own.
  Mask pockets(raster.size());
  for (std::size_t k = 0; k < pockets.size(); ++k) pockets[k] = free[k] && labels[k] == 0;
  out.regions_end = labelComponents(raster, pockets, labels, next);
  return out;
}

}  // namespace bimloc::bim::detail
