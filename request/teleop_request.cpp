#include "request/teleop_request.hpp"

#include <utility>

namespace graspsynth::request {
namespace {

// A number option of request type R over the field `field`.
template <class R>
Option<R> Number(OptionInfo info, double R::*field) {
  return FieldOption<R>(std::move(info), [field](R& r) -> double& { return r.*field; });
}

// An integer option of request type R over the field `field`.
template <class R>
Option<R> Integer(OptionInfo info, int R::*field) {
  return FieldOption<R>(std::move(info), [field](R& r) -> int& { return r.*field; });
}

// A text option of request type R over the field `field`.
template <class R>
Option<R> Text(OptionInfo info, std::string R::*field) {
  return FieldOption<R>(std::move(info), [field](R& r) -> std::string& { return r.*field; });
}

// The server's link: port, address, the insecure switch.
void AddLinkOptions(OptionList<TeleopRequest>* list) {
  using R = TeleopRequest;
  list->push_back(
      Integer<R>(WithRange(MakeInfo("port", OptionKind::kInt,
                                    "UDP port to listen on (0..65535); 0 picks a free one"),
                           0, 65535),
                 &R::port));
  list->push_back(Text<R>(MakeInfo("bind", OptionKind::kText,
                                   "IPv4 address to listen on; 0.0.0.0 accepts operators from the "
                                   "network (then with --key-file, or --insecure)"),
                          &R::bind));
  list->push_back(FieldOption<R>(
      MakeInfo("insecure", OptionKind::kBool,
               "Allow --bind beyond this machine without a key (anyone who reaches the port can "
               "then drive the robot)"),
      [](R& r) -> bool& { return r.insecure; }));
}

// The session: orientations, object position, rate, timeout, hold.
void AddSessionOptions(OptionList<TeleopRequest>* list) {
  using R = TeleopRequest;
  list->push_back(NumberListOption<R>(
      "orientations", "degrees",
      "Object orientations theta (deg), in the order the session walks through them (the "
      "next-orientation button): numbers and ranges FROM:TO:STEP, e.g. 20,30 or 20:100:10",
      [](R& r) -> std::string& { return r.orientations; }));
  list->push_back(
      AtOption<R>("X,Y: the object centre on the table, world frame, metres (e.g. "
                  "-0.30,0.90); default: the scene's object centre (the paper's fixed "
                  "position)",
                  [](R& r) -> std::optional<Eigen::Vector2d>& { return r.at; }));
  list->push_back(Number<R>(
      WithRange(MakeInfo("rate", OptionKind::kNumber, "Control rate, Hz (1..1000)"), 1.0, 1000.0),
      &R::rate_hz));
  list->push_back(
      Number<R>(WithRange(MakeInfo("timeout_ms", OptionKind::kNumber,
                                   "A silence longer than this (ms) holds the robot still"),
                          0.0, INFINITY, true),
                &R::timeout_ms));
  list->push_back(Number<R>(
      WithRange(MakeInfo("end_hold", OptionKind::kNumber,
                         "Seconds the robot holds after the end-of-trial button before the "
                         "judgement (0..60)"),
                0.0, 60.0),
      &R::end_hold_s));
}

// The viewer, the logs' operator and the session's end.
void AddOutputOptions(OptionList<TeleopRequest>* list) {
  using R = TeleopRequest;
  list->push_back(Integer<R>(
      WithRange(MakeInfo("viewer_port", OptionKind::kInt,
                         "Serve the browser viewer on this TCP port (0: a free one; -1: no "
                         "viewer); the URL is printed"),
                -1, 65535),
      &R::viewer_port));
  list->push_back(Text<R>(MakeInfo("camera", OptionKind::kText,
                                   "Viewer start camera: eye EX,EY,EZ and optionally target "
                                   "TX,TY,TZ (m); default: a side view of the arm and the table"),
                          &R::camera));
  list->push_back(Text<R>(MakeInfo("operator", OptionKind::kText,
                                   "Operator name written into the logs (default: none)"),
                          &R::operator_name));
  list->push_back(Number<R>(
      WithRange(
          MakeInfo("exit_after", OptionKind::kNumber,
                   "End the session after this many seconds in any case, for scripts (0: never)"),
          0.0),
      &R::exit_after_s));
}

OptionList<TeleopRequest> MakeServerOptions() {
  OptionList<TeleopRequest> list;
  AddLinkOptions(&list);
  AddSessionOptions(&list);
  AddOutputOptions(&list);
  return list;
}

OptionList<TeleopClientRequest> MakeClientOptions() {
  using R = TeleopClientRequest;
  OptionList<R> list;
  list.push_back(Text<R>(MakeInfo("host", OptionKind::kText, "Server's IPv4 address"), &R::host));
  list.push_back(Integer<R>(
      WithRange(MakeInfo("port", OptionKind::kInt, "Server's UDP port (1..65535)"), 1, 65535),
      &R::port));
  list.push_back(
      Number<R>(WithRange(MakeInfo("speed", OptionKind::kNumber, "Replay speed factor (> 0)"), 0.0,
                          INFINITY, true),
                &R::speed));
  list.push_back(Number<R>(
      WithRange(MakeInfo("linger", OptionKind::kNumber,
                         "After the end of session, listen for states until none came for this "
                         "long (s)"),
                0.0),
      &R::linger_s));
  return list;
}

}  // namespace

const OptionList<TeleopRequest>& TeleopServerOptions() {
  static const OptionList<TeleopRequest> options = MakeServerOptions();
  return options;
}

const OptionList<TeleopClientRequest>& TeleopClientOptions() {
  static const OptionList<TeleopClientRequest> options = MakeClientOptions();
  return options;
}

}  // namespace graspsynth::request
