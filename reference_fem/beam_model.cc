#include "beam_model.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/table.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/petsc_solver.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <petscksp.h>
#include <petscpc.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "atomic_file.h"
#include "fibre.h"
#include "input_error.h"
#include "petsc_check.h"

namespace fibrecheck {

using namespace dealii;

namespace {
// Components of the finite element: deflection and moment in the bending plane of e1, then e2.
constexpr unsigned int kW[2] = {0, 2};
constexpr unsigned int kM[2] = {1, 3};

/// A solve that PETSc says diverged (a failed factorisation, CG out of iterations) is an error.
void converged(KSP ksp, const char* what) {
  KSPConvergedReason reason;
  KSPGetConvergedReason(ksp, &reason);
  if (reason < 0)
    throw std::runtime_error(std::string(what) + " did not solve the beam system (PETSc reason " +
                             std::to_string(static_cast<int>(reason)) + ")");
}

/// A solve is judged by its own residual, never by the solver's word alone: the normwise backward
/// error ‖b − A·x‖∞ / (‖A‖∞·‖x‖∞ + ‖b‖∞) must be at most `bound` (a backward-stable direct solve
/// gives a few times machine epsilon; conjugate gradients to a relative 1e-12 about that).
void judge_solve(const PETScWrappers::SparseMatrix& A, const PETScWrappers::MPI::Vector& x,
                 const PETScWrappers::MPI::Vector& b, double bound, const char* what) {
  PETScWrappers::MPI::Vector r(b);
  A.residual(r, x, b);
  const double scale = A.linfty_norm() * x.linfty_norm() + b.linfty_norm();
  const double error = scale > 0.0 ? r.linfty_norm() / scale : 0.0;
  if (!(error <= bound)) {
    std::ostringstream out;
    out.precision(3);
    out << what << " returned a solution of the beam system with backward error " << error
        << ", above " << bound;
    throw std::runtime_error(out.str());
  }
}

/// Physical curve tags of the mesh by name (the fibre ids), from its $PhysicalNames block.
std::map<std::string, int> curve_tags(const std::string& mesh_file) {
  std::ifstream in(mesh_file);
  std::string line;
  std::map<std::string, int> tags;
  while (std::getline(in, line) && line != "$PhysicalNames") {
  }
  int count = 0;
  if (!(in >> count)) return tags;
  for (int i = 0; i < count; ++i) {
    int dim = 0, tag = 0;
    std::string name;
    in >> dim >> tag >> std::ws;
    std::getline(in, name);
    if (name.size() >= 2 && name.front() == '"') name = name.substr(1, name.size() - 2);
    if (dim == 1) tags[name] = tag;
  }
  return tags;
}
/// The displacement vector u = w1·e1 + w2·e2 (mm), in each fibre's own frame, for ParaView's
/// "Warp by vector".
class Displacement : public DataPostprocessorVector<3> {
 public:
  Displacement(const std::vector<Fibre>& fibres,
               const std::map<types::material_id, int>& fibre_of_material)
      : DataPostprocessorVector<3>("displacement", update_values),
        fibres_(fibres),
        fibre_of_material_(fibre_of_material) {}

  void evaluate_vector_field(const DataPostprocessorInputs::Vector<3>& inputs,
                             std::vector<Vector<double>>& computed) const override {
    const Fibre& f = fibres_[fibre_of_material_.at(inputs.template get_cell<1>()->material_id())];
    for (std::size_t q = 0; q < computed.size(); ++q) {
      const Eigen::Vector3d u =
          inputs.solution_values[q][kW[0]] * f.e1 + inputs.solution_values[q][kW[1]] * f.e2;
      for (unsigned int d = 0; d < 3; ++d) computed[q][d] = u[d];
    }
  }

 private:
  const std::vector<Fibre>& fibres_;
  const std::map<types::material_id, int>& fibre_of_material_;
};

}  // namespace

struct BeamModel::Implementation {
  const Scene& scene;
  std::vector<Fibre> fibres;
  std::map<types::material_id, int> fibre_of_material;
  Triangulation<1, 3> triangulation;
  const unsigned int degree;
  FESystem<1, 3> fe;
  DoFHandler<1, 3> dof_handler{triangulation};
  AffineConstraints<double> constraints;
  /// The solution in the mixed element's unknowns (w1, M1, w2, M2), for every use after a solve.
  PETScWrappers::MPI::Vector solution;
  /// The mixed system's matrix, only to build a larger system around it (for_each_matrix_entry).
  PETScWrappers::SparseMatrix system_matrix;
  bool matrix_assembled = false;
  /// The Laplace matrix's solver, set up once: MUMPS's Cholesky factor (solver direct) or
  /// conjugate gradients with hypre's BoomerAMG (cg_amg).
  KSP laplace_solver = nullptr;

