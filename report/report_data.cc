#include "report_data.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "input_error.h"

namespace fibrecheck {

namespace {

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  try {
    return nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(path, "", std::string("malformed JSON: ") + e.what());
  }
}

}  // namespace

ReportData read_report_data(const std::vector<std::string>& folders) {
  namespace fs = std::filesystem;
  ReportData data;
  std::vector<fs::path> files;
  for (const std::string& folder : folders) {
    if (!fs::is_directory(folder)) throw InputError(folder, "", "no such folder");
    for (const auto& entry : fs::recursive_directory_iterator(folder))
      if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    const std::string name = file.filename().string();
    if (name == "compare.json") {
      StoredComparison c;
      c.folder = file.parent_path().string();
      c.summary = read_json(file.string());
      if (!c.summary.contains("scene") || !c.summary.contains("runs"))
        throw InputError(file.string(), "", "not a comparison written by fibrecheck compare");
      const nlohmann::json files_of = c.summary.value("files", nlohmann::json::object());
      const std::string truth = c.summary.value("ground_truth", "reference_slices");
      if (files_of.contains("user") && files_of.contains(truth)) {
        c.user = read_result((file.parent_path() / files_of["user"].get<std::string>()).string());
        c.truth = read_result((file.parent_path() / files_of[truth].get<std::string>()).string());
        c.has_results = true;
      }
      if (files_of.contains("scene"))
        c.scene = read_scene((file.parent_path() / files_of["scene"].get<std::string>()).string());
      data.comparisons.push_back(std::move(c));
    } else if (name == "slice_study.json" || name == "tolerance_study.json" ||
               name == "stability_study.json") {
      const nlohmann::json j = read_json(file.string());
      if (!j.is_array())
        throw InputError(file.string(), "", "not a study written by fibrecheck study");
      nlohmann::json& into = name == "slice_study.json"       ? data.slice_studies
                             : name == "tolerance_study.json" ? data.tolerance_studies
                                                              : data.stability_studies;
      for (const nlohmann::json& entry : j) into.push_back(entry);
    } else if (name == "compaction_study.json") {
      const nlohmann::json j = read_json(file.string());
      if (!j.is_array())
        throw InputError(file.string(), "", "not a study written by fibrecheck study");
      // Its pictures read the result files it kept, named relative to its folder.
      for (nlohmann::json entry : j) {
        entry["folder"] = file.parent_path().string();
        data.compaction_studies.push_back(std::move(entry));
      }
    } else if (name == "scale_study.json") {
      const nlohmann::json j = read_json(file.string());
      if (!j.is_object() || j.value("study", "") != "scale")
        throw InputError(file.string(), "", "not a study written by fibrecheck study scale");
      data.scale_studies.push_back(j);
    } else {
      continue;
    }
    data.sources.push_back(file.string());
  }
  return data;
}

}  // namespace fibrecheck
