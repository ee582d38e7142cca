#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace fibrecheck {

/// How a contact was found (seed §4.3.3): closest points of crossing fibres, a cross-section slice
/// of a line contact between nearly parallel fibres, or a fibre against a rigid wall.
enum class ContactKind : std::uint8_t { point, line, wall };

const char* to_string(ContactKind kind);

/// The point of the disk |F| ≤ radius nearest to z (the Coulomb disk of §4.3.4, Eq. 4.31).
inline Eigen::Vector3d onto_coulomb_disk(const Eigen::Vector3d& z, double radius) {
  const double size = z.norm();
  return size > radius ? Eigen::Vector3d(size > 0.0 ? z * (radius / size) : z) : z;
}

/// One contact point: where it acts, its normal, its overlap and the force it carries.
///
/// Sign conventions: `normal` is the unit vector from fibre A's centre towards fibre B's (for a
/// wall, the wall's normal), both taken on the undeformed fibres. The overlap is
/// d = (rA + rB) − n·(Bc − Ac) (Eq. 4.14 with the sign of §4.3.2: d > 0 overlaps). Fibre A receives
/// −P·n + F, fibre B receives +P·n − F (a wall pushes its fibre with +P·n + F), where F is the
/// friction force of §4.3.4.
///
/// Friction (DESIGN §2) acts in the tangential directions the two fibres can move in: for a slice
/// or a wall station the line of the cross-section plane ⊥ n (one direction), for a crossing the
/// plane ⊥ n (two). The slip s is the tangential part of the relative displacement since the step
/// began, u_B − u_A (−u_A against a wall) minus its value at the step's start (`origin`); a force
/// F on A removes slip (∂s/∂F = −(C_A + C_B)), as P removes overlap.
struct Contact {
  ContactKind kind = ContactKind::point;
  int a = -1;      ///< fibre A
  int b = -1;      ///< fibre B, or the wall's index for wall contacts
  int slice = -1;  ///< index of its point in the line quadrature (line, wall); −1 for crossings
  double s_a = 0;  ///< fraction of fibre A's length
  double s_b = 0;  ///< fraction of fibre B's length (unused for walls)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double overlap = 0;                                  ///< d, mm
  double force = 0;                                    ///< P ≥ 0, N
  Eigen::Vector3d friction = Eigen::Vector3d::Zero();  ///< F on fibre A, N
  /// Share of the line this point stands for: 1 for a crossing, 1/n for one of n slices
  /// (Eq. 4.28), the Gauss weight in the continuous line contact.
  double weight = 1;
  bool normal_held = false;  ///< centres nearly coincident: a fixed normal was taken
  /// Tangential directions: 0, 1 (`tangent`) or 2 (`tangent` and normal × tangent).
  std::uint8_t tangents = 0;
  Eigen::Vector3d tangent = Eigen::Vector3d::Zero();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< relative displacement at the step's start
  Eigen::Vector3d slip = Eigen::Vector3d::Zero();    ///< s, tangential, mm

  /// The second tangential direction of a crossing, normal × tangent.
  Eigen::Vector3d second_tangent() const { return normal.cross(tangent); }
  /// The tangential part of a vector, in the directions this contact can slip in.
  Eigen::Vector3d tangential(const Eigen::Vector3d& v) const {
    if (tangents == 0) return Eigen::Vector3d::Zero();
    if (tangents == 1) return v.dot(tangent) * tangent;
    return v - v.dot(normal) * normal;
  }
  /// The relative displacement u_B − u_A of the contact's sides (−u_A against a wall), mm.
  Eigen::Vector3d relative(const Eigen::Vector3d& u_a, const Eigen::Vector3d& u_b) const {
    return kind == ContactKind::wall ? Eigen::Vector3d(-u_a) : Eigen::Vector3d(u_b - u_a);
  }

  /// The force vector fibre A (or the walled fibre) receives, N.
  Eigen::Vector3d force_on_a() const {
    return (kind == ContactKind::wall ? force : -force) * normal + friction;
  }
  /// Identity that survives a rebuild of the candidate list.
  std::uint64_t key() const {
    return (static_cast<std::uint64_t>(kind) << 62) ^ (static_cast<std::uint64_t>(a) << 42) ^
           (static_cast<std::uint64_t>(b) << 21) ^ static_cast<std::uint64_t>(slice + 1);
  }
};

/// The fibres that crossings (point contacts) act on, sorted, each once.
std::vector<int> fibres_with_crossings(const std::vector<Contact>& contacts);

}  // namespace fibrecheck
