#include "solver/library_info.hpp"

#include <CGAL/version.h>
#include <ceres/version.h>
#include <nlopt.hpp>

namespace graspsynth {

std::string SolverLibraryInfo() {
  return std::string("Ceres ") + CERES_VERSION_STRING + ", NLopt " +
         std::to_string(nlopt::version_major()) + "." + std::to_string(nlopt::version_minor()) +
         "." + std::to_string(nlopt::version_bugfix()) + ", CGAL " + CGAL_VERSION_STR;
}

}  // namespace graspsynth
