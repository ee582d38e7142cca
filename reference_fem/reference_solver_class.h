#pragma once

// The reference solver's class, shared by the files that define its phases (reference_solver.cc,
// reference_assembly.cc, reference_output.cc, reference_result.cc); not part of the reference's
// interface (reference_solver.h).

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <mpi.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <chrono>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "beam_model.h"
#include "contact.h"
#include "contact_detection.h"
#include "contact_problem.h"
#include "fibre.h"
#include "fibre_mesh.h"
#include "frictional_contact.h"
#include "influence_compliance.h"
#include "normal_mixing.h"
#include "reference_result.h"
#include "reference_solver.h"
#include "result.h"
#include "saddle_point_compliance.h"
#include "scene.h"
#include "slip_origins.h"

namespace fibrecheck {

/// One load step of the implicit reference (DESIGN §3), in the manner of deal.II's step-41: `run()`
/// meshes the fibres with a node at every contact candidate, assembles the contact problem from
/// finite-element solutions, solves it exactly, and re-detects the candidates on the deformed
/// finite-element fibres, until they no longer change. The fibres are shared out among the
/// processes of `options.communicator`; every process ends with the same result.
class ReferenceSolver {
 public:
  ReferenceSolver(const Scene& scene, const ReferenceOptions& options);
  ~ReferenceSolver();
  Result run();
  /// The mesh of the first outer iteration: the candidates on the fibres under the scene's loads.
  MeshOptions first_mesh_options();
  /// Friction: where this step's slip is measured from (the previous step's end).
  void start_from(SlipOrigins origins) { origins_ = std::move(origins); }
  /// After `run`: where the next step's slip is measured from.
  const SlipOrigins& end_state() const { return end_state_; }
  /// The previous step's contacts: their forces (and friction), matched by contact key, are this
  /// step's first guess. Only the start of its active sets changes, not the answer they find.
  void guess_from(std::vector<Contact> last_step) { last_step_ = std::move(last_step); }
  /// After `run`: the contacts with their final forces, for the next step's guess.
  const std::vector<Contact>& final_contacts() const { return contacts_; }

 private:
  /// One side of a contact on a fibre: the contact, its station on that fibre, and the sign α of a
  /// unit normal force on it (−1 on fibre A, +1 on fibre B or a fibre against a wall).
  struct ContactSide {
    Eigen::Index contact;
    int station;
    double alpha;
    bool on_a;
  };
  /// The finite-element fields of the final state (mm and N·mm), every fibre's on every process.
  struct FinalFields {
    std::vector<double> stations;      ///< displacement at each contact station, packed
    std::vector<double> displacement;  ///< at each fibre's samples, 3 per sample
    std::vector<double> moment;        ///< bending moments at each fibre's samples, 2 per sample
  };

  // The phases of run(), in order (reference_solver.cc, reference_assembly.cc,
  // reference_output.cc, reference_result.cc).
  void deform_under_scene_loads();
  void detect();
  void detect(std::vector<Eigen::Vector3d>& u_a, std::vector<Eigen::Vector3d>& u_b);
  void place_on_the_finite_elements(const std::vector<Eigen::Vector3d>& u_a,
                                    const std::vector<Eigen::Vector3d>& u_b);
  void take_last_step_forces();
  void make_grid();
  void setup_system();
  void assemble_system();
  /// From the answer of the last solve (each geometric update of the deformed contact starts
  /// from the one before), or with friction from the frictionless answer.
  enum class Start { frictionless, last_answer };
  void solve(Start start = Start::frictionless);
  void follow_the_deformed_fibres();
  void mix_normals(NormalMixing& mixing, std::vector<Contact>& followed) const;
  void settle_the_friction();
  bool update_active_set();
  void report_progress(int outer) const;
  void report_geometric_update(double residual, double turned) const;
  void output_results(Result& r);
  void hand_over_contact_problem(Status status);
  void describe_run(Result& r, const std::vector<std::string>& ambiguous, int outer,
                    std::chrono::steady_clock::time_point start);

  // Meshing and detection (reference_solver.cc).
  void collect_stations();
  void check_memory_reach();
  double own_unknowns() const;
  MeshOptions mesh_options() const;
  void deform();
  void displacements_at_contacts(std::vector<Eigen::Vector3d>& u_a,
                                 std::vector<Eigen::Vector3d>& u_b) const;
  std::vector<NodalForce> nodal_forces() const;
  /// The force each contact's fibre A receives, from the contacts' forces.
  void gather_forces() {
    force_on_a_.resize(contacts_.size());
    for (std::size_t k = 0; k < contacts_.size(); ++k) force_on_a_[k] = contacts_[k].force_on_a();
  }
  int station(int fibre, double s) const;
  Eigen::Vector3d packed(const std::vector<double>& u, int fibre, int station) const {
    const double* v = &u[3 * (offset_[fibre] + station)];
    return {v[0], v[1], v[2]};
  }

  // The contact problem (reference_assembly.cc, reference_solver.cc).
  std::vector<double> loads_and_influence();
  std::vector<std::vector<ContactSide>> assemble_compliance(const std::vector<double>& G,
                                                            bool in_place);
  void assemble_frictional_problem(const std::vector<double>& G,
                                   const std::vector<std::vector<ContactSide>>& sides,
                                   bool in_place);
  Eigen::Vector3d reaction_direction(Eigen::Index k, int i, bool on_a) const;
  bool solve_frictionless(const std::vector<char>& excluded);
  void solve_friction(const std::vector<char>& excluded, Start start);
  /// The problem just solved, with its answer, for options_.contact_problem.
  void keep_contact_problem(const std::vector<char>& excluded);

