// IFC 4.3 read through IFC4 (localizer/src/bim/ifc4x3.hpp). The truths: the two schemas'
// attribute lists (the rewrite's table, checked instance by instance), and a room of four walls
// written twice, once as IFC 4.3 writes it and once as IFC4 does, whose walls are known
// boxes: both must read as those boxes.
#include "plan_mutation.hpp"
#include "test_support.hpp"

#include "bim/ifc4x3.hpp"

#include <bimloc/bim/ifc_reader.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using bimloc::bim::detail::rewriteIfc4x3AsIfc4;
using bimloc::test::tempDir;
using bimloc::test::writeFile;

namespace {

std::string header(const std::string& schema) {
  return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('ViewDefinition [ReferenceView]'),'2;1');\n"
         "FILE_NAME('room.ifc','2026-11-29T00:00:00',(''),(''),'bimloc test','bimloc test','');\nFILE_SCHEMA(('" +
         schema + "'));\nENDSEC;\nDATA;\n";
}

struct Box {
  double x0, y0, x1, y1;
};

// The walls of a 5 m x 4 m room, 0.2 m thick, 2.7 m high, and a column beside it.
const std::array<Box, 4> kWalls = {{{-0.2, -0.2, 5.2, 0.0}, {-0.2, 4.0, 5.2, 4.2}, {-0.2, 0.0, 0.0, 4.0}, {5.0, 0.0, 5.2, 4.0}}};
const Box kColumn = {7.0, 1.0, 7.3, 1.3};
constexpr double kHeightM = 2.7;

// A box as 8 points and 12 triangles (1-based indices into the points).
std::string points(const Box& b) {
  std::ostringstream s;
  s.precision(17);
  s << "(";
  for (int k = 0; k < 8; ++k) {
    const double x = (k % 4 == 1 || k % 4 == 2) ? b.x1 : b.x0, y = (k % 4 >= 2) ? b.y1 : b.y0, z = k < 4 ? 0.0 : kHeightM;
    s << (k ? "," : "") << "(" << std::showpoint << x << "," << y << "," << z << ")";
  }
  return s.str() + ")";
}
const char* kTriangles =
    "((1,3,2),(1,4,3),(5,6,7),(5,7,8),(1,2,6),(1,6,5),(2,3,7),(2,7,6),(3,4,8),(3,8,7),(4,1,5),(4,5,8))";

// The plan as IFC 4.3 writes it (`ifc43`: point lists with a TagList, one face set in the
// draft's order, the column an IfcBuiltElement) or as IFC4 does.
std::string roomPlan(bool ifc43) {
  std::string t = header(ifc43 ? "IFC4X3_ADD2" : "IFC4");
  t += "#1=IFCPROJECT('0YvctVUKr0kugbFTf53O9L',$,'p',$,$,$,$,(#5),#2);\n"
       "#2=IFCUNITASSIGNMENT((#3));\n#3=IFCSIUNIT(*,.LENGTHUNIT.,$,.METRE.);\n"
       "#4=IFCAXIS2PLACEMENT3D(#6,$,$);\n#5=IFCGEOMETRICREPRESENTATIONCONTEXT($,'Model',3,1.E-05,#4,$);\n"
       "#6=IFCCARTESIANPOINT((0.,0.,0.));\n#7=IFCGEOMETRICREPRESENTATIONSUBCONTEXT('Body','Model',*,*,*,*,#5,$,.MODEL_VIEW.,$);\n"
       "#10=IFCLOCALPLACEMENT($,#4);\n"
       "#11=IFCBUILDINGSTOREY('1YvctVUKr0kugbFTf53O9L',$,'Ground',$,$,#10,$,$,.ELEMENT.,0.);\n"
       "#12=IFCRELAGGREGATES('2YvctVUKr0kugbFTf53O9L',$,$,$,#1,(#11));\n";
  std::string contained;
  for (std::size_t w = 0; w <= kWalls.size(); ++w) {
    const bool column = w == kWalls.size();
    const int id = 100 + 10 * static_cast<int>(w);
    const auto ref = [&](int k) { return "#" + std::to_string(id + k); };
    const std::string gid = std::string("3YvctVUKr0kugbFTf53O9") + static_cast<char>('A' + w);
    if (column)
      t += ref(0) + (ifc43 ? "=IFCBUILTELEMENT('" + gid + "',$,'column',$,$," + ref(1) + "," + ref(2) + ",$);\n"
                           : "=IFCBUILDINGELEMENTPROXY('" + gid + "',$,'column',$,$," + ref(1) + "," + ref(2) + ",$,$);\n");
    else
      t += ref(0) + "=IFCWALL('" + gid + "',$,'wall " + std::to_string(w) + "',$,$," + ref(1) + "," + ref(2) + ",$,.STANDARD.);\n";
    t += ref(1) + "=IFCLOCALPLACEMENT(#10,#4);\n";
    t += ref(2) + "=IFCPRODUCTDEFINITIONSHAPE($,$,(" + ref(3) + "));\n";
    t += ref(3) + "=IFCSHAPEREPRESENTATION(#7,'Body','Tessellation',(" + ref(4) + "));\n";
    // Wall 1 in the draft's order (Closed before Normals), the others as IFC4X3_ADD2 and IFC4 write it.
    t += ref(4) + "=IFCTRIANGULATEDFACESET(" + ref(5) + (ifc43 && w == 1 ? ",.T.,$," : ",$,.T.,") + kTriangles + ",$);\n";
    // Wall 2's tags hold what a tag may: commas, parentheses, a quote, a semicolon, a line break.
    const std::string tags = w == 2 ? ",\n('a,b','(c)','d''e;','f','g','h','i','j')" : ",$";
    t += ref(5) + "=IFCCARTESIANPOINTLIST3D(" + points(column ? kColumn : kWalls[w]) + (ifc43 ? tags : "") + ");\n";
    contained += (contained.empty() ? "" : ",") + ref(0);
  }
  t += "#900=IFCRELCONTAINEDINSPATIALSTRUCTURE('4YvctVUKr0kugbFTf53O9L',$,$,$,(" + contained + "),#11);\n";
  return t + "ENDSEC;\nEND-ISO-10303-21;\n";
}

