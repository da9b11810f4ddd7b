// RANSAC's inner loop: how many points lie within a plane's band. The sequential RANSAC of
// plane_extraction.cpp scores every hypothesis over the whole pool (up to 500 a plane, 60
// attempts a scan), so this count is most of the plane extraction's RANSAC.
#pragma once

#include <cstddef>
#include <vector>

namespace bimloc::planes::detail {

// The number of points i in [0, n) with |r_i| < t, where the residual r_i is computed in float
// as (a x_i + b y_i) + (c z_i + d) for i < 4 floor(n / 4) and as ((a x_i + b y_i) + c z_i) + d
// for the (at most 3) last ones: the same numbers whatever the vector width (SSE2, or AVX2
// where the processor has it; neither fuses a multiply and an add).
// RANSAC keeps a hypothesis only when it counts more than the best so far (`best`): once the
// points left cannot lift the count above it, the count stops and returns what it has, a
// number <= best, which RANSAC discards as it would the full count. Larger than best, the
// count is exact.
std::size_t countInBand(const float* x, const float* y, const float* z, std::size_t n, float a, float b, float c, float d,
                        float t, std::size_t best);

// The same count, point by point in plain C++ (the reference the tests hold it to).
std::size_t countInBandPlain(const float* x, const float* y, const float* z, std::size_t n, float a, float b, float c, float d,
                             float t);

// The indices i (ascending) of the points with !(|r_i| > t), the residual r_i computed in float
// as Eigen's n.dot(p) + d for 3-vectors: (n_x x_i + (n_y y_i + n_z z_i)) + d, eight points at a
// time where AVX2 is (the raw returns near a plane: every return of the scan, for every
// candidate plane). Appended to `out`.
void indicesInBand(const float* x, const float* y, const float* z, std::size_t n, float nx, float ny, float nz, float d, float t,
                   std::vector<int>& out);

// RANSAC's last step, the inliers of the plane it chose (PCL's
// SampleConsensusModelPlane::selectWithinDistance, about 14 ns a point through its indices):
// ids[i] for the points with |r_i| < t, t in double, the residual r_i computed in float as PCL's
// build computes the dot of its coefficients with (x, y, z, 1) (Eigen's SSE reduction of one
// 4-float packet, objdump of libpcl_sample_consensus 1.13: mulps, movhlps + addps, shufps +
// addss): (a x_i + c z_i) + (b y_i + d). Appended to `ids_out`, with |r_i| to `distances`.
void pclPlaneInliers(const float* x, const float* y, const float* z, const int* ids, std::size_t n, float a, float b, float c,
                     float d, double t, std::vector<int>& ids_out, std::vector<double>& distances);

}  // namespace bimloc::planes::detail
