// Generated tows (DESIGN §2, "Tows and well-posedness"): deterministic for a seed, no overlap
// anywhere before compaction, shallow overlaps after it, supports clear of each other and of the
// walls.
#include "tow_generator.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "input_error.h"
#include "load_path.h"

namespace fibrecheck {
namespace {

Eigen::Vector2d yz(const Eigen::Vector3d& p) {
  return {p.y(), p.z()};
}

TEST(TowGenerator, SameSeedSameTowOtherSeedOtherTow) {
  TowOptions o;
  o.fibres = 60;
  o.seed = 42;
  const auto first = scene_to_json(generate_tow(o)), second = scene_to_json(generate_tow(o));
  EXPECT_EQ(first.dump(), second.dump());
  o.seed = 43;
  EXPECT_NE(scene_to_json(generate_tow(o)).dump(), first.dump());
}

TEST(TowGenerator, NoOverlapBeforeCompactionShallowOverlapsAfter) {
  TowOptions o;
  o.fibres = 200;
  o.seed = 9;
  o.compaction = 1.0;  // the tow as placed
  const Scene placed = generate_tow(o);
  o.compaction = 0.9;
  const Scene compacted = generate_tow(o);
  ASSERT_EQ(placed.fibres.size(), 200u);
  const double r = o.radius, limit = 2 * r * (1 - o.compaction);
  int overlapping = 0, misaligned = 0;
  for (std::size_t i = 0; i < placed.fibres.size(); ++i) {
    const FibreSpec& f = compacted.fibres[i];
    if ((yz(f.end) - yz(f.start)).norm() > 1e-12) ++misaligned;
    EXPECT_LE(std::atan((yz(f.end) - yz(f.start)).norm() / o.length),
              o.misalignment_deg * M_PI / 180 + 1e-12);
    for (const WallSpec& w : compacted.walls)
      for (const Eigen::Vector3d& p : {f.start, f.end})
        EXPECT_GE(w.normal.dot(p - w.point), r - 1e-12) << "support of " << f.id << " on a wall";
    for (std::size_t j = i + 1; j < placed.fibres.size(); ++j) {
      const FibreSpec &a = placed.fibres[i], &b = placed.fibres[j];
      EXPECT_GE(min_slice_distance(yz(a.start), yz(a.end), yz(b.start), yz(b.end)), 2 * r)
          << a.id << " and " << b.id << " overlap before compaction";
      const FibreSpec &ca = compacted.fibres[i], &cb = compacted.fibres[j];
      const double d = min_slice_distance(yz(ca.start), yz(ca.end), yz(cb.start), yz(cb.end));
      EXPECT_GE(d, 2 * r - limit - 1e-12);
      EXPECT_GE((yz(ca.start) - yz(cb.start)).norm(), 2 * r) << "supports overlap";
      EXPECT_GE((yz(ca.end) - yz(cb.end)).norm(), 2 * r) << "supports overlap";
      if (d < 2 * r) ++overlapping;
    }
  }
  EXPECT_GT(misaligned, 20);
  EXPECT_GT(overlapping, 5);  // compaction does create contacts
}

TEST(TowGenerator, ImpossibleOptionsAreInputErrors) {
  TowOptions o;
  o.volume_fraction = 0.95;
  EXPECT_THROW(generate_tow(o), InputError);
  o = TowOptions{};
  o.compaction = 0.0;
  EXPECT_THROW(generate_tow(o), InputError);
  o = TowOptions{};
  o.fibres = 0;
  EXPECT_THROW(generate_tow(o), InputError);
}

TEST(TowGenerator, MinSliceDistanceOfCrossingLines) {
  // Two fibres swapping sides pass through each other mid-way; parallel ones keep their distance.
  EXPECT_NEAR(min_slice_distance({0, 0}, {1, 0}, {1, 0}, {0, 0}), 0.0, 1e-15);
  EXPECT_NEAR(min_slice_distance({0, 0}, {0, 0}, {0, 3}, {0, 3}), 3.0, 1e-15);
  EXPECT_NEAR(min_slice_distance({0, 0}, {0, 0}, {1, 1}, {-1, 1}), 1.0, 1e-15);
}

}  // namespace
}  // namespace fibrecheck

namespace fibrecheck {
namespace {

// With a load path the tow is written before compaction; its last step is the compacted tow the
// generator writes without one, support for support and wall for wall.
// A load path that starts where the walls begin to carry force: evenly from the first factor to
// the last, the friction coefficient written into the scene, bad ranges refused.
TEST(TowGenerator, StepsFromAFirstCompactionAndFriction) {
  TowOptions o;
  o.fibres = 7;
  o.volume_fraction = 0.35;
  o.compaction = 0.7;
  o.steps = 5;
  o.first_compaction = 0.8;
  o.friction = 0.2;
  const Scene path = generate_tow(o);
  ASSERT_EQ(path.steps.size(), 5u);
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(path.steps[k].compaction, 0.8 - 0.025 * k, 1e-15);
  EXPECT_EQ(path.contact.friction, 0.2);
  EXPECT_EQ(path.solver.max_iterations, 400000);  // room for the Tresca fixed point
  o.first_compaction = 0.6;
  EXPECT_THROW(generate_tow(o), InputError);
  o.first_compaction = 0.8;
  o.friction = -1;
  EXPECT_THROW(generate_tow(o), InputError);
}

TEST(TowGenerator, StepsCompactTheTowTheGeneratorCompacts) {
  TowOptions o;
  o.fibres = 19;
  o.seed = 4;
  o.compaction = 0.85;
  const Scene compacted = generate_tow(o);
  o.steps = 5;
  const Scene path = generate_tow(o);
  ASSERT_EQ(path.steps.size(), 5u);
  EXPECT_DOUBLE_EQ(path.steps[0].compaction, 0.97);
  EXPECT_DOUBLE_EQ(path.steps.back().compaction, 0.85);
  const Scene last = scene_at_step(path, path.steps.back());
  ASSERT_EQ(last.fibres.size(), compacted.fibres.size());
  for (std::size_t i = 0; i < last.fibres.size(); ++i) {
    EXPECT_LT((last.fibres[i].start - compacted.fibres[i].start).norm(), 1e-12) << i;
    EXPECT_LT((last.fibres[i].end - compacted.fibres[i].end).norm(), 1e-12) << i;
  }
  for (std::size_t w = 0; w < last.walls.size(); ++w)
    EXPECT_NEAR(last.walls[w].normal.dot(last.walls[w].point - compacted.walls[w].point), 0.0,
                1e-12);
  EXPECT_NEAR(fibre_volume_fraction(last), fibre_volume_fraction(compacted), 1e-12);
  EXPECT_NEAR(fibre_volume_fraction(path) * std::pow(1.0 / 0.85, 2),
              fibre_volume_fraction(compacted), 1e-12);
}

}  // namespace
}  // namespace fibrecheck
