#pragma once

/// @file
/// The grammar of a list of object orientations on the command line, one for every command:
/// comma-separated items, each a number of degrees or an inclusive range FROM:TO:STEP (and of
/// other lists of numbers in the same shape: the positions of --x and --y).

#include <string>
#include <vector>

#include <Eigen/Core>

namespace graspsynth {

/// Parses a comma-separated list of orientations (deg); each item is a finite number or a
/// range FROM:TO:STEP (inclusive, FROM <= TO, STEP > 0), at most 100000 values in all, e.g.
/// "0:20:1,100:120:5" or "40,45". Throws InputError naming `option` (e.g. "--orientations"),
/// the item and the whole text when an item is malformed or the list is empty.
std::vector<double> ParseOrientationList(const std::string& text, const std::string& option);

/// The same grammar for other quantities: `unit` names them in the messages ("metres").
std::vector<double> ParseNumberList(const std::string& text, const std::string& option,
                                    const std::string& unit);

/// The object positions of two lists of metres in this grammar, `x` (option `x_option`) and `y`
/// (`y_option`): every x at every y, y outermost; none when both are empty. Throws InputError
/// when only one is given or a list is malformed.
std::vector<Eigen::Vector2d> ParsePositionGrid(const std::string& x, const std::string& y,
                                               const std::string& x_option,
                                               const std::string& y_option);

}  // namespace graspsynth
