// Messages that quote damaged bytes stay valid UTF-8 (sim/common/printable.hpp). The truth:
// RFC 3629's table of well-formed sequences, worked by hand.
#include "test_support.hpp"

#include "sim/common/printable.hpp"

#include <gtest/gtest.h>

#include <fstream>

using bimloc::sim::printable;

TEST(Printable, ValidUtf8IsKeptAndEveryOtherByteIsEscaped) {
  EXPECT_EQ(printable("K\xC3\xBC" "che, room 3\tok\n"), "K\xC3\xBC" "che, room 3\tok\n");  // 2 bytes
  EXPECT_EQ(printable("\xE2\x82\xAC 5"), "\xE2\x82\xAC 5");                                // 3 bytes (euro)
  EXPECT_EQ(printable("\xF0\x9F\x8F\xA2"), "\xF0\x9F\x8F\xA2");                            // 4 bytes
  EXPECT_EQ(printable("last read: '\xBA'"), "last read: '\\xBA'");                        // a lone continuation
  EXPECT_EQ(printable("\xC0\x80"), "\\xC0\\x80");                                          // overlong NUL
  EXPECT_EQ(printable("\xE0\x80\xAF"), "\\xE0\\x80\\xAF");                                 // overlong '/'
  EXPECT_EQ(printable("\xED\xA0\x80"), "\\xED\\xA0\\x80");                                 // a surrogate
  EXPECT_EQ(printable("\xF4\x90\x80\x80"), "\\xF4\\x90\\x80\\x80");                        // above U+10FFFF
  EXPECT_EQ(printable("cut \xE2\x82"), "cut \\xE2\\x82");                                   // cut short
  EXPECT_EQ(printable(std::string("a\x01" "b\x7F" "c\0d", 7)), "a\\x01b\\x7Fc\\x00d");     // control characters
  EXPECT_EQ(printable(""), "");
}

TEST(Printable, AnErrorQuotingGarbageIsValidUtf8AndNamesTheFile) {
  const std::string dir = bimloc::test::tempDir("printable");
  std::ofstream(dir + "/bad.json", std::ios::binary) << "{\"wall_seconds\": \x01\xBA\xFF}";
  const auto r = bimloc::test::runBimloc("report merge '" + dir + "/bad.json'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(dir + "/bad.json: not valid JSON"), std::string::npos) << r.err;
  EXPECT_EQ(printable(r.err), r.err) << "stderr holds bytes that are not valid UTF-8: " << r.err;
}

// A damaged byte in a --config value (found by scripts/damage_probe.py, seed 31): the library's
// "invalid UTF-8 byte" surfaced with no file; now the file and line are named.
TEST(Printable, ADamagedByteInAConfigIsRefusedAtItsLine) {
  const std::string dir = bimloc::test::tempDir("printable-config");
  std::ofstream(dir + "/c.yaml", std::ios::binary) << "pf:\n  particles: \xB6" "800\n";
  const auto r = bimloc::test::runBimloc("run --plan '" + std::string(BIMLOC_WORLDS_DIR) +
                                         "/site_office.ifc' --all-rooms --rooms R101 --duration 1 --config '" + dir + "/c.yaml'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(dir + "/c.yaml:2: '\\xB6800' is not valid UTF-8"), std::string::npos) << r.err;
  EXPECT_EQ(printable(r.err), r.err);
  std::ofstream(dir + "/k.yaml", std::ios::binary) << "pf:\n  parti\xFF" "cles: 800\n";
  const auto k = bimloc::test::runBimloc("run --plan '" + std::string(BIMLOC_WORLDS_DIR) +
                                         "/site_office.ifc' --all-rooms --rooms R101 --duration 1 --config '" + dir + "/k.yaml'");
  EXPECT_EQ(k.exit_code, 2);
  EXPECT_NE(k.err.find(dir + "/k.yaml:2: the key 'parti\\xFFcles' is not valid UTF-8"), std::string::npos) << k.err;
}
