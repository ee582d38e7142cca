// The frictionless contact problem solved on the candidates near touching: whatever set it starts
// on, its answer must solve the problem of every candidate, judged by the answer's own overlaps.
#include "frictionless_problem.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "contact_detection.h"
#include "projected_cg.h"
#include "tow_generator.h"

namespace fibrecheck {
namespace {

// A 30-fibre tow compacted to F = 0.8, every force zero: only the contacts with the walls and a
// few slices overlap. Started on those alone (reach 0), the set must grow as the forces spread
// through the tow, and the answer must leave no overlap beyond the tolerance where no force
// pushes and no gap beyond it where one does, on every candidate, as the answer started on every
// candidate does.
TEST(FrictionlessProblem, AnswerOnAGrowingSetSolvesTheProblemOfEveryCandidate) {
  TowOptions tow;
  tow.fibres = 30;
  tow.slices = 30;
  tow.seed = 4;
  tow.volume_fraction = 0.4;
  tow.compaction = 0.8;
  const Scene scene = generate_tow(tow);
  const std::vector<Fibre> fibres = make_fibres(scene);
  const ContactDetector detector(fibres, scene, candidate_margin(fibres));
  const std::vector<std::vector<Eigen::Vector3d>> grid(
      fibres.size(), std::vector<Eigen::Vector3d>(detector.grid().size(), Eigen::Vector3d::Zero()));
  const std::vector<Contact> contacts = detector.detect(grid);
  Superposition beams(fibres, scene);
  beams.attach(contacts);
  const Eigen::Index n = static_cast<Eigen::Index>(contacts.size());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  const Eigen::VectorXd d = contact_overlaps(beams, detector.geometry(), contacts, zero);
  const Eigen::Index overlapping = (d.array() > 0.0).count();
  ASSERT_GT(overlapping, 0);
  ASSERT_LT(overlapping, n / 4);
  const double tolerance = 1e-9 * d.maxCoeff();
  std::vector<Eigen::VectorXd> answers;
  for (const double reach : {0.0, std::numeric_limits<double>::infinity()}) {
    SCOPED_TRACE(reach);
    Eigen::VectorXd P = zero;
    const FrictionlessProblemOutcome outcome = solve_frictionless_problem(
        scene, fibres, beams, detector.geometry(), contacts, reach, tolerance, 1e9, d, P);
    ASSERT_TRUE(outcome.settled);
    if (reach == 0.0) {
      EXPECT_GE(outcome.growths, 1);
      EXPECT_LT(outcome.members, n);
    } else {
      EXPECT_EQ(outcome.growths, 0);
      EXPECT_EQ(outcome.members, n);
    }
    EXPECT_GE(P.minCoeff(), 0.0);
    const Eigen::VectorXd left = contact_overlaps(beams, detector.geometry(), contacts, P);
    EXPECT_LT(contact_residual(P, -left), tolerance);
    answers.push_back(left);
  }
  // Both answers minimise the same convex programme, whose gradient (minus the overlaps) is the
  // same at every minimiser: they differ only as far as their tolerances let them.
  EXPECT_LT((answers[0] - answers[1]).cwiseAbs().maxCoeff(), 10.0 * tolerance);
}

}  // namespace
}  // namespace fibrecheck
