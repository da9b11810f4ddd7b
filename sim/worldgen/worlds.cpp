#include "sim/worldgen/worlds.hpp"

#include "sim/worldgen/storey_builder.hpp"

#include <cmath>
#include <stdexcept>

namespace bimloc::worldgen {
namespace {

using Eigen::Vector2d;

constexpr double kDoorHeight_m = 2.1;

// Four exterior walls around the clear interior [0, w] × [0, h]: the south and north walls
// run the full length over the corners, the west and east walls fit between them.
void rectangularShell(StoreyBuilder& b, const std::string& prefix, double w, double h,
                      double t) {
  b.outline(boxOutline(-t, -t, w + t, h + t));
  b.wallX(prefix + "EXT-S", -t / 2, -t, w + t, t, true);
  b.wallX(prefix + "EXT-N", h + t / 2, -t, w + t, t, true);
  b.wallY(prefix + "EXT-W", -t / 2, 0.0, h, t, true);
  b.wallY(prefix + "EXT-E", w + t / 2, 0.0, h, t, true);
}

// One storey: a 2 m corridor along x between two rows of four identical 4 m × 5 m offices.
// Every office is the same room turned about: facing its door from inside, the door is
// 0.8 m from the right-hand corner. The building as a whole is not symmetric: the entrance
// is in the plain west end wall, while at the east end the corridor widens into a 5 m deep
// lobby that reaches the north wall but stops 2 m south of the corridor, at a WC and a store
// room in the south-east corner. So once out of an office, a lidar tells east from west and
// north from south by the walls alone.
WorldSpec siteOffice() {
  const double ext = 0.30, in = 0.12;              // wall thicknesses
  const double room_w = 4.0, room_d = 5.0, corridor = 2.0;
  const int per_side = 4;
  const double pitch = room_w + in;                // x from one office to the next
  const double offices = per_side * room_w + (per_side - 1) * in;  // office rows, 16.36 m
  // The walls between the office rows and the lobby (DIV-S4, DIV-N4) are 0.24 m double
  // partitions. Also, tests/test_worlds.cpp wants wall thicknesses within 1e-6 m from float
  // meshes, and beyond x = 16 m a float step is 1.9e-6 m: 0.12 m faces at x = 16.36 and 16.48
  // round to 1.07e-6 m off, 16.36 and 16.60 to 2.3e-7 m.
  const double lobby_wall = 0.24;
  const double x_lobby = offices + lobby_wall;     // west face of the lobby, 16.60 m
  const double lobby = 5.0;                        // lobby depth along x
  const double width = x_lobby + lobby;            // clear, 21.60 m
  const double y_corr = room_d + in, y_north = y_corr + corridor + in;
  const double depth = y_north + room_d;           // clear, 12.24 m
  const double wc_d = 3.0;                         // WC and store: y from 0 to 3
  const double wc_w = 2.4;                         // WC: x from the lobby's west face
  const double x_store = x_lobby + wc_w + in;      // store: x from here to the east wall

  WorldSpec world;
  world.name = "site_office";
  world.description =
      "Construction-site office floor: corridor between 8 identical offices, lobby, WC and store "
      "at the east end";
  world.roof_thickness_m = 0.2;
  world.space_boundaries = true;
  StoreyBuilder b("Ground floor", 0.0, 3.0, 0.2, 3.0 - world.roof_thickness_m);
  rectangularShell(b, "", width, depth, ext);
  // The corridor partitions run on to the lobby's west face, over the tops of DIV-S4 and
  // DIV-N4, so the corridor's corners into the lobby are closed (as in the apartment).
  b.wallX("PART-S", room_d + in / 2, 0.0, x_lobby, in, false);
  b.wallX("PART-N", y_corr + corridor + in / 2, 0.0, x_lobby, in, false);
  for (int k = 1; k < per_side; ++k) {
    const double x = k * pitch - in / 2;
    b.wallY("DIV-S" + std::to_string(k), x, 0.0, room_d, in, false);
    b.wallY("DIV-N" + std::to_string(k), x, y_north, depth, in, false);
  }
  // The fourth dividers close the office rows towards the lobby and reach the corridor.
  const std::string last = std::to_string(per_side);
  b.wallY("DIV-S" + last, offices + lobby_wall / 2, 0.0, y_corr, lobby_wall, false);
  b.wallY("DIV-N" + last, offices + lobby_wall / 2, y_corr + corridor, depth, lobby_wall, false);
  b.wallX("WC-N", wc_d + in / 2, x_lobby, width, in, false);  // WC and store | lobby
  b.wallY("WC-E", x_lobby + wc_w + in / 2, 0.0, wc_d, in, false);  // WC | store
  auto side = [&](const char* row, int k) {  // the wall between office k and k + 1
    return k < 0 ? std::string("EXT-W") : row + std::to_string(k + 1);
  };
  for (int k = 0; k < per_side; ++k) {
    const double x0 = k * pitch;
    const std::string w = side("DIV-S", k - 1), e = side("DIV-S", k);
    b.room("R10" + std::to_string(k + 1), "Office", x0, 0.0, x0 + room_w, room_d,
           {"EXT-S", e.c_str(), "PART-S", w.c_str()});
    b.door("PART-S", x0 + room_w - 0.8, 0.9, kDoorHeight_m);
  }
  for (int k = 0; k < per_side; ++k) {
    const double x0 = k * pitch;
    const std::string w = side("DIV-N", k - 1), e = side("DIV-N", k);
    b.room("R10" + std::to_string(k + 1 + per_side), "Office", x0, y_north, x0 + room_w, depth,
           {"PART-N", e.c_str(), "EXT-N", w.c_str()});
    b.door("PART-N", x0 + 0.8, 0.9, kDoorHeight_m);
  }
  // The corridor and the lobby it opens into are one space: no wall between them.
  b.room("C100", "Corridor",
         {{0.0, y_corr},
          {x_lobby, y_corr},
          {x_lobby, wc_d + in},
          {width, wc_d + in},
          {width, depth},
          {x_lobby, depth},
          {x_lobby, y_corr + corridor},
          {0.0, y_corr + corridor}},
         {"PART-S", "DIV-S4", "WC-N", "EXT-E", "EXT-N", "DIV-N4", "PART-N", "EXT-W"});
  b.room("W100", "WC", x_lobby, 0.0, x_lobby + wc_w, wc_d, {"EXT-S", "WC-E", "WC-N", "DIV-S4"});
  b.room("S100", "Storage", x_store, 0.0, width, wc_d, {"EXT-S", "EXT-E", "WC-N", "WC-E"});
  b.door("EXT-W", y_corr + corridor / 2, 1.0, kDoorHeight_m);  // the entrance
  b.door("WC-N", x_lobby + 1.0, 0.8, kDoorHeight_m);            // lobby - WC
  b.door("WC-N", x_store + 1.0, 0.9, kDoorHeight_m);            // lobby - store
  world.storeys.push_back(b.storey());
  return world;
}

// One storey, clear interior [0, 10] × [0, 8] with the north-east corner cut off by a 45°
// exterior wall along x + y = 15: an L-shaped living room, a pentagonal kitchen under the
// diagonal, bath, hall and bedroom.
WorldSpec apartment() {
  const double ext = 0.25, in = 0.10;
  const double w = 10.0, h = 8.0, cut = 15.0;  // inner face of the diagonal: x + y = cut
  const double r2 = std::sqrt(2.0);
  // Where the diagonal's outer face (x + y = cut + ext·√2) meets the north and east outer
  // faces: the outline corners. The north and east walls end there, and the diagonal wall's
  // square ends pass through them, so the three boxes close the corner without a gap and
  // without sticking out of the outline.
  const Vector2d corner_n(cut + ext * r2 - h - ext, h + ext);
  const Vector2d corner_e(w + ext, cut + ext * r2 - w - ext);
  const Vector2d half_out = Vector2d(1.0, 1.0) / r2 * (ext / 2);

  WorldSpec world;
  world.name = "apartment";
  world.description = "Small apartment: L-shaped living room, kitchen under a 45 degree wall";
  world.roof_thickness_m = 0.2;
  world.space_boundaries = false;
  StoreyBuilder b("Apartment", 0.0, 2.7, 0.2, 2.7 - world.roof_thickness_m);
  b.outline({{-ext, -ext}, {w + ext, -ext}, corner_e, corner_n, {-ext, h + ext}});
  b.wallX("EXT-S", -ext / 2, -ext, w + ext, ext, true);
  b.wallY("EXT-W", -ext / 2, 0.0, h, ext, true);
  b.wallX("EXT-N", h + ext / 2, -ext, corner_n.x(), ext, true);
  b.wallY("EXT-E", w + ext / 2, 0.0, corner_e.y(), ext, true);
  b.wall("EXT-D", corner_n - half_out, corner_e - half_out, ext, true);
  b.wallY("A", 4.0 + in / 2, 0.0, 4.5, in, false);  // living | bath, hall
  b.wallX("B", 4.5 - in / 2, 4.0, w, in, false);    // hall, bedroom | living, kitchen
  b.wallY("C", 6.5 + in / 2, 4.5, h, in, false);    // living | kitchen
  b.wallY("D", 6.5 + in / 2, 0.0, 4.4, in, false);  // bath, hall | bedroom
  b.wallX("E", 2.4 + in / 2, 4.1, 6.5, in, false);  // bath | hall

  b.room("LIV", "Living room", {{0, 0}, {4, 0}, {4, 4.5}, {6.5, 4.5}, {6.5, h}, {0, h}},
         {"EXT-S", "A", "B", "C", "EXT-N", "EXT-W"});
  b.room("KIT", "Kitchen", {{6.6, 4.5}, {w, 4.5}, {w, cut - w}, {cut - h, h}, {6.6, h}},
         {"B", "EXT-E", "EXT-D", "EXT-N", "C"});
  b.room("BATH", "Bathroom", 4.1, 0.0, 6.5, 2.4, {"EXT-S", "D", "E", "A"});
  b.room("HALL", "Hall", 4.1, 2.5, 6.5, 4.4, {"E", "D", "B", "A"});
  b.room("BED", "Bedroom", 6.6, 0.0, w, 4.4, {"EXT-S", "EXT-E", "B", "D"});

  b.door("EXT-S", 2.0, 1.0, kDoorHeight_m);  // entrance into the living room
  b.door("A", 3.45, 0.9, kDoorHeight_m);     // living - hall
  b.door("E", 5.3, 0.8, kDoorHeight_m);      // hall - bath
  b.door("D", 3.45, 0.9, kDoorHeight_m);     // hall - bedroom
  b.door("C", 6.25, 0.9, kDoorHeight_m);     // living - kitchen
  world.storeys.push_back(b.storey());
  return world;
}

// Two storeys of 3 m on the same 12 m × 8 m clear shell, different partitions per floor:
// four rooms downstairs, five upstairs. Floor slabs of 0.2 m, roof slab of 0.2 m.
WorldSpec twoStorey() {
  const double ext = 0.30, in = 0.12, w = 12.0, h = 8.0, storey_h = 3.0, slab = 0.2;
  WorldSpec world;
  world.name = "two_storey";
  world.description = "Two-storey workshop and office building, different layout per floor";
  world.roof_thickness_m = slab;
  world.space_boundaries = true;

  StoreyBuilder g("Ground floor", 0.0, storey_h, slab, storey_h - slab);
  rectangularShell(g, "G-", w, h, ext);
  g.wallY("G-1", 5.0 + in / 2, 0.0, h, in, false);
  g.wallX("G-2", 4.0 + in / 2, 5.0 + in, w, in, false);
  g.wallX("G-3", 5.5 + in / 2, 0.0, 5.0, in, false);
  g.room("G01", "Workshop", 0.0, 0.0, 5.0, 5.5, {"G-EXT-S", "G-1", "G-3", "G-EXT-W"});
  g.room("G02", "Stair hall", 0.0, 5.5 + in, 5.0, h, {"G-3", "G-1", "G-EXT-N", "G-EXT-W"});
  g.room("G03", "Office", 5.0 + in, 0.0, w, 4.0, {"G-EXT-S", "G-EXT-E", "G-2", "G-1"});
  g.room("G04", "Storage", 5.0 + in, 4.0 + in, w, h, {"G-2", "G-EXT-E", "G-EXT-N", "G-1"});
  g.door("G-EXT-S", 2.5, 1.2, 2.2);           // entrance into the workshop
  g.door("G-1", 2.0, 0.9, kDoorHeight_m);     // workshop - office
  g.door("G-3", 2.5, 1.0, kDoorHeight_m);     // workshop - stair hall
  g.door("G-1", 6.8, 0.9, kDoorHeight_m);     // stair hall - storage
  g.door("G-2", 8.5, 0.9, kDoorHeight_m);     // office - storage
  world.storeys.push_back(g.storey());

  StoreyBuilder u("First floor", storey_h, storey_h, slab, storey_h - world.roof_thickness_m);
  rectangularShell(u, "U-", w, h, ext);
  u.wallX("U-1", 3.0 + in / 2, 0.0, w, in, false);
  u.wallY("U-2", 7.0 + in / 2, 3.0 + in, h, in, false);
  u.wallY("U-3", 4.0 + in / 2, 0.0, 3.0, in, false);
  u.wallY("U-4", 6.0 + 1.5 * in, 0.0, 3.0, in, false);
  u.room("U01", "Landing", 0.0, 0.0, 4.0, 3.0, {"U-EXT-S", "U-3", "U-1", "U-EXT-W"});
  u.room("U02", "WC", 4.0 + in, 0.0, 6.0 + in, 3.0, {"U-EXT-S", "U-4", "U-1", "U-3"});
  u.room("U03", "Archive", 6.0 + 2 * in, 0.0, w, 3.0, {"U-EXT-S", "U-EXT-E", "U-1", "U-4"});
  u.room("U04", "Meeting room", 0.0, 3.0 + in, 7.0, h, {"U-1", "U-2", "U-EXT-N", "U-EXT-W"});
  u.room("U05", "Office", 7.0 + in, 3.0 + in, w, h, {"U-1", "U-EXT-E", "U-EXT-N", "U-2"});
  u.door("U-1", 2.0, 1.0, kDoorHeight_m);  // landing - meeting room
  u.door("U-3", 1.5, 0.8, kDoorHeight_m);  // landing - WC
  u.door("U-2", 5.5, 0.9, kDoorHeight_m);  // meeting room - office
  u.door("U-1", 9.5, 0.9, kDoorHeight_m);  // archive - office
  world.storeys.push_back(u.storey());
  return world;
}

// Room A of the nebula driver's real recordings (../shared/realdata/nebula/): measured from the
// wall planes the project's extractor finds in the five real frames, not designed
// (docs/realdata_room.md has the planes, the sensors and the numbers). The clear interior is
// wall to wall: the east end is the far wall (a pilaster or door frame 0.15 m in front of it is
// not modelled), and the north side is the wall behind the shelving, which every sensor sees
// between and above the shelves (4.93 m from the VLP-16, the median of the five): the shelving's
// front, 0.56 m before it, is furniture, which a plan does not hold (a lidar sees through it).
// No door: none was measured.
WorldSpec nebulaRoom() {
  const double w = 14.17, h = 7.12, t = 0.20, clear = 3.50, slab = 0.2;
  WorldSpec world;
  world.name = "nebula_room";
  world.description = "Room A of the nebula lidar recordings: one 14.17 m x 7.12 m room, measured from real scans";
  world.roof_thickness_m = slab;
  world.space_boundaries = true;
  StoreyBuilder b("Room A", 0.0, clear + slab, slab, clear);
  rectangularShell(b, "", w, h, t);
  b.room("A", "Lab", 0.0, 0.0, w, h, {"EXT-S", "EXT-E", "EXT-N", "EXT-W"});
  world.storeys.push_back(b.storey());
  return world;
}

// A house open at both ends: its walls all run along y, and its front and back are not walls
// (the IFC 4.3 sample house of buildingSMART's Sample-Test-Files is drawn so: its gables are
// no IfcWall). No wall plane fixes a position along y; only where the walls end does
// (ParticleFilterConfig::match_wall_ends). A long side wall on the west, a shorter one on the
// east with a step at y = 2.5, and a thin partition inside the back room; two rooms, no door
// (the rooms meet in the open).
WorldSpec openHouse() {
  const double t = 0.2, clear = 2.6, slab = 0.2;
  WorldSpec world;
  world.name = "open_house";
  world.description = "A house open at both ends: walls only along y, its front and back open (no wall fixes y)";
  world.roof_thickness_m = slab;
  world.space_boundaries = false;
  StoreyBuilder b("Ground floor", 0.0, clear + slab, slab, clear);
  b.outline(boxOutline(-t, 0.0, 5.6, 7.0));
  b.wallY("W-WEST", -t / 2, 0.0, 7.0, t, true);
  b.wallY("W-EAST-FRONT", 4.0 + t / 2, 0.0, 2.5, t, true);
  b.wallY("W-EAST-BACK", 5.4 + t / 2, 2.5, 7.0, t, true);
  b.wallY("W-PARTITION", 4.9, 3.0, 6.4, 0.05, false);
  b.room("H01", "Entry hall", 0.0, 0.0, 4.0, 2.5, {"W-WEST", "W-EAST-FRONT"});
  b.room("H02", "Living room", {{0.0, 2.5}, {4.875, 2.5}, {4.875, 3.0}, {4.875, 6.4}, {4.875, 7.0}, {0.0, 7.0}},
         {"W-WEST", "W-PARTITION"});
  StoreySpec storey = b.storey();
  storey.rooms[0].open_edges = {0, 2};     // the front (y = 0) and the back room's side
  storey.rooms[1].open_edges = {0, 1, 3, 4};  // the entry hall's side, beside the partition, the back
  world.storeys.push_back(storey);
  return world;
}

}  // namespace

std::vector<std::string> worldNames() { return {"site_office", "apartment", "two_storey", "nebula_room", "open_house"}; }

WorldSpec makeWorld(const std::string& name) {
  if (name == "site_office") return siteOffice();
  if (name == "apartment") return apartment();
  if (name == "two_storey") return twoStorey();
  if (name == "nebula_room") return nebulaRoom();
  if (name == "open_house") return openHouse();
  std::string valid;
  for (const std::string& n : worldNames()) valid += (valid.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown world '" + name + "' (valid: " + valid + ")");
}

}  // namespace bimloc::worldgen
