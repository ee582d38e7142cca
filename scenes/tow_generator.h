#pragma once

#include <cstdint>

#include "scene.h"

namespace fibrecheck {

/// A random tow of nearly parallel, slightly misaligned straight fibres along x (DESIGN §2, "Tows
/// and well-posedness"). Both supports of every fibre sit on sites of one hexagonal lattice
/// (spacing ≥ 2r(1 + clearance)/F) in a square cross-section; a fibre is misaligned by moving its
/// far support to a vacant site within L·tan(θ), kept only if the fibre then overlaps no other
/// fibre anywhere along its length. The cross-section is then compacted by F = `compaction`: every
/// position scales about the centre, supports included, and four walls bound the compacted
/// section. Supports therefore stay clear of each other and of the walls; the overlaps arise where
/// misaligned fibres pass between their neighbours, are shallow (at most 2r(1 − F)), and the
/// equilibrium is well defined.
struct TowOptions {
  int fibres = 100;
  int slices = 100;
  std::uint64_t seed = 1;
  double volume_fraction = 0.45;  ///< before compaction (below 0.6 at the default F)
  double misalignment_deg = 2.0;  ///< largest angle between a fibre and the tow axis
  double length = 1.0;            ///< mm
  double radius = 0.01;           ///< mm
  double youngs_modulus = 80000;  ///< MPa
  double compaction = 0.9;        ///< factor F on the cross-section, (0, 1]
  double clearance = 0.02;        ///< extra gap when placing, fraction of 2r
  /// 0: the tow as compacted. K > 0: the tow before compaction (walls at the uncompacted
  /// section) with a load path of K steps F_k = 1 − (1 − F)·k/K, k = 1…K, the last the compaction
  /// (or from `first_compaction` to F).
  int steps = 0;
  /// The first step's factor (0: 1 − (1 − F)/K, evenly spaced from the uncompacted tow); the
  /// steps run evenly from it to F.
  double first_compaction = 0.0;
  double friction = 0.0;  ///< Coulomb coefficient μ of the scene's contacts
};

/// Throws InputError (field = the option's name) for impossible options or when the fibres cannot
/// be packed at that volume fraction.
Scene generate_tow(const TowOptions& options);

/// Smallest in-plane distance (perpendicular to x) between two straight fibres spanning the same
/// x-range [0, L], given their (y, z) at both ends: the distance each slice would measure.
double min_slice_distance(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1,
                          const Eigen::Vector2d& b0, const Eigen::Vector2d& b1);

}  // namespace fibrecheck
