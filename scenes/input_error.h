#pragma once

#include <stdexcept>
#include <string>

namespace fibrecheck {

/// Bad input: a scene or option that cannot be used. Carries the file, the field and the reason so
/// the program can print one clear line and exit with code 2.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string field, std::string reason)
      : std::runtime_error(compose(file, field, reason)),
        file_(std::move(file)),
        field_(std::move(field)),
        reason_(std::move(reason)) {}

  const std::string& file() const { return file_; }
  const std::string& field() const { return field_; }
  const std::string& reason() const { return reason_; }

 private:
  static std::string compose(const std::string& file, const std::string& field,
                             const std::string& reason) {
    std::string message = file.empty() ? std::string("<input>") : file;
    if (!field.empty()) message += ": " + field;
    return message + ": " + reason;
  }

  std::string file_, field_, reason_;
};

}  // namespace fibrecheck
