#include "simulation/library_info.hpp"

#include <ode/ode.h>

#include <stdexcept>

#ifndef dDOUBLE
#error "graspsynth needs ODE built in double precision (Debian's libode-dev is)"
#endif

namespace graspsynth {

std::string SimulationLibraryInfo() {
  // the header's precision must match the library's, or every call corrupts memory.
  if (!dCheckConfiguration("ODE_double_precision")) {
    throw std::runtime_error("libode is not the double-precision build; install libode-dev");
  }
  return std::string("ODE (") + dGetConfiguration() + ")";
}

}  // namespace graspsynth
