// Tests of the graspsynth command line itself (apps/main.cpp): --help and --version answer with
// exit status 0; every refusal of a command line (an unknown flag or command, a missing or bad
// value) exits 2, as the README says of bad input, and a misspelt flag or command is answered
// with the nearest one. Every help fits a screen: `graspsynth --help` at most 40 lines with one
// line per command, no line of any command's help over 100 columns, and no text said twice.

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tests/utils/run_command.hpp"

namespace graspsynth {
namespace {

using testing::RunGraspsynth;

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The columns a line takes: its UTF-8 code points.
size_t Columns(const std::string& line) {
  return static_cast<size_t>(
      std::count_if(line.begin(), line.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

// The commands a help lists under "Commands:", each with the lines its entry takes (a line
// that starts deeper than the names is the entry's continuation).
std::map<std::string, int> ListedCommands(const std::string& help) {
  std::map<std::string, int> commands;
  std::string last;
  bool inside = false;
  for (const std::string& line : Lines(help)) {
    if (line == "Commands:") {
      inside = true;
    } else if (inside && line.rfind("  ", 0) == 0 && line[2] != ' ') {
      last = line.substr(2, line.find(' ', 2) - 2);
      commands[last] = 1;
    } else if (inside && line.rfind("   ", 0) == 0 && !last.empty()) {
      ++commands[last];
    } else {
      inside = false;
    }
  }
  return commands;
}

// The help as one line of words (blanks and line breaks collapsed), for texts that a wrap
// breaks across lines.
std::string Flattened(const std::string& help) {
  std::istringstream words(help);
  std::string flat;
  for (std::string word; words >> word;) flat += (flat.empty() ? "" : " ") + word;
  return flat;
}

// What a help says twice, or "" when nothing: a line repeated (a non-blank one that is not a
// heading), a run of 8 words repeated (a sentence or a clause, wherever the lines break), or a
// parenthesis that opens with the two or more words just before it ("spline reach (spline
// reach ...").
std::string RepeatedText(const std::string& help) {
  std::set<std::string> seen;
  for (const std::string& line : Lines(help)) {
    if (line.find_first_not_of(' ') == std::string::npos || line.back() == ':') continue;
    if (!seen.insert(line).second) return "the line '" + line + "'";
  }
  // every run of kRunWords words, once.
  constexpr size_t kRunWords = 8;
  const std::string flat = Flattened(help);
  std::vector<std::string> words;
  std::istringstream all(flat);
  for (std::string w; all >> w;) words.push_back(w);
  std::set<std::string> runs;
  for (size_t i = 0; i + kRunWords <= words.size(); ++i) {
    std::string run;
    for (size_t j = i; j < i + kRunWords; ++j) run += words[j] + " ";
    if (!runs.insert(run).second) return "the words '" + run + "'";
  }
  for (size_t open = flat.find('('); open != std::string::npos; open = flat.find('(', open + 1)) {
    std::istringstream back(flat.substr(0, open)), ahead(flat.substr(open + 1));
    std::vector<std::string> words_before, words_after;
    for (std::string w; back >> w;) words_before.push_back(w);
    for (std::string w; ahead >> w && words_after.size() < words_before.size();) {
      words_after.push_back(w);
    }
    for (size_t n = 2; n <= std::min(words_before.size(), words_after.size()); ++n) {
      if (std::equal(words_before.end() - static_cast<long>(n), words_before.end(),
                     words_after.begin())) {
        return "the parenthesis at '" + flat.substr(open, 60) + "'";
      }
    }
  }
  return "";
}

TEST(CommandLine, HelpAndVersionExitZero) {
  const testing::CommandOutput version = RunGraspsynth("--version");
  EXPECT_EQ(version.exit_code, 0) << version.err;
  EXPECT_EQ(version.out, "graspsynth 0.1.0\n");
  const testing::CommandOutput help = RunGraspsynth("run --help");
  EXPECT_EQ(help.exit_code, 0) << help.err;
  EXPECT_NE(help.out.find("--select-perturb"), std::string::npos) << help.out;
  EXPECT_NE(RunGraspsynth("version").out.find("graspsynth 0.1.0"), std::string::npos);
}

TEST(CommandLine, AMisspeltFlagExits2WithTheNearestFlag) {
  const testing::CommandOutput r = RunGraspsynth("synthesize --theta 45 --seeed 3 --out x.json");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--seeed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--seeed: did you mean --seed?"), std::string::npos) << r.err;
  // a flag of another command is not suggested, and a far-off one gets no guess.
  const testing::CommandOutput far = RunGraspsynth("fk --zzzzzzzz");
  EXPECT_EQ(far.exit_code, 2) << far.err;
  EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
}

TEST(CommandLine, AnUnknownCommandExits2WithTheNearestCommand) {
  const testing::CommandOutput r = RunGraspsynth("synthesise --theta 45");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("'synthesise' is not a command (did you mean 'synthesize'?)"),
            std::string::npos)
      << r.err;
  const testing::CommandOutput nothing_near = RunGraspsynth("frobnicate");
  EXPECT_EQ(nothing_near.exit_code, 2);
  EXPECT_NE(nothing_near.err.find("'frobnicate' is not a command; 'graspsynth --help' lists"),
            std::string::npos)
      << nothing_near.err;
}

TEST(CommandLine, AMissingCommandFlagOrValueExits2) {
  EXPECT_EQ(RunGraspsynth("").exit_code, 2);                    // no command
  EXPECT_EQ(RunGraspsynth("generalize").exit_code, 2);          // --out is required
  EXPECT_EQ(RunGraspsynth("synthesize --theta").exit_code, 2);  // a flag without its value
  EXPECT_EQ(RunGraspsynth("run --seed many").exit_code, 2);     // not a number
  EXPECT_EQ(RunGraspsynth("demos").exit_code, 2);               // generate or calibrate
}

TEST(CommandLine, TheTopLevelHelpListsEachCommandOnOneLine) {
  const testing::CommandOutput help = RunGraspsynth("--help");
  ASSERT_EQ(help.exit_code, 0) << help.err;
  EXPECT_LE(Lines(help.out).size(), 40u) << help.out;
  const std::map<std::string, int> commands = ListedCommands(help.out);
  for (const char* name : {"run", "analyze", "demos", "select", "synthesize", "generalize",
                           "simulate", "scripted-grasp", "fk", "ik", "robots", "view", "teleop",
                           "teleop-client", "teleop-keygen", "version"}) {
    ASSERT_TRUE(commands.count(name)) << name << " is not listed:\n" << help.out;
  }
  for (const auto& [name, lines] : commands) EXPECT_EQ(lines, 1) << name << ":\n" << help.out;
}

TEST(CommandLine, EveryHelpFitsA100ColumnScreenAndSaysNothingTwice) {
  // every command listed by the top-level help, and the commands of a command (demos generate).
  std::vector<std::string> commands = {""};
  for (size_t k = 0; k < commands.size(); ++k) {
    const std::string command = commands[k];  // a copy: the list grows below
    const testing::CommandOutput help = RunGraspsynth(command + " --help");
    ASSERT_EQ(help.exit_code, 0) << command << ": " << help.err;
    ASSERT_FALSE(help.out.empty()) << command;
    for (const std::string& line : Lines(help.out)) {
      EXPECT_LE(Columns(line), 100u) << "graspsynth " << command << " --help:\n" << line;
    }
    const std::string repeated = RepeatedText(help.out);
    EXPECT_EQ(repeated, "") << "graspsynth " << command << " --help says twice " << repeated;
    for (const auto& [name, lines] : ListedCommands(help.out)) {
      commands.push_back(command.empty() ? name : command + " " + name);
    }
  }
  EXPECT_GE(commands.size(), 18u);  // the 15 above, demos' two, and the top level
}

TEST(CommandLine, TheRepeatedTextCheckFindsWhatItLooksFor) {
  // the checks of the test above can fail: each finds the text it is meant to.
  EXPECT_EQ(RepeatedText("Usage: x\n  --a  one thing\n  --b  another\n"), "");
  EXPECT_NE(RepeatedText("  --reach  spline reach (spline reach (the paper's))\n"), "");
  EXPECT_NE(RepeatedText("Usage: x\nA command that does this and that to a file. Then\nit does "
                         "more. A command that does this and that to a file.\n"),
            "");
  EXPECT_NE(RepeatedText("  --a  one thing\n  --a  one thing\n"), "");
}

}  // namespace
}  // namespace graspsynth
