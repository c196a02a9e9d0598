#pragma once

/// @file
/// The exception thrown for bad user input: a file, a line of text, a command-line value.

#include <stdexcept>
#include <string>

namespace graspsynth {

/// Bad input from a user or a file. The message names where (file, line, field) and the value,
/// so that it can be shown as it is.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace graspsynth
