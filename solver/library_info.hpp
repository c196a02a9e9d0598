#pragma once

#include <string>

namespace graspsynth {

/// Versions of the optimization and geometry libraries of the solver module: Ceres, NLopt, CGAL.
std::string SolverLibraryInfo();

}  // namespace graspsynth
