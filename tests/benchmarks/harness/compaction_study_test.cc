// The compaction study's fits and data, on load paths whose pressures are known exactly.
#include "compaction_study.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "input_error.h"

namespace fibrecheck {
namespace {

std::vector<double> law(const std::vector<double>& vf, double E, double k, double n, double vf0) {
  std::vector<double> p;
  for (double v : vf) p.push_back(E * k * (std::pow(v, n) - std::pow(vf0, n)));
  return p;
}

TEST(CompactionFit, VanWykRecoversItsConstants) {
  const std::vector<double> vf = {0.42, 0.45, 0.48, 0.51};
  const PowerLawFit f = fit_power_law(vf, law(vf, 80000, 2e-6, 3.0, 0.4), 80000, 3.0);
  ASSERT_TRUE(f.valid);
  EXPECT_NEAR(f.k, 2e-6, 1e-12);
  EXPECT_NEAR(f.vf0, 0.4, 1e-9);
  EXPECT_NEAR(f.r2, 1.0, 1e-12);
  EXPECT_EQ(f.points, 4);
}

TEST(CompactionFit, TollFindsItsExponent) {
  const std::vector<double> vf = {0.41, 0.43, 0.45, 0.47, 0.5};
  const PowerLawFit f = fit_toll(vf, law(vf, 80000, 3e-3, 8.0, 0.4), 80000);
  ASSERT_TRUE(f.valid);
  EXPECT_NEAR(f.n, 8.0, 1e-9);  // on the grid of 0.01
  EXPECT_NEAR(f.vf0, 0.4, 1e-9);
  EXPECT_NEAR(f.k, 3e-3, 1e-9);
  // Van Wyk's cube fits it worse.
  EXPECT_LT(fit_power_law(vf, law(vf, 80000, 3e-3, 8.0, 0.4), 80000, 3.0).r2, f.r2);
}

// A curve steeper than any power within reach (here n = 45) ends Toll's fit at its largest
// exponent: the report then says n ≥ 30 instead of a measured 30.
TEST(CompactionFit, TollEndsAtItsLargestExponentOnASteeperCurve) {
  const std::vector<double> vf = {0.59, 0.6, 0.61, 0.62, 0.63, 0.64, 0.65};
  const PowerLawFit f = fit_toll(vf, law(vf, 80000, 1e-2, 45.0, 0.58), 80000);
  ASSERT_TRUE(f.valid);
  EXPECT_EQ(f.n, kTollLargestExponent);
  EXPECT_LT(f.r2, 1.0);
}

TEST(CompactionFit, TooFewPointsGiveNoFit) {
  EXPECT_FALSE(fit_power_law({0.45}, {1e-3}, 80000, 3.0).valid);
  EXPECT_FALSE(fit_toll({0.45, 0.5}, {1e-3, 2e-3}, 80000).valid);
}

/// A solver that returns a load path whose mean wall pressure follows van Wyk's law in Vf (each
/// wall p and 3p, mean 2p), converging on every step but the last when `fail_last`; step k (from
/// 0) updated its normals k + 2 times and its Tresca radii k times, and left Coulomb's law broken
/// by (k + 1)·1e-9 mm at sticking contacts and twice that at slipping ones.
Result made_up(const Scene& s, double offset, bool fail_last) {
  Result r;
  r.scene = s.name;
  r.solver = "iterative";
  r.status = Status::converged;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    StepResult st;
    st.compaction = s.steps[k].compaction;
    st.fibre_volume_fraction = 0.3 / (st.compaction * st.compaction);
    const double p =
        0.5 * std::max(0.0,
                       80000 * 1e-6 * (std::pow(st.fibre_volume_fraction, 3) - std::pow(0.4, 3))) +
        offset;
    st.wall_pressure = {{"low", p}, {"high", 3 * p}};
    st.strain_energy = 1e-6 * (k + 1);
    st.geometric_updates = static_cast<long>(k) + 2;
    st.fixed_point_updates = static_cast<long>(k);
    st.stick_residual = 1e-9 * static_cast<double>(k + 1);
    st.slip_residual = 2e-9 * static_cast<double>(k + 1);
    st.status = fail_last && k + 1 == s.steps.size() ? Status::max_iterations : Status::converged;
    r.steps.push_back(st);
  }
  return r;
}

TEST(CompactionStudy, WritesCurvesFitsAndAgreement) {
  Scene s;
  s.name = "made_up_tow";
  FibreSpec f;
  f.id = "F";
  f.end = {1, 0, 0};
  f.radius = 0.01;
  f.youngs_modulus = 80000;
  s.fibres = {f};
  WallSpec w;
  w.id = "low";
  s.walls = {w};
  for (double F : {0.9, 0.85, 0.8, 0.75, 0.7}) s.steps.push_back({F, 1.0});
  Solvers solvers;
  solvers.iterative = [](const Scene& x) { return made_up(x, 0.0, false); };
  solvers.reference_slices = [](const Scene& x) {
    Result r = made_up(x, 1e-6, true);
    r.solver = "fem";
    return r;
  };
  const std::string folder = ::testing::TempDir() + "compaction_study_test";
  std::filesystem::remove_all(folder);
  CompactionStudyOptions options;
  options.quiet = true;
  const auto out = run_compaction_study({s}, options, solvers, folder);
  ASSERT_EQ(out.size(), 1u);
  // Frictionless: iterative and reference, in the scene's geometry and in the other.
  ASSERT_EQ(out[0].runs.size(), 4u);
  EXPECT_EQ(out[0].runs[0].geometry, "deformed");
  EXPECT_EQ(out[0].runs[3].geometry, "linearised");
  const CompactionRun& it = out[0].runs[0];
  ASSERT_TRUE(it.van_wyk.valid);
  EXPECT_NEAR(it.van_wyk.k, 1e-6, 1e-12);  // the mean pressure is exactly van Wyk's
  EXPECT_NEAR(it.van_wyk.vf0, 0.4, 1e-9);
  // The reference's curve is 1e-6 MPa above on the four steps it converged.
  ASSERT_EQ(out[0].agreement.size(), 2u);  // one per geometry
  EXPECT_EQ(out[0].agreement[1].geometry, "linearised");
  EXPECT_EQ(out[0].agreement[0].steps, 4);
  double largest = 0.0;
  for (const CompactionPoint& p : out[0].runs[1].points)
    if (p.status == "converged") largest = std::max(largest, p.pressure);
  EXPECT_NEAR(out[0].agreement[0].pressure_error, 2e-6 / largest, 1e-12);
  // The CSV: the columns outside tools read, a row per solver and step.
  std::ifstream csv(folder + "/compaction.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("scene,solver,step,fibre_volume_fraction,pressure_MPa,strain_energy,"
                         "contacts_per_fibre",
                         0),
            0u);
  int rows = 0;
  for (std::string line; std::getline(csv, line);) rows += line.empty() ? 0 : 1;
  EXPECT_EQ(rows, 20);
  std::ifstream fits(folder + "/compaction_fit.json");
  const nlohmann::json j = nlohmann::json::parse(fits);
  const nlohmann::json& first = j["scenes"][0]["fits"][0];
  EXPECT_EQ(first["solver"], "iterative");
  EXPECT_TRUE(first["van_wyk"].contains("k") && first["van_wyk"].contains("vf0") &&
              first["van_wyk"].contains("r2"));
  EXPECT_TRUE(first["toll"].contains("n"));
  // Each point keeps its step's updates and Coulomb's residuals.
  EXPECT_EQ(it.points.at(3).geometric_updates, 5);
  EXPECT_EQ(it.points.at(3).fixed_point_updates, 3);
  EXPECT_EQ(it.points.at(3).stick_residual, 4e-9);
  EXPECT_EQ(it.points.at(3).slip_residual, 8e-9);
  // Run again: every point comes from disk, with its updates.
  solvers.iterative = [](const Scene&) -> Result { throw std::runtime_error("not again"); };
  std::vector<CompactionStudyScene> again;
  EXPECT_NO_THROW(again = run_compaction_study({s}, options, solvers, folder));
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].runs.at(0).points.at(3).geometric_updates, 5);
  EXPECT_EQ(again[0].runs.at(0).points.at(3).fixed_point_updates, 3);
  EXPECT_EQ(again[0].runs.at(0).points.at(3).stick_residual, 4e-9);
  EXPECT_EQ(again[0].runs.at(0).points.at(3).slip_residual, 8e-9);
}

