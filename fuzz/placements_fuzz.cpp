// The triangulation of a library's demonstrated placements (solver/placement_cell.hpp), which a
// library over placements (graspsynth-library/2) makes when it is used: the input is (x, y,
// theta) triples of doubles, the last of them a query. A set that spans no volume, also up to
// roundoff, or that repeats a placement is refused with InputError; any other is triangulated,
// and the query located. As the library reader does, only finite values of a sensible size
// reach it (larger or non-finite ones end the input here).
#include <cmath>
#include <cstring>
#include <vector>

#include "fuzz/fuzz_support.hpp"
#include "solver/placement_cell.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth;
  constexpr size_t kTriple = 3 * sizeof(double);
  constexpr size_t kMostPlacements = 64;
  std::vector<Eigen::Vector3d> placements;
  for (size_t at = 0; at + kTriple <= size && placements.size() <= kMostPlacements; at += kTriple) {
    double v[3];
    std::memcpy(v, data + at, kTriple);
    for (const double x : v) {
      if (!std::isfinite(x) || std::abs(x) > 10.0) return 0;
    }
    placements.emplace_back(v[0], v[1], v[2]);
  }
  if (placements.size() < 2) return 0;
  const Eigen::Vector3d query = placements.back();
  placements.pop_back();
  fuzz::RefusedOnlyWithInputError([&] {
    const PlacementTriangulation cells(placements, kDefaultThetaLength, "fuzz placements");
    const PlacementCell cell = cells.Locate(query);
    double sum = 0.0;
    for (const double w : cell.weights) sum += w;
    // inside, the weights are a convex combination; outside, the reason says why.
    if (cell.inside && std::abs(sum - 1.0) > 1e-9) __builtin_trap();
    if (!cell.inside && cell.reason.empty()) __builtin_trap();
    cells.Nearest(query);
  });
  return 0;
}