// The wall's box as the extraction reports it: axis end points (either order), thickness, height.
void expectWallIs(const bimloc::bim::Wall& wall, const Box& b) {
  const bool along_x = b.x1 - b.x0 >= b.y1 - b.y0;
  const Eigen::Vector2d a = along_x ? Eigen::Vector2d(b.x0, 0.5 * (b.y0 + b.y1)) : Eigen::Vector2d(0.5 * (b.x0 + b.x1), b.y0);
  const Eigen::Vector2d e = along_x ? Eigen::Vector2d(b.x1, 0.5 * (b.y0 + b.y1)) : Eigen::Vector2d(0.5 * (b.x0 + b.x1), b.y1);
  const Eigen::Vector2d s = wall.start.head<2>(), f = wall.end.head<2>();
  EXPECT_LT(std::min((s - a).norm() + (f - e).norm(), (s - e).norm() + (f - a).norm()), 2e-3) << wall.name;
  EXPECT_NEAR(wall.thickness_m, 0.2, 1e-3) << wall.name;
  EXPECT_NEAR(wall.height_m, kHeightM, 1e-3) << wall.name;
}

}  // namespace

TEST(Ifc4x3, EachRewriteFollowsTheTwoSchemasAttributeLists) {
  const std::string in = header("IFC4X3_ADD2") +
                         "#1=IFCCARTESIANPOINTLIST3D(((0.,0.,0.)),('a,b;',$));\n"
                         "#2=IFCCARTESIANPOINTLIST3D(((0.,0.,0.)));\n"
                         "#3=IFCBUILTELEMENT('g',$,'n',$,$,#4,#5,$);\n"
                         "#6=IFCTRIANGULATEDFACESET(#1,.T.,((0.,0.,1.)),((1,1,1)),$);\n"
                         "#7=IFCTRIANGULATEDFACESET(#1,$,.T.,((1,1,1)),$);\n"
                         "#8 = IFCCARTESIANPOINTLIST2D(((0.,0.)),\n('x'));\n"
                         "#9=IFCLABEL('#10=IFCBUILTELEMENT(a,b,c,d,e,f,g,h);');\n"
                         "/* #11=IFCANNOTATION('g',$,$,$,$,$,$,.USERDEFINED.); */\n"
                         "#12=IFCANNOTATION('g',$,$,$,$,$,$,.USERDEFINED.);\n"
                         "#13=IFCVIRTUALELEMENT('g',$,$,$,$,$,$,$,.BOUNDARY.);\n"
                         "#14=IFCBUILTELEMENTTYPE('g',$,'t',$,$,$,$,$,$);\n"
                         "#15=IFCTRIANGULATEDIRREGULARNETWORK(#1,$,.F.,((1,1,1)),$,(0));\n"
                         "ENDSEC;\nEND-ISO-10303-21;\n";
  const std::string want = header("IFC4") +
                           "#1=IFCCARTESIANPOINTLIST3D(((0.,0.,0.)));\n"
                           "#2=IFCCARTESIANPOINTLIST3D(((0.,0.,0.)));\n"
                           "#3=IFCBUILDINGELEMENTPROXY('g',$,'n',$,$,#4,#5,$,$);\n"
                           "#6=IFCTRIANGULATEDFACESET(#1,((0.,0.,1.)),.T.,((1,1,1)),$);\n"
                           "#7=IFCTRIANGULATEDFACESET(#1,$,.T.,((1,1,1)),$);\n"
                           "#8 = IFCCARTESIANPOINTLIST2D(((0.,0.)))\n;\n"
                           "#9=IFCLABEL('#10=IFCBUILTELEMENT(a,b,c,d,e,f,g,h);');\n"
                           "/* #11=IFCANNOTATION('g',$,$,$,$,$,$,.USERDEFINED.); */\n"
                           "#12=IFCANNOTATION('g',$,$,$,$,$,$);\n"
                           "#13=IFCVIRTUALELEMENT('g',$,$,$,$,$,$,$);\n"
                           "#14=IFCBUILDINGELEMENTPROXYTYPE('g',$,'t',$,$,$,$,$,$,.NOTDEFINED.);\n"
                           "#15=IFCTRIANGULATEDFACESET(#1,$,.F.,((1,1,1)),$);\n"
                           "ENDSEC;\nEND-ISO-10303-21;\n";
  const auto out = rewriteIfc4x3AsIfc4(in, "IFC4X3_ADD2");
  EXPECT_EQ(out.text, want);
  // Every instance stays on its line: warnings name lines of the file as written.
  EXPECT_EQ(std::count(out.text.begin(), out.text.end(), '\n'), std::count(in.begin(), in.end(), '\n'));
  ASSERT_EQ(out.warnings.size(), 1u);
  for (const char* part : {"'IFC4X3_ADD2' read as IFC4", "1 IfcCartesianPointList3D (TagList dropped)", "1 IfcCartesianPointList2D (TagList dropped)",
                           "1 IfcBuiltElement (as IfcBuildingElementProxy)",
                           "1 IfcTriangulatedFaceSet (Closed put after Normals", "1 IfcAnnotation (PredefinedType dropped)"})
    EXPECT_NE(out.warnings[0].find(part), std::string::npos) << part << " in " << out.warnings[0];
}

