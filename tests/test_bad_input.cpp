// Bad input through the real binary: one line on stderr naming the file and the problem,
// a non-zero exit, and no output files.
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

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

TEST(Cli, HelpExplainsEverySubcommand) {
  for (const char* sub : {"extract", "worldgen", "bench extract"}) {
    const auto r = runBimloc(std::string(sub) + " --help");
    EXPECT_EQ(r.exit_code, 0) << sub;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << sub << ": " << r.out;
  }
}
