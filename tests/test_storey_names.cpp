// Storeys that share a name (a site of two buildings, each with its "Ground floor"): a name that
// is several storeys' finds none and the error names each with its index and GlobalId; tables
// and reports label them "name [#index]", which --storey takes back; a sweep gives each its row.
// End to end on a plan written here: worlds/site_office.ifc and worlds/two_storey.ifc as two
// IfcBuildings of one IfcSite, the second 100 m east.
#include <bimloc/bim/building.hpp>
#include <bimloc/bim/ifc_reader.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

using bimloc::bim::Building;

Building threeStoreys() {
  Building b;
  b.storeys.resize(4);
  b.storeys[0].name = "Ground floor", b.storeys[0].id = "A0";
  b.storeys[1].name = "Ground floor", b.storeys[1].id = "B0";
  b.storeys[2].name = "First floor", b.storeys[2].id = "B1";
  b.storeys[3].name = "", b.storeys[3].id = "C0";
  return b;
}

// The DATA section's entities of a STEP file, by id, in file order.
std::vector<std::pair<long, std::string>> entities(const std::string& path, std::string* head, std::string* tail) {
  std::ifstream in(path);
  std::string line, before, after;
  std::vector<std::pair<long, std::string>> out;
  bool data = false, done = false;
  while (std::getline(in, line)) {
    if (!data && !done) {
      before += line + "\n";
      data = line == "DATA;";
    } else if (data && line == "ENDSEC;") {
      data = false, done = true, after += line + "\n";
    } else if (data) {
      out.emplace_back(std::stol(line.substr(1, line.find('=') - 1)), line);
    } else {
      after += line + "\n";
    }
  }
  if (head) *head = before;
  if (tail) *tail = after;
  return out;
}

std::string shifted(const std::string& line, long by) {
  std::string out;
  const std::regex ref("#([0-9]+)");
  auto it = std::sregex_iterator(line.begin(), line.end(), ref);
  std::size_t at = 0;
  for (; it != std::sregex_iterator(); ++it) {
    out += line.substr(at, static_cast<std::size_t>(it->position()) - at) + "#" + std::to_string(std::stol((*it)[1]) + by);
    at = static_cast<std::size_t>(it->position() + it->length());
  }
  return out + line.substr(at);
}

bool is(const std::string& line, const std::string& type) { return line.find("=" + type + "(") != std::string::npos; }

// worlds/site_office.ifc with worlds/two_storey.ifc's building added to its site, 100 m east.
std::string twoBuildings(const std::string& dir) {
  const std::string worlds = BIMLOC_WORLDS_DIR;
  std::string head, tail;
  auto a = entities(worlds + "/site_office.ifc", &head, &tail);
  const auto b = entities(worlds + "/two_storey.ifc", nullptr, nullptr);
  long top = 0;
  for (const auto& [id, line] : a) top = std::max(top, id);
  long project = -1, site = -1, building = -1, site_a = -1;
  for (const auto& [id, line] : b) {
    if (is(line, "IFCPROJECT")) project = id;
    if (is(line, "IFCSITE")) site = id;
    if (is(line, "IFCBUILDING")) building = id;
  }
  for (const auto& [id, line] : a)
    if (is(line, "IFCSITE")) site_a = id;
  std::string data;
  for (auto& [id, line] : a) {
    // The site's aggregation gets the second building.
    const std::string whole = ",#" + std::to_string(site_a) + ",(";
    if (is(line, "IFCRELAGGREGATES") && line.find(whole) != std::string::npos)
      line = line.substr(0, line.size() - 3) + ",#" + std::to_string(building + top) + "));";
    data += line + "\n";
  }
  const long offset = 2 * top + 1000;  // new entities, past both files' ids
  for (const auto& [id, line] : b) {
    if (id == project || id == site) continue;
    if (is(line, "IFCRELAGGREGATES") && (line.find(",#" + std::to_string(project) + ",(") != std::string::npos ||
                                         line.find(",#" + std::to_string(site) + ",(") != std::string::npos))
      continue;
    std::string moved = shifted(line, top);
    // The second site's placement (absolute, its building's parent) moves the building east.
    const std::regex site_placement("^#([0-9]+)=IFCLOCALPLACEMENT\\(\\$,#([0-9]+)\\);$");
    if (std::regex_match(moved, site_placement) && line.find(std::to_string(id) + "=IFCLOCALPLACEMENT($") != std::string::npos) {
      std::smatch m;
      std::regex_match(moved, m, site_placement);
      moved = "#" + m[1].str() + "=IFCLOCALPLACEMENT($,#" + std::to_string(offset + 3) + ");";
    }
    data += moved + "\n";
  }
  data += "#" + std::to_string(offset) + "=IFCCARTESIANPOINT((100.,0.,0.));\n";
  data += "#" + std::to_string(offset + 1) + "=IFCDIRECTION((0.,0.,1.));\n";
  data += "#" + std::to_string(offset + 2) + "=IFCDIRECTION((1.,0.,0.));\n";
  data += "#" + std::to_string(offset + 3) + "=IFCAXIS2PLACEMENT3D(#" + std::to_string(offset) + ",#" + std::to_string(offset + 1) +
          ",#" + std::to_string(offset + 2) + ");\n";
  const std::string path = dir + "/campus.ifc";
  std::ofstream(path) << head << data << tail;
  return path;
}

}  // namespace

