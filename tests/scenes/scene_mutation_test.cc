// Bad input at volume: thousands of scenes mutated from the committed ones — truncated, bytes
// flipped, numbers replaced by extremes, keys dropped, duplicated or misspelt, arrays resized —
// go through the scene reader and, when it accepts them, the iterative solver. Each must end as
// the program would end with exit code 2 (an InputError with a message naming the file), or 0 or
// 3 (a result whose status says what happened, with a message when it did not converge), never a
// crash, a hang or a non-finite number in a result. The solver is capped at 200 iterations: the
// question is whether it copes, not whether it converges.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "extreme_catalogue.h"
#include "input_error.h"
#include "iterative_solver.h"
#include "scene.h"
#include "slurp.h"

namespace fibrecheck {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

/// Every node of a JSON document by pointer, so that one can be picked at random.
void collect(const json& node, const json::json_pointer& at, std::vector<json::json_pointer>& all) {
  all.push_back(at);
  if (node.is_object())
    for (auto it = node.begin(); it != node.end(); ++it) collect(*it, at / it.key(), all);
  if (node.is_array())
    for (std::size_t i = 0; i < node.size(); ++i) collect(node[i], at / i, all);
}

class Mutator {
 public:
  explicit Mutator(unsigned seed) : random_(seed) {}

  std::string mutate(const std::string& text) {
    switch (pick(7)) {
      case 0:  // truncated
        return text.substr(0, pick(text.size()));
      case 1: {  // a byte flipped
        std::string t = text;
        t[pick(t.size())] = static_cast<char>(pick(256));
        return t;
      }
      case 2: {  // a key's name repeated inside its object
        const auto at = text.find("\": ", pick(text.size()));
        if (at == std::string::npos) return text;
        const auto open = text.rfind('"', at - 1);
        const auto end = text.find_first_of(",}\n", at);
        if (open == std::string::npos || end == std::string::npos) return text;
        return text.substr(0, end) + ", " + text.substr(open, end - open) + text.substr(end);
      }
      default:
        return mutate_document(json::parse(text)).dump(1);
    }
  }

 private:
  std::size_t pick(std::size_t n) { return n == 0 ? 0 : random_() % n; }

  json mutate_document(json document) {
    std::vector<json::json_pointer> nodes;
    collect(document, json::json_pointer(), nodes);
    const json::json_pointer at = nodes[pick(nodes.size())];
    json& node = document[at];
    static const double kExtremes[] = {0.0,    -1.0,  -0.0,    1e308, -1e308, 1e-308,
                                       5e-324, 1e300, 1e-300,  1e12,  -1e12,  0.5,
                                       2.0,    1e6,   1000001, 3.0e9, -3e9,   1e-15};
    static const char* const kStrings[] = {"", "x", "point", "line", "seed", "A", "\u00e9\u00e9"};
    switch (pick(4)) {
      case 0:  // a number replaced by an extreme, or the node by something of another type
        if (node.is_number())
          node = kExtremes[pick(std::size(kExtremes))];
        else if (node.is_string())
          node = kStrings[pick(std::size(kStrings))];
        else
          node = pick(2) ? json(nullptr) : json(kExtremes[pick(std::size(kExtremes))]);
        return document;
      case 1:  // a key dropped, or misspelt
        if (!at.empty()) {
          json& parent = document[at.parent_pointer()];
          if (parent.is_object()) {
            const std::string key = at.back();
            json value = parent[key];
            parent.erase(key);
            if (pick(2)) {
              std::string misspelt = key;
              if (!misspelt.empty()) misspelt[pick(misspelt.size())] ^= 0x20;
              parent[misspelt + (pick(2) ? "" : "s")] = value;
            }
          }
        }
        return document;
      case 2:  // an array resized: an element dropped, repeated or added
        if (node.is_array()) {
          if (!node.empty() && pick(2)) {
            node.erase(node.begin() + static_cast<long>(pick(node.size())));
          } else {
            node.push_back(node.empty() ? json(1.0) : node[pick(node.size())]);
          }
        }
        return document;
      default:  // a whole object emptied or replaced by an array
        node = pick(2) ? json::object() : json::array();
        return document;
    }
  }

  std::mt19937 random_;
};

TEST(SceneMutation, EveryMutatedSceneIsBadInputOrAnHonestResult) {
  std::vector<fs::path> originals;
  for (const auto& entry : fs::directory_iterator(FIBRECHECK_SCENES_DIR))
    if (entry.path().extension() == ".json") originals.push_back(entry.path());
  for (const std::string& name : testing::extreme_catalogue())
    if (name != "parallel_100000_slices")  // 200 iterations on 1e5 contacts: slow, not different
      originals.push_back(testing::extreme_scene_path(name));
  std::sort(originals.begin(), originals.end());
  const fs::path dir =
      fs::temp_directory_path() / ("fibrecheck_mutation_" + std::to_string(getpid()));
  fs::create_directories(dir);
  Mutator mutator(20261201);
  int bad = 0, solved = 0, unsolved = 0;
  constexpr int kPerScene = 200;
  for (const fs::path& original : originals) {
    const std::string text = slurp(original);
    for (int i = 0; i < kPerScene; ++i) {
      const std::string mutated = mutator.mutate(text);
      const fs::path file = dir / (original.stem().string() + "_" + std::to_string(i) + ".json");
      std::ofstream(file, std::ios::binary) << mutated;
      Scene scene;
      try {
        scene = read_scene(file.string());
      } catch (const InputError& e) {
        ++bad;  // exit code 2
        const std::string what = e.what();
        EXPECT_NE(what.find(file.string()), std::string::npos) << what;
        EXPECT_GT(what.size(), file.string().size() + 4) << "a reason, not only the file";
        continue;
      }
      SolverOptions options = SolverOptions::from_scene(scene);
      options.max_iterations = std::min(options.max_iterations, 200L);
      std::string trouble;
      if (!options.is_valid(&trouble)) {
        ++bad;
        continue;
      }
      const Result r = solve_iteratively(scene, options);
      EXPECT_EQ(testing::first_non_finite(r), "") << file << "\n" << mutated;
      if (r.status == Status::converged) {
        ++solved;  // exit code 0
      } else {
        ++unsolved;  // exit code 3
        EXPECT_FALSE(r.message.empty()) << file;
      }
    }
  }
  fs::remove_all(dir);
  const int total = static_cast<int>(originals.size()) * kPerScene;
  EXPECT_EQ(bad + solved + unsolved, total);
  // The mutations must exercise both sides of the reader.
  EXPECT_GT(bad, total / 4);
  EXPECT_GT(solved + unsolved, total / 10);
  std::cout << total << " mutated scenes: " << bad << " bad input, " << solved << " converged, "
            << unsolved << " valid but not converged\n";
}

}  // namespace
}  // namespace fibrecheck