TEST(Ifc4x3, ARoomWrittenAsIfc43ReadsAsTheSameWallsAsWrittenAsIfc4) {
  const std::string dir = tempDir("ifc4x3");
  const auto as43 = bimloc::bim::readIfc(writeFile(dir, "room43.ifc", roomPlan(true)));
  const auto as4 = bimloc::bim::readIfc(writeFile(dir, "room4.ifc", roomPlan(false)));
  EXPECT_EQ(as43.schema, "IFC4X3");
  EXPECT_EQ(as4.schema, "IFC4");
  for (const auto* b : {&as43, &as4}) {
    ASSERT_EQ(b->storeys.size(), 1u);
    const auto& storey = b->storeys[0];
    ASSERT_EQ(storey.walls.size(), kWalls.size()) << b->schema;
    for (std::size_t w = 0; w < kWalls.size(); ++w) {
      const auto wall = std::find_if(storey.walls.begin(), storey.walls.end(),
                                     [&](const auto& x) { return x.name == "wall " + std::to_string(w); });
      ASSERT_NE(wall, storey.walls.end()) << b->schema << " wall " << w;
      expectWallIs(*wall, kWalls[w]);
    }
    ASSERT_EQ(storey.rooms.size(), 1u) << b->schema;
    EXPECT_NEAR(storey.rooms[0].area_m2, 20.0, 0.05) << b->schema;
    // The column: IFC 4.3's IfcBuiltElement is IFC4's proxy, in the storey's mesh.
    EXPECT_TRUE(std::any_of(storey.mesh_parts.begin(), storey.mesh_parts.end(),
                            [](const auto& p) { return p.ifc_class == "IfcBuildingElementProxy" && p.name == "column"; }))
        << b->schema;
  }
  // What was rewritten is said; the IFC4 plan says nothing of it.
  const auto said = [](const bimloc::bim::Building& b, const std::string& what) {
    return std::any_of(b.warnings.begin(), b.warnings.end(), [&](const std::string& w) { return w.find(what) != std::string::npos; });
  };
  EXPECT_TRUE(said(as43, "5 IfcCartesianPointList3D (TagList dropped)"));
  EXPECT_TRUE(said(as43, "1 IfcTriangulatedFaceSet (Closed put after Normals"));
  EXPECT_FALSE(said(as4, "read as IFC4"));
}

TEST(Ifc4x3, DamagedTextIsRewrittenWithoutACrashAndKeepsEveryLine) {
  // Whatever the bytes (cut anywhere, bytes flipped, quotes and parentheses left open), the
  // rewrite ends, and every line stays where it was: the reader after it names what it cannot use.
  const std::string plan = roomPlan(true);
  std::mt19937 rng(4303);
  const std::string specials = "'\"();,#=/*\n$.";
  for (int k = 0; k < 3000; ++k) {
    std::string t = plan;
    std::uniform_int_distribution<std::size_t> at(0, t.size() - 1);
    switch (k % 4) {
      case 0: t.resize(at(rng)); break;
      case 1: for (int n = 0; n < 5; ++n) t[at(rng)] = static_cast<char>(rng() & 0xFF); break;
      case 2: for (int n = 0; n < 5; ++n) t[at(rng)] = specials[rng() % specials.size()]; break;
      default: t.erase(at(rng), std::min<std::size_t>(40, t.size() / 4)); break;
    }
    const auto out = rewriteIfc4x3AsIfc4(t, "IFC4X3_ADD2");
    ASSERT_EQ(std::count(out.text.begin(), out.text.end(), '\n'), std::count(t.begin(), t.end(), '\n')) << "case " << k;
    ASSERT_EQ(out.warnings.size(), 1u);
  }
}
