// The exported contact problem: written and read back exactly, bad files rejected by field, and
// its residual and comparison on answers known in closed form.
#include "contact_problem.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "contact_problem_check.h"
#include "input_error.h"

namespace fibrecheck {
namespace {

/// One contact with one tangent: W = diag(2, 1) mm/N, overlap 1 mm, slip 3 mm, μ = 0.5. Its
/// answer: P = 1/2 closes the overlap; sticking would need F = 3 > μP = 1/4, so it slips with
/// F = 1/4 and slip 3 − 1/4 left, along F.
ContactProblem one_slipping_contact() {
  ContactProblem p;
  p.scene = "one";
  p.mu = 0.5;
  p.contacts = {{"point", {"A", "B"}, 1, false}};
  set_offsets(p);
  p.W.resize(2, 2);
  p.W.insert(0, 0) = 2.0;
  p.W.insert(1, 1) = 1.0;
  p.q = Eigen::Vector2d(1.0, 3.0);
  p.reaction = Eigen::Vector2d(0.5, 0.25);
  p.status = "converged";
  return p;
}

std::string temporary(const std::string& name) {
  return ::testing::TempDir() + name;
}

TEST(ContactProblem, WrittenAndReadBackExactly) {
  ContactProblem p = one_slipping_contact();
  p.W.coeffRef(0, 1) = p.W.coeffRef(1, 0) = 0.1 + 1e-17;  // 17 digits survive
  write_contact_problem(temporary("one.problem.json"), p);
  const ContactProblem q = read_contact_problem(temporary("one.problem.json"));
  EXPECT_EQ(q.scene, "one");
  EXPECT_EQ(q.mu, 0.5);
  ASSERT_EQ(q.contacts.size(), 1u);
  EXPECT_EQ(q.contacts[0].tangents, 1);
  EXPECT_EQ(q.offset, (std::vector<Eigen::Index>{0, 2}));
  EXPECT_EQ(Eigen::MatrixXd(q.W), Eigen::MatrixXd(p.W));
  EXPECT_EQ(q.q, p.q);
  EXPECT_EQ(q.reaction, p.reaction);
  EXPECT_EQ(q.status, "converged");
}

TEST(ContactProblem, ResidualIsZeroExactlyAtTheSolution) {
  const ContactProblem p = one_slipping_contact();
  const ProblemResidual exact = problem_residual(p, p.reaction);
  EXPECT_EQ(exact.overlap_mm, 0.0);
  EXPECT_EQ(exact.slip_mm, 0.0);
  // Sticking with F = 0.2 < μP: the slip 2.8 mm left is the violation, capped by what the friction
  // could still take up, (μP − F)·W_tt = 0.05 mm.
  const ProblemResidual sticking = problem_residual(p, Eigen::Vector2d(0.5, 0.2));
  EXPECT_NEAR(sticking.slip_mm, 0.05, 1e-15);
  // A force 0.1 N short leaves an overlap of 0.2 mm.
  EXPECT_NEAR(problem_residual(p, Eigen::Vector2d(0.4, 0.2)).overlap_mm, 0.2, 1e-15);
}

TEST(ContactProblem, AnAnswerSolvesItOnlyByItsOwnResidual) {
  const ContactProblem p = one_slipping_contact();
  EXPECT_EQ(residual_scale(p), 3.0);  // the largest |q|, mm
  EXPECT_TRUE(solves(p, problem_residual(p, p.reaction), 1e-12));
  // The sticking answer above leaves 0.05 mm of slip: 1/60 of the scale.
  const ProblemResidual sticking = problem_residual(p, Eigen::Vector2d(0.5, 0.2));
  EXPECT_TRUE(solves(p, sticking, 0.02));
  EXPECT_FALSE(solves(p, sticking, 0.01));
  // A non-finite answer solves nothing.
  EXPECT_FALSE(solves(p, problem_residual(p, Eigen::Vector2d(NAN, 0.0)), 1.0));
}

TEST(ContactProblem, FrictionIsComparedOnlyWhereSomethingCanSlip) {
  ContactProblem p = one_slipping_contact();
  const Eigen::Vector2d a(0.5, 0.25), b(0.5, 0.1);
  ProblemAgreement g = compare_answers(p, a, b);
  EXPECT_NEAR(g.friction_N, 0.15, 1e-15);
  EXPECT_EQ(g.frictions_compared, 1);
  // Nothing can move along the tangent: any friction in the disk is an answer.
  p.W.coeffRef(1, 1) = 0.0;
  g = compare_answers(p, a, b);
  EXPECT_EQ(g.friction_N, 0.0);
  EXPECT_EQ(g.frictions_not_unique, 1);
}

TEST(ContactProblem, BadFilesNameTheField) {
  ContactProblem p = one_slipping_contact();
  p.W.coeffRef(0, 1) = 0.5;  // not symmetric
  write_contact_problem(temporary("asymmetric.problem.json"), p);
  try {
    read_contact_problem(temporary("asymmetric.problem.json"));
    FAIL() << "an asymmetric W was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("W"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("symmetric"), std::string::npos) << e.what();
  }
  std::ofstream(temporary("short.problem.json"))
      << R"({"format": "fibrecheck-contact-problem", "version": 1, "mu": 0.5,
            "contacts": [{"tangents": 1}], "W": {"size": 2, "rows": [0], "cols": [0],
            "values": [1]}, "q": [1]})";
  try {
    read_contact_problem(temporary("short.problem.json"));
    FAIL() << "a q of the wrong length was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("q"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_contact_problem(temporary("missing.problem.json")), InputError);
}

}  // namespace
}  // namespace fibrecheck
