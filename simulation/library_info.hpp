#pragma once

#include <string>

namespace graspsynth {

/// Throws std::runtime_error when the libode loaded is not the double-precision build that the
/// headers describe (every call would then corrupt memory). The simulation calls it before its
/// first use of ODE (EnsureOdeThread).
void RequireDoublePrecisionOde();

/// The ODE build the simulation module runs on, e.g. "ODE 0.16.2 (ODE_double_precision ...)".
/// Throws std::runtime_error when libode is not the double-precision build graspsynth needs.
std::string SimulationLibraryInfo();

}  // namespace graspsynth
