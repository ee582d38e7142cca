// Micro-benchmarks of the iterative solver's kernels and end-to-end tows.
//
// Sample runs:
//   build/fibrecheck_benchmarks --benchmark_filter=Superposition
//   build/fibrecheck_benchmarks --benchmark_filter=TowIteration
#include <benchmark/benchmark.h>

#include <random>

#include "beam.h"
#include "closest_points.h"
#include "fibre.h"
#include "iterative_solver.h"
#include "slice_broad_phase.h"
#include "superposition.h"
#include "tow_generator.h"

namespace fibrecheck {
namespace {

// One fibre of length 1 mm (r = 0.01 mm, E = 80 GPa) under k random point loads across it.
Scene loaded_fibre(int k) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> position(0.0, 1.0), force(-1e-4, 1e-4);
  Scene scene;
  FibreSpec f;
  f.id = "F";
  f.end = {1.0, 0.0, 0.0};
  f.radius = 0.01;
  f.youngs_modulus = 80000;
  scene.fibres.push_back(f);
  for (int i = 0; i < k; ++i) {
    LoadSpec load;
    load.fibre = "F";
    load.position = position(rng);
    load.force = {0.0, force(rng), force(rng)};
    scene.loads.push_back(load);
  }
  return scene;
}

std::vector<double> fractions(int n) {
  std::vector<double> s(n);
  for (int i = 0; i < n; ++i) s[i] = (i + 0.5) / n;
  return s;
}

// Deflection at n = k points under k point loads by the solver's superposition (the running sums
// of beam.h, both planes at once): O(k + n).
void BM_SuperpositionPrefixSums(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0));
  const Scene scene = loaded_fibre(k);
  const std::vector<Fibre> fibres = make_fibres(scene);
  const Superposition superposition(fibres, scene);
  const std::vector<double> s = fractions(k);
  std::vector<Eigen::Vector3d> u;
  for (auto _ : state) {
    superposition.fibre_field(0, {}, true, s, u);
    benchmark::DoNotOptimize(u.data());
  }
  state.SetComplexityN(k);
}
BENCHMARK(BM_SuperpositionPrefixSums)->RangeMultiplier(4)->Range(16, 4096)->Complexity();

// The same by summing Eqs. 4.12–4.13 load by load in both planes: O(k·n).
void BM_SuperpositionNaive(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0));
  const Scene scene = loaded_fibre(k);
  const Fibre fibre = make_fibres(scene)[0];
  const std::vector<double> s = fractions(k);
  std::vector<Eigen::Vector3d> u(k);
  for (auto _ : state) {
    for (int i = 0; i < k; ++i) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (const LoadSpec& l : scene.loads) {
        const double a = l.position * fibre.length, x = s[i] * fibre.length;
        sum +=
            point_load_deflection(l.force.dot(fibre.e1), a, x, fibre.length, fibre.EI) * fibre.e1 +
            point_load_deflection(l.force.dot(fibre.e2), a, x, fibre.length, fibre.EI) * fibre.e2;
      }
      u[i] = sum;
    }
    benchmark::DoNotOptimize(u.data());
  }
  state.SetComplexityN(k);
}
BENCHMARK(BM_SuperpositionNaive)->RangeMultiplier(4)->Range(16, 4096)->Complexity();

void BM_SegmentClosestPoints(benchmark::State& state) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector3d> p(4096);
  for (auto& q : p) q = Eigen::Vector3d(u(rng), u(rng), u(rng));
  std::size_t i = 0;
  for (auto _ : state) {
    const ClosestPoints cp = segment_closest_points(p[i], p[i + 1], p[i + 2], p[i + 3]);
    benchmark::DoNotOptimize(cp.distance);
    i = (i + 4) % 4092;
  }
}
BENCHMARK(BM_SegmentClosestPoints);

// One slice of a tow: centres of n fibres packed at a volume fraction of about 0.6.
void slice_centres(int n, std::vector<Eigen::Vector2d>& centres, std::vector<double>& radii) {
  std::mt19937_64 rng(3);
  const double r = 0.01, side = std::sqrt(n * M_PI * r * r / 0.6);
  std::uniform_real_distribution<double> u(0.0, side);
  centres.resize(n);
  radii.assign(n, r);
  for (auto& c : centres) c = Eigen::Vector2d(u(rng), u(rng));
}

using PairFinder = void (*)(const std::vector<Eigen::Vector2d>&, const std::vector<double>&, double,
                            std::vector<std::pair<int, int>>&, const std::vector<double>&);

// One slice's contact pairs: by the grid broad phase (slice_pairs) or all pairs (slice_pairs_all).
template <PairFinder find>
void BM_SlicePairs(benchmark::State& state) {
  std::vector<Eigen::Vector2d> centres;
  std::vector<double> radii;
  slice_centres(static_cast<int>(state.range(0)), centres, radii);
  std::vector<std::pair<int, int>> pairs;
  for (auto _ : state) {
    find(centres, radii, 0.0025, pairs, {});
    benchmark::DoNotOptimize(pairs.data());
  }
  state.SetComplexityN(state.range(0));
}
BENCHMARK_TEMPLATE(BM_SlicePairs, slice_pairs)->RangeMultiplier(4)->Range(64, 16384)->Complexity();
BENCHMARK_TEMPLATE(BM_SlicePairs, slice_pairs_all)
    ->RangeMultiplier(4)
    ->Range(64, 4096)
    ->Complexity();

// A generated, compacted tow (default options, 100 slices) under the accelerated rule: the time of
// one iteration as the tow grows, without the set-up (detection, the estimate of λmax(W)). Two runs
// of 200 and 2200 iterations; the difference of their times over 2000.
/// A generated tow of `fibres` fibres (default options, 100 slices).
Scene default_tow(int fibres) {
  TowOptions options;
  options.fibres = fibres;
  options.slices = 100;
  return generate_tow(options);
}

SolverOptions accelerated(const Scene& scene) {
  SolverOptions solver = SolverOptions::from_scene(scene);
  solver.rule = UpdateRule::accelerated;
  return solver;
}

void BM_TowIteration(benchmark::State& state) {
  const Scene scene = default_tow(static_cast<int>(state.range(0)));
  SolverOptions solver = accelerated(scene);
  for (auto _ : state) {
    solver.max_iterations = 200;
    const Result short_run = solve_iteratively(scene, solver);
    solver.max_iterations = 2200;
    const Result long_run = solve_iteratively(scene, solver);
    state.counters["ms_per_iteration"] =
        1e3 * (long_run.wall_time_s - short_run.wall_time_s) /
        static_cast<double>(long_run.iterations - short_run.iterations);
    double contacts = 0;
    for (const ContactResult& c : long_run.contacts)
      contacts += static_cast<double>(c.points.size());
    state.counters["contacts"] = contacts;
  }
}
BENCHMARK(BM_TowIteration)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond)->Iterations(3);

// Whole runs to convergence of a generated tow, accelerated rule.
void BM_TowSolve(benchmark::State& state) {
  const Scene scene = default_tow(static_cast<int>(state.range(0)));
  const SolverOptions solver = accelerated(scene);
  for (auto _ : state) {
    const Result r = solve_iteratively(scene, solver);
    state.counters["iterations"] = static_cast<double>(r.iterations);
    state.counters["ms_per_iteration"] = 1e3 * r.wall_time_s / static_cast<double>(r.iterations);
    state.counters["converged"] = r.status == Status::converged ? 1 : 0;
  }
}
BENCHMARK(BM_TowSolve)->Arg(19)->Arg(100)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace fibrecheck

BENCHMARK_MAIN();
