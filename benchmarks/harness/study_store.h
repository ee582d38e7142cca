#pragma once

#include <chrono>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "csv_file.h"

namespace fibrecheck {

/// The finished points of one study, kept on disk as they finish: `<folder>/<study>.points.jsonl`,
/// one JSON object a line, each with its `key`. A study run again reads them and computes only the
/// points not there; a line cut short by an interrupted run is ignored.
class StudyStore {
 public:
  StudyStore(const std::string& folder, const std::string& study);

  bool has(const std::string& key) const { return index_.count(key) > 0; }
  const nlohmann::json& get(const std::string& key) const { return points_.at(index_.at(key)); }
  /// Appends a finished point (its "key" field set to `key`) and flushes it to disk.
  void add(const std::string& key, nlohmann::json point);
  /// Every point, in the order they were finished.
  const std::vector<nlohmann::json>& points() const { return points_; }
  const std::string& folder() const { return folder_; }

 private:
  std::string folder_, path_;
  std::vector<nlohmann::json> points_;
  std::map<std::string, std::size_t> index_;
  bool broken_line_ = false;  ///< the file ends in a line cut short
};

/// A number as a point's key and its scene's name say it: as short as it reads ("0.9").
std::string key_number(double x);

/// "point i of N, elapsed, estimated remaining" on standard error, for long studies.
class StudyProgress {
 public:
  StudyProgress(std::string study, std::size_t total, bool quiet);
  /// Before point i (from 0) starts; `what` names it.
  void start(std::size_t i, const std::string& what);
  /// A point that was already on disk.
  void skip() { ++skipped_; }

 private:
  std::string study_;
  std::size_t total_, skipped_ = 0, done_ = 0;
  bool quiet_;
  std::chrono::steady_clock::time_point begin_;
};

}  // namespace fibrecheck
