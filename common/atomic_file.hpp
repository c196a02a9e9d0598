#pragma once

/// @file
/// Atomic file output: write to a temporary file in the same folder, then rename it over the
/// destination, so that an interrupted run never leaves a half-written file. (Input files are
/// read by common/input_file.hpp.)

#include <filesystem>
#include <string>
#include <string_view>

namespace graspsynth {

/// Writes `contents` to `path` atomically (temporary file + rename). Creates missing parent
/// folders. Throws InputError naming the path when the folder or file cannot be written.
void WriteFileAtomically(const std::filesystem::path& path, std::string_view contents);

/// Creates `path` with `contents`, readable and writable by its owner only (mode 0600), for
/// secrets: the file appears whole or not at all, and an existing file is never replaced.
/// Throws InputError naming the path when it exists or cannot be written.
void CreateOwnerOnlyFileAtomically(const std::filesystem::path& path, std::string_view contents);

}  // namespace graspsynth
