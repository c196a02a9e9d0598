#pragma once

/// @file
/// The one way graspsynth reads an input file. Every reader (JSON documents, demonstration logs,
/// meshes, the robot description, key files, resume folders, the viewer's assets) goes through
/// ReadInputFile, which reads regular files only and each kind of file up to a size limit:
///
/// - a folder, a named pipe (FIFO), a device or a socket is refused by name, looked at before it
///   is opened, and opened without blocking (a FIFO put in its place in between does not hang);
/// - a file over its kind's limit is refused before anything is allocated for it, and one that
///   grows past the limit while it is read is refused when the limit is passed;
/// - a path that holds a NUL byte (possible from a JSON field or from Python) is refused, not cut.
///
/// The limits are stated in docs/formats.md ("Input limits"); the shipped files sit far under
/// them.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace graspsynth {

/// What an input file is: its name in messages (e.g. "object description") and the most bytes
/// it may hold.
struct InputFileKind {
  std::string_view name;
  uint64_t max_bytes = 0;
};

/// The kinds of input file and their limits (docs/formats.md, "Input limits").
namespace input_kind {
inline constexpr uint64_t kMiB = uint64_t{1} << 20;
/// A JSON document (libraries, scenes, objects, operators, trajectories, grasps, calibrations,
/// a resume folder's run.json). The largest shipped one, the placements library, is 11 MiB.
inline constexpr uint64_t kJsonBytes = 256 * kMiB;
inline constexpr InputFileKind kJson{"JSON file", kJsonBytes};
inline constexpr InputFileKind kLibrary{"grasp library", kJsonBytes};
inline constexpr InputFileKind kObject{"object description", kJsonBytes};
inline constexpr InputFileKind kScene{"scene description", kJsonBytes};
inline constexpr InputFileKind kTrajectory{"trajectory file", kJsonBytes};
inline constexpr InputFileKind kCalibration{"teleoperation calibration", kJsonBytes};
inline constexpr InputFileKind kOperator{"synthetic operator file", kJsonBytes};
/// A demonstration log (CSV); the shipped ones are at most 0.2 MiB.
inline constexpr InputFileKind kDemoLog{"demonstration log", 64 * kMiB};
/// A mesh (STL or OBJ); the shipped ones are at most 19 KiB; a scanned object's mesh of a few
/// million triangles fits.
inline constexpr InputFileKind kMesh{"mesh", 512 * kMiB};
/// The robot description (URDF); the shipped one is 34 KiB.
inline constexpr InputFileKind kRobot{"robot description", 16 * kMiB};
/// A teleoperation key file: one line of at most 2 x 1024 hexadecimal digits and comments.
inline constexpr InputFileKind kKey{"key file", 64 * 1024};
/// A finished job of a resume folder.
inline constexpr InputFileKind kResumeJob{"resume job file", 256 * kMiB};
/// A file the viewer serves (its page, scripts, three.js).
inline constexpr InputFileKind kViewerAsset{"viewer file", 64 * kMiB};
/// A file of a resumed run's input folder, read for its fingerprint.
inline constexpr InputFileKind kFingerprinted{"input file", 512 * kMiB};
/// A file another program wrote for us (gnuplot's figure and log).
inline constexpr InputFileKind kToolOutput{"tool output", 256 * kMiB};
}  // namespace input_kind

/// The bytes of the regular file at `path`, which must hold at most `kind.max_bytes`. Throws
/// InputError "cannot read <kind.name> '<path>': <why>" when the file is missing, unreadable,
/// not a regular file (a folder, FIFO, device or socket: refused without blocking), over the
/// limit, or when `path` holds a NUL byte.
std::string ReadInputFile(const std::filesystem::path& path, const InputFileKind& kind);

}  // namespace graspsynth
