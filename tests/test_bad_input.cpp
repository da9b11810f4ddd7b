// Bad input through the real binary: one line on stderr naming the file and the problem,
// a non-zero exit, and no output files.
#include "test_support.hpp"

#include "bim/step_references.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>

namespace fs = std::filesystem;
using bimloc::test::runBimloc;
using bimloc::test::tempDir;

namespace {

const char* kHeader =
    "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('ViewDefinition [CoordinationView]'),'2;1');\n"
    "FILE_NAME('t.ifc','2026-01-01T00:00:00',(''),(''),'','','');\nFILE_SCHEMA(('IFC4'));\nENDSEC;\nDATA;\n";
const char* kProject =
    "#1=IFCPROJECT('0YvctVUKr0kugbFTf53O9L',$,'p',$,$,$,$,(#5),#2);\n"
    "#2=IFCUNITASSIGNMENT((#3));\n#3=IFCSIUNIT(*,.LENGTHUNIT.,$,.METRE.);\n"
    "#4=IFCAXIS2PLACEMENT3D(#6,$,$);\n#5=IFCGEOMETRICREPRESENTATIONCONTEXT($,'Model',3,1.E-05,#4,$);\n"
    "#6=IFCCARTESIANPOINT((0.,0.,0.));\n";
const char* kStorey =
    "#10=IFCLOCALPLACEMENT($,#4);\n"
    "#11=IFCBUILDINGSTOREY('1YvctVUKr0kugbFTf53O9L',$,'Ground',$,$,#10,$,$,.ELEMENT.,0.);\n"
    "#12=IFCRELAGGREGATES('2YvctVUKr0kugbFTf53O9L',$,$,$,#1,(#11));\n";
const char* kFooter = "ENDSEC;\nEND-ISO-10303-21;\n";

std::string write(const std::string& dir, const std::string& name, const std::string& contents) {
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << contents;
  return path;
}

// Runs `bimloc extract` on `path` and checks the failure contract.
void expectCleanFailure(const std::string& path, const std::string& problem) {
  const std::string out = tempDir("out") + "/result";
  const auto r = runBimloc("extract '" + path + "' --out '" + out + "' --json");
  EXPECT_NE(r.exit_code, 0) << path;
  EXPECT_TRUE(r.out.empty()) << "stdout must stay empty: " << r.out;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(path), std::string::npos) << "the message names the file: " << r.err;
  EXPECT_NE(r.err.find(problem), std::string::npos) << "expected '" << problem << "' in: " << r.err;
  EXPECT_FALSE(fs::exists(out)) << "no output on failure";
  // Nor any staging leftovers beside it.
  for (const auto& e : fs::directory_iterator(fs::path(out).parent_path())) ADD_FAILURE() << "left " << e.path();
}

}  // namespace

TEST(BadInput, EmptyFile) {
  const auto dir = tempDir("bad");
  expectCleanFailure(write(dir, "empty.ifc", ""), "empty file");
}

TEST(BadInput, TruncatedFile) {
  const auto dir = tempDir("bad");
  const std::string whole = std::string(kHeader) + kProject + kStorey + kFooter;
  expectCleanFailure(write(dir, "truncated.ifc", whole.substr(0, whole.size() / 2)), "truncated");
}

TEST(BadInput, TextThatIsNotIfc) {
  const auto dir = tempDir("bad");
  expectCleanFailure(write(dir, "notes.ifc", "These are my notes about the building.\nNothing else.\n"),
                     "not an IFC file");
}

TEST(BadInput, BinaryGarbage) {
  const auto dir = tempDir("bad");
  std::mt19937 rng(42);
  std::string bytes(4096, '\0');
  for (auto& b : bytes) b = static_cast<char>(rng() & 0xFF);
  expectCleanFailure(write(dir, "garbage.ifc", bytes), "binary");
}

TEST(BadInput, IfcWithoutStoreys) {
  const auto dir = tempDir("bad");
  expectCleanFailure(write(dir, "nostorey.ifc", std::string(kHeader) + kProject + kFooter), "no IfcBuildingStorey");
}

TEST(BadInput, IfcWithoutWalls) {
  const auto dir = tempDir("bad");
  expectCleanFailure(write(dir, "nowall.ifc", std::string(kHeader) + kProject + kStorey + kFooter), "no IfcWall");
}

TEST(BadInput, PathThatDoesNotExist) {
  expectCleanFailure(tempDir("bad") + "/missing.ifc", "cannot open");
}

TEST(BadInput, PathThatCannotBeRead) {
  // Root reads any file whatever its mode, so an unreadable path is a directory here.
  const auto dir = tempDir("bad");
  fs::create_directory(dir + "/plan.ifc");
  expectCleanFailure(dir + "/plan.ifc", "cannot read");
}

TEST(BadInput, UnknownOptionIsAUsageError) {
  const auto r = runBimloc("extract --no-such-option x.ifc");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("no-such-option"), std::string::npos) << r.err;
}

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The shared plan's text with `from` replaced by `to` (which must occur exactly once).
std::string mutated(const std::string& text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << from;
  std::string out = text;
  if (at != std::string::npos) out.replace(at, from.size(), to);
  return out;
}

