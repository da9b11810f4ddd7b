// The page of `bimloc compare --out` opened in a real browser (headless Chromium): it shows
// its tables, every picture it names loads from the file system, and it is not blank; and
// the terminal tables fit 100 columns. The HTML writer escapes what it is given.
#include "render_fixtures.hpp"
#include "test_support.hpp"

#include "sim/cli/html_writer.hpp"
#include "sim/cli/table.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace fs = std::filesystem;
using bimloc::test::runBimloc;
using bimloc::test::tempDir;

namespace {

const std::string kOffice = std::string("--plan '") + BIMLOC_WORLDS_DIR + "/site_office.ifc' --storey 'Ground floor'";

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Chromium from Debian's package, or "" when it is not installed.
std::string chromium() {
  for (const char* path : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (fs::exists(path)) return path;
  return "";
}

// Headless Chromium on a file, as root needs it (no sandbox), with a profile of its own.
bimloc::test::CommandResult browse(const std::string& browser, const std::string& what, const std::string& page) {
  const std::string profile = tempDir("chromium-profile");
  return bimloc::test::runCommand(browser,
                                  "--headless --no-sandbox --disable-gpu --no-first-run --hide-scrollbars "
                                  "--user-data-dir='" + profile + "' --virtual-time-budget=5000 " + what + " 'file://" +
                                      page + "'",
                                  120);
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST(HtmlWriter, EscapesTextAndAttributesAndClosesEverything) {
  EXPECT_EQ(bimloc::cli::escapeHtml("<a href=\"x\">'&'</a>"), "&lt;a href=&quot;x&quot;&gt;&#39;&amp;&#39;&lt;/a&gt;");
  bimloc::cli::HtmlWriter h;
  h.open("p", {{"title", "\"><script>"}}).text("R101 <b>&").close();
  EXPECT_EQ(h.document(), "<!DOCTYPE html>\n<p title=\"&quot;&gt;&lt;script&gt;\">R101 &lt;b&gt;&amp;</p>\n");
  bimloc::cli::HtmlWriter unclosed;
  unclosed.open("div");
  EXPECT_THROW(unclosed.document(), std::logic_error);
  EXPECT_THROW(bimloc::cli::HtmlWriter().close(), std::logic_error);
  EXPECT_THROW(bimloc::cli::HtmlWriter().open("p onclick=x"), std::logic_error);
}

// A table wider than the limit is split into blocks of columns, each with the first column.
TEST(Table, SplitsIntoBlocksThatFitTheWidth) {
  bimloc::cli::Table table({"room", "aaaaaaaaaaaaaaaaaaaa", "bbbbbbbbbbbbbbbbbbbb", "cccccccccccccccccccc", "dddddddddddddddddddd"});
  table.add({"R101", "1", "2", "3", "4"});
  std::ostringstream out;
  table.print(out, 50);
  std::istringstream lines(out.str());
  int rows = 0;
  for (std::string line; std::getline(lines, line);) {
    EXPECT_LE(line.size(), 50u) << line;
    rows += line.rfind("R101", 0) == 0;
  }
  EXPECT_EQ(rows, 2) << out.str();  // two blocks of two columns each
  for (const char c : {'a', 'b', 'c', 'd'}) EXPECT_EQ(count(out.str(), std::string(20, c)), 1u) << c;  // each column once
  EXPECT_EQ(bimloc::cli::wrapText("one two three four", 9), "one two\nthree\nfour\n");
}

// Every line of the tables within 100 columns, with the five methods and two seeds; --wide
// keeps each table whole.
TEST(ComparePage, TheTablesFitHundredColumns) {
  const std::string args = "compare " + kOffice + " --rooms R101,S100 --seeds 2 --duration 6 --methods sgraph,pf,pf-no-rooms,amcl,ndt";
  const auto r = runBimloc(args, 600);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream lines(r.out);
  std::size_t n = 0;
  for (std::string line; std::getline(lines, line); ++n) EXPECT_LE(line.size(), 100u) << line;
  EXPECT_GT(n, 20u) << r.out;
  for (const char* says : {"Convergence time [s]", "ATE [m]", "Per method", "localized", "pf-no-rooms"})
    EXPECT_NE(r.out.find(says), std::string::npos) << says << "\n" << r.out;
  const auto wide = runBimloc(args + " --wide", 600);
  ASSERT_EQ(wide.exit_code, 0) << wide.err;
  EXPECT_NE(wide.out.find("Position error at the end"), std::string::npos) << wide.out;
  // Whole: one header row per room table, each naming every method.
  EXPECT_EQ(count(wide.out, "start room  "), 3u) << wide.out;
}

// A small comparison's page in headless Chromium: the tables are there, every picture loads
// (the page's script counts them into body's data-images), and the screenshot is not blank.
TEST(ComparePage, OpensInABrowserWithEveryPicture) {
  const std::string browser = chromium();
  if (browser.empty()) GTEST_SKIP() << "chromium not installed (Debian package chromium; `make test` installs it)";
  const std::string dir = tempDir("compare-page");
  const std::string out = dir + "/page";
  const auto r = runBimloc("compare " + kOffice + " --rooms S100 --duration 8 --methods sgraph,pf-no-rooms,amcl,ndt --out '" +
                               out + "'",
                           600);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = slurp(out + "/index.html");
  ASSERT_FALSE(html.empty());
  // Self-contained: no address outside the folder.
  for (const char* remote : {"http://", "https://", "//cdn", "@import"}) EXPECT_EQ(html.find(remote), std::string::npos) << remote;
  // Every picture it names is a file beside it; every snapshot folder's picture is named.
  const std::regex src("src=\"([^\"]+)\"");
  std::set<std::string> named;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), src); it != std::sregex_iterator(); ++it) named.insert((*it)[1]);
  for (const auto& path : named) EXPECT_TRUE(fs::is_regular_file(out + "/" + path)) << path;
  std::size_t on_disk = 0;
  for (const auto& e : fs::recursive_directory_iterator(out)) on_disk += e.path().extension() == ".png";
  EXPECT_EQ(named.size(), on_disk);
  EXPECT_GE(named.size(), 2u + 4u * 3u) << "two figures, and for each method at least two snapshots and its error plot";

