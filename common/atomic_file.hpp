#pragma once

/// @file
/// Whole-file input, and atomic file output: write to a temporary file in the same folder, then
/// rename it over the destination, so that an interrupted run never leaves a half-written file.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace graspsynth {

/// The bytes of the file at `path`, or std::nullopt when it cannot be opened or is a folder (the
/// caller names what the file is in its error). Throws InputError naming the path when reading
/// fails after the file was opened.
std::optional<std::string> ReadWholeFile(const std::filesystem::path& path);

/// Writes `contents` to `path` atomically (temporary file + rename). Creates missing parent
/// folders. Throws InputError naming the path when the folder or file cannot be written.
void WriteFileAtomically(const std::filesystem::path& path, std::string_view contents);

/// Creates `path` with `contents`, readable and writable by its owner only (mode 0600), for
/// secrets: the file appears whole or not at all, and an existing file is never replaced.
/// Throws InputError naming the path when it exists or cannot be written.
void CreateOwnerOnlyFileAtomically(const std::filesystem::path& path, std::string_view contents);

}  // namespace graspsynth
