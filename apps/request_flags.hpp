#pragma once

/// @file
/// A request's options (request/option.hpp) as a command's flags: each option is a flag named
/// after it (--min-robustness; a bool that is on by default is --no-NAME, one spelled on|off
/// takes the word), with its help, range and default, and --config FILE reads a JSON object of
/// options. RequestFlags::Build() makes the request: the defaults, then the config file, then
/// the flags as given, each value checked by the one check every front end shares.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/job_runner.hpp"
#include "request/option.hpp"

namespace CLI {
class App;
}

namespace graspsynth::apps {

/// The flags a command was given, as text, in the order given (filled while CLI11 parses).
struct GivenFlags {
  struct Given {
    size_t option = 0;  ///< index in the option list
    std::string flag;   ///< as the command line spells it, for messages
    std::string text;   ///< its value ("true"/"false" for a switch; "a b" for a pair)
  };
  std::vector<Given> given;
  std::string config;  ///< --config FILE, or ""
};

/// Adds a flag for each of `infos` (with the defaults `defaults`, shown in the help), and
/// --config when `with_config`, to `app`; what the command line gives is recorded in `*given`.
void AddOptionFlags(CLI::App* app, const std::vector<request::OptionInfo>& infos,
                    const std::vector<request::Value>& defaults, bool with_config,
                    GivenFlags* given);

/// Throws InputError "<flag> is required" for the first required option of `infos` that
/// neither the config file nor the command line gave (`set[i]`: option i was given).
void RequireGiven(const std::vector<request::OptionInfo>& infos,
                  const std::vector<request::Value>& defaults, const std::vector<bool>& set);

/// Adds each option of `request` but threads (which changes no result) to a resume folder's
/// `identity` as its value, wherever it came from (default, --config or flag), so that a run
/// resumed with other options, in a flag or in the config file, is refused.
template <class R>
void AddRequestIdentity(const request::OptionList<R>& options, const R& request,
                        RunIdentity* identity) {
  for (const request::Option<R>& o : options) {
    if (o.info.name == "threads") continue;
    identity->Add("option " + o.info.name, request::ShowValue(o.info, o.get(request)));
  }
}

/// A request's options as flags of a command (see the file comment).
template <class R>
class RequestFlags {
 public:
  /// Adds the flags of `options` (which must outlive this) to `app`, and --config unless
  /// `with_config` is false (a part of a command's options, such as the physics perturbation's).
  RequestFlags(CLI::App* app, const request::OptionList<R>& options, bool with_config = true)
      : options_(&options), given_(std::make_shared<GivenFlags>()) {
    const R defaults{};
    for (const request::Option<R>& o : options) {
      infos_.push_back(o.info);
      defaults_.push_back(o.get(defaults));
    }
    AddOptionFlags(app, infos_, defaults_, with_config, given_.get());
  }

  /// The file --config gave, or "" (read by Build()).
  const std::string& config() const { return given_->config; }

  /// The request of the defaults, the config file and the flags, in that order. Throws
  /// InputError naming the file and field or the flag at fault.
  R Build() const {
    R request{};
    std::vector<bool> set(options_->size(), false);
    if (!given_->config.empty()) {
      for (size_t k : request::ApplyConfig(*options_, given_->config, &request)) set[k] = true;
    }
    for (const GivenFlags::Given& g : given_->given) {
      const request::Option<R>& o = (*options_)[g.option];
      request::Apply(o, request::ParseText(o.info, g.text, g.flag), g.flag, &request);
      set[g.option] = true;
    }
    RequireGiven(infos_, defaults_, set);
    return request;
  }

 private:
  const request::OptionList<R>* options_;
  std::vector<request::OptionInfo> infos_;  // what the flags show, in the options' order
  std::vector<request::Value> defaults_;
  std::shared_ptr<GivenFlags> given_;  // shared with the flags' callbacks
};

}  // namespace graspsynth::apps
