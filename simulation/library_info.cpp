#include "simulation/library_info.hpp"

#include <ode/ode.h>

#include <stdexcept>

#ifndef dDOUBLE
#error "graspsynth needs ODE built in double precision (Debian's libode-dev is)"
#endif

namespace graspsynth {

void RequireDoublePrecisionOde() {
  // the header's precision must match the library's, or every call corrupts memory.
  if (!dCheckConfiguration("ODE_double_precision")) {
    throw std::runtime_error(
        "the ODE library loaded is not the double-precision build that graspsynth was compiled "
        "for (ODE reports: " +
        std::string(dGetConfiguration()) + "); install Debian's libode-dev and rebuild");
  }
}

std::string SimulationLibraryInfo() {
  RequireDoublePrecisionOde();
  return std::string("ODE (") + dGetConfiguration() + ")";
}

}  // namespace graspsynth
