// The finite-element beams are exact at their nodes for point loads at nodes and uniform loads
// (mixed w–M form, quadratic elements): compared with Eqs. 4.10–4.13. Their energies come from
// their own moments, so linear elements give an energy the beam formulas do not.
#include "beam_model.h"

#include <deal.II/base/mpi.h>
#include <gtest/gtest.h>

#include <memory>

#include "beam.h"
#include "fibre.h"
#include "fibre_mesh.h"

namespace fibrecheck {
namespace {

// Both linear solvers: MUMPS on the mixed system, and CG with BoomerAMG on its two Laplace halves.
class BeamModelSolvers : public ::testing::TestWithParam<BeamSolver> {};

TEST_P(BeamModelSolvers, NodalDeflectionsAreExactForPointAndUniformLoads) {
  Scene s;
  s.name = "skew_beam";
  FibreSpec f;
  f.id = "F";
  f.start = {0.1, 0.2, 0.3};
  f.end = {0.9, -0.2, 0.7};
  f.radius = 0.012;
  f.youngs_modulus = 70000;
  s.fibres.push_back(f);
  const Fibre fibre = make_fibre(f, s.contact.axis, s.contact.parallel_angle_deg);
  const double positions[3] = {0.2, 0.55, 0.8};
  const Eigen::Vector3d forces[3] = {2e-4 * fibre.e1 + 5e-5 * fibre.t, -1e-4 * fibre.e2,
                                     3e-5 * fibre.e1 + 4e-5 * fibre.e2};
  for (int i = 0; i < 3; ++i) {
    LoadSpec load;
    load.fibre = "F";
    load.position = positions[i];
    load.force = forces[i];
    s.loads.push_back(load);
  }
  LoadSpec uniform;
  uniform.fibre = "F";
  uniform.kind = LoadKind::distributed;
  uniform.force = 1e-4 * fibre.e2;
  s.loads.push_back(uniform);
  s.contact.slices = 7;  // a coarse mesh: 7 elements plus the load stations
  // One file per solver: ctest runs the two at once.
  const std::string mesh =
      ::testing::TempDir() + "skew_beam_" + std::to_string(static_cast<int>(GetParam())) + ".msh";
  write_mesh(s, MeshOptions{}, mesh);
  BeamModel model(s, mesh, {}, GetParam());
  model.run();
  EXPECT_GT(model.unknowns(), 0u);

  const double L = fibre.length;
  for (double at : {0.0, 0.2, 0.55, 0.8, 1.0}) {
    Eigen::Vector2d expected(0, 0);
    for (int i = 0; i < 3; ++i) {
      const double a = positions[i] * L;
      expected[0] += point_load_deflection(forces[i].dot(fibre.e1), a, at * L, L, fibre.EI);
      expected[1] += point_load_deflection(forces[i].dot(fibre.e2), a, at * L, L, fibre.EI);
    }
    expected[1] += uniform_load_deflection(1e-4, at * L, L, fibre.EI);
    const Eigen::Vector3d u = model.displacement(0, at);
    const double scale = 1e-3;  // mm, the size of these deflections
    EXPECT_NEAR(u.dot(fibre.e1), expected[0], 1e-8 * scale) << "s = " << at;
    EXPECT_NEAR(u.dot(fibre.e2), expected[1], 1e-8 * scale) << "s = " << at;
    EXPECT_NEAR(u.dot(fibre.t), 0.0, 1e-15);
  }
}

// One fibre (L = 1 mm, r = 0.01 mm, E = 80 GPa) under a uniform load q across it, meshed with
// `elements` equal elements (slices = elements, no other stations). Exact: M(x) = q·x(L − x)/2,
// U = ∫M²/(2EI) dx = q²L⁵/(240EI). The moment equation −M'' = q is a 1-D Laplace problem, so the
// finite-element moment is exact at the nodes for either degree. Quadratic elements hold the
// quadratic M exactly, and their energy is U. Linear ones hold only its interpolant I_h M: their
// energy is Σ_e h(M_i² + M_i·M_j + M_j²)/(6EI) over the elements, less than U.
class UniformlyLoadedFibre : public ::testing::Test {
 protected:
  static constexpr double q = 1e-4;  // N/mm
  static constexpr int elements = 8;
  void SetUp() override {
    scene.name = "uniform";
    scene.fibres.push_back(testing_fibre());
    LoadSpec load;
    load.fibre = "F";
    load.kind = LoadKind::distributed;
    load.force = {0, 0, -q};
    scene.loads.push_back(load);
    scene.contact.slices = elements;
    EI = make_fibre(scene.fibres[0], scene.contact.axis, 10.0).EI;
  }
  static FibreSpec testing_fibre() {
    FibreSpec f;
    f.id = "F";
    f.end = {1, 0, 0};
    f.radius = 0.01;
    f.youngs_modulus = 80000;
    return f;
  }
  double moment(double x) const { return q * x * (1 - x) / 2; }
  double linear_element_energy() const {
    double energy = 0.0;
    const double h = 1.0 / elements;
    for (int e = 0; e < elements; ++e) {
      const double Mi = moment(e * h), Mj = moment((e + 1) * h);
      energy += h * (Mi * Mi + Mi * Mj + Mj * Mj) / (6 * EI);
    }
    return energy;
  }
  std::unique_ptr<BeamModel> model(unsigned int degree) {
    const std::string mesh = ::testing::TempDir() + "uniform_" + std::to_string(degree) + ".msh";
    MeshOptions options;
    options.sample_stations = {{0.0, 1.0}};
    write_mesh(scene, options, mesh);
    auto m =
        std::make_unique<BeamModel>(scene, mesh, std::vector<char>{}, BeamSolver::direct, degree);
    m->run();
    return m;
  }
  Scene scene;
  double EI = 0.0;
};

TEST_F(UniformlyLoadedFibre, QuadraticElementsGiveTheExactEnergyAndMoment) {
  const auto m = model(2);
  EXPECT_EQ(m->unknowns(), 4u * (2 * elements + 1));
  const double U = q * q / (240 * EI);
  EXPECT_NEAR(m->strain_energy(), U, 1e-10 * U);
  EXPECT_NEAR(m->load_work(), U, 1e-10 * U);
  // Between the nodes too: the element's M is the quadratic itself.
  for (double s : {0.0, 0.03, 0.5, 0.61, 1.0})
    EXPECT_NEAR(m->moment(0, s).norm(), moment(s), 1e-10 * moment(0.5)) << s;
  EXPECT_EQ(m->axial_load_dropped(), 0.0);
}

TEST_F(UniformlyLoadedFibre, LinearElementsGiveTheEnergyOfTheInterpolatedMoment) {
  const auto m = model(1);
  EXPECT_EQ(m->unknowns(), 4u * (elements + 1));
  const double U = q * q / (240 * EI), Uh = linear_element_energy();
  ASSERT_GT(U - Uh, 1e-3 * U);  // the mesh is coarse enough to tell the two apart
  EXPECT_NEAR(m->strain_energy(), Uh, 1e-10 * U);
  EXPECT_NEAR(m->load_work(), Uh, 1e-10 * U);  // the mixed form's energy identity
  for (int e = 0; e <= elements; ++e)
    EXPECT_NEAR(m->moment(0, e / double(elements)).norm(), moment(e / double(elements)),
                1e-10 * moment(0.5));
  // Half-way along an element: the mean of its nodes' moments, not the parabola.
  const double h = 1.0 / elements;
  EXPECT_NEAR(m->moment(0, 1.5 * h).norm(), 0.5 * (moment(h) + moment(2 * h)), 1e-10 * moment(0.5));
}

// The dropped axial part of a skew load: |F·t| for a point load, |q·t|·L for a uniform one.
TEST_F(UniformlyLoadedFibre, DropsTheAxialPartOfEveryLoad) {
  scene.loads[0].force = {3e-5, 0, -q};
  LoadSpec point;
  point.fibre = "F";
  point.position = 0.5;
  point.force = {-2e-5, 1e-5, 0};
  scene.loads.push_back(point);
  const auto m = model(2);
  EXPECT_NEAR(m->axial_load_dropped(), 3e-5 * 1.0 + 2e-5, 1e-18);
}

INSTANTIATE_TEST_SUITE_P(Direct, BeamModelSolvers, ::testing::Values(BeamSolver::direct));
INSTANTIATE_TEST_SUITE_P(ConjugateGradients, BeamModelSolvers,
                         ::testing::Values(BeamSolver::cg_amg));

}  // namespace
}  // namespace fibrecheck

int main(int argc, char** argv) {
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