  /// The mixed system is symmetric but indefinite, and as a whole as badly conditioned as the
  /// bi-Laplacian it is (about (elements)⁴: a factorisation of it left nodal deflections 1e-8 off
  /// the exact ones). It is solved as its two symmetric positive definite halves, per plane:
  /// K·m = b for the moment (from −∫M'ψ' = −∫qψ − ΣPψ(a)), then K·w = A·m for the deflection (from
  /// ∫Mφ/EI = ∫w'φ'), with K the Laplace matrix ∫ψ'φ' and A the mass matrix ∫ψφ/EI on the scalar
  /// quadratic element, both with the supports' zero values: each as well conditioned as a
  /// Laplace problem, and one factor of K serves both halves and both planes.
  BeamSolver solver_kind = BeamSolver::direct;
  FE_Q<1, 3> scalar_fe;
  DoFHandler<1, 3> scalar_dofs{triangulation};
  AffineConstraints<double> scalar_constraints;
  PETScWrappers::SparseMatrix laplace, mass;
  PETScWrappers::MPI::Vector plane_rhs[2], moment[2], deflection[2], mass_times_moment;
  /// Per fibre: node fraction s → the scalar DoF of that vertex.
  std::vector<std::map<double, types::global_dof_index>> scalar_nodes;
  long cg_iterations = 0;

  ~Implementation() {
    if (laplace_solver) KSPDestroy(&laplace_solver);
  }
  /// Per fibre: node fraction s → the four DoFs (w1, M1, w2, M2) of that vertex.
  std::vector<std::map<double, std::array<types::global_dof_index, 4>>> nodes;
  /// Per fibre: the fraction at each element's first vertex → the element, for evaluating the
  /// solution between nodes.
  std::vector<std::map<double, DoFHandler<1, 3>::active_cell_iterator>> elements;
  /// The last load case: its point forces and whether the scene's uniform loads were on.
  std::vector<NodalForce> last_forces;
  bool last_scene_loads = false;
  std::vector<char> in_mesh;  ///< per fibre of the scene: in this mesh

  Implementation(const Scene& s, const std::string& mesh_file, const std::vector<char>& meshed,
                 BeamSolver kind, unsigned int element_degree)
      : scene(s),
        degree(element_degree),
        fe(FE_Q<1, 3>(element_degree), 4),
        solver_kind(kind),
        scalar_fe(element_degree) {
    fibres = make_fibres(scene);
    const auto tags = curve_tags(mesh_file);
    for (std::size_t i = 0; i < fibres.size(); ++i) {
      if (!meshed.empty() && !meshed[i]) continue;
      auto it = tags.find(fibres[i].id);
      if (it == tags.end())
        throw InputError(mesh_file, fibres[i].id, "no physical curve for this fibre");
      fibre_of_material[static_cast<types::material_id>(it->second)] = static_cast<int>(i);
    }
    in_mesh.assign(fibres.size(), 0);
    for (const auto& [material, f] : fibre_of_material) in_mesh[f] = 1;
    make_grid(mesh_file);
  }

  /// Reads the Gmsh mesh: each cell's material id is its fibre's physical curve tag.
  void make_grid(const std::string& mesh_file) {
    GridIn<1, 3> grid_in;
    grid_in.attach_triangulation(triangulation);
    std::ifstream in(mesh_file);
    if (!in) throw InputError(mesh_file, "", "no such mesh file");
    grid_in.read_msh(in);
  }

  /// DoFs, the pinned supports (w = 0 and M = 0 in both planes) and the node table.
  void setup_system() {
    dof_handler.distribute_dofs(fe);
    nodes.assign(fibres.size(), {});
    elements.assign(fibres.size(), {});
    constraints.clear();
    for (const auto& cell : dof_handler.active_cell_iterators()) {
      const int f = fibre_of_material.at(cell->material_id());
      elements[f][std::min(fraction(f, cell->vertex(0)), fraction(f, cell->vertex(1)))] = cell;
      for (unsigned int v = 0; v < 2; ++v) {
        const double s = fraction(f, cell->vertex(v));
        std::array<types::global_dof_index, 4> dofs;
        for (unsigned int c = 0; c < 4; ++c) dofs[c] = cell->vertex_dof_index(v, c);
        nodes[f][s] = dofs;
        if (std::fabs(s) < 1e-9 || std::fabs(s - 1.0) < 1e-9)
          for (unsigned int c = 0; c < 4; ++c) constraints.add_line(dofs[c]);
      }
    }
    constraints.close();
    solution.reinit(MPI_COMM_SELF, dof_handler.n_dofs(), dof_handler.n_dofs());
    setup_split_system();
  }

