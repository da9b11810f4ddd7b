// One-line edits of shared plans that once crashed the reader or changed the model without a
// word (issue 10, items 1 and 8). The truth is the edit itself: the instance it broke, and the
// product that reaches it, must be named; a plan left without a usable wall is an error.
#include "plan_mutation.hpp"
#include "test_support.hpp"

#include "bim/step_references.hpp"

#include <gtest/gtest.h>

using namespace bimloc::test;

namespace {

// revit_quantities.ifc: #38 is the storey 'Level 1', #37 its placement, #45 the placement of
// the wall 2OPn9Eo7X5uQL7Jvq1iSyR, #53 that wall's body extrusion, #54 a colour of its style.
const char* kWall = "2OPn9Eo7X5uQL7Jvq1iSyR";

struct Plan {
  std::string path;
  std::string text;
};

Plan revit() {
  const std::string path = sharedPlan("revit_quantities.ifc");
  return {path, path.empty() ? std::string() : slurp(path)};
}

int wallCount(const nlohmann::json& doc) { return doc["storeys"][0]["walls"].get<int>(); }

}  // namespace

// A boolean operand that is its own result: IFC++ recursed without end (a segfault).
TEST(HostileIfc, ABooleanResultThatIsItsOwnOperandIsNamedNotACrash) {
  BIMLOC_REQUIRE_SHARED(plan, "Duplex_A_20110907.ifc");
  const std::string path = writeFile(tempDir("hostile"), "bool.ifc",
                                     mutated(slurp(plan), "#4284=IFCBOOLEANCLIPPINGRESULT(.DIFFERENCE.,#4273,",
                                             "#4284=IFCBOOLEANCLIPPINGRESULT(.DIFFERENCE.,#4284,"));
  const auto doc = extractJson(path);
  EXPECT_TRUE(anyWarningHas(doc, "#4284", "cycle")) << doc["warnings"];
  EXPECT_TRUE(anyWarningHas(doc, "wall skipped", "#4284")) << doc["warnings"];
}

// The storey's placement made relative to a wall's placement, which is relative to it: every
// wall hangs off that cycle, so none is usable.
TEST(HostileIfc, APlacementCycleIsAnErrorNamingTheCycle) {
  const Plan p = revit();
  if (p.path.empty()) GTEST_SKIP() << "../shared/ifc not found";
  const std::string path = writeFile(tempDir("hostile"), "cycle.ifc",
                                     mutated(p.text, "#37=IFCLOCALPLACEMENT(#25,#36);", "#37=IFCLOCALPLACEMENT(#45,#36);"));
  expectCleanFailure(path, "cycle of references (#37, #45)");
}

TEST(HostileIfc, ANonFiniteStoreyElevationIsReplacedAndNamed) {
  const Plan p = revit();
  if (p.path.empty()) GTEST_SKIP() << "../shared/ifc not found";
  const std::string path = writeFile(tempDir("hostile"), "nan.ifc", mutated(p.text, ",.ELEMENT.,0.);", ",.ELEMENT.,NaN);"));
  const auto doc = extractJson(path);
  ASSERT_TRUE(doc.contains("storeys"));
  EXPECT_EQ(doc["storeys"][0]["elevation"], 0.0);  // the placement's height, not null
  EXPECT_TRUE(anyWarningHas(doc, "'Level 1'", "Elevation is not a finite number")) << doc["warnings"];
  EXPECT_TRUE(anyWarningHas(doc, "#38", "'NaN'")) << doc["warnings"];
}

TEST(HostileIfc, ANegativeExtrusionSkipsTheWallAndNamesIt) {
  const Plan p = revit();
  if (p.path.empty()) GTEST_SKIP() << "../shared/ifc not found";
  const std::string path = writeFile(tempDir("hostile"), "depth.ifc",
                                     mutated(p.text, "#53=IFCEXTRUDEDAREASOLID(#51,#52,#9,3.999999999999669);",
                                             "#53=IFCEXTRUDEDAREASOLID(#51,#52,#9,-4.);"));
  const auto doc = extractJson(path);
  EXPECT_EQ(wallCount(doc), 9);
  // The wall named by class, instance id, GlobalId and name; the broken instance by id and line.
  EXPECT_TRUE(anyWarningHas(doc, "IfcWallStandardCase #61 2OPn9Eo7X5uQL7Jvq1iSyR 'Basic Wall", "depth -4, which is not positive"))
      << doc["warnings"];
}

// The wall's body extrusion defined twice, under a negative id, or with an unknown type:
// the wall loses its body, and both the wall and the instance are named.
TEST(HostileIfc, ABrokenInstanceDefinitionNamesTheWallThatLostIt) {
  const Plan p = revit();
  if (p.path.empty()) GTEST_SKIP() << "../shared/ifc not found";
  const std::string line = "#53=IFCEXTRUDEDAREASOLID(#51,#52,#9,3.999999999999669);";
  const struct {
    std::string to, instance_warning;
  } cases[] = {
      {line + "\n#53=IFCCARTESIANPOINT((0.,0.,0.));", "#53 is defined 2 times"},
      {"#-53=IFCEXTRUDEDAREASOLID(#51,#52,#9,3.999999999999669);", "not an entity instance: '#-53="},
      {"#53=IFCEXTRUDEDAREASOLIDX(#51,#52,#9,3.999999999999669);", "#53 IFCEXTRUDEDAREASOLIDX (line 48) could not be read"},
  };
  const std::string dir = tempDir("hostile");
  for (const auto& c : cases) {
    const auto doc = extractJson(writeFile(dir, "instance.ifc", mutated(p.text, line, c.to)));
    ASSERT_TRUE(doc.contains("storeys")) << c.to;
    EXPECT_EQ(wallCount(doc), 9) << c.to;
    EXPECT_TRUE(anyWarningHas(doc, kWall, "wall skipped")) << c.to << ": " << doc["warnings"];
    EXPECT_TRUE(anyWarningHas(doc, c.instance_warning, "")) << c.to << ": " << doc["warnings"];
  }
}