  /// The contact problem can be held as saddle points: frictionless, by MUMPS, not handed out.
  bool saddle_point_possible() const {
    return mu_ == 0.0 && options_.beam_solver == BeamSolver::direct && !options_.contact_problem;
  }
  /// It is: asked for, and possible.
  bool saddle_point() const {
    return saddle_point_possible() && options_.contact_assembly == ContactAssembly::saddle_point;
  }
  /// W is shared out over the processes by fibres and applied through their influence matrices
  /// (influence_compliance.h), never formed; with friction too, its tangential blocks gathered on
  /// the working set alone (frictional_working_set.h). A problem handed out takes the whole W.
  bool compliance_shared() const { return !options_.contact_problem; }
  void make_saddle_point(const std::vector<std::vector<ContactSide>>& sides);

  // Deformed contact (deformed_contact.cc).
  double deformed_residual(const std::vector<Eigen::Vector3d>& u_a,
                           const std::vector<Eigen::Vector3d>& u_b) const;
  double largest_crossing_step(const std::vector<Contact>& moved) const;
  bool crossings_move_on(double step);
  double largest_relative_displacement(const std::vector<Eigen::Vector3d>& u_a,
                                       const std::vector<Eigen::Vector3d>& u_b) const;
  void assemble_about_normals();

  // The final state (reference_output.cc).
  FinalFields final_fields();
  void write_vtu() const;
  void measure_contacts(const std::vector<double>& u, Result& r, std::vector<Eigen::Vector3d>& u_a,
                        std::vector<Eigen::Vector3d>& u_b);
  void add_energies(Result& r);

  const Scene& scene_;
  ReferenceOptions options_;
  MPI_Comm comm_;
  unsigned int rank_ = 0, processes_ = 1;
  dealii::ConditionalOStream pcout_;
  dealii::TimerOutput timer_;
  std::vector<Fibre> fibres_;
  std::vector<char> owned_;  ///< fibres this process meshes and solves
  double tolerance_;
  double threshold_ = 0.0;  ///< overlaps the active set resolves: far below the tolerance
  ContactDetector detector_;
  /// Each fibre's finite-element displacements (mm) at the detector's grid, for detection.
  std::vector<std::vector<Eigen::Vector3d>> grid_u_;
  std::vector<double> sample_s_;

  std::vector<Contact> contacts_;
  std::vector<Eigen::Vector3d> force_on_a_;
  /// Per fibre, the sorted fractions where contacts act on it; per contact, its stations on A, B.
  std::vector<std::vector<double>> stations_;
  std::vector<int> station_a_, station_b_;
  std::vector<std::size_t> offset_, g_offset_;  ///< per fibre, into packed station data and G
  std::string mesh_file_;
  std::unique_ptr<BeamModel> model_;
  std::vector<double> u0_;  ///< displacements at every station under the scene's loads
  /// The influence matrices of the current mesh (this process's fibres' where the compliance is
  /// shared, and for the deformed contact).
  std::vector<double> G_;
  long geometric_updates_ = 0;
  /// The contacts with the places their crossings moved to, for the next detection to keep.
  std::vector<Contact> moved_crossings_;
  bool remesh_ = false;  ///< deformed contact: a crossing moved off its station
  int crossing_moves_ = 0;
  double last_crossing_step_ = INFINITY;  ///< mm, the largest step of the last crossing move
  Eigen::VectorXd d0_, P_;
  /// W is sparse: two contacts interact only through a fibre they share.
  Eigen::SparseMatrix<double> W_;
  /// Or, shared, W applied through G_ (compliance_shared()).
  std::unique_ptr<InfluenceCompliance> influence_;
  /// Or W never formed (saddle_point()).
  std::unique_ptr<SaddlePointCompliance> saddle_;
  std::vector<char> pushing_;
  long active_set_iterations_ = 0;
  ReferenceTrouble trouble_;  ///< why the problem could not be solved, if it could not

  double mu_;
  double within_reach_;  ///< bytes each process may take (memory_reach.h)
  SlipOrigins origins_, end_state_;
  std::vector<Contact> last_step_;  ///< the previous load step's final contacts, if any
  /// The frictional problem of the candidates (μ > 0): q, and W with the tangential blocks where
  /// it is not shared.
  FrictionalProblem friction_problem_;
  /// Or, shared, that W applied through G_.
  std::unique_ptr<InfluenceCompliance> frictional_influence_;
  ContactProblem exported_;  ///< the problem last solved (only with options_.contact_problem)
  /// mm: how far short of its fixed point the next Tresca problem may stop (deformed contact).
  double friction_slack_ = 0.0;
  long newton_steps_ = 0;
  long tresca_updates_ = 0;
  long newton_finishes_ = 0;
  /// mm: the largest violation of Coulomb's law a Tresca fixed point was settled to above what it
  /// aimed at (the round-off floor of a nearly singular sticking set), and that aim; 0: none.
  double friction_settled_to_ = 0.0, friction_aimed_ = 0.0;
};

}  // namespace fibrecheck
