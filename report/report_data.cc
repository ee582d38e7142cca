#include "report_data.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "input_error.h"

namespace fibrecheck {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json read_json(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  try {
    return json::parse(text.str());
  } catch (const json::parse_error& e) {
    throw InputError(path, "", std::string("malformed JSON: ") + e.what());
  }
}

/// The records of `file` as `Record`s, by `read`; a record without a field the harness writes (or
/// with a field of another type) is not the harness's: InputError saying `what` it is not.
template <typename Read>
auto read_records(const fs::path& file, const std::string& what, const Read& read) {
  const json j = read_json(file.string());
  try {
    return read(j);
  } catch (const json::exception& e) {
    throw InputError(file.string(), "", "not " + what + ": " + e.what());
  }
}

template <typename Record>
std::vector<Record> study_entries(const fs::path& file) {
  return read_records(file, "a study written by fibrecheck study", [&](const json& j) {
    if (!j.is_array())
      throw InputError(file.string(), "", "not a study written by fibrecheck study");
    return j.get<std::vector<Record>>();
  });
}

StoredComparison stored_comparison(const fs::path& file) {
  StoredComparison c;
  c.folder = file.parent_path().string();
  c.summary = read_records(file, "a comparison written by fibrecheck compare", [&](const json& j) {
    if (!j.contains("scene") || !j.contains("runs"))
      throw InputError(file.string(), "", "not a comparison written by fibrecheck compare");
    return j.get<ComparisonRecord>();
  });
  const std::map<std::string, std::string>& files = c.summary.files;
  auto beside = [&](const std::string& label) {
    return (file.parent_path() / files.at(label)).string();
  };
  if (files.count("user") && files.count(c.summary.ground_truth)) {
    c.user = read_result(beside("user"));
    c.truth = read_result(beside(c.summary.ground_truth));
    c.has_results = true;
  }
  if (files.count("scene")) c.scene = read_scene(beside("scene"));
  return c;
}

/// Reads `file` into `data` when it is the harness's; false for any other file.
bool read_data_file(const fs::path& file, ReportData& data) {
  const std::string name = file.filename().string();
  auto append = [](auto& into, auto&& entries) {
    into.insert(into.end(), entries.begin(), entries.end());
  };
  if (name == "compare.json") {
    data.comparisons.push_back(stored_comparison(file));
  } else if (name == "slice_study.json") {
    append(data.slice_studies, study_entries<SliceStudyScene>(file));
  } else if (name == "tolerance_study.json") {
    append(data.tolerance_studies, study_entries<ToleranceStudyScene>(file));
  } else if (name == "stability_study.json") {
    append(data.stability_studies, study_entries<StabilityStudyScene>(file));
  } else if (name == "compaction_study.json") {
    // Its pictures read the result files it kept, named relative to its folder.
    for (CompactionStudyScene& s : study_entries<CompactionStudyScene>(file))
      data.compaction_studies.push_back({file.parent_path().string(), std::move(s)});
  } else if (name == "friction_study.json") {
    append(data.friction_study, study_entries<FrictionPoint>(file));
  } else if (name == "scale_study.json") {
    const std::string what = "a study written by fibrecheck study scale";
    data.scale_studies.push_back(read_records(file, what, [&](const json& j) {
      if (!is_scale_study(j)) throw InputError(file.string(), "", "not " + what);
      return j.get<ScaleStudy>();
    }));
  } else {
    return false;
  }
  return true;
}

}  // namespace

ReportData read_report_data(const std::vector<std::string>& folders) {
  std::vector<fs::path> files;
  for (const std::string& folder : folders) {
    if (!fs::is_directory(folder)) throw InputError(folder, "", "no such folder");
    for (const auto& entry : fs::recursive_directory_iterator(folder))
      if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  ReportData data;
  for (const fs::path& file : files)
    if (read_data_file(file, data)) data.sources.push_back(file.string());
  return data;
}

}  // namespace fibrecheck
