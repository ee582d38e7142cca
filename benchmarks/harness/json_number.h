#pragma once

#include <nlohmann/json.hpp>

namespace fibrecheck {

/// A number as the harness writes it: JSON has no NaN or infinity, so those are null (a fit with
/// too few points, a speed-up no run reached).
nlohmann::json number_or_null(double x);

/// A number as the harness reads it back: NaN where the file holds null.
double number_from(const nlohmann::json& j);

/// The number `key` of the object `j`, which must be there (null reads as NaN); throws
/// nlohmann::json::out_of_range naming the key otherwise.
double number_at(const nlohmann::json& j, const char* key);

}  // namespace fibrecheck
