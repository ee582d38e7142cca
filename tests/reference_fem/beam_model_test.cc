// The finite-element beams are exact at their nodes for point loads at nodes and uniform loads
// (mixed w–M form, quadratic elements): compared with Eqs. 4.10–4.13 by superposition.
#include "beam_model.h"

#include <deal.II/base/mpi.h>
#include <gtest/gtest.h>

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
