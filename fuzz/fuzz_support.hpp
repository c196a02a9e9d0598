#pragma once

/// @file
/// What every fuzz target shares: the input as text, and the rule that bad input may only
/// end in an InputError. Any other exception escapes LLVMFuzzerTestOneInput, and libFuzzer
/// reports it as a crash, as it does for a sanitizer report or an abort.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "common/errors.hpp"

namespace graspsynth::fuzz {

inline std::string_view AsText(const uint8_t* data, size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// Runs `parse`; an InputError (a clear message for the user) is the accepted way to refuse.
template <typename Parse>
void RefusedOnlyWithInputError(Parse&& parse) {
  try {
    parse();
  } catch (const InputError&) {
  }
}

}  // namespace graspsynth::fuzz
