#pragma once

#include <functional>
#include <string>

namespace fibrecheck {

/// Writes `path` so that an interrupted run never leaves half a file: `write` fills a temporary
/// file in the same folder (its name keeps the extension, for writers that choose the format by
/// it, and the process id, so two runs never share it), which is then renamed to `path`. The
/// folder is made if missing; on failure the temporary file is removed. Throws InputError naming
/// `path` when it cannot be written (what `write` throws is passed on).
void write_atomically(const std::string& path,
                      const std::function<void(const std::string& temporary)>& write);

/// `write_atomically` with `contents` as the file.
void write_file_atomically(const std::string& path, const std::string& contents);

/// Makes sure the folder that will hold `path` exists (creating it and its parents); throws
/// InputError naming `path` when it cannot be made.
void create_parent_folder(const std::string& path);

/// `name` fit for a file name: every character but letters, digits, '_' and '-' becomes '_'.
std::string file_name_slug(std::string name);

}  // namespace fibrecheck
