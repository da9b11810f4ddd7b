#include "plan_mutation.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace bimloc::test {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string writeFile(const std::string& dir, const std::string& name, const std::string& contents) {
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << contents;
  return path;
}

std::string mutated(const std::string& text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << from;
  std::string out = text;
  if (at != std::string::npos) out.replace(at, from.size(), to);
  return out;
}

std::string firstOf(const std::string& text, const std::string& ifc_class) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(text, m, std::regex("(#[0-9]+)= ?" + ifc_class + "\\(")));
  return m.empty() ? std::string("#0") : m[1].str();
}

void expectCleanFailure(const std::string& path, const std::string& problem) {
  namespace fs = std::filesystem;
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

}  // namespace bimloc::test
