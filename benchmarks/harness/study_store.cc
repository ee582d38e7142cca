#include "study_store.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "atomic_file.h"
#include "input_error.h"

namespace fibrecheck {

std::string key_number(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

StudyStore::StudyStore(const std::string& folder, const std::string& study)
    : folder_(folder), path_((std::filesystem::path(folder) / (study + ".points.jsonl")).string()) {
  std::filesystem::create_directories(folder);
  std::ifstream in(path_);
  // A run killed in the middle of a line leaves no newline at the end: the next point must start
  // a line of its own.
  if (in) {
    in.seekg(0, std::ios::end);
    if (in.tellg() > 0) {
      in.seekg(-1, std::ios::end);
      broken_line_ = in.get() != '\n';
    }
    in.clear();
    in.seekg(0);
  }
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    nlohmann::json point;
    try {
      point = nlohmann::json::parse(line);
    } catch (const nlohmann::json::parse_error&) {
      continue;  // cut short by an interrupted run: computed again
    }
    if (!point.contains("key")) continue;
    index_[point["key"].get<std::string>()] = points_.size();
    points_.push_back(std::move(point));
  }
}

void StudyStore::add(const std::string& key, nlohmann::json point) {
  point["key"] = key;
  std::ofstream out(path_, std::ios::app);
  if (broken_line_) out << "\n";
  broken_line_ = false;
  out << point.dump() << "\n";
  out.flush();
  if (!out) throw InputError(path_, "", "cannot append the study's point");
  index_[key] = points_.size();
  points_.push_back(std::move(point));
}

StudyProgress::StudyProgress(std::string study, std::size_t total, bool quiet)
    : study_(std::move(study)),
      total_(total),
      quiet_(quiet),
      begin_(std::chrono::steady_clock::now()) {}

void StudyProgress::start(std::size_t i, const std::string& what) {
  if (quiet_) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin_).count();
  std::ostringstream line;
  line.precision(3);
  line << "  " << study_ << ": point " << i + 1 << " of " << total_ << " (" << what << "), "
       << std::fixed;
  line.precision(1);
  line << elapsed << " s elapsed";
  if (done_ > 0 && i < total_) {
    const double remaining = elapsed / done_ * (total_ - i);
    line << ", about " << remaining << " s to go";
  }
  if (skipped_ > 0) line << ", " << skipped_ << " already done";
  std::cerr << line.str() << std::endl;
  ++done_;
}

}  // namespace fibrecheck
