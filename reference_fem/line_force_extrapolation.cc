#include "line_force_extrapolation.h"

#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace fibrecheck {

int continuous_cells(const Scene& scene, int K) {
  const int n = scene.contact.slices;
  if (K >= 0) return n << K;
  if (K < coarsest_refinement(scene))
    throw std::invalid_argument("continuous_cells: refinement " + std::to_string(K) +
                                " below the coarsest for " + std::to_string(n) + " slices");
  return n >> -K;
}

int coarsest_refinement(const Scene& scene) {
  int K = 0;
  for (int n = scene.contact.slices; K > -2 && n % 2 == 0 && n / 2 >= 4; n /= 2) --K;
  return K;
}

int finest_refinement(const Scene& scene, long points) {
  int K = 0;
  while ((2L * scene.contact.slices << (K + 1)) <= points) ++K;
  return K;
}

namespace {

/// A line or wall pair of a result: its kind and its two names.
using PairKey = std::tuple<std::string, std::string, std::string>;

/// The summed total force (N) of a result's line and wall contacts.
double line_force(const Result& r) {
  double total = 0.0;
  for (const ContactResult& c : r.contacts)
    if (c.kind != "point") total += c.total_force;
  return total;
}

/// Each line and wall pair's total force (N).
std::map<PairKey, double> pair_forces(const Result& r) {
  std::map<PairKey, double> forces;
  for (const ContactResult& c : r.contacts)
    if (c.kind != "point") forces[{c.kind, c.fibres[0], c.fibres[1]}] = c.total_force;
  return forces;
}

/// The line forces of successive refinements (each cell halved) and what they say about their
/// limit. Three forces f0, f1, f2 with differences of one sign converge at the observed order
/// p = log2((f1 − f0)/(f2 − f1)); while p lies between 1/2 and 4 the data are taken as asymptotic
/// and extrapolated (Richardson) to f2 + (f2 − f1)/(2^p − 1). The error estimate is the change of
/// the extrapolation from one refinement to the next, relative — or, before two extrapolations
/// exist, the last change of the force itself.
class LineForceSequence {
 public:
  /// Adds the next refinement's line force (N); returns its extrapolation (N, NaN when none).
  double add(double force) {
    force_.push_back(force);
    const std::size_t m = force_.size();
    double E = NAN;
    if (m >= 3) {
      const double d1 = force_[m - 2] - force_[m - 3], d2 = force_[m - 1] - force_[m - 2];
      const double p = d1 * d2 > 0.0 ? std::log2(d1 / d2) : NAN;
      if (p >= 0.5 && p <= 4.0) {
        order_ = p;
        E = force_[m - 1] + d2 / (std::exp2(p) - 1.0);
      } else if (d2 == 0.0) {
        E = force_[m - 1];
      }
    }
    extrapolated_.push_back(E);
    if (m >= 4 && std::isfinite(E) && std::isfinite(extrapolated_[m - 2]))
      estimate_ = std::fabs(E - extrapolated_[m - 2]) / std::fabs(E);
    else if (m >= 2)
      estimate_ = std::fabs(force_[m - 1] - force_[m - 2]) / std::fabs(force_[m - 1]);
    return E;
  }
  std::size_t size() const { return force_.size(); }
  /// The order last observed in the asymptotic range (NaN before).
  double order() const { return order_; }
  /// The relative error estimate of the last refinement (NaN before the second).
  double estimate() const { return estimate_; }

 private:
  std::vector<double> force_, extrapolated_;
  double order_ = NAN, estimate_ = NAN;
};

/// The progress line of refinement K with line force `force` and extrapolation E (N).
std::string progress_line(int K, double force, double E, const LineForceSequence& sequence) {
  std::ostringstream line;
  line.precision(8);
  line << "refinement K = " << K << ": line and wall force " << force << " N";
  if (std::isfinite(E)) line << ", extrapolated " << E << " N (order " << sequence.order() << ")";
  if (std::isfinite(sequence.estimate())) line << ", estimated error " << sequence.estimate();
  return line.str();
}

/// Each line and wall pair's force extrapolated with the line force's order, from its force at
/// the previous refinement (a pair new at this refinement keeps its own).
void extrapolate_pairs(Result& r, const std::map<PairKey, double>& previous, double order) {
  for (ContactResult& c : r.contacts) {
    if (c.kind == "point") continue;
    auto it = previous.find({c.kind, c.fibres[0], c.fibres[1]});
    const double before = it == previous.end() ? c.total_force : it->second;
    c.extrapolated_force = c.total_force + (c.total_force - before) / (std::exp2(order) - 1.0);
  }
}

}  // namespace

Result solve_refined_until_settled(
    const Scene& scene, const ReferenceOptions& options,
    const std::function<Result(const ReferenceOptions& once)>& solve_once) {
  ReferenceOptions once = options;
  once.refine_until_converged = false;
  LineForceSequence sequence;
  std::map<PairKey, double> previous_pairs;
  Result r;
  for (int K = std::min(options.refine, coarsest_refinement(scene)); K <= options.max_refine; ++K) {
    once.refine = K;
    r = solve_once(once);
    if (r.status != Status::converged) return r;
    const double force = line_force(r);
    if (force == 0.0) return r;  // no line contact: nothing to refine
    const double E = sequence.add(force);
    if (options.progress) options.progress(progress_line(K, force, E, sequence));
    const std::map<PairKey, double> pairs = pair_forces(r);
    if (sequence.size() >= 2) {
      FiniteElementFigures& figures = *r.finite_elements;
      figures.refinement = K;
      figures.line_force_order = std::isfinite(E) ? sequence.order() : 0.0;
      figures.line_force_error_estimate = sequence.estimate();
    }
    if (std::isfinite(E)) extrapolate_pairs(r, previous_pairs, sequence.order());
    previous_pairs = pairs;
    if (sequence.size() >= 4 && std::isfinite(E) &&
        sequence.estimate() <= options.refinement_tolerance) {
      std::ostringstream out;
      out.precision(3);
      out << "continuous line contact extrapolated at refinement " << K << " ("
          << r.finite_elements->unknowns << " unknowns): line force converging at order "
          << sequence.order() << ", extrapolated line force within an estimated "
          << sequence.estimate() << " (relative); " << r.message;
      r.message = out.str();
      return r;
    }
  }
  std::ostringstream out;
  out.precision(3);
  out << "the continuous line contact's extrapolated line force did not settle to "
      << options.refinement_tolerance << " by refinement " << options.max_refine;
  if (std::isfinite(sequence.estimate())) out << " (estimated error " << sequence.estimate() << ")";
  r.warnings.push_back(out.str());
  return r;
}

}  // namespace fibrecheck
