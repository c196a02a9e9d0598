#include "request/view_request.hpp"

namespace graspsynth::request {
namespace {

using R = ViewRequest;

// A number of at least `lo` (more than `lo` when `lo_open`) and at most `hi`.
Option<R> Number(const char* name, const char* help, double R::*field, double lo, bool lo_open,
                 double hi = INFINITY) {
  return FieldOption<R>(WithRange(MakeInfo(name, OptionKind::kNumber, help), lo, hi, lo_open),
                        [field](R& r) -> double& { return r.*field; });
}

Option<R> Switch(const char* name, const char* help, bool R::*field) {
  return FieldOption<R>(MakeInfo(name, OptionKind::kBool, help),
                        [field](R& r) -> bool& { return r.*field; });
}

OptionList<R> MakeOptions() {
  OptionList<R> list;
  list.push_back(
      AtOption<R>("X,Y: the object centre on the table for a --trajectory, world frame, "
                  "metres (e.g. -0.30,0.90); default: where the file puts it (its "
                  "\"object_xy\", else the scene's object centre)",
                  [](R& r) -> std::optional<Eigen::Vector2d>& { return r.at; }));
  list.push_back(
      FieldOption<R>(MakeInfo("address", OptionKind::kText,
                              "IPv4 address to serve on; 0.0.0.0 opens the viewer to the network"),
                     [](R& r) -> std::string& { return r.address; }));
  list.push_back(FieldOption<R>(
      WithRange(MakeInfo("port", OptionKind::kInt, "TCP port; 0 picks a free one (printed)"), 0,
                65535),
      [](R& r) -> int& { return r.port; }));
  list.push_back(FieldOption<R>(
      MakeInfo("camera", OptionKind::kText,
               "Start camera: eye EX,EY,EZ and optionally target TX,TY,TZ (metres, world); "
               "default: a side view of the arm and the table"),
      [](R& r) -> std::string& { return r.camera; }));
  list.push_back(Switch("loop", "Replay again and again until stopped", &R::loop));
  list.push_back(Number("speed", "Replay speed factor (> 0)", &R::speed, 0.0, true));
  list.push_back(Number("rate",
                        "Frames published per second (Hz), in (0, 1000]; a --trajectory's "
                        "simulated trial is recorded at this rate",
                        &R::rate_hz, 0.0, true, 1000.0));
  list.push_back(Switch("no_wait",
                        "Start the replay at once instead of when a page first asks for a frame",
                        &R::no_wait));
  list.push_back(Number("hold",
                        "Seconds to keep serving the last frame after the end of the replay",
                        &R::hold_s, 0.0, false));
  list.push_back(Number("exit_after",
                        "Stop after this many seconds in any case (0: no limit; for scripts and "
                        "tests)",
                        &R::exit_after_s, 0.0, false));
  list.push_back(Switch("joints_only",
                        "Play a --trajectory's joint commands alone, without simulating it (the "
                        "object stands still)",
                        &R::joints_only));
  return list;
}

}  // namespace

const OptionList<ViewRequest>& ViewOptions() {
  static const OptionList<ViewRequest> options = MakeOptions();
  return options;
}

}  // namespace graspsynth::request