  void setup_split_system() {
    scalar_dofs.distribute_dofs(scalar_fe);
    scalar_nodes.assign(fibres.size(), {});
    scalar_constraints.clear();
    for (const auto& cell : scalar_dofs.active_cell_iterators()) {
      const int f = fibre_of_material.at(cell->material_id());
      for (unsigned int v = 0; v < 2; ++v) {
        const double s = fraction(f, cell->vertex(v));
        const types::global_dof_index dof = cell->vertex_dof_index(v, 0);
        scalar_nodes[f][s] = dof;
        if (std::fabs(s) < 1e-9 || std::fabs(s - 1.0) < 1e-9) scalar_constraints.add_line(dof);
      }
    }
    scalar_constraints.close();
    DynamicSparsityPattern pattern(scalar_dofs.n_dofs());
    DoFTools::make_sparsity_pattern(scalar_dofs, pattern, scalar_constraints, false);
    laplace.reinit(pattern);
    mass.reinit(pattern);
    const auto n = scalar_dofs.n_dofs();
    for (int plane = 0; plane < 2; ++plane) {
      plane_rhs[plane].reinit(MPI_COMM_SELF, n, n);
      moment[plane].reinit(MPI_COMM_SELF, n, n);
      deflection[plane].reinit(MPI_COMM_SELF, n, n);
    }
    mass_times_moment.reinit(MPI_COMM_SELF, n, n);
    const QGauss<1> quadrature(degree + 1);
    FEValues<1, 3> values(scalar_fe, quadrature,
                          update_values | update_gradients | update_JxW_values);
    const unsigned int m = scalar_fe.n_dofs_per_cell();
    FullMatrix<double> cell_laplace(m, m), cell_mass(m, m);
    std::vector<types::global_dof_index> dofs(m);
    for (const auto& cell : scalar_dofs.active_cell_iterators()) {
      const double EI = fibres[fibre_of_material.at(cell->material_id())].EI;
      values.reinit(cell);
      cell_laplace = 0;
      cell_mass = 0;
      for (unsigned int k = 0; k < quadrature.size(); ++k)
        for (unsigned int i = 0; i < m; ++i)
          for (unsigned int j = 0; j < m; ++j) {
            cell_laplace(i, j) += values.shape_grad(i, k) * values.shape_grad(j, k) * values.JxW(k);
            cell_mass(i, j) +=
                values.shape_value(i, k) * values.shape_value(j, k) / EI * values.JxW(k);
          }
      cell->get_dof_indices(dofs);
      scalar_constraints.distribute_local_to_global(cell_laplace, dofs, laplace);
      scalar_constraints.distribute_local_to_global(cell_mass, dofs, mass);
    }
    laplace.compress(VectorOperation::add);
    mass.compress(VectorOperation::add);
    check(KSPCreate(PETSC_COMM_SELF, &laplace_solver), "KSPCreate");
    check(KSPSetOperators(laplace_solver, laplace, laplace), "KSPSetOperators");
    PC pc;
    check(KSPGetPC(laplace_solver, &pc), "KSPGetPC");
    if (solver_kind == BeamSolver::direct) {
      check(KSPSetType(laplace_solver, KSPPREONLY), "KSPSetType");
      check(PCSetType(pc, PCCHOLESKY), "PCSetType");
      check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
      check(KSPSetUp(laplace_solver), "KSPSetUp (MUMPS factorisation)");
      return;
    }
    // CG stops at a relative decrease of 1e-12 of its (preconditioned) residual; BoomerAMG on a
    // one-dimensional Laplace matrix is nearly exact, so that takes one or two iterations.
    check(KSPSetType(laplace_solver, KSPCG), "KSPSetType");
    check(KSPSetTolerances(laplace_solver, 1e-12, 0.0, PETSC_DEFAULT, 1000), "KSPSetTolerances");
    check(PCSetType(pc, PCHYPRE), "PCSetType");
    check(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType");
    check(KSPSetUp(laplace_solver), "KSPSetUp (BoomerAMG)");
  }

  /// Both planes by the two halves (see `solver_kind`), then the mixed solution vector filled
  /// from the scalar ones, so every later use sees one kind of solution.
  void solve(const std::vector<NodalForce>& extra, bool scene_loads) {
    const QGauss<1> quadrature(degree + 1);
    FEValues<1, 3> values(scalar_fe, quadrature, update_values | update_JxW_values);
    const unsigned int m = scalar_fe.n_dofs_per_cell();
    std::vector<types::global_dof_index> dofs(m);
    const std::vector<Eigen::Vector2d> q = uniform_loads(scene_loads);
    const bool distributed =
        std::any_of(q.begin(), q.end(), [](const Eigen::Vector2d& qf) { return !qf.isZero(); });
    for (int plane = 0; plane < 2; ++plane) plane_rhs[plane] = 0;
    for (const auto& cell : scalar_dofs.active_cell_iterators()) {
      if (!distributed) break;
      const int f = fibre_of_material.at(cell->material_id());
      if (q[f].isZero()) continue;
      values.reinit(cell);
      cell->get_dof_indices(dofs);
      for (unsigned int k = 0; k < quadrature.size(); ++k)
        for (unsigned int i = 0; i < m; ++i)
          for (int plane = 0; plane < 2; ++plane)
            plane_rhs[plane](dofs[i]) += q[f][plane] * values.shape_value(i, k) * values.JxW(k);
    }
    auto add_point_force = [&](int f, double s, const Eigen::Vector3d& force) {
      const types::global_dof_index dof = node(scalar_nodes, f, s);
      if (scalar_constraints.is_constrained(dof)) return;
      plane_rhs[0](dof) += force.dot(fibres[f].e1);
      plane_rhs[1](dof) += force.dot(fibres[f].e2);
    };
    for (const NodalForce& force : point_forces(extra, scene_loads))
      add_point_force(force.fibre, force.s, force.force);
    for (int plane = 0; plane < 2; ++plane) {
      plane_rhs[plane].compress(VectorOperation::add);
      solve_laplace(moment[plane], plane_rhs[plane]);
      mass.vmult(mass_times_moment, moment[plane]);
      solve_laplace(deflection[plane], mass_times_moment);
    }
    // The mixed solution vector from the scalar ones, cell by cell.
    std::vector<types::global_dof_index> mixed(fe.n_dofs_per_cell());
    auto cell = dof_handler.begin_active();
    for (const auto& scalar_cell : scalar_dofs.active_cell_iterators()) {
      scalar_cell->get_dof_indices(dofs);
      cell->get_dof_indices(mixed);
      for (unsigned int i = 0; i < mixed.size(); ++i) {
        const auto [component, index] = fe.system_to_component_index(i);
        const int plane = component == kW[0] || component == kM[0] ? 0 : 1;
        const bool is_w = component == kW[plane];
        solution(mixed[i]) = is_w ? deflection[plane](dofs[index]) : moment[plane](dofs[index]);
      }
      ++cell;
    }
    solution.compress(VectorOperation::insert);
  }

  /// K·x = b with the supports' values zero, judged by its own residual.
  void solve_laplace(PETScWrappers::MPI::Vector& x, PETScWrappers::MPI::Vector& b) {
    scalar_constraints.set_zero(b);
    b.compress(VectorOperation::insert);
    x = 0;
    if (b.l2_norm() == 0.0) return;
    const bool direct = solver_kind == BeamSolver::direct;
    check(KSPSolve(laplace_solver, b, x), direct ? "KSPSolve (MUMPS)" : "KSPSolve (CG)");
    converged(laplace_solver, direct ? "MUMPS" : "conjugate gradients");
    judge_solve(laplace, x, b, direct ? 1e-12 : 1e-10, direct ? "MUMPS" : "conjugate gradients");
    if (!direct) {
      PetscInt steps = 0;
      KSPGetIterationNumber(laplace_solver, &steps);
      cg_iterations += steps;
    }
    scalar_constraints.distribute(x);
  }

  /// Fraction of fibre f's length at which a mesh point lies.
  double fraction(int f, const Point<3>& p) const {
    const Fibre& fibre = fibres[f];
    return (Eigen::Vector3d(p[0], p[1], p[2]) - fibre.start).dot(fibre.t) / fibre.length;
  }

  /// The four fields (w1, M1, w2, M2) of the last solution at fraction s of fibre f: the nodal
  /// values at a node, else the element's shape functions at s.
  std::array<double, 4> fields(int f, double s) const {
    std::array<double, 4> value{};
    const auto& nodes_of_fibre = nodes.at(f);
    auto node_it = nodes_of_fibre.lower_bound(s - 1e-9);
    if (node_it != nodes_of_fibre.end() && std::fabs(node_it->first - s) <= 1e-9) {
      for (unsigned int c = 0; c < 4; ++c) value[c] = solution(node_it->second[c]);
      return value;
    }
    const auto& elements_of_fibre = elements.at(f);
    auto it = elements_of_fibre.upper_bound(s);
    if (it == elements_of_fibre.begin() || s < 0.0 || s > 1.0)
      throw std::runtime_error("s = " + std::to_string(s) + " lies outside fibre " + fibres[f].id);
    const auto& cell = std::prev(it)->second;
    const double s0 = fraction(f, cell->vertex(0)), s1 = fraction(f, cell->vertex(1));
    const Point<1> xi((s - s0) / (s1 - s0));
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    cell->get_dof_indices(dofs);
    for (unsigned int i = 0; i < dofs.size(); ++i)
      value[fe.system_to_component_index(i).first] += solution(dofs[i]) * fe.shape_value(i, xi);
    return value;
  }

  /// The DoF of the node at fraction s of fibre f in one of the node tables.
  template <typename Table>
  typename Table::value_type::mapped_type node(const Table& table, int f, double s) const {
    const auto& nodes_of_fibre = table.at(f);
    auto it = nodes_of_fibre.lower_bound(s - 1e-9);
    if (it == nodes_of_fibre.end() || std::fabs(it->first - s) > 1e-9)
      throw std::runtime_error("no mesh node at s = " + std::to_string(s) + " of fibre " +
                               fibres[f].id);
    return it->second;
  }

  /// Each fibre's uniform load per length in its two bending planes (N/mm), if `scene_loads`.
  std::vector<Eigen::Vector2d> uniform_loads(bool scene_loads) const {
    std::vector<Eigen::Vector2d> q(fibres.size(), Eigen::Vector2d::Zero());
    for (const LoadSpec& load : scene.loads)
      if (scene_loads && load.kind == LoadKind::distributed) {
        const int f = scene.fibre_index(load.fibre);
        q[f] += Eigen::Vector2d(load.force.dot(fibres[f].e1), load.force.dot(fibres[f].e2));
      }
    return q;
  }

  /// The point forces of one load case: the scene's point loads (if `scene_loads`) and `extra`.
  std::vector<NodalForce> point_forces(const std::vector<NodalForce>& extra,
                                       bool scene_loads) const {
    std::vector<NodalForce> forces;
    for (const LoadSpec& load : scene.loads) {
      const int f = scene.fibre_index(load.fibre);
      if (scene_loads && load.kind == LoadKind::point && in_mesh[f])
        forces.push_back({f, load.position, load.force});
    }
    forces.insert(forces.end(), extra.begin(), extra.end());
    return forces;
  }

  /// The mixed form's matrix in both planes. Only w and M of one plane meet in the equations (and
  /// the planes not at all): the pattern says so.
  void assemble_mixed_matrix() {
    Table<2, DoFTools::Coupling> coupling(4, 4);
    coupling.fill(DoFTools::none);
    for (int plane = 0; plane < 2; ++plane) {
      coupling[kW[plane]][kM[plane]] = DoFTools::always;
      coupling[kM[plane]][kW[plane]] = DoFTools::always;
      coupling[kM[plane]][kM[plane]] = DoFTools::always;
    }
    DynamicSparsityPattern pattern(dof_handler.n_dofs());
    DoFTools::make_sparsity_pattern(dof_handler, coupling, pattern, constraints, false);
    system_matrix.reinit(pattern);
    const QGauss<1> quadrature(degree + 2);
    FEValues<1, 3> fe_values(fe, quadrature, update_values | update_gradients | update_JxW_values);
    const unsigned int n = fe.n_dofs_per_cell();
    FullMatrix<double> cell_matrix(n, n);
    std::vector<types::global_dof_index> dof_indices(n);
    for (const auto& cell : dof_handler.active_cell_iterators()) {
      const double EI = fibres[fibre_of_material.at(cell->material_id())].EI;
      fe_values.reinit(cell);
      cell_matrix = 0;
      for (unsigned int k = 0; k < quadrature.size(); ++k)
        for (unsigned int i = 0; i < n; ++i) {
          const unsigned int ci = fe.system_to_component_index(i).first;
          for (unsigned int j = 0; j < n; ++j) {
            const unsigned int cj = fe.system_to_component_index(j).first;
            double value = 0.0;
            for (int plane = 0; plane < 2; ++plane) {
              if (ci == kM[plane] && cj == kM[plane])  // ∫ M φ / EI
                value += fe_values.shape_value(i, k) * fe_values.shape_value(j, k) / EI;
              if ((ci == kM[plane] && cj == kW[plane]) || (ci == kW[plane] && cj == kM[plane]))
                value -=
                    fe_values.shape_grad(i, k) * fe_values.shape_grad(j, k);  // −∫ w'φ', −∫ M'ψ'
            }
            cell_matrix(i, j) += value * fe_values.JxW(k);
          }
        }
      cell->get_dof_indices(dof_indices);
      constraints.distribute_local_to_global(cell_matrix, dof_indices, system_matrix);
    }
    system_matrix.compress(VectorOperation::add);
    matrix_assembled = true;
  }
};

BeamModel::BeamModel(const Scene& scene, const std::string& mesh_file,
                     const std::vector<char>& fibres, BeamSolver solver, unsigned int degree)
    : impl_(std::make_unique<Implementation>(scene, mesh_file, fibres, solver, degree)) {
  if (degree < 1 || degree > 2) throw std::invalid_argument("BeamModel: degree must be 1 or 2");
}

BeamModel::~BeamModel() = default;

void BeamModel::run(const std::vector<NodalForce>& extra, bool scene_loads) {
  if (impl_->dof_handler.n_dofs() == 0) impl_->setup_system();
  impl_->last_forces = impl_->point_forces(extra, scene_loads);
  impl_->last_scene_loads = scene_loads;
  impl_->solve(extra, scene_loads);
}

std::vector<Eigen::MatrixXd> BeamModel::influence_matrices(
    const std::vector<std::vector<double>>& stations,
    const std::function<void(std::size_t, std::size_t)>& progress) {
  Implementation& m = *impl_;
  if (m.dof_handler.n_dofs() == 0) m.setup_system();
  const std::size_t fibres = m.fibres.size();
  std::vector<Eigen::MatrixXd> G(fibres);
  std::size_t rounds = 0;
  for (std::size_t f = 0; f < fibres; ++f) {
    if (m.nodes[f].empty()) continue;
    G[f].resize(stations[f].size(), stations[f].size());
    rounds = std::max(rounds, stations[f].size());
  }
  if (m.solver_kind == BeamSolver::cg_amg) {
    // One right-hand side at a time.
    std::vector<NodalForce> unit;
    for (std::size_t i = 0; i < rounds; ++i) {
      unit.clear();
      for (std::size_t f = 0; f < fibres; ++f)
        if (G[f].size() > 0 && i < stations[f].size())
          unit.push_back({static_cast<int>(f), stations[f][i], m.fibres[f].e1});
      run(unit, false);
      for (std::size_t f = 0; f < fibres; ++f)
        if (G[f].size() > 0 && i < stations[f].size())
          for (std::size_t j = 0; j < stations[f].size(); ++j)
            G[f](j, i) = displacement(static_cast<int>(f), stations[f][j]).dot(m.fibres[f].e1);
      if (progress) progress(i + 1, rounds);
    }
    return G;
  }
  // MUMPS: blocks of right-hand sides through the Laplace matrix's factor (MatMatSolve) twice, the
  // moments between multiplied by the mass matrix, read back from the dense deflection block. A
  // unit force along e1 enters the moment equation as +1 at its node. Eight columns a block: the
  // dense blocks then take about what the factor takes, and wider blocks hardly solve faster.
  std::vector<std::vector<types::global_dof_index>> w1(fibres);
  for (std::size_t f = 0; f < fibres; ++f)
    if (G[f].size() > 0)
      for (double s : stations[f]) w1[f].push_back(m.node(m.scalar_nodes, static_cast<int>(f), s));
  std::vector<types::global_dof_index> supports;
  for (types::global_dof_index i = 0; i < m.scalar_dofs.n_dofs(); ++i)
    if (m.scalar_constraints.is_constrained(i)) supports.push_back(i);
  Mat factor;
  PC pc;
  check(KSPGetPC(m.laplace_solver, &pc), "KSPGetPC");
  check(PCFactorGetMatrix(pc, &factor), "PCFactorGetMatrix");
  const PetscInt n = static_cast<PetscInt>(m.scalar_dofs.n_dofs());
  if (rounds == 0) return G;
  // The blocks are made once (a short last block solves some zero columns too).
  constexpr std::size_t kBlock = 8;
  const PetscInt width = static_cast<PetscInt>(std::min(kBlock, rounds));
  Mat B, moments, loads = nullptr, X;
  check(MatCreateSeqDense(PETSC_COMM_SELF, n, width, nullptr, &B), "MatCreateSeqDense");
  check(MatCreateSeqDense(PETSC_COMM_SELF, n, width, nullptr, &moments), "MatCreateSeqDense");
  check(MatCreateSeqDense(PETSC_COMM_SELF, n, width, nullptr, &X), "MatCreateSeqDense");
  for (std::size_t first = 0; first < rounds; first += kBlock) {
    const PetscInt columns = static_cast<PetscInt>(std::min(kBlock, rounds - first));
    PetscScalar* b = nullptr;
    check(MatDenseGetArray(B, &b), "MatDenseGetArray");
    std::fill(b, b + static_cast<std::size_t>(width) * n, 0.0);
    for (PetscInt c = 0; c < columns; ++c)
      for (std::size_t f = 0; f < fibres; ++f)
        if (first + c < w1[f].size() && !m.scalar_constraints.is_constrained(w1[f][first + c]))
          b[static_cast<std::size_t>(c) * n + w1[f][first + c]] = 1.0;
    check(MatDenseRestoreArray(B, &b), "MatDenseRestoreArray");
    check(MatMatSolve(factor, B, moments), "MatMatSolve (MUMPS)");
    check(MatMatMult(m.mass.petsc_matrix(), moments, loads ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX,
                     PETSC_DEFAULT, &loads),
          "MatMatMult");
    check(MatDenseGetArray(loads, &b), "MatDenseGetArray");
    for (PetscInt c = 0; c < width; ++c)
      for (types::global_dof_index i : supports) b[static_cast<std::size_t>(c) * n + i] = 0.0;
    check(MatDenseRestoreArray(loads, &b), "MatDenseRestoreArray");
    check(MatMatSolve(factor, loads, X), "MatMatSolve (MUMPS)");
    const PetscScalar* x = nullptr;
    check(MatDenseGetArrayRead(X, &x), "MatDenseGetArrayRead");
    for (PetscInt c = 0; c < columns; ++c)
      for (std::size_t f = 0; f < fibres; ++f) {
        const std::size_t i = first + c;
        if (i >= w1[f].size()) continue;
        for (std::size_t j = 0; j < w1[f].size(); ++j)
          G[f](j, i) = m.scalar_constraints.is_constrained(w1[f][j])
                           ? 0.0
                           : x[static_cast<std::size_t>(c) * n + w1[f][j]];
      }
    check(MatDenseRestoreArrayRead(X, &x), "MatDenseRestoreArrayRead");
    if (progress) progress(first + static_cast<std::size_t>(columns), rounds);
  }
  MatDestroy(&B);
  MatDestroy(&moments);
  MatDestroy(&loads);
  MatDestroy(&X);
  return G;
}

long BeamModel::cg_iterations() const {
  return impl_->cg_iterations;
}

Eigen::Vector3d BeamModel::displacement(int fibre, double s) const {
  const std::array<double, 4> value = impl_->fields(fibre, s);
  const Fibre& f = impl_->fibres[fibre];
  return value[kW[0]] * f.e1 + value[kW[1]] * f.e2;
}

Eigen::Vector2d BeamModel::moment(int fibre, double s) const {
  const std::array<double, 4> value = impl_->fields(fibre, s);
  return {value[kM[0]], value[kM[1]]};
}

double BeamModel::strain_energy() const {
  const Implementation& m = *impl_;
  // M_h has the element's degree p: p + 1 Gauss points integrate M_h² exactly.
  const QGauss<1> quadrature(m.degree + 1);
  FEValues<1, 3> values(m.fe, quadrature, update_values | update_JxW_values);
  std::vector<types::global_dof_index> dofs(m.fe.n_dofs_per_cell());
  double energy = 0.0;
  for (const auto& cell : m.dof_handler.active_cell_iterators()) {
    const double EI = m.fibres[m.fibre_of_material.at(cell->material_id())].EI;
    values.reinit(cell);
    cell->get_dof_indices(dofs);
    for (unsigned int k = 0; k < quadrature.size(); ++k) {
      double M[4] = {0, 0, 0, 0};
      for (unsigned int i = 0; i < dofs.size(); ++i)
        M[m.fe.system_to_component_index(i).first] +=
            m.solution(dofs[i]) * values.shape_value(i, k);
      energy += (M[kM[0]] * M[kM[0]] + M[kM[1]] * M[kM[1]]) / (2.0 * EI) * values.JxW(k);
    }
  }
  return energy;
}

double BeamModel::load_work() const {
  const Implementation& m = *impl_;
  double work = 0.0;
  for (const NodalForce& force : m.last_forces)
    work += force.force.dot(displacement(force.fibre, force.s));
  // ∫q·w over the elements: w_h has degree p, p + 1 Gauss points are exact for q·w_h.
  const std::vector<Eigen::Vector2d> q = m.uniform_loads(m.last_scene_loads);
  const QGauss<1> quadrature(m.degree + 1);
  FEValues<1, 3> values(m.fe, quadrature, update_values | update_JxW_values);
  std::vector<types::global_dof_index> dofs(m.fe.n_dofs_per_cell());
  for (const auto& cell : m.dof_handler.active_cell_iterators()) {
    const int f = m.fibre_of_material.at(cell->material_id());
    if (q[f].isZero()) continue;
    values.reinit(cell);
    cell->get_dof_indices(dofs);
    for (unsigned int k = 0; k < quadrature.size(); ++k) {
      double w[4] = {0, 0, 0, 0};
      for (unsigned int i = 0; i < dofs.size(); ++i)
        w[m.fe.system_to_component_index(i).first] +=
            m.solution(dofs[i]) * values.shape_value(i, k);
      work += (q[f][0] * w[kW[0]] + q[f][1] * w[kW[1]]) * values.JxW(k);
    }
  }
  return 0.5 * work;
}

double BeamModel::axial_load_dropped() const {
  const Implementation& m = *impl_;
  double total = 0.0;
  for (const NodalForce& force : m.last_forces)
    total += std::fabs(force.force.dot(m.fibres[force.fibre].t));
  if (m.last_scene_loads)
    for (const LoadSpec& load : m.scene.loads) {
      const int f = m.scene.fibre_index(load.fibre);
      if (load.kind == LoadKind::distributed && m.in_mesh[f])
        total += std::fabs(load.force.dot(m.fibres[f].t)) * m.fibres[f].length;
    }
  return total;
}

std::size_t BeamModel::unknowns() const {
  return impl_->dof_handler.n_dofs();
}

void BeamModel::setup_system() {
  if (impl_->dof_handler.n_dofs() == 0) impl_->setup_system();
}

long BeamModel::deflection_unknown(int fibre, double s, int plane) const {
  const Implementation& m = *impl_;
  const types::global_dof_index dof = m.node(m.nodes, fibre, s)[kW[plane]];
  return m.constraints.is_constrained(dof) ? -1 : static_cast<long>(dof);
}

void BeamModel::for_each_matrix_entry(const std::function<void(long, long, double)>& entry) {
  Implementation& m = *impl_;
  if (m.dof_handler.n_dofs() == 0) m.setup_system();
  if (!m.matrix_assembled) m.assemble_mixed_matrix();
  const PetscInt rows = static_cast<PetscInt>(m.dof_handler.n_dofs());
  for (PetscInt row = 0; row < rows; ++row) {
    PetscInt count = 0;
    const PetscInt* columns = nullptr;
    const PetscScalar* values = nullptr;
    check(MatGetRow(m.system_matrix, row, &count, &columns, &values), "MatGetRow");
    for (PetscInt i = 0; i < count; ++i) entry(row, columns[i], values[i]);
    check(MatRestoreRow(m.system_matrix, row, &count, &columns, &values), "MatRestoreRow");
  }
}

void BeamModel::write_vtu(const std::string& path, const std::string& record,
                          const std::vector<std::string>& pieces) const {
  const Implementation& m = *impl_;
  // The finite-element solution itself, interpolated to the mesh nodes.
  Vector<double> values(m.dof_handler.n_dofs());
  for (types::global_dof_index i = 0; i < values.size(); ++i) values[i] = m.solution(i);
  const Displacement displacement(m.fibres, m.fibre_of_material);
  DataOut<1, 3> data_out;
  data_out.attach_dof_handler(m.dof_handler);
  data_out.add_data_vector(values, std::vector<std::string>{"w1", "M1", "w2", "M2"});
  data_out.add_data_vector(values, displacement);
  Vector<double> fibre(m.triangulation.n_active_cells());
  for (const auto& cell : m.triangulation.active_cell_iterators())
    fibre[cell->active_cell_index()] = m.fibre_of_material.at(cell->material_id());
  data_out.add_data_vector(fibre, "fibre", DataOut<1, 3>::type_cell_data);
  data_out.build_patches();
  std::ostringstream vtu;
  data_out.write_vtu(vtu);
  write_file_atomically(path, vtu.str());
  if (!record.empty()) {
    std::ostringstream collection;
    data_out.write_pvtu_record(collection, pieces);
    write_file_atomically(record, collection.str());
  }
}

}  // namespace fibrecheck
