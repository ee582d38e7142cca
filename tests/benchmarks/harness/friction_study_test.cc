// The friction study: each of its points is the iterative solver on the tow the generator makes
// with the study's options and the point's friction model, and a study run again reads its
// points instead of running them.
#include "friction_study.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "iterative_solver.h"
#include "tow_generator.h"

namespace fibrecheck {
namespace {

namespace fs = std::filesystem;

Result iterative(const Scene& scene) {
  return solve_iteratively(scene, SolverOptions::from_scene(scene));
}

FrictionStudyOptions small_study() {
  FrictionStudyOptions o;
  o.fibres = {7};
  o.mu = {0.2};
  o.compactions = {0.9};
  o.slices = 10;
  o.max_iterations = 20000;
  o.quiet = true;
  return o;
}

fs::path fresh_folder(const std::string& name) {
  const fs::path folder =
      fs::path(::testing::TempDir()) / (name + "_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  return folder;
}

TEST(FrictionStudy, EachPointIsTheSolverOnTheGeneratedTow) {
  const FrictionStudyOptions o = small_study();
  const fs::path folder = fresh_folder("friction_study");
  const std::vector<FrictionPoint> points = run_friction_study(o, iterative, folder.string());
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0].model, "seed");
  EXPECT_EQ(points[1].model, "coulomb");
  for (const FrictionPoint& p : points) {
    TowOptions tow;
    tow.fibres = 7, tow.slices = 10, tow.seed = o.seed, tow.volume_fraction = o.volume_fraction;
    tow.compaction = 0.9, tow.friction = 0.2;
    Scene scene = generate_tow(tow);
    scene.contact.friction_model = p.model == "seed" ? FrictionModel::seed : FrictionModel::coulomb;
    scene.solver.max_iterations = o.max_iterations;
    const Result r = iterative(scene);
    SCOPED_TRACE(p.model);
    EXPECT_EQ(p.status, to_string(r.status));
    EXPECT_EQ(p.iterations, r.iterations);
    ASSERT_TRUE(r.friction.has_value());
    EXPECT_DOUBLE_EQ(p.stick_residual, r.friction->stick_residual);
    ASSERT_EQ(r.walls.size(), 4u);
    double pressure = 0.0;
    for (const WallResult& w : r.walls) pressure += 0.25 * w.pressure;
    EXPECT_NEAR(p.pressure, pressure, 1e-12 * std::fabs(pressure));
    // The fibres' cross-sections over the section the four walls bound (the tow along x).
    double y_min = INFINITY, y_max = -INFINITY, z_min = INFINITY, z_max = -INFINITY;
    for (const WallSpec& w : scene.walls) {
      if (std::fabs(w.normal.y()) > 0.5)
        y_min = std::min(y_min, w.point.y()), y_max = std::max(y_max, w.point.y());
      if (std::fabs(w.normal.z()) > 0.5)
        z_min = std::min(z_min, w.point.z()), z_max = std::max(z_max, w.point.z());
    }
    const double radius = scene.fibres.at(0).radius;
    EXPECT_NEAR(p.fibre_volume_fraction,
                7 * M_PI * radius * radius / ((y_max - y_min) * (z_max - z_min)), 1e-12);
  }
  EXPECT_TRUE(fs::exists(folder / "friction_study.json"));
  EXPECT_TRUE(fs::exists(folder / "friction_study.csv"));
  fs::remove_all(folder);
}

TEST(FrictionStudy, ARunAgainReadsItsPoints) {
  const FrictionStudyOptions o = small_study();
  const fs::path folder = fresh_folder("friction_study_again");
  const std::vector<FrictionPoint> first = run_friction_study(o, iterative, folder.string());
  int runs = 0;
  const std::vector<FrictionPoint> again = run_friction_study(
      o,
      [&](const Scene& scene) {
        ++runs;
        return iterative(scene);
      },
      folder.string());
  EXPECT_EQ(runs, 0);
  ASSERT_EQ(again.size(), first.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(again[i].status, first[i].status);
    EXPECT_EQ(again[i].iterations, first[i].iterations);
    EXPECT_DOUBLE_EQ(again[i].pressure, first[i].pressure);
  }
  fs::remove_all(folder);
}

}  // namespace
}  // namespace fibrecheck
