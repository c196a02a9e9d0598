#pragma once

#include <string>

namespace graspsynth {

/// The ODE build the simulation module runs on, e.g. "ODE 0.16.2 (ODE_double_precision ...)".
/// Throws std::runtime_error when libode is not the double-precision build graspsynth needs.
std::string SimulationLibraryInfo();

}  // namespace graspsynth
