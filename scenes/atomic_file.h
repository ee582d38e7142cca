#pragma once

#include <string>

namespace fibrecheck {

/// Writes `contents` to `path` through a temporary file in the same folder and a rename, so an
/// interrupted run never leaves a half-written file. Throws std::runtime_error on failure.
void write_file_atomically(const std::string& path, const std::string& contents);

/// Makes sure the folder that will hold `path` exists (creating it and its parents); throws
/// InputError naming `path` when it cannot be made.
void create_parent_folder(const std::string& path);

}  // namespace fibrecheck
