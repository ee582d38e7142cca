#pragma once

#include <Eigen/Core>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "scene.h"

namespace fibrecheck {

/// Linear solver of the beams' finite-element systems.
enum class BeamSolver {
  direct,  ///< MUMPS's Cholesky factor of the Laplace matrix, made once, for both halves (default)
  cg_amg   ///< conjugate gradients with hypre's BoomerAMG on the Laplace matrix
};

/// A point force on the finite-element beams (N), at a mesh node of one fibre.
struct NodalForce {
  int fibre;
  double s;  ///< fraction of the fibre's length; must be a station of the mesh
  Eigen::Vector3d force;
};

/// The fibres of a scene as implicit finite-element beams (deal.II, Gmsh mesh, PETSc): on each
/// fibre's chord, the transverse deflection w and the bending moment M in both bending planes,
/// the mixed form of Euler–Bernoulli bending
///   ∫ M φ / EI dx − ∫ w' φ' dx = 0,     −∫ M' ψ' dx = −∫ q ψ dx − Σ P ψ(a),
/// with w = 0 and M = 0 at both pinned supports (both essential). Each equation is a 1-D Laplace
/// problem, whose finite-element solution is exact at the nodes; with quadratic elements the
/// moment of a uniform load is represented exactly too, so nodal deflections are exact for point
/// loads at nodes and uniform loads (Eqs. 4.10–4.13). Linear elements (`degree` 1) are there to
/// study the finite element itself: their moment is only the interpolant of the exact one.
///
/// Like deal.II's tutorial programs, only `run()` does the work: make_grid, setup_system,
/// assemble_system, solve. The fibres do not interact through the beams, so the mesh may hold any
/// subset of them: a process can solve its own fibres alone.
class BeamModel {
 public:
  /// Reads the fibres' mesh (written by `write_mesh`) for the scene; `fibres` marks the fibres the
  /// mesh holds (by index in the scene; empty: all of them).
  BeamModel(const Scene& scene, const std::string& mesh_file, const std::vector<char>& fibres = {},
            BeamSolver solver = BeamSolver::direct, unsigned int degree = 2);
  ~BeamModel();

  /// Degrees of freedom, supports and the sparsity pattern (done by the first `run` otherwise).
  void setup_system();

  /// Solves under `extra` forces at mesh nodes, plus the scene's own loads if `scene_loads`.
  void run(const std::vector<NodalForce>& extra = {}, bool scene_loads = true);

  /// Displacement (mm) of a meshed fibre at fraction `s` of its length: the nodal value at a mesh
  /// node (within 1e-9 of the length), else the finite-element field inside its element.
  Eigen::Vector3d displacement(int fibre, double s) const;

  /// Bending moments (N·mm) in the fibre's two bending planes (e1, e2) at fraction `s`, from the
  /// moment unknowns as `displacement` does.
  Eigen::Vector2d moment(int fibre, double s) const;

  /// Strain energy Σ∫(M1² + M2²)/(2EI) dx (N·mm, Eq. 4.34) of the last solution over every element
  /// of the meshed fibres, by Gauss quadrature exact for the element's M².
  double strain_energy() const;

  /// The work of the last load case, ½(ΣP·u(a) + ∫q·u dx) (N·mm), from the finite-element
  /// displacements at the point forces and over the elements for uniform loads: equal to
  /// `strain_energy` by the mixed form's energy identity.
  double load_work() const;

  /// Σ|axial part| (N) of the last load case's forces, which the beams drop (a uniform load counts
  /// with its total over the length).
  double axial_load_dropped() const;

  /// Influence matrices of the meshed fibres: for fibre f, G_f(j, k) (mm/N) is its deflection at
  /// `stations[f][j]` under a unit force across it at `stations[f][k]` (the same in both bending
  /// planes). One right-hand side loads one station of every fibre at once (the fibres do not
  /// interact through the beams); with MUMPS the right-hand sides are solved in blocks. Fibres not
  /// in the mesh get an empty matrix. Fractions must be mesh nodes.
  /// `progress`, if given, hears (right-hand sides done, all of them) now and then.
  std::vector<Eigen::MatrixXd> influence_matrices(
      const std::vector<std::vector<double>>& stations,
      const std::function<void(std::size_t, std::size_t)>& progress = {});

  /// Number of unknowns (both planes, w and M).
  std::size_t unknowns() const;

  /// The unknown of the deflection in bending plane `plane` (0 along e1, 1 along e2) at the mesh
  /// node at fraction `s` of a meshed fibre, or −1 where the support pins it (the deflection is
  /// zero there, and nothing may act on it).
  long deflection_unknown(int fibre, double s, int plane) const;

  /// Calls `entry(row, column, value)` for every stored entry of the mixed system's matrix (with
  /// the supports' rows and columns condensed to their diagonal, as the solves use it), to build a
  /// larger system around it; the matrix is assembled on the first call.
  void for_each_matrix_entry(const std::function<void(long, long, double)>& entry);

  /// Conjugate-gradient iterations so far (solver cg_amg).
  long cg_iterations() const;

  /// Writes the last solution (deflections w1, w2 and moments M1, M2 in each fibre's two bending
  /// planes, the displacement vector and the fibre's index) on the mesh as a ParaView .vtu file;
  /// with `record` also a .pvtu file that collects the .vtu files `pieces` (of several processes).
  void write_vtu(const std::string& path, const std::string& record = "",
                 const std::vector<std::string>& pieces = {}) const;

 private:
  struct Implementation;
  std::unique_ptr<Implementation> impl_;
};

}  // namespace fibrecheck
