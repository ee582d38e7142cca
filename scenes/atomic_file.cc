#include "atomic_file.h"

#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "input_error.h"

namespace fibrecheck {

void create_parent_folder(const std::string& path) {
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::error_code error;
  if (!folder.empty() && !std::filesystem::is_directory(folder) &&
      !std::filesystem::create_directories(folder, error))
    throw InputError(path, "", "cannot create its folder: " + error.message());
}

void write_atomically(const std::string& path,
                      const std::function<void(const std::string& temporary)>& write) {
  namespace fs = std::filesystem;
  create_parent_folder(path);
  const fs::path target(path);
  const std::string temporary =
      (target.parent_path() / ("." + target.stem().string() + "-tmp" + std::to_string(getpid()) +
                               target.extension().string()))
          .string();
  try {
    write(temporary);
  } catch (...) {
    std::remove(temporary.c_str());
    throw;
  }
  std::error_code error;
  fs::rename(temporary, target, error);
  if (error) {
    std::remove(temporary.c_str());
    throw InputError(path, "", "cannot write it: " + error.message());
  }
}

void write_file_atomically(const std::string& path, const std::string& contents) {
  write_atomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (out) out << contents;
    if (out) out.flush();
    if (!out) throw InputError(path, "", "cannot write it");
  });
}

std::string file_name_slug(std::string name) {
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '_';
  return name;
}

}  // namespace fibrecheck
