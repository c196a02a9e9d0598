#include "common/orientation_list.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "common/errors.hpp"

namespace graspsynth {
namespace {

constexpr size_t kMaxOrientations = 100000;

// The number in `item`, or nullopt-like NaN when it is not a finite number.
double Number(const std::string& item) {
  char* end = nullptr;
  const double v = std::strtod(item.c_str(), &end);
  if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(v)) return NAN;
  return v;
}

}  // namespace

std::vector<double> ParseOrientationList(const std::string& text, const std::string& option) {
  return ParseNumberList(text, option, "degrees");
}

std::vector<double> ParseNumberList(const std::string& text, const std::string& option,
                                    const std::string& unit) {
  const std::string values = unit == "degrees" ? "orientations" : "values";
  std::vector<double> thetas;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto bad = [&](const std::string& why) {
      return InputError(option + ": '" + item + "' " + why + " (in '" + text + "')");
    };
    std::vector<std::string> parts;
    std::stringstream is(item);
    std::string part;
    while (std::getline(is, part, ':')) parts.push_back(part);
    if (parts.size() == 1) {
      const double v = Number(parts[0]);
      if (std::isnan(v)) throw bad("is not a finite number of " + unit);
      thetas.push_back(v);
    } else if (parts.size() == 3) {
      const double from = Number(parts[0]), to = Number(parts[1]), step = Number(parts[2]);
      if (std::isnan(from) || std::isnan(to) || std::isnan(step)) {
        throw bad("is not a range FROM:TO:STEP of finite numbers");
      }
      if (!(step > 0.0) || to < from) throw bad("needs FROM <= TO and STEP > 0");
      // counted in double first: the count of a wide range does not fit an int (to - from
      // can even overflow to infinity).
      const double n = std::floor((to - from) / step + 1e-9);
      if (!(n < kMaxOrientations)) throw bad("has more than 100000 " + values);
      for (int k = 0; k <= static_cast<int>(n); ++k) thetas.push_back(from + k * step);
    } else {
      throw bad("is neither a number nor a range FROM:TO:STEP");
    }
    if (thetas.size() > kMaxOrientations) {
      throw InputError(option + ": more than 100000 " + values + " in all (in '" + text + "')");
    }
  }
  if (thetas.empty()) {
    throw InputError(option + ": no " + (unit == "degrees" ? "orientation" : "value") + " in '" +
                     text + "'");
  }
  return thetas;
}

std::vector<Eigen::Vector2d> ParsePositionGrid(const std::string& x, const std::string& y,
                                               const std::string& x_option,
                                               const std::string& y_option) {
  if (x.empty() != y.empty()) {
    throw InputError(x_option + " and " + y_option + " go together (a grid of positions)");
  }
  std::vector<Eigen::Vector2d> grid;
  if (x.empty()) return grid;
  const std::vector<double> xs = ParseNumberList(x, x_option, "metres");
  for (double yv : ParseNumberList(y, y_option, "metres")) {
    for (double xv : xs) grid.emplace_back(xv, yv);
  }
  return grid;
}

}  // namespace graspsynth
