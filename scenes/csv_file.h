#pragma once

#include <string>
#include <vector>

namespace fibrecheck {

/// Writes `rows` (each a list of cells) as CSV with `header`, atomically.
void write_csv(const std::string& path, const std::vector<std::string>& header,
               const std::vector<std::vector<std::string>>& rows);

/// A number as a CSV cell: 17 significant digits, empty for NaN or infinity.
std::string cell(double value);

}  // namespace fibrecheck
