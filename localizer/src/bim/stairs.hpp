// The plan's stairs and ramps as flights (stairs.cpp): pure functions of the RawModel, tested
// without any IFC file.
#pragma once

#include "raw_model.hpp"

#include <bimloc/bim/building.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::bim::detail {

// The upward horizontal faces of a body grouped by height (within 1 cm), lowest first; with
// either_side, the downward ones too (for open shells, whose faces may face either way).
struct TreadLevel {
  double z_m = 0.0;
  double area_m2 = 0.0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();  // area centroid in world XY
  std::vector<Eigen::Vector2d> corners;               // its triangles' corners
};
std::vector<TreadLevel> treadLevels(const TriangleMesh& body, bool either_side = false);

// A flight's numbers from its body alone: the treads are its horizontal upward faces.
struct BodyFlight {
  Eigen::Vector3d bottom = Eigen::Vector3d::Zero(), top = Eigen::Vector3d::Zero();  // as StairFlight's
  int risers = 0;
  double riser_height_m = 0.0, going_m = 0.0, width_m = 0.0;
};
// `floors`: the heights a flight may start or end on (storeys' elevations, landings' tops): they
// tell whether the body's highest step face is the top floor or the last tread below it.
// Nothing, with the reason in `problem`, when the body is not a flight of steps.
std::optional<BodyFlight> flightFromBody(const TriangleMesh& body, const std::vector<double>& floors,
                                         std::string& problem);
// The same from the faces facing up (either_side false) or from the horizontal ones facing either
// way; flightFromBody tries the second when the first finds no flight.
std::optional<BodyFlight> flightFromFaces(const TriangleMesh& body, const std::vector<double>& floors, bool either_side,
                                          std::string& problem);

// A ramp's (IfcRamp, IfcRampFlight) run line and width from its sloped walking surface (faces
// up, 0.5° to 25°): from its lowest edge to its highest along the slope, at mid width; risers,
// riser height and going stay 0 (the slope is rise / run).
std::optional<BodyFlight> rampFromBody(const TriangleMesh& body, std::string& problem);

// One flight (an IfcStairFlight, or a whole IfcStair read from its body; a ramp from its slope):
// the body gives the run line, width and a first count; the attributes replace the numbers where
// they are sane and agree with the body. `problem` says why it is unusable (nothing returned) or what was ignored.
std::optional<StairFlight> stairFlightOf(const RawProduct& flight, const TriangleMesh& body,
                                         const std::vector<double>& floors, std::string& problem);

// Index of the storey (of `storeys`, in height order) whose elevation is within 0.2 m of z,
// the closest; -1 when none is (a landing between storeys).
int storeyAt(double z, const std::vector<Storey>& storeys);

// Every flight of the plan's stairs and ramps, in the stairs' file order. `body_of` gives an
// element's mesh (IFC++'s, or the one rebuilt from its extrusion). Each unusable flight is
// named in `warnings`, and counted in a last one.
std::vector<StairFlight> stairFlightsOf(const RawModel& raw, const std::vector<Storey>& storeys,
                                        const std::function<const TriangleMesh&(const RawProduct&)>& body_of,
                                        std::vector<std::string>& warnings);

}  // namespace bimloc::bim::detail
