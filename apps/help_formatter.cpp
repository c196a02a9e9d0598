#include "apps/help_formatter.hpp"

#include <memory>
#include <sstream>
#include <vector>

namespace graspsynth::apps {
namespace {

// The left column of the option list, and of the command list, in columns.
constexpr size_t kNameColumn = 32;
constexpr size_t kCommandColumn = 18;

std::vector<std::string_view> LinesOf(std::string_view text) {
  std::vector<std::string_view> lines;
  size_t start = 0;
  for (size_t end = text.find('\n'); end != std::string_view::npos; end = text.find('\n', start)) {
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  lines.push_back(text.substr(start));
  return lines;
}

// One line of text, broken at blanks into lines of at most `width` columns (see WrapText).
std::string WrapLine(std::string_view line, size_t width, size_t hang) {
  if (line.size() <= width) return std::string(line);
  const size_t indent = line.find_first_not_of(' ');
  if (indent == std::string_view::npos) return std::string();
  const std::string continuation(indent + hang, ' ');
  std::string out(line.substr(0, indent));
  size_t column = indent;
  bool first_word = true;
  std::istringstream words{std::string(line.substr(indent))};
  for (std::string word; words >> word;) {
    if (!first_word && column + 1 + word.size() > width) {
      out += "\n" + continuation;
      column = continuation.size();
      first_word = true;
    }
    if (!first_word) {
      out += ' ';
      ++column;
    }
    out += word;
    column += word.size();
    first_word = false;
  }
  return out;
}

}  // namespace

std::string WrapText(std::string_view text, size_t width, size_t hang) {
  std::string out;
  const std::vector<std::string_view> lines = LinesOf(text);
  for (size_t i = 0; i < lines.size(); ++i) {
    if (i > 0) out += '\n';
    out += WrapLine(lines[i], width, hang);
  }
  return out;
}

std::string SummaryOf(std::string_view description) {
  return std::string(description.substr(0, description.find('\n')));
}

HelpFormatter::HelpFormatter() {
  column_width(kNameColumn);
  label("SUBCOMMAND", "COMMAND");
}

std::string HelpFormatter::TwoColumns(const std::string& name, const std::string& text,
                                      size_t column) const {
  const std::string left = "  " + name;
  const std::string pad(column, ' ');
  std::string out = left;
  if (text.empty()) return out + "\n";
  if (left.size() + 1 > column) {
    out += "\n" + pad;
  } else {
    out += std::string(column - left.size(), ' ');
  }
  const std::string wrapped = WrapText(text, kHelpWidth - column);
  const std::vector<std::string_view> lines = LinesOf(wrapped);
  for (size_t i = 0; i < lines.size(); ++i) {
    if (i > 0) out += "\n" + pad;
    out += lines[i];
  }
  return out + "\n";
}

std::string HelpFormatter::make_help(const CLI::App* app, std::string name,
                                     CLI::AppFormatMode mode) const {
  if (mode == CLI::AppFormatMode::Sub) return CLI::Formatter::make_help(app, name, mode);
  // the usage first, then what the command does, its options and its commands.
  std::string help = make_usage(app, std::move(name)) + "\n" + make_description(app) +
                     make_positionals(app) + make_groups(app, mode) + make_subcommands(app, mode) +
                     "\n" + make_footer(app);
  // CLI11 parts each open with a blank line, and a group closes with one: one blank line apart.
  for (size_t at = help.find("\n\n\n"); at != std::string::npos; at = help.find("\n\n\n", at)) {
    help.erase(at, 1);
  }
  while (help.size() > 1 && help[help.size() - 1] == '\n' && help[help.size() - 2] == '\n') {
    help.pop_back();
  }
  return help;
}

std::string HelpFormatter::make_description(const CLI::App* app) const {
  std::string description = CLI::Formatter::make_description(app);
  // the summary, a blank line, the long text.
  if (const size_t end = description.find('\n'); end + 1 < description.size()) {
    description.insert(end, "\n");
  }
  return WrapText(description, kHelpWidth);
}

std::string HelpFormatter::make_usage(const CLI::App* app, std::string name) const {
  return WrapText(CLI::Formatter::make_usage(app, std::move(name)), kHelpWidth, 4);
}

std::string HelpFormatter::make_footer(const CLI::App* app) const {
  return WrapText(CLI::Formatter::make_footer(app), kHelpWidth);
}

std::string HelpFormatter::make_subcommands(const CLI::App* app, CLI::AppFormatMode mode) const {
  std::string list = CLI::Formatter::make_subcommands(app, mode);
  // CLI11 heads the list with the commands' group, "Subcommands" unless a command names another.
  const std::string heading = "\nSubcommands:\n";
  if (list.rfind(heading, 0) == 0) list.replace(0, heading.size(), "\nCommands:\n");
  return list;
}

std::string HelpFormatter::make_expanded(const CLI::App* sub) const {
  if (!sub->get_name().empty()) return CLI::Formatter::make_expanded(sub);
  // an option group ("What to replay"): its description as a heading, then its options.
  std::string heading = sub->get_description();
  while (!heading.empty() && heading.back() == ' ') heading.pop_back();
  if (sub->get_require_option_max() == 1) heading += " (at most one of these)";
  std::string out = "\n" + WrapText(heading + ":", kHelpWidth) + "\n";
  for (const CLI::Option* opt : sub->get_options()) {
    if (opt != sub->get_help_ptr() && opt != sub->get_help_all_ptr()) {
      out += make_option(opt, false);
    }
  }
  return out;
}

std::string HelpFormatter::make_subcommand(const CLI::App* sub) const {
  return TwoColumns(sub->get_display_name(true), SummaryOf(sub->get_description()), kCommandColumn);
}

std::string HelpFormatter::make_option(const CLI::Option* opt, bool is_positional) const {
  return TwoColumns(make_option_name(opt, is_positional) + make_option_opts(opt),
                    make_option_desc(opt), column_width_);
}

std::string HelpFormatter::make_option_opts(const CLI::Option* opt) const {
  std::string opts = CLI::Formatter::make_option_opts(opt);
  // a placeholder that names each of an option's values ("MIN MAX") needs no " x 2" after it.
  const std::string count = " x " + std::to_string(opt->get_expected());
  if (opt->get_type_name().find(' ') != std::string::npos) {
    if (const size_t at = opts.find(count); at != std::string::npos) opts.erase(at, count.size());
  }
  return opts;
}

void UseHelpFormatter(CLI::App* app) { app->formatter(std::make_shared<HelpFormatter>()); }

}  // namespace graspsynth::apps
