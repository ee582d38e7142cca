#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fibrecheck {

/// The whole content of a file, as it is (empty when it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace fibrecheck
