// --help within a terminal's width (sim/cli/help_format.hpp): descriptions reflowed at spaces,
// examples kept as written, and a subcommand listed by its first sentence. The commands' own
// pages check every --help line against the width (scripts/command_docs.py --check).
#include "sim/cli/help_format.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

using bimloc::cli::firstSentence;
using bimloc::cli::wrapLines;

namespace {

std::size_t widest(const std::string& text) {
  std::istringstream in(text);
  std::size_t most = 0;
  for (std::string line; std::getline(in, line);) most = std::max(most, line.size());
  return most;
}

}  // namespace

TEST(HelpFormat, ReflowsAParagraphAndKeepsIndentedLines) {
  const std::string text =
      "A description written broken at one width\nand read at another, whose words must all stay, in order.\n"
      "  bimloc worldgen NAME [--out FILE|DIR]   an example, kept as it is even when it is rather long\n"
      "\nA second paragraph.";
  const std::string out = wrapLines(text, 30);
  EXPECT_LE(widest(out.substr(0, out.find("  bimloc"))), 30u);
  EXPECT_NE(out.find("\n  bimloc worldgen NAME [--out FILE|DIR]   an example, kept as it is even when it is rather long\n"),
            std::string::npos);
  EXPECT_NE(out.find("\n\nA second paragraph."), std::string::npos);
  // The same words in the same order: only the breaks moved.
  std::istringstream a(text), b(out);
  std::string wa, wb;
  while (a >> wa) {
    ASSERT_TRUE(static_cast<bool>(b >> wb));
    EXPECT_EQ(wa, wb);
  }
  EXPECT_FALSE(static_cast<bool>(b >> wb));
  EXPECT_NE(out.back(), '\n');  // as the text: no newline added at the end
}

TEST(HelpFormat, FirstSentenceOfTheFirstParagraph) {
  EXPECT_EQ(firstSentence("Merge the shards (`bimloc run ... --shard`) back. The rest."), "Merge the shards (`bimloc run ... --shard`) back.");
  EXPECT_EQ(firstSentence("One line\nbroken. Two."), "One line broken.");
  EXPECT_EQ(firstSentence("No full stop\n\nNext paragraph. More."), "No full stop");
  EXPECT_EQ(firstSentence(""), "");
}
