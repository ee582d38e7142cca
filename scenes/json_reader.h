#pragma once

#include <Eigen/Core>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "input_error.h"

namespace fibrecheck {

/// A view of one JSON object at a path (`fibres[2]`): typed, range-checked reads that name the
/// field on failure, and a final check that no key was left unread (a typo must not silently
/// change the physics).
class ObjectReader {
 public:
  ObjectReader(const nlohmann::json& object, std::string path, const std::string& file)
      : object_(object), path_(std::move(path)), file_(file) {
    if (!object_.is_object()) fail(path_, "must be a JSON object");
  }

  [[noreturn]] void fail(const std::string& field, const std::string& reason) const {
    throw InputError(file_, field, reason);
  }

  std::string field(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }

  bool has(const std::string& key) {
    used_.insert(key);
    return object_.contains(key) && !object_.at(key).is_null();
  }

  const nlohmann::json& at(const std::string& key) {
    used_.insert(key);
    if (!object_.contains(key)) fail(field(key), "is required");
    return object_.at(key);
  }

  double number(const std::string& key, double fallback) {
    return has(key) ? number(key) : fallback;
  }

  double number(const std::string& key) {
    const nlohmann::json& value = at(key);
    if (!value.is_number()) fail(field(key), "must be a number, got " + type_name(value));
    const double x = value.get<double>();
    if (!std::isfinite(x)) fail(field(key), "must be a finite number");
    return x;
  }

  long integer(const std::string& key, long fallback) {
    if (!has(key)) return fallback;
    const nlohmann::json& value = at(key);
    if (value.is_number_integer()) return value.get<long>();
    if (value.is_number_float()) {
      const double x = value.get<double>();
      if (std::isfinite(x) && x == std::floor(x) && std::fabs(x) < 9e15)
        return static_cast<long>(x);
    }
    fail(field(key), "must be a whole number, got " + value.dump());
  }

  std::string string(const std::string& key) {
    const nlohmann::json& value = at(key);
    if (!value.is_string()) fail(field(key), "must be a string, got " + type_name(value));
    return value.get<std::string>();
  }

  std::string string(const std::string& key, const std::string& fallback) {
    return has(key) ? string(key) : fallback;
  }

  Eigen::Vector3d vector3(const std::string& key) {
    const nlohmann::json& value = at(key);
    if (!value.is_array() || value.size() != 3)
      fail(field(key), "must be an array of three numbers, got " + value.dump());
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) {
      if (!value[i].is_number())
        fail(field(key) + "[" + std::to_string(i) + "]",
             "must be a number, got " + type_name(value[i]));
      v[i] = value[i].get<double>();
      if (!std::isfinite(v[i]))
        fail(field(key) + "[" + std::to_string(i) + "]", "must be a finite number");
    }
    return v;
  }

  Eigen::Vector3d vector3(const std::string& key, const Eigen::Vector3d& fallback) {
    return has(key) ? vector3(key) : fallback;
  }

  const nlohmann::json& array(const std::string& key) {
    const nlohmann::json& value = at(key);
    if (!value.is_array()) fail(field(key), "must be an array, got " + type_name(value));
    return value;
  }

  /// Rejects keys that were never asked for.
  void finish() const {
    for (auto it = object_.begin(); it != object_.end(); ++it)
      if (!used_.count(it.key())) fail(field(it.key()), "unknown key");
  }

  static std::string type_name(const nlohmann::json& value) {
    return std::string(value.type_name()) + (value.is_primitive() ? " " + value.dump() : "");
  }

 private:
  const nlohmann::json& object_;
  std::string path_;
  std::string file_;
  std::set<std::string> used_;
};

/// `array[i]`, as a field name in messages.
inline std::string indexed(const std::string& array, std::size_t i) {
  return array + "[" + std::to_string(i) + "]";
}

}  // namespace fibrecheck
