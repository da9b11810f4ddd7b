// The occupancy raster behind room inference: a storey's plan on a square grid, and the few
// morphological operations the inference needs (exact Euclidean distances, closings,
// connected components, a marker-based watershed, outlines). Internal to localizer/bim.
#pragma once

#include <bimloc/bim/geometry2d.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace bimloc::bim::detail {

using Mask = std::vector<std::uint8_t>;  // one byte per cell, row-major, 0 or 1
using Labels = std::vector<std::int32_t>;

struct Raster {
  int width = 0;
  int height = 0;
  double cell_m = 0.05;
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // world XY of cell (0, 0)'s lower-left corner

  std::size_t size() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * width + i; }
  Eigen::Vector2d corner(int i, int j) const { return origin + cell_m * Eigen::Vector2d(i, j); }
  Eigen::Vector2d centre(std::size_t k) const {
    return origin + cell_m * Eigen::Vector2d(double(k % width) + 0.5, double(k / width) + 0.5);
  }
};

// Marks the cells whose centre lies inside the polygon (even-odd rule, any simple polygon).
void fillPolygon(const Raster& raster, const Polygon2& polygon, Mask& mask);

// Squared distance, in cells, from every cell centre to the nearest cell centre of `feature`
// (0 on feature cells); exact (Felzenszwalb and Huttenlocher), integers, so deterministic.
std::vector<std::int32_t> squaredDistance(const Raster& raster, const Mask& feature);

// Morphological closing of `mask` by a disk of radius_cells: gaps narrower than about twice
// the radius are filled, straight edges stay where they are.
Mask closing(const Raster& raster, const Mask& mask, double radius_cells);

// The cells of `passable` 4-connected to the raster's border.
Mask reachedFromBorder(const Raster& raster, const Mask& passable);

// 4-connected components of the set cells, labelled first_label, first_label + 1, ... in
// raster order; other cells keep their label in `labels`. Returns the next free label.
std::int32_t labelComponents(const Raster& raster, const Mask& cells, Labels& labels, std::int32_t first_label);

// Grows the labelled cells (label > 0) into the unlabelled cells of `free`, highest distance
// to the walls first (priority flood): neighbouring basins meet at the narrowest passage.
void watershed(const Raster& raster, const Mask& free, const std::vector<std::int32_t>& d2, Labels& labels);

// Outer boundary of the 4-connected region with this label, along cell edges, counter-
// clockwise, in world coordinates, without collinear vertices.
Polygon2 regionOutline(const Raster& raster, const Labels& labels, std::int32_t label);

}  // namespace bimloc::bim::detail

namespace bimloc::bim {
struct RoomInferenceConfig;
}

namespace bimloc::bim::detail {

// The free space of one level split into regions (rooms before filtering): labels > 1 are
// regions, 1 the exterior, 0 walls. See room_inference.cpp for the steps.
struct Segmentation {
  Raster raster;
  Labels labels;
  std::int32_t regions_end = 2;            // regions are labelled 2 .. regions_end - 1
  std::vector<std::int32_t> clearance_d2;  // squared distance in cells to the nearest wall cell
  bool coarsened = false;                  // coarser than config.cell_m (too many cells)
};
constexpr std::int32_t kExteriorLabel = 1;

Segmentation segmentFreeSpace(const std::vector<Polygon2>& obstacles, const RoomInferenceConfig& config);

}  // namespace bimloc::bim::detail
