#include "apps/request_flags.hpp"

#include <CLI/CLI.hpp>

#include <cctype>

#include "common/errors.hpp"

namespace graspsynth::apps {
namespace {

using request::OptionInfo;
using request::OptionKind;

std::string HelpOf(const OptionInfo& info, const request::Value& default_value) {
  std::string help = info.help;
  if (info.Negated(default_value) && !help.empty()) {
    help[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(help[0])));
    help = "Turn off: " + help;
  }
  if (info.required) help += " (required)";
  return help;
}

}  // namespace

void AddOptionFlags(CLI::App* app, const std::vector<OptionInfo>& infos,
                    const std::vector<request::Value>& defaults, bool with_config,
                    GivenFlags* given) {
  for (size_t k = 0; k < infos.size(); ++k) {
    const OptionInfo& info = infos[k];
    const std::string flag = info.Flag(defaults[k]);
    const std::string help = HelpOf(info, defaults[k]);
    const auto record = [given, k, flag](std::string text) {
      given->given.push_back({k, flag, std::move(text)});
    };
    CLI::Option* option = nullptr;
    if (info.kind == OptionKind::kBool && !info.on_off) {
      const bool negated = info.Negated(defaults[k]);
      option = app->add_flag_callback(
          flag, [record, negated] { record(negated ? "false" : "true"); }, help);
    } else if (info.kind == OptionKind::kNumberPair) {
      option =
          app->add_option_function<std::vector<std::string>>(
                 flag, [record](const std::vector<std::string>& v) { record(v[0] + " " + v[1]); },
                 help)
              ->expected(2);
    } else {
      option = app->add_option_function<std::string>(flag, record, help);
    }
    const std::string shown = request::ShowValue(info, defaults[k]);
    if (!(info.kind == OptionKind::kBool && !info.on_off) && !shown.empty() && !info.required) {
      option->default_str(shown);
    }
    if (!info.group.empty()) option->group(info.group);
    if (const std::string placeholder = info.Placeholder(); !placeholder.empty()) {
      option->type_name(placeholder);
    }
  }
  if (!with_config) return;
  app->add_option("--config", given->config,
                  "A JSON file of these options, by name ({\"perturb\": 5, \"method\": "
                  "\"line\"}), read before the flags, which override it");
}

void RequireGiven(const std::vector<OptionInfo>& infos, const std::vector<request::Value>& defaults,
                  const std::vector<bool>& set) {
  for (size_t k = 0; k < infos.size(); ++k) {
    if (infos[k].required && !set[k]) {
      throw InputError(infos[k].Flag(defaults[k]) + " is required (or give '" + infos[k].name +
                       "' in --config)");
    }
  }
}

}  // namespace graspsynth::apps
