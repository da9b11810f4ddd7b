// A wall node of the metric-semantic layer and the planes of its faces, as functions of the
// node's three parameters, templated so that Ceres can differentiate them (autodiff).
//
// A plan wall is one rigid body with two faces (paper Eq. 1 and 2): its node estimates how it
// stands relative to its plan position, minimally, with three numbers:
//   s      shift of the wall along faces[0]'s normal e (m),
//   alpha  rotation about the vertical line through the wall's centre c (rad, CCW),
//   tau    change of thickness, shared equally by the two faces (m).
// Face k (side sigma = +1 for faces[0], -1 for faces[1]) lies at offset h_k from c along e:
//   n_k = sigma R(alpha) e,   d_k = -sigma (R(alpha) e . c + h_k + s) - tau / 2.
// With s = alpha = tau = 0 this is the plan's face (n_k . m_k + d_k = 0 for a point m_k of it).
// Rotating about the centre instead of the map's origin keeps s and alpha decoupled: a wall
// far from the origin would otherwise shift by a lever arm for every bit of rotation.
// A new plane (not in the plan) uses the same form with one face, c a point of it and tau
// held at zero.
#pragma once

#include <bimloc/geometry/planar_pose.hpp>

#include <Eigen/Core>
#include <cmath>

namespace bimloc::sgraph::detail {

using bimloc::wrapAngle;  // doubles and Ceres jets: geometry/planar_pose.hpp

// What one face of a node needs to give its plane: constants of the plan, and which side.
struct FaceGeometry {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();    // c: the rotation centre of the node
  Eigen::Vector2d e = Eigen::Vector2d::UnitX();        // faces[0]'s normal (unit, horizontal)
  double h = 0;                                        // the face's offset from c along e
  double side = 1;                                     // +1 faces[0], -1 faces[1]

  // The face's plane n·p + d = 0 in the map (n horizontal: n[0], n[1]) for node params p.
  template <typename T>
  void plane(const T* p, T n[2], T& d) const {
    using std::cos, std::sin;
    const T ca = cos(p[1]), sa = sin(p[1]);
    const T rx = ca * e.x() - sa * e.y(), ry = sa * e.x() + ca * e.y();  // R(alpha) e
    n[0] = side * rx;
    n[1] = side * ry;
    d = -side * (rx * centre.x() + ry * centre.y() + h + p[0]) - p[2] / 2.0;
  }

  // Signed distance of a map point to the face (positive in front of it, where it is seen).
  template <typename T>
  T distance(const T* p, const T& x, const T& y) const {
    T n[2], d;
    plane(p, n, d);
    return n[0] * x + n[1] * y + d;
  }
};

}  // namespace bimloc::sgraph::detail