  const auto dom = browse(browser, "--dump-dom", out + "/index.html");
  ASSERT_EQ(dom.exit_code, 0) << dom.err;
  std::smatch images;
  ASSERT_TRUE(std::regex_search(dom.out, images, std::regex("data-images=\"(\\d+)/(\\d+)\""))) << dom.out.substr(0, 2000);
  EXPECT_EQ(images[1], images[2]) << "pictures that did not load";
  EXPECT_EQ(std::stoul(images[2]), count(html, "<img "));
  for (const char* id : {"id=\"summary\"", "id=\"times\"", "id=\"ate\""}) EXPECT_NE(dom.out.find(id), std::string::npos) << id;
  for (const char* says : {"Verdict.", "sgraph", "pf-no-rooms", "amcl", "ndt", "S100"})
    EXPECT_NE(dom.out.find(says), std::string::npos) << says;

  const std::string shot = dir + "/shot.png";
  const auto screenshot = browse(browser, "--screenshot='" + shot + "' --window-size=1280,1600", out + "/index.html");
  ASSERT_EQ(screenshot.exit_code, 0) << screenshot.err;
  const bimloc::sim::Image image = bimloc::test::readPng(shot);
  ASSERT_EQ(image.width, 1280);
  ASSERT_EQ(image.height, 1600);
  // Not blank: a good share of the pixels is not the white of the background, in many colours.
  std::size_t inked = 0;
  std::set<std::uint32_t> colours;
  for (std::size_t i = 0; i + 2 < image.rgb.size(); i += 3) {
    const std::uint32_t c = image.rgb[i] << 16 | image.rgb[i + 1] << 8 | image.rgb[i + 2];
    inked += c != 0xffffff;
    colours.insert(c);
  }
  EXPECT_GT(inked, image.rgb.size() / 3 / 20) << "under 5 % of the screenshot is not white";
  EXPECT_GT(colours.size(), 50u);
}
