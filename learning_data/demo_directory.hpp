#pragma once

/// @file
/// Reading a folder of demonstration logs: the good files are read, every bad one is reported
/// with its reason, and one bad file never stops the others.

#include <filesystem>
#include <string>
#include <vector>

#include "learning_data/demo_log.hpp"

namespace graspsynth {

/// A file of a demonstration folder that the reader rejected.
struct RejectedDemoFile {
  std::string file;    ///< the file's path
  std::string reason;  ///< the reader's message (names the file, line and column)
};

/// What ReadDemoDirectory found.
struct DemoDirectory {
  std::string directory;                   ///< the folder as named (ReadDemoDirectory's `name`)
  std::vector<DemoLog> logs;               ///< the good logs, sorted by file name
  std::vector<RejectedDemoFile> rejected;  ///< the bad files with reasons, sorted by file name
};

/// Reads every entry whose name ends in ".csv" directly in `directory` (no recursion; other
/// files and names starting with '.', such as temporary files of an interrupted atomic write,
/// are ignored) with ReadDemoLog: one that is not a regular file (a folder, a named pipe, a
/// device) is rejected with that reason. Files are visited in file-name order, so the result does
/// not depend on the file system's listing order.
/// The result names the folder `name`, or `directory` as given when `name` is empty, and each file
/// the folder's name joined with the file's name (every log's `source`, every rejected `file`,
/// and the reader's reasons about a file's content; a file that cannot be opened is named as
/// opened): the shipped folder read by a default is named relative to the project root
/// (DataRelativeName), so that outputs are the same bytes on every clone.
/// Throws InputError only when `directory` does not exist or is not a readable folder; a bad log
/// goes to `rejected` with its reason.
DemoDirectory ReadDemoDirectory(const std::filesystem::path& directory,
                                const std::string& name = {});

/// ReadDemoDirectory(DefaultDemoDirectory(object_name)), named relative to the project root
/// ("learning_data/demos/theta020_trial03.csv").
DemoDirectory ReadDefaultDemoDirectory(const std::string& object_name = "pan");

/// The folder of an object's shipped learning data (its demonstrations, operator and library):
/// learning_data/ for the pan, the study's reference object, whose files have always been
/// there; learning_data/objects/<object_name>/ for every other object. Under the data directory
/// (common/data_dir.hpp).
std::filesystem::path ObjectLearningDataDirectory(const std::string& object_name);

/// The shipped demonstrations of `object_name`: <ObjectLearningDataDirectory>/demos.
std::filesystem::path DefaultDemoDirectory(const std::string& object_name = "pan");

}  // namespace graspsynth
