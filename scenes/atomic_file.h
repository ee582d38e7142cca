#pragma once

#include <string>

namespace fibrecheck {

/// Writes `contents` to `path` through a temporary file in the same folder and a rename, so an
/// interrupted run never leaves a half-written file. Throws std::runtime_error on failure.
void write_file_atomically(const std::string& path, const std::string& contents);

}  // namespace fibrecheck
