#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace fibrecheck {

/// How a contact was found (seed §4.3.3): closest points of crossing fibres, a cross-section slice
/// of a line contact between nearly parallel fibres, or a fibre against a rigid wall.
enum class ContactKind : std::uint8_t { point, line, wall };

const char* to_string(ContactKind kind);

/// One contact point: where it acts, its normal, its overlap and the force it carries.
///
/// Sign conventions: `normal` is the unit vector from fibre A's centre towards fibre B's (for a
/// wall, the wall's normal), both taken on the undeformed fibres. The overlap is
/// d = (rA + rB) − n·(Bc − Ac) (Eq. 4.14 with the sign of §4.3.2: d > 0 overlaps). Fibre A receives
/// −P·n + F, fibre B receives +P·n − F (a wall pushes its fibre with +P·n + F), where F is the
/// friction force of §4.3.4.
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

}  // namespace fibrecheck
