#pragma once

/// @file
/// The requests of `graspsynth teleop` (the live teleoperation server) and `graspsynth
/// teleop-client` (a demonstration log replayed over UDP): their options described once
/// (TeleopServerOptions, TeleopClientOptions), with their ranges, so that the command line and
/// a file of options (`--config FILE`) are checked by the same code. The files are not options:
/// the calibration (`--calibration`, graspsynth-teleop-config/1), the key (`--key-file`), the
/// record folder, the summary, the port file and the replayed log. The command turns the
/// request into the session's options (teleop::TeleopOptions; this module does not link
/// teleop/, which links no request either); the defaults are the session's. Python has no
/// counterpart.

#include <optional>
#include <string>

#include <Eigen/Core>

#include "request/option.hpp"

namespace graspsynth::request {

/// How the teleoperation server listens, ticks and ends; the defaults are the command's and
/// those of teleop::TeleopOptions.
struct TeleopRequest {
  int port = 9870;                 ///< UDP port to listen on; 0: a free one
  std::string bind = "127.0.0.1";  ///< IPv4 address to listen on
  bool insecure = false;           ///< allow a bind beyond 127.0.0.0/8 without a key
  /// Object orientations theta, deg: numbers and ranges FROM:TO:STEP, in the session's order.
  std::string orientations = "20,30,40,50,60,70,80,90,100";
  std::optional<Eigen::Vector2d> at;  ///< object centre on the table, world, m; none: the scene's
  double rate_hz = 60.0;              ///< control rate, Hz, in [1, 1000]
  double timeout_ms = 200.0;          ///< ms of silence (> 0) after which the robot holds still
  double end_hold_s = 1.0;            ///< s held after the end-of-trial button, in [0, 60]
  int viewer_port = -1;               ///< TCP port of the browser viewer; 0: a free one; -1: none
  std::string camera;                 ///< viewer camera "EX,EY,EZ[,TX,TY,TZ]", m; empty: default
  std::string operator_name;          ///< written into the logs; empty: none
  double exit_after_s = 0.0;          ///< s after which the session ends in any case; 0: never
};

/// How the client replays a log to a server; the defaults are the command's.
struct TeleopClientRequest {
  std::string host = "127.0.0.1";  ///< the server's IPv4 address
  int port = 9870;                 ///< the server's UDP port, in [1, 65535]
  double speed = 1.0;              ///< replay speed factor, > 0
  double linger_s = 2.0;           ///< s without a state, after the end, before it stops
};

/// The options of TeleopRequest, in the order the flags list them.
const OptionList<TeleopRequest>& TeleopServerOptions();

/// The options of TeleopClientRequest, in the order the flags list them.
const OptionList<TeleopClientRequest>& TeleopClientOptions();

}  // namespace graspsynth::request
