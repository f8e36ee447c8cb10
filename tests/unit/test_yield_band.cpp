// The pore-water stage's end criterion (server/solver/yield_band.h) on hand-made frames: a 2D
// block of soil particles, 40 × 10 at dp = 0.1 m, whose top row is the free surface, with the
// yielded particles (yield_ratio 1) placed by hand.
#include <gtest/gtest.h>

#include <functional>

#include "server/core/types.h"
#include "server/solver/yield_band.h"

namespace cascade {
namespace {

constexpr double kDp = 0.1;
constexpr int kColumns = 40, kRows = 10;

// yielded(column, row): is that particle at yield? Row kRows − 1 is the free surface.
FieldFrame block(const std::function<bool(int, int)>& yielded) {
  FieldFrame f;
  f.dimensions = 2;
  FieldFrame::RealField ratio{"yield_ratio", "1", 1, {}};
  for (int r = 0; r < kRows; ++r)
    for (int c = 0; c < kColumns; ++c) {
      f.position.insert(f.position.end(), {(c + 0.5) * kDp, 0.0, (r + 0.5) * kDp});
      f.phase.push_back(std::uint8_t(Phase::soil));
      f.id.push_back(std::uint32_t(f.id.size()));
      f.free_surface.push_back(r == kRows - 1 ? 1 : 0);
      ratio.values.push_back(yielded(c, r) ? 1.0 : 0.5);
    }
  f.fields.push_back(ratio);
  return f;
}

YieldBandCriterion connected(double span) {
  YieldBandCriterion c;
  c.connected = true;
  c.span = span;
  return c;
}

TEST(YieldBand, CountsTheYieldedVolume) {
  const FieldFrame f = block([](int c, int r) { return r == 0 && c < 25; });
  YieldBandCriterion volume;
  volume.volume = 0.2;
  const YieldBandMeasure m = measure_yield_band(f, volume, kDp);
  EXPECT_EQ(m.yielded, 25u);
  EXPECT_NEAR(m.volume, 0.25, 1e-12);
  EXPECT_FALSE(yield_band_reached(m, volume).empty());
  volume.volume = 0.3;
  EXPECT_TRUE(yield_band_reached(m, volume).empty());
}

// A band along the base that rises to the surface at one end only (a toe that daylights): no
// slip surface yet, whatever its length.
TEST(YieldBand, ABandThatMeetsTheSurfaceOnceDoesNotSpan) {
  const FieldFrame f = block([](int c, int r) { return r == 0 || (c == 0); });
  const YieldBandMeasure m = measure_yield_band(f, connected(2.0), kDp);
  EXPECT_EQ(m.yielded, std::size_t(kColumns + kRows - 1));
  EXPECT_NEAR(m.connected_span, 0.0, 1e-12);  // one surface member
  EXPECT_TRUE(yield_band_reached(m, connected(2.0)).empty());
}

// The same band rising to the surface at both ends, 3.5 m apart: a slip surface cut out.
TEST(YieldBand, ABandFromSurfaceToSurfaceSpansTheDistanceBetweenItsEnds) {
  const FieldFrame f = block([](int c, int r) { return r == 0 || c == 0 || c == 35; });
  const YieldBandMeasure m = measure_yield_band(f, connected(2.0), kDp);
  EXPECT_NEAR(m.connected_span, 3.5, 1e-12);
  EXPECT_FALSE(yield_band_reached(m, connected(2.0)).empty());
  EXPECT_TRUE(yield_band_reached(m, connected(4.0)).empty());
}

// Two columns that reach the surface 3.5 m apart but are not joined below: two sets, each
// meeting the surface once.
TEST(YieldBand, UnconnectedSetsDoNotAddUp) {
  const FieldFrame f = block([](int c, int r) { return (c == 0 || c == 35) && r > 0; });
  const YieldBandMeasure m = measure_yield_band(f, connected(2.0), kDp);
  EXPECT_NEAR(m.connected_span, 0.0, 1e-12);
  // A gap of one particle in the base of the band of the previous test breaks it the same way.
  const FieldFrame broken = block([](int c, int r) { return (r == 0 && c != 20) || c == 0 || c == 35; });
  EXPECT_NEAR(measure_yield_band(broken, connected(2.0), kDp).connected_span, 0.0, 1e-12);
}

}  // namespace
}  // namespace cascade
