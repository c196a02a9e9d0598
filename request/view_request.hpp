#pragma once

/// @file
/// The request of `graspsynth view`: how the browser viewer serves and replays. Its options are
/// described once (ViewOptions); the command checks the replay's figures (speed, rate, hold)
/// with the messages it always had. The replayed file, robot, scene and object are not
/// options. Python has no counterpart.

#include <optional>
#include <string>

#include <Eigen/Core>

#include "request/option.hpp"

namespace graspsynth::request {

/// How to serve and replay; the defaults are the command's.
struct ViewRequest {
  std::optional<Eigen::Vector2d> at;  ///< a trajectory's object centre on the table, m
  std::string address = "127.0.0.1";  ///< IPv4 address to serve on
  int port = 8765;                    ///< TCP port; 0: a free one
  std::string camera;                 ///< "EX,EY,EZ[,TX,TY,TZ]", m; empty: a side view
  bool loop = false;                  ///< replay until stopped
  double speed = 1.0;                 ///< replay speed factor
  double rate_hz = 60.0;              ///< frames published per second
  bool no_wait = false;               ///< start at once, not at the first page's request
  double hold_s = 1.0;                ///< s the last frame is served after the end
  double exit_after_s = 0.0;          ///< s; 0: no limit
  bool joints_only = false;           ///< a trajectory's joint commands, without the physics
};

/// The options of ViewRequest, in the order the flags list them.
const OptionList<ViewRequest>& ViewOptions();

}  // namespace graspsynth::request
