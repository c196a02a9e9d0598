#pragma once

/// @file
/// The one policy for invalid options, whoever gave them (a flag, a Python argument, a file, a
/// caller of the library): an InputError that says what is wrong, never an abort.

#include <string>
#include <string_view>

#include "common/errors.hpp"

namespace graspsynth {

/// Throws InputError "<what>: <why>" unless options.IsValid(&why) (every options struct of the
/// library has IsValid(std::string* why)).
template <class Options>
void RequireValid(const Options& options, std::string_view what) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError(std::string(what) + ": " + why);
}

}  // namespace graspsynth
