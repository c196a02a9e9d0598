#pragma once

/// @file
/// The help of the graspsynth command (`graspsynth --help`, `graspsynth COMMAND --help`), made by
/// one CLI11 formatter: every line at most kHelpWidth columns (descriptions, option help and
/// footers wrapped at blanks), and a command listed by its summary, the first line of its
/// description. A command's description is thus written as a summary line, then the long text
/// that only `graspsynth COMMAND --help` prints.

#include <CLI/CLI.hpp>

#include <cstddef>
#include <string>
#include <string_view>

namespace graspsynth::apps {

/// The widest line of any help, in columns.
inline constexpr size_t kHelpWidth = 100;

/// `text` with every line longer than `width` columns broken at blanks; a continuation line
/// takes the indentation of the line it continues, plus `hang` columns. Lines that fit stay as
/// they are; a word longer than the width stays whole.
std::string WrapText(std::string_view text, size_t width, size_t hang = 0);

/// The summary of a command: the first line of its description.
std::string SummaryOf(std::string_view description);

/// The formatter of every help: CLI11's layout, wrapped at kHelpWidth, with commands listed by
/// their summary.
class HelpFormatter : public CLI::Formatter {
 public:
  HelpFormatter();
  std::string make_help(const CLI::App* app, std::string name,
                        CLI::AppFormatMode mode) const override;
  std::string make_description(const CLI::App* app) const override;
  std::string make_usage(const CLI::App* app, std::string name) const override;
  std::string make_footer(const CLI::App* app) const override;
  std::string make_subcommands(const CLI::App* app, CLI::AppFormatMode mode) const override;
  std::string make_subcommand(const CLI::App* sub) const override;
  std::string make_expanded(const CLI::App* sub) const override;
  std::string make_option(const CLI::Option* opt, bool is_positional) const override;
  std::string make_option_opts(const CLI::Option* opt) const override;

 private:
  // "  NAME" in a left column `column` wide, `text` wrapped in the right one (from the next line
  // when the name does not leave it room).
  std::string TwoColumns(const std::string& name, const std::string& text, size_t column) const;
};

/// Makes HelpFormatter the formatter of `app`; commands added to it afterwards take it too.
void UseHelpFormatter(CLI::App* app);

}  // namespace graspsynth::apps
