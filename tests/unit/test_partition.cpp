// The slabs of a run split over processes (server/core/partition.h): which process owns a moving
// particle or a dummy, which processes hold it, and where balanced_cuts puts the cuts. Exact
// arithmetic on small numbers: the expected values are worked out by hand in each test.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "server/core/partition.h"

namespace cascade {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

Slabs three_slabs() {
  Slabs s;
  s.axis = 0;
  s.cut = {-kInfinity, 1.0, 2.0, kInfinity};
  s.halo = 0.25;
  return s;
}

TEST(Slabs, OwnerAndDistanceAlongTheAxis) {
  const Slabs s = three_slabs();
  EXPECT_EQ(s.owner_of(-5.0), 0);  // the first slab reaches past the domain
  EXPECT_EQ(s.owner_of(0.999), 0);
  EXPECT_EQ(s.owner_of(1.0), 1);  // a cut belongs to the slab above it
  EXPECT_EQ(s.owner_of(2.5), 2);
  EXPECT_EQ(s.distance_to(1, 1.5), 0.0);
  EXPECT_EQ(s.distance_to(1, 0.5), 0.5);
  EXPECT_EQ(s.distance_to(1, 2.75), 0.75);
}

// A dummy is held by the process whose slab holds its ghost node (it computes the dummy's values
// from the particles around that node) and by every process whose halo holds the dummy itself.
TEST(Slabs, ADummyIsHeldWhereItsGhostNodeIsAndWithinEveryHalo) {
  const Slabs s = three_slabs();
  // Dummy at x = 0.9 (slab 0), its ghost node at 1.3 (slab 1): owned by 1, held by 0 (inside),
  // 1 (owner; also within its halo, 0.1 < 0.25), not by 2 (1.1 away).
  EXPECT_TRUE(s.holds_dummy(0, 0.9, 1.3));
  EXPECT_TRUE(s.holds_dummy(1, 0.9, 1.3));
  EXPECT_FALSE(s.holds_dummy(2, 0.9, 1.3));
  // A wall beyond the halo: the dummy at 0.5 with its ghost node at 1.2 is 0.5 from slab 1, past
  // its halo, but slab 1 owns it and holds it.
  EXPECT_TRUE(s.holds_dummy(1, 0.5, 1.2));
  EXPECT_FALSE(s.holds_dummy(2, 0.5, 1.2));
  // Held by one process only where it is far from every other slab.
  EXPECT_TRUE(s.holds_dummy(2, 3.0, 3.1));
  EXPECT_FALSE(s.holds_dummy(1, 3.0, 3.1));
}

TEST(BalancedCuts, EvenWorkGivesEvenSlabs) {
  const std::vector<double> histogram(8, 1.0);  // [0, 8], one unit of work per unit length
  const std::vector<double> cut = balanced_cuts(histogram, 0.0, 8.0, 4);
  ASSERT_EQ(cut.size(), 5u);
  EXPECT_EQ(cut[0], -kInfinity);
  EXPECT_NEAR(cut[1], 2.0, 1e-12);
  EXPECT_NEAR(cut[2], 4.0, 1e-12);
  EXPECT_NEAR(cut[3], 6.0, 1e-12);
  EXPECT_EQ(cut[4], kInfinity);
}

// Work 6 in the first bin of [0, 4] and 1 in each of the other three (9 in all): two processes
// take 4.5 each, the cut three quarters into the first bin (linear within a bin).
TEST(BalancedCuts, TheCutsFollowTheWork) {
  const std::vector<double> cut = balanced_cuts({6.0, 1.0, 1.0, 1.0}, 0.0, 4.0, 2);
  ASSERT_EQ(cut.size(), 3u);
  EXPECT_NEAR(cut[1], 0.75, 1e-12);
  // Three processes take 3 each: the work reaches 3 at x = 0.5 and 6 at x = 1, both in the first
  // bin.
  const std::vector<double> three = balanced_cuts({6.0, 1.0, 1.0, 1.0}, 0.0, 4.0, 3);
  EXPECT_NEAR(three[1], 0.5, 1e-12);
  EXPECT_NEAR(three[2], 1.0, 1e-12);
}

}  // namespace
}  // namespace cascade