// With friction: the iterative solver with Coulomb's law and with the seed's rule, and the
// reference with Coulomb's law — but only on scenes within --frictional-reference-fibres, and the
// reference at all only on those within --reference-fibres.
TEST(CompactionStudy, TheFrictionalReferenceOnlyWithinItsFibreLimit) {
  Scene s;
  s.name = "made_up_frictional_tow";
  FibreSpec f;
  f.id = "F";
  f.end = {1, 0, 0};
  f.radius = 0.01;
  f.youngs_modulus = 80000;
  s.fibres = {f, f};
  s.fibres[1].id = "G";
  WallSpec w;
  w.id = "low";
  s.walls = {w};
  s.contact.friction = 0.2;
  for (double F : {0.9, 0.8, 0.7}) s.steps.push_back({F, 1.0});
  Solvers solvers;
  solvers.iterative = [](const Scene& x) { return made_up(x, 0.0, false); };
  solvers.reference_slices = [](const Scene& x) {
    Result r = made_up(x, 1e-6, false);
    r.solver = "fem";
    return r;
  };
  // (runs, reference runs, frictional reference runs) with the two limits.
  auto references = [&](int reference_limit, int frictional_limit) {
    const std::string folder = ::testing::TempDir() + "compaction_study_limit_" +
                               std::to_string(reference_limit) + "_" +
                               std::to_string(frictional_limit);
    std::filesystem::remove_all(folder);
    CompactionStudyOptions options;
    options.quiet = true;
    options.reference_fibres = reference_limit;
    options.frictional_reference_fibres = frictional_limit;
    int runs = 0, fem = 0, frictional = 0;
    for (const CompactionRun& r : run_compaction_study({s}, options, solvers, folder).at(0).runs) {
      ++runs;
      fem += r.solver == "fem";
      frictional += r.solver == "fem" && r.mu > 0.0;
    }
    return std::tuple{runs, fem, frictional};
  };
  EXPECT_EQ(references(0, 0), std::tuple(7, 3, 1));
  EXPECT_EQ(references(0, 2), std::tuple(7, 3, 1));
  EXPECT_EQ(references(0, 1), std::tuple(6, 2, 0));
  EXPECT_EQ(references(2, 0), std::tuple(7, 3, 1));
  EXPECT_EQ(references(1, 0), std::tuple(4, 0, 0));
}

TEST(CompactionStudy, RefusesScenesWithoutWallsOrSteps) {
  Scene s;
  s.name = "bare";
  s.source = "bare.json";
  Solvers solvers;
  const std::string folder = ::testing::TempDir() + "compaction_study_refused";
  EXPECT_THROW(run_compaction_study({s}, {}, solvers, folder), InputError);
  s.walls.push_back({});
  EXPECT_THROW(run_compaction_study({s}, {}, solvers, folder), InputError);
  EXPECT_FALSE(std::filesystem::exists(folder));
}

}  // namespace
}  // namespace fibrecheck