// The id of the first instance of an IFC class in the text ("#390").
std::string firstOf(const std::string& text, const std::string& ifc_class) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(text, m, std::regex("(#[0-9]+)= ?" + ifc_class + "\\(")));
  return m.empty() ? std::string("#0") : m[1].str();
}

nlohmann::json extractJson(const std::string& path) {
  const auto r = runBimloc("extract '" + path + "' --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  try {
    return nlohmann::json::parse(r.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << e.what() << ": " << r.out;
    return {};
  }
}

bool anyWarningHas(const nlohmann::json& doc, const std::string& a, const std::string& b) {
  for (const auto& w : doc.value("warnings", nlohmann::json::array()))
    if (w.get<std::string>().find(a) != std::string::npos && w.get<std::string>().find(b) != std::string::npos)
      return true;
  return false;
}

}  // namespace

// IFC++ reads a reference of the wrong type as a null pointer, and its curve converter
// dereferenced it: a segfault in every command. revit_quantities' #47 is the 'Axis' polyline
// of the wall 2OPn9Eo7X5uQL7Jvq1iSyR; its first point is made the polyline itself, a profile
// and an IfcSpace. The wall keeps its body; the warning names it and the broken instance.
TEST(BadInput, PointsOfTheWrongTypeAreSkippedWithAWarningNotACrash) {
  BIMLOC_REQUIRE_SHARED(plan, "revit_quantities.ifc");
  const std::string text = slurp(plan);
  const auto dir = tempDir("wrong-type");
  for (const std::string& point : {std::string("#47"), firstOf(text, "IFCRECTANGLEPROFILEDEF"), firstOf(text, "IFCSPACE")}) {
    const std::string path = write(dir, "point.ifc", mutated(text, "#47=IFCPOLYLINE((#4,#46));", "#47=IFCPOLYLINE((" + point + ",#46));"));
    const auto doc = extractJson(path);
    ASSERT_TRUE(doc.contains("storeys")) << point;
    EXPECT_EQ(doc["storeys"][0]["walls"], 10) << point;
    EXPECT_TRUE(anyWarningHas(doc, "2OPn9Eo7X5uQL7Jvq1iSyR", "#47 IfcPolyline")) << point << ": " << doc["warnings"];
  }
}

TEST(BadInput, AWallWhoseBodyCannotBeReadIsSkippedAndNamed) {
  BIMLOC_REQUIRE_SHARED(plan, "revit_quantities.ifc");
  const std::string text = slurp(plan);
  const auto dir = tempDir("wrong-type");
  // The swept area of that wall's body extrusion (#53) becomes an IfcSpace.
  const std::string path = write(dir, "body.ifc", mutated(text, "#53=IFCEXTRUDEDAREASOLID(#51,",
                                                          "#53=IFCEXTRUDEDAREASOLID(" + firstOf(text, "IFCSPACE") + ","));
  const auto doc = extractJson(path);
  ASSERT_TRUE(doc.contains("storeys"));
  EXPECT_EQ(doc["storeys"][0]["walls"], 9);
  EXPECT_TRUE(anyWarningHas(doc, "2OPn9Eo7X5uQL7Jvq1iSyR", "wall skipped")) << doc["warnings"];
}

TEST(BadInput, APlanLeftWithNoUsableWallIsAnError) {
  BIMLOC_REQUIRE_SHARED(plan, "revit_quantities.ifc");
  const std::string text = slurp(plan);
  // The model context every body refers to gets an IfcSpace for its coordinate system.
  const std::string path = write(tempDir("wrong-type"), "context.ifc",
                                 mutated(text, "#27=IFCGEOMETRICREPRESENTATIONCONTEXT($,'Model',3,1.E-009,#26,$);",
                                         "#27=IFCGEOMETRICREPRESENTATIONCONTEXT($,'Model',3,1.E-009," +
                                             firstOf(text, "IFCSPACE") + ",$);"));
  expectCleanFailure(path, "no usable wall");
}

TEST(StepReferences, CountsTheReferencesOfEachInstanceOutsideStringsAndComments) {
  const std::string text =
      "ISO-10303-21;\nHEADER;\nFILE_NAME('#1 is not a reference',$);\nENDSEC;\nDATA;\n"
      "#1=IFCPOLYLINE((#2,#3));\n"
      "#2 = IFCCARTESIANPOINT((0.,0.));\n"
      "/* #9=IFCPOLYLINE((#2)); */ #4=IFCWALL('it''s #5',#2,\n  #3, $);\n"
      "#12=IFCX(#1,'#7;',(#2,#3,#4));\nENDSEC;\nEND-ISO-10303-21;\n";
  const auto counts = bimloc::bim::detail::stepReferenceCounts(text);
  const std::vector<std::pair<int, int>> expected{{1, 2}, {4, 2}, {12, 4}};
  EXPECT_EQ(counts, expected);
}

TEST(Cli, HelpExplainsEverySubcommand) {
  for (const char* sub : {"extract", "worldgen", "bench extract"}) {
    const auto r = runBimloc(std::string(sub) + " --help");
    EXPECT_EQ(r.exit_code, 0) << sub;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << sub << ": " << r.out;
  }
}