// What IFC++ alone made of these: exit 0 with no wall and no room.
TEST(HostileIfc, AWrongSchemaOrLengthUnitLeavesNoWallAndIsAnError) {
  const Plan p = revit();
  if (p.path.empty()) GTEST_SKIP() << "../shared/ifc not found";
  const std::string dir = tempDir("hostile");
  expectCleanFailure(writeFile(dir, "schema.ifc", mutated(p.text, "FILE_SCHEMA(('IFC2X3'));", "FILE_SCHEMA(('IFC4'));")),
                     "no usable wall");
  expectCleanFailure(writeFile(dir, "unit.ifc", mutated(p.text, "#15=IFCSIUNIT(*,.LENGTHUNIT.,$,.METRE.);",
                                                        "#15=IFCSIUNIT(*,.LENGTHUNIT.,.MILLI.,.METRE.);")),
                     "no usable wall");
}

// Bytes 0x80-0xFF in a wall's line of AC20-FZK-Haus: outside a string the line is unreadable
// and named; inside the name string it is the same wall.
TEST(HostileIfc, HighBytesInALineNameTheInstance) {
  BIMLOC_REQUIRE_SHARED(plan, "AC20-FZK-Haus.ifc");
  const std::string text = slurp(plan);
  const std::string line = "#15042= IFCWALLSTANDARDCASE('2XPyKWY018sA1ygZKgQPtU',#12,'Wand-Int-ERDG-4',";
  const std::string dir = tempDir("hostile");
  const auto before = extractJson(plan);
  const auto in_type = extractJson(writeFile(dir, "type.ifc", mutated(text, line, "#15042= IFCWA\xE9LLSTANDARDCASE('2XPyKWY018sA1ygZKgQPtU',#12,'Wand-Int-ERDG-4',")));
  EXPECT_EQ(in_type["storeys"][0]["walls"], before["storeys"][0]["walls"].get<int>() - 1);
  EXPECT_TRUE(anyWarningHas(in_type, "#15042 IFCWA\\xE9LLSTANDARDCASE", "could not be read")) << in_type["warnings"];
  const auto in_args = extractJson(writeFile(dir, "args.ifc", mutated(text, line, "#15042= IFCWALLSTANDARDCASE('2XPyKWY018sA1ygZKgQPtU',\x80\xFF#12,'Wand-Int-ERDG-4',")));
  EXPECT_TRUE(anyWarningHas(in_args, "#15042", "the byte \\x80 outside a string")) << in_args["warnings"];
  EXPECT_TRUE(anyWarningHas(in_args, "2XPyKWY018sA1ygZKgQPtU", "skipped")) << in_args["warnings"];
  const auto in_name = extractJson(writeFile(dir, "name.ifc", mutated(text, line, "#15042= IFCWALLSTANDARDCASE('2XPyKWY018sA1ygZKgQPtU',#12,'Wand-\x80\xFF-ERDG-4',")));
  EXPECT_EQ(in_name["storeys"][0]["walls"], before["storeys"][0]["walls"]);
}

// The text alone: a duplicate id, a non-finite number, a cycle of three, a self reference and
// a statement that is no instance, each found; the clean instances are not.
TEST(StepProblems, FindsDuplicatesNonFiniteValuesCyclesAndMalformedStatements) {
  const std::string text =
      "ISO-10303-21;\nHEADER;\nFILE_NAME('NaN #1',$);\nENDSEC;\nDATA;\n"
      "#1=IFCCARTESIANPOINT((0.,1.E-009,-2.5));\n"
      "#2=IFCCARTESIANPOINT((NaN,0.));\n#3=IFCCARTESIANPOINT((1.E999,0.));\n"
      "#4=IFCPOLYLINE((#1,#5));\n#5=IFCPOLYLINE((#6));\n#6=IFCPOLYLINE((#4,#1));\n"
      "#7=IFCBOOLEANRESULT(.DIFFERENCE.,#7,#1);\n#8=IFCLABEL('x');\n#8=IFCLABEL('y');\n"
      "#-9=IFCLABEL('z');\n#10=IFCWALL('a',$,IFCLABEL('b'),.T.,3);\nENDSEC;\nEND-ISO-10303-21;\n";
  const auto scan = bimloc::bim::detail::scanStep(text);
  const auto problems = bimloc::bim::detail::stepProblems(scan);
  std::vector<int> ids;
  for (const auto& [id, why] : problems) ids.push_back(id);
  EXPECT_EQ(ids, (std::vector<int>{2, 3, 4, 5, 6, 7, 8})) << ::testing::PrintToString(problems);
  EXPECT_NE(problems.at(2).find("'NaN', which is no finite number"), std::string::npos) << problems.at(2);
  EXPECT_NE(problems.at(5).find("cycle of references (#4, #5, #6)"), std::string::npos) << problems.at(5);
  EXPECT_NE(problems.at(8).find("defined 2 times (lines 13, 14)"), std::string::npos) << problems.at(8);
  ASSERT_EQ(scan.malformed.size(), 1u);
  EXPECT_EQ(scan.malformed[0], "line 15: not an entity instance: '#-9=IFCLABEL('z')'");
}
