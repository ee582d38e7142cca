#include "json_number.h"

#include <cmath>

namespace fibrecheck {

nlohmann::json number_or_null(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
}

double number_from(const nlohmann::json& j) {
  return j.is_number() ? j.get<double>() : NAN;
}

double number_at(const nlohmann::json& j, const char* key) {
  return number_from(j.at(key));
}

}  // namespace fibrecheck
