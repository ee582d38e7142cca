// The stored points of the main job's 1 000-fibre studies (benchmarks/stored/): every point the
// main job asks for is there and reads as the study's record, so the main job takes them from disk
// instead of running them. A tow the generator makes differently, or a record the studies read
// differently, fails here rather than turning the main job into hours of solves.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "compaction_study.h"
#include "friction_study.h"
#include "scene.h"

namespace fibrecheck {
namespace {

namespace fs = std::filesystem;

const fs::path kStored = fs::path(FIBRECHECK_STORED_DIR);

fs::path fresh_folder(const std::string& name) {
  const fs::path folder =
      fs::path(::testing::TempDir()) / (name + "_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

Result no_solve(const Scene& scene) {
  throw std::runtime_error("the stored points lack a run on " + scene.name);
}

// The compaction study of run.sh on the 1 000-fibre tow it generates.
TEST(StoredPoints, TheMainJobsCompactionOfAThousandFibresIsStored) {
  const fs::path folder = fresh_folder("stored_compaction");
  const fs::path scene = folder / "tow_1000_compaction.json";
  const std::string generate = std::string(FIBRECHECK_BINARY) +
                               " generate tow --fibres 1000 --slices 100 --seed 2 --steps 12"
                               " --first-compaction 0.855 --final-compaction 0.806 --friction 0.2"
                               " --out " +
                               scene.string() + " > /dev/null";
  ASSERT_EQ(std::system(generate.c_str()), 0) << generate;
  fs::copy_file(kStored / "compaction_1000.points.jsonl", folder / "compaction_study.points.jsonl");
  CompactionStudyOptions options;
  options.reference_fibres = 100;
  options.quiet = true;
  Solvers solvers;
  solvers.iterative = no_solve;
  solvers.reference_slices = no_solve;
  const std::vector<CompactionStudyScene> study =
      run_compaction_study({read_scene(scene.string())}, options, solvers, folder.string());
  ASSERT_EQ(study.size(), 1u);
  ASSERT_EQ(study[0].runs.size(), 4u);
  for (const CompactionRun& r : study[0].runs) {
    EXPECT_EQ(r.solver, "iterative");
    EXPECT_EQ(r.points.size() == 12u, r.status == "converged") << r.label();
  }
}

// The friction study of run.sh on tows of 1 000 fibres.
TEST(StoredPoints, TheMainJobsFrictionStudyOfAThousandFibresIsStored) {
  const fs::path folder = fresh_folder("stored_friction");
  fs::copy_file(kStored / "friction_1000.points.jsonl", folder / "friction_study.points.jsonl");
  FrictionStudyOptions options;
  options.fibres = {1000};
  options.compactions = {0.9, 0.8};
  options.quiet = true;
  const std::vector<FrictionPoint> points = run_friction_study(options, no_solve, folder.string());
  EXPECT_EQ(points.size(), 12u);
  for (const FrictionPoint& p : points) EXPECT_EQ(p.fibres, 1000);
}

}  // namespace
}  // namespace fibrecheck
