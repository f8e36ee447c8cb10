// The colour maps against their published values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "render/colour_map.h"

namespace cascade::render {

namespace {

void expect_near(Rgb8 got, Rgb8 want, int tolerance) {
  EXPECT_LE(std::abs(got.r - want.r), tolerance) << int(got.r) << " vs " << int(want.r);
  EXPECT_LE(std::abs(got.g - want.g), tolerance) << int(got.g) << " vs " << int(want.g);
  EXPECT_LE(std::abs(got.b - want.b), tolerance) << int(got.b) << " vs " << int(want.b);
}

double luminance(Rgb8 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

}  // namespace

TEST(ColourMap, ViridisMatchesPublishedColours) {
  const ColourMap& m = ColourMap::get(ColourMapKind::viridis);
  expect_near(m.at(0.0), {0x44, 0x01, 0x54}, 5);  // matplotlib's first, middle and last entries
  expect_near(m.at(0.5), {0x21, 0x91, 0x8c}, 5);
  expect_near(m.at(1.0), {0xfd, 0xe7, 0x25}, 5);
}

TEST(ColourMap, ViridisLightnessRisesMonotonically) {
  const ColourMap& m = ColourMap::get(ColourMapKind::viridis);
  for (int i = 1; i < 256; ++i)
    EXPECT_GT(luminance(m.table()[std::size_t(i)]), luminance(m.table()[std::size_t(i - 1)]) - 0.5) << i;
}

TEST(ColourMap, CoolWarmMatchesMoreland) {
  const ColourMap& m = ColourMap::get(ColourMapKind::cool_warm);
  expect_near(m.at(0.0), {59, 76, 192}, 0);   // the paper's end points
  expect_near(m.at(1.0), {180, 4, 38}, 0);
  expect_near(m.at(0.5), {221, 221, 221}, 2);  // the grey-white middle
  expect_near(m.at(0.25), {141, 176, 254}, 2);  // Moreland's table at 0.25 and 0.75
  expect_near(m.at(0.75), {244, 154, 123}, 2);
}

TEST(ColourMap, OutOfRangeClamps) {
  const ColourMap& m = ColourMap::get(ColourMapKind::viridis);
  EXPECT_EQ(m.at(-3), m.at(0));
  EXPECT_EQ(m.at(7), m.at(1));
  EXPECT_EQ(m.at(std::nan("")), m.at(0));
}

TEST(ColourMap, PhaseColoursDiffer) {
  EXPECT_FALSE(phase_colour(0) == phase_colour(1));
  EXPECT_FALSE(phase_colour(1) == phase_colour(2));
  EXPECT_FALSE(phase_colour(0) == phase_colour(2));
}

}  // namespace cascade::render
