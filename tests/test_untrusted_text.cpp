// Text from a file or an option on its way into an interpreter (issue 46: a map key ran a
// command in gnuplot): a map's keys are the sweep's keys or refused, and every string a
// figure's script holds is a gnuplot literal that gnuplot reads back as the same one string.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include <unistd.h>

#include "heavytop/body.hpp"
#include "heavytop/io/config.hpp"
#include "heavytop/io/map_file.hpp"
#include "heavytop/report/figures.hpp"
#include "heavytop/sweep.hpp"

namespace heavytop {
namespace {
namespace fs = std::filesystem;
using report::gnuplot_string;

// Quotes, gnuplot's substitutions (`command`, @macro), a command separator, a continuation, a
// newline and other control characters, bytes that are not UTF-8.
const std::vector<std::string> kHostile = {
    "",
    "B/A' ; system('touch MARKER') ; x='",
    "'",
    "''",
    "'''x",
    "`touch MARKER`",
    "`0`7 \\140 \\",  // octal digits after a backquote
    "\" ; system(\"touch MARKER\") ; x=\"",
    "it's `touch MARKER` @macro $0 \\",
    "a\nsystem('touch MARKER')\n",
    std::string("nul\0byte", 8),
    "\r\t\x1b[31m\x7f",
    "\xff\xfe caf\xc3\xa9",
    "B/A\\",
};

TEST(GnuplotString, IsOneLiteralWithNothingGnuplotExpands) {
  for (const std::string& text : kHostile) {
    const std::string literal = gnuplot_string(text);
    ASSERT_GE(literal.size(), 2u) << text;
    EXPECT_EQ(literal.front(), '"');
    EXPECT_EQ(literal.back(), '"');
    // Inside: no backquote, and each quote or backslash escaped by a backslash of its own.
    const std::string inside = literal.substr(1, literal.size() - 2);
    EXPECT_EQ(inside.find('`'), std::string::npos) << literal;
    for (std::size_t i = 0; i < inside.size(); ++i) {
      EXPECT_NE(inside[i], '"') << literal;
      if (inside[i] == '\\') ++i;  // the escaped character, or the first digit of \ooo
    }
    for (const char c : literal) {
      const auto u = static_cast<unsigned char>(c);
      EXPECT_TRUE(u >= 0x20 && u != 0x7f) << "a control character in " << io::printable(literal);
    }
  }
  EXPECT_EQ(gnuplot_string("the paper's (4)"), "\"the paper's (4)\"");
  EXPECT_EQ(gnuplot_string("a\nb"), "\"a\\\\nb\"");  // shown as printable() shows it: a\nb
  EXPECT_EQ(gnuplot_string("`12`x"), "\"\\140\\061\\062\\140x\"");  // no digit read into the escape
  EXPECT_EQ(gnuplot_string("say \"hi\""), "\"say \\\"hi\\\"\"");
}

// gnuplot itself reads each literal back as the text printable() shows, and runs nothing.
TEST(GnuplotString, GnuplotReadsItBackAndRunsNothing) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "no gnuplot";
  const fs::path dir = fs::temp_directory_path() / fs::path("heavytop-gnuplot-string-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  {
    std::ofstream script(dir / "print.gp");
    // A string variable for @macro to expand, were it expanded.
    script << "macro = \"system('touch MARKER')\"\nset print '-'\n";
    for (const std::string& text : kHostile) script << "print " << gnuplot_string(text) << "\n";
  }
  const std::string command = "cd '" + dir.string() + "' && gnuplot print.gp > out.txt 2> err.txt";
  ASSERT_EQ(std::system(command.c_str()), 0) << std::ifstream(dir / "err.txt").rdbuf();
  std::ifstream out(dir / "out.txt");
  for (const std::string& text : kHostile) {
    std::string line;
    ASSERT_TRUE(std::getline(out, line));
    EXPECT_EQ(line, io::printable(text));
  }
  EXPECT_FALSE(fs::exists(dir / "MARKER"));
  fs::remove_all(dir);
}

// A map file whose key is not one a sweep varies is refused, naming the key and the rule.
TEST(MapKeys, AKeyASweepDoesNotVaryIsRefused) {
  const fs::path file = fs::temp_directory_path() / fs::path("heavytop-map-key-" + std::to_string(::getpid()) + ".csv");
  const std::string rows = ",first-order,body-fixed,linearized,lyapunov,lyapunov_certificate\n"
                           "0.8,0,0,0,0,0,linear-instability\n0.8,1,0,1,0,0,linear-instability\n"
                           "1.2,0,0,0,0,0,linear-instability\n1.2,1,0,1,0,0,linear-instability\n";
  for (const std::string key : {"B/A' ; system('touch MARKER') ; x='", "b/a", "spin ", "theta0", "B/A\r"}) {
    std::ofstream(file) << key << ",spin" << rows;
    try {
      io::read_map(file.string(), "--map");
      ADD_FAILURE() << "read: " << io::printable(key);
    } catch (const InvalidInput& e) {
      EXPECT_EQ(e.key(), "--map");
      EXPECT_NE(e.rule().find("'" + io::printable(key) + "' is not one a sweep varies"), std::string::npos) << e.rule();
      EXPECT_NE(e.rule().find(sweep_keys_text()), std::string::npos) << e.rule();
    }
  }
  std::ofstream(file) << "B/A,spin" << rows;
  EXPECT_EQ(io::read_map(file.string(), "--map").axes.at(0).key, "B/A");
  fs::remove(file);
}

// The keys in the rule are exactly those the sweep takes.
TEST(MapKeys, TheRuleListsTheKeysTheSweepTakes) {
  std::istringstream words(sweep_keys_text());
  std::string key;
  int n = 0;
  while (std::getline(words, key, ',')) {
    if (key.front() == ' ') key.erase(0, 1);
    EXPECT_TRUE(is_sweep_key(key)) << key;
    EXPECT_NO_THROW(parse_sweep_axis(key + "=1:2:3")) << key;
    ++n;
  }
  EXPECT_EQ(n, 10);
  EXPECT_FALSE(is_sweep_key("B/A'"));
  EXPECT_FALSE(is_sweep_key(""));
}

}  // namespace
}  // namespace heavytop