TEST(StoreyNames, ANameOfSeveralStoreysFindsNoneAndTheErrorNamesEach) {
  const Building b = threeStoreys();
  EXPECT_EQ(b.findStorey("Ground floor"), nullptr);
  EXPECT_EQ(b.findStorey("First floor"), &b.storeys[2]);
  EXPECT_EQ(b.findStorey("B0"), &b.storeys[1]);  // GlobalId
  EXPECT_EQ(b.findStorey("1"), &b.storeys[1]);   // index
  EXPECT_EQ(b.findStorey(""), nullptr);
  EXPECT_EQ(b.findStorey("4"), nullptr);
  const std::string why = b.storeyLookupError("Ground floor");
  EXPECT_NE(why.find("2 storeys are named 'Ground floor'"), std::string::npos) << why;
  EXPECT_NE(why.find("A0"), std::string::npos) << why;
  EXPECT_NE(why.find("B0"), std::string::npos) << why;
  EXPECT_NE(b.storeyLookupError("Roof").find("no storey 'Roof'"), std::string::npos);
}

TEST(StoreyNames, LabelsTellStoreysApartAndAreFoundAgain) {
  const Building b = threeStoreys();
  EXPECT_EQ(b.storeyLabel(0), "Ground floor [#0]");
  EXPECT_EQ(b.storeyLabel(1), "Ground floor [#1]");
  EXPECT_EQ(b.storeyLabel(2), "First floor");  // a unique name is its own label
  EXPECT_EQ(b.storeyLabel(3), "#3");
  for (std::size_t i = 0; i < b.storeys.size(); ++i) EXPECT_EQ(b.findStorey(b.storeyLabel(i)), &b.storeys[i]) << i;
}

TEST(StoreyNames, TwoBuildingsOfOneSiteKeepTheirStoreysApart) {
  const std::string dir = (std::filesystem::temp_directory_path() / "bimloc_storey_names").string();
  std::filesystem::create_directories(dir);
  const Building b = bimloc::bim::readIfc(twoBuildings(dir), {});
  // site_office's one storey and two_storey's two.
  ASSERT_EQ(b.storeys.size(), 3u);
  std::map<std::string, std::size_t> rooms;
  for (std::size_t i = 0; i < b.storeys.size(); ++i) rooms[b.storeyLabel(i)] = b.storeys[i].rooms.size();
  EXPECT_EQ(rooms.count("Ground floor [#0]") + rooms.count("Ground floor [#1]"), 2u);
  EXPECT_EQ(rooms.count("First floor"), 1u);
  EXPECT_EQ(b.findStorey("Ground floor"), nullptr);
  // The refusal names the plan (a damaged plan that lost a storey is refused so too).
  EXPECT_EQ(b.storeyLookupError("Ground floor").rfind(b.file + ": 2 storeys are named 'Ground floor'", 0), 0u);
  EXPECT_EQ(b.storeyLookupError("9").rfind(b.file + ": no storey '9'", 0), 0u);
  // The warning says so, once.
  const auto warned = std::count_if(b.warnings.begin(), b.warnings.end(),
                                    [](const std::string& w) { return w.find("storeys named 'Ground floor' are several") != std::string::npos; });
  EXPECT_EQ(warned, 1);
  // The second building stands 100 m east of the first: no wall of one overlaps the other's.
  double east_of_first = -1e9, west_of_second = 1e9;
  for (std::size_t i = 0; i < b.storeys.size(); ++i)
    for (const auto& w : b.storeys[i].walls)
      for (const auto& p : {w.start, w.end}) {
        if (b.storeys[i].rooms.size() == 11) east_of_first = std::max(east_of_first, p.x());
        else west_of_second = std::min(west_of_second, p.x());
      }
  EXPECT_LT(east_of_first + 50.0, west_of_second);
  std::filesystem::remove_all(dir);
}
