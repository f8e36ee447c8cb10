// Known particle layouts render known colours at known pixels: the colour maps, the cameras (side
// view in 2D, look-at and orbit in 3D), depth, the colour bar's range, phase filters, sections,
// level of detail and the size limits. Expected pixels are worked out here by hand from the
// framing rules in render/camera.h, not from the renderer's own camera.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "render/overlay.h"
#include "render/snapshot_renderer.h"
#include "tests/render/frame_builder.h"

namespace cascade::render {

namespace {

using test::make_frame;

SnapshotRenderer& renderer() {
  static SnapshotRenderer r;
  return r;
}

// Settings with nothing drawn over the particles, so that the whole image is the scene.
SnapshotSettings plain(int width, int height, double diameter) {
  SnapshotSettings s;
  s.width = width;
  s.height = height;
  s.particle_diameter = diameter;
  s.colour_bar = false;
  s.time_label = false;
  return s;
}

::testing::AssertionResult near(Rgb8 got, Rgb8 want, int tolerance = 2) {
  if (std::abs(got.r - want.r) <= tolerance && std::abs(got.g - want.g) <= tolerance &&
      std::abs(got.b - want.b) <= tolerance)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "(" << int(got.r) << ", " << int(got.g) << ", " << int(got.b)
                                       << ") is not (" << int(want.r) << ", " << int(want.g) << ", " << int(want.b)
                                       << ") within " << tolerance;
}

Rgb8 pixel(const Snapshot& s, double column, double row) { return s.image.at(int(column), int(row)); }

const Rgb8 kWhite{255, 255, 255};
const ColourMap& viridis() { return ColourMap::get(ColourMapKind::viridis); }

}  // namespace

TEST(SnapshotRenderer, SideView2dPlacesAndColoursParticles) {
  // Three particles on z = 0 at x = 0, 1, 2, coloured 0, 0.5 and 1 on a fixed range [0, 1].
  const FieldFrame frame = make_frame(2, {{{0, 0, 0}, 0, 0.0}, {{1, 0, 0}, 0, 0.5}, {{2, 0, 0}, 0, 1.0}});
  SnapshotSettings s = plain(300, 100, 0.5);
  s.field = "pressure";
  s.range_min = 0;
  s.range_max = 1;
  const Snapshot shot = renderer().render(frame, s);
  ASSERT_EQ(shot.image.width, 300);
  ASSERT_EQ(shot.image.height, 100);
  // Extent x in [-0.25, 2.25], z in [-0.25, 0.25], 5% more each side: the width limits,
  // 300 px / (2 × 1.25 × 1.05) m; the centre (x = 1, z = 0) at pixel (150, 50).
  const double px_per_m = 300 / (2 * 1.25 * 1.05);
  EXPECT_NEAR(shot.camera.pixel_scale, px_per_m, 1e-9);
  for (int k = 0; k < 3; ++k)
    EXPECT_TRUE(near(pixel(shot, 150 + (k - 1) * px_per_m, 50), viridis().at(0.5 * k))) << "particle " << k;
  EXPECT_EQ(shot.image.at(0, 0), kWhite);
  EXPECT_EQ(shot.image.at(150, 5), kWhite);  // above the row of spheres (radius 28.6 px)
  EXPECT_EQ(shot.drawn_particles, 3u);
}

TEST(SnapshotRenderer, SideViewHasZUp) {
  const FieldFrame frame = make_frame(2, {{{0, 0, 0}, 0, 0.0}, {{0, 0, 1}, 0, 1.0}});
  SnapshotSettings s = plain(100, 200, 0.5);
  s.field = "pressure";
  const Snapshot shot = renderer().render(frame, s);
  EXPECT_EQ(shot.range_min, 0);  // automatic range
  EXPECT_EQ(shot.range_max, 1);
  // Height limits: 200 px / (2 × 0.75 × 1.05) m; z = 1 is 0.5 m above the centre.
  const double px_per_m = 200 / (2 * 0.75 * 1.05);
  EXPECT_TRUE(near(pixel(shot, 50, 100 - 0.5 * px_per_m), viridis().at(1)));
  EXPECT_TRUE(near(pixel(shot, 50, 100 + 0.5 * px_per_m), viridis().at(0)));
}

TEST(SnapshotRenderer, LookAt3dProjectsAndHidesWhatIsBehind) {
  // Camera 10 m in front (-y) of the origin, 30° vertical field of view, square image: a point
  // (a, 0, b) is at column 100 + 100 a / (10 tan 15°), row 100 - 100 b / (10 tan 15°).
  // A sphere at the origin is hidden by a nearer one at y = -2, whichever is drawn first.
  for (bool near_first : {false, true}) {
    std::vector<test::TestParticle> particles = {{{0, 0, 0}, 0, 0.0}, {{0, -2, 0}, 0, 1.0}, {{2, 0, 1}, 0, 0.5}};
    if (near_first) std::swap(particles[0], particles[1]);
    SnapshotSettings s = plain(200, 200, 0.5);
    s.field = "pressure";
    s.range_min = 0;
    s.range_max = 1;
    s.camera.kind = CameraKind::look_at;
    s.camera.eye = {0, -10, 0};
    s.camera.target = {0, 0, 0};
    s.camera.vertical_fov = 30;
    const Snapshot shot = renderer().render(make_frame(3, particles), s);
    const double k = 100 / (10 * std::tan(15 * 3.14159265358979323846 / 180));
    EXPECT_TRUE(near(pixel(shot, 100, 100), viridis().at(1))) << "near_first " << near_first;
    EXPECT_TRUE(near(pixel(shot, 100 + 2 * k, 100 - 1 * k), viridis().at(0.5)));
    EXPECT_EQ(shot.image.at(5, 195), kWhite);
  }
}

TEST(SnapshotRenderer, OrbitAt90DegreesLooksAlongMinusX) {
  // Seen from +x, +y is to the right.
  const FieldFrame frame = make_frame(3, {{{0, -1, 0}, 1, 0.0}, {{0, 1, 0}, 1, 1.0}});
  SnapshotSettings s = plain(200, 100, 0.5);
  s.field = "pressure";
  s.camera.kind = CameraKind::orbit;
  s.camera.azimuth = 90;
  s.camera.elevation = 0;
  const Snapshot shot = renderer().render(frame, s);
  const Eigen::Vector2d left = shot.camera.pixel_of({0, -1, 0}), right = shot.camera.pixel_of({0, 1, 0});
  EXPECT_LT(left.x(), 100);
  EXPECT_GT(right.x(), 100);
  EXPECT_NEAR(left.x() + right.x(), 200, 1e-6);  // symmetric about the centre
  EXPECT_NEAR(left.y(), 50, 1e-6);
  EXPECT_TRUE(near(pixel(shot, left.x(), left.y()), viridis().at(0)));
  EXPECT_TRUE(near(pixel(shot, right.x(), right.y()), viridis().at(1)));
}

TEST(SnapshotRenderer, ColourBarShowsTheRange) {
  std::vector<test::TestParticle> particles;
  for (int i = 0; i <= 10; ++i) particles.push_back({{0.1 * i, 0, 0}, 0, double(i)});
  SnapshotSettings s = plain(640, 360, 0.1);
  s.field = "pressure";
  s.colour_bar = true;
  const Snapshot shot = renderer().render(make_frame(2, particles), s);
  EXPECT_EQ(shot.range_min, 0);
  EXPECT_EQ(shot.range_max, 10);
  EXPECT_EQ(shot.units, "Pa");
  EXPECT_EQ(colour_bar_labels(shot.range_min, shot.range_max), (std::vector<std::string>{"0", "2.5", "5", "7.5", "10"}));
  const ColourBarLayout bar = colour_bar_layout(640, 360);
  EXPECT_LT(bar.scene_width, bar.bar_x);
  EXPECT_EQ(shot.camera.viewport_width, bar.scene_width);
  const int x = bar.bar_x + bar.bar_width / 2;
  EXPECT_EQ(shot.image.at(x, bar.bar_top), viridis().at(1));
  EXPECT_EQ(shot.image.at(x, bar.bar_top + bar.bar_height - 1), viridis().at(0));
  EXPECT_TRUE(near(shot.image.at(x, bar.bar_top + bar.bar_height / 2), viridis().at(0.5), 3));
  // Labels and title are drawn: dark pixels right of the bar and above it.
  int label_ink = 0, title_ink = 0;
  for (int y = 0; y < 360; ++y)
    for (int col = bar.label_x; col < 640; ++col) label_ink += shot.image.at(col, y) == Rgb8{0, 0, 0};
  for (int y = 0; y < bar.bar_top; ++y)
    for (int col = bar.scene_width; col < 640; ++col) title_ink += shot.image.at(col, y) == Rgb8{0, 0, 0};
  EXPECT_GT(label_ink, 50);
  EXPECT_GT(title_ink, 50);
}

TEST(SnapshotRenderer, DivergingAutomaticRangeIsSymmetric) {
  const FieldFrame frame = make_frame(2, {{{0, 0, 0}, 1, -2.0}, {{1, 0, 0}, 1, 5.0}, {{2, 0, 0}, 1, 0.0}});
  SnapshotSettings s = plain(300, 100, 0.5);
  s.field = "pressure";
  s.colour_map = ColourMapKind::cool_warm;
  const Snapshot shot = renderer().render(frame, s);
  EXPECT_EQ(shot.range_min, -5);
  EXPECT_EQ(shot.range_max, 5);
  const double px_per_m = 300 / (2 * 1.25 * 1.05);
  const ColourMap& m = ColourMap::get(ColourMapKind::cool_warm);
  EXPECT_TRUE(near(pixel(shot, 150 + px_per_m, 50), m.at(0.5)));  // zero is the middle
  EXPECT_TRUE(near(pixel(shot, 150, 50), m.at(1)));
  EXPECT_TRUE(near(pixel(shot, 150 - px_per_m, 50), m.at(0.3)));
}

TEST(SnapshotRenderer, VectorFieldIsColouredByItsMagnitude) {
  const FieldFrame frame = make_frame(2, {{{0, 0, 0}, 0, 0.0}, {{1, 0, 0}, 0, 3.0}});
  SnapshotSettings s = plain(200, 100, 0.5);
  s.field = "velocity";
  const Snapshot shot = renderer().render(frame, s);
  EXPECT_NEAR(shot.range_max, 3.0, 1e-12);
  s.field = "velocity_z";
  EXPECT_NEAR(renderer().render(frame, s).range_max, 2.4, 1e-12);
  s.field = "temperature";
  try {
    renderer().render(frame, s);
    FAIL() << "no error for an unknown field";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("'temperature'"), std::string::npos) << e.what();
  }
}

TEST(SnapshotRenderer, ImageIsNotBlankAndHasTheRequestedSize) {
  std::vector<test::TestParticle> particles;
  for (int i = 0; i < 50; ++i)
    for (int k = 0; k < 20; ++k) particles.push_back({{0.02 * i, 0, 0.02 * k}, std::uint8_t(k < 10), 0.0});
  SnapshotSettings s;
  s.width = 321;
  s.height = 123;
  s.particle_diameter = 0.02;
  const Snapshot shot = renderer().render(make_frame(2, particles), s);
  ASSERT_EQ(shot.image.width, 321);
  ASSERT_EQ(shot.image.height, 123);
  ASSERT_EQ(shot.image.pixels.size(), 321u * 123u * 3u);
  // The block (1.0 m × 0.4 m with the spheres' radius, 5% margin) fills the height and 293 of the
  // 321 columns: circles on a square lattice cover π/4 of that, over half the image. Each sphere's
  // centre pixel shows its phase colour unshaded.
  int drawn = 0, water = 0, soil = 0;
  for (int y = 0; y < 123; ++y)
    for (int x = 0; x < 321; ++x) {
      drawn += !(shot.image.at(x, y) == kWhite);
      water += shot.image.at(x, y) == phase_colour(0);
      soil += shot.image.at(x, y) == phase_colour(1);
    }
  EXPECT_GT(drawn, 321 * 123 / 2);
  EXPECT_GE(water, 100);
  EXPECT_GE(soil, 100);
}

TEST(SnapshotRenderer, PhaseFilterHidesAndSeesThrough) {
  const FieldFrame side_by_side = make_frame(2, {{{0, 0, 0}, 0, 0.0}, {{1, 0, 0}, 1, 0.0}, {{2, 0, 0}, 2, 0.0}});
  SnapshotSettings s = plain(300, 100, 0.5);
  s.phases = {PhaseStyle::opaque, PhaseStyle::opaque, PhaseStyle::opaque};
  const double px_per_m = 300 / (2 * 1.25 * 1.05);
  Snapshot shot = renderer().render(side_by_side, s);
  for (int k = 0; k < 3; ++k) EXPECT_TRUE(near(pixel(shot, 150 + (k - 1) * px_per_m, 50), phase_colour(std::uint8_t(k))));
  // Soil only: the framing is the soil's, and the others are not drawn.
  s.phases = {PhaseStyle::hidden, PhaseStyle::opaque, PhaseStyle::hidden};
  shot = renderer().render(side_by_side, s);
  EXPECT_EQ(shot.drawn_particles, 1u);
  EXPECT_TRUE(near(pixel(shot, 150, 50), phase_colour(1)));
  EXPECT_EQ(shot.image.at(10, 50), kWhite);
  EXPECT_EQ(shot.image.at(290, 50), kWhite);

  // Translucent water in front of soil: 35% water over 65% soil at the centre.
  const FieldFrame stacked = make_frame(3, {{{0, -1, 0}, 0, 0.0}, {{0, 0, 0}, 1, 0.0}});
  SnapshotSettings t = plain(100, 100, 0.5);
  t.camera.kind = CameraKind::look_at;
  t.camera.eye = {0, -10, 0};
  t.phases = {PhaseStyle::translucent, PhaseStyle::opaque, PhaseStyle::hidden};
  shot = renderer().render(stacked, t);
  const Rgb8 w = phase_colour(0), soil = phase_colour(1);
  auto mixed = [](std::uint8_t a, std::uint8_t b) { return std::uint8_t(std::lround(0.35 * a + 0.65 * b)); };
  EXPECT_TRUE(near(shot.image.at(50, 50), {mixed(w.r, soil.r), mixed(w.g, soil.g), mixed(w.b, soil.b)}, 3));
}

TEST(SnapshotRenderer, FieldColoursOnlyItsPhases) {
  // A soil field: the water keeps its phase colour and does not widen the range.
  const FieldFrame frame = make_frame(2, {{{0, 0, 0}, 0, 100.0}, {{1, 0, 0}, 1, 1.0}, {{2, 0, 0}, 1, 3.0}});
  SnapshotSettings s = plain(300, 100, 0.5);
  s.field = "pressure";
  s.field_phases = {false, true, false};
  const Snapshot shot = renderer().render(frame, s);
  EXPECT_EQ(shot.range_min, 1);
  EXPECT_EQ(shot.range_max, 3);
  const double px_per_m = 300 / (2 * 1.25 * 1.05);
  EXPECT_TRUE(near(pixel(shot, 150 - px_per_m, 50), phase_colour(0)));
  EXPECT_TRUE(near(pixel(shot, 150 + px_per_m, 50), viridis().at(1)));
}

TEST(SnapshotRenderer, ClipBoxAndSlabSelectASection) {
  std::vector<test::TestParticle> particles;
  for (int j = 0; j < 5; ++j) particles.push_back({{0, double(j), 0}, 1, double(j)});
  SnapshotSettings s = plain(100, 100, 0.5);
  s.camera.kind = CameraKind::orbit;
  s.slab = Slab{1, 2.0, 0.5};
  EXPECT_EQ(renderer().render(make_frame(3, particles), s).drawn_particles, 1u);
  s.slab.reset();
  s.clip = ClipBox{{-1, 0.5, -1}, {1, 3.5, 1}};
  EXPECT_EQ(renderer().render(make_frame(3, particles), s).drawn_particles, 3u);
}

TEST(SnapshotRenderer, LevelOfDetailDrawsFewerLargerSprites) {
  std::vector<test::TestParticle> particles;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
      for (int k = 0; k < 40; ++k) particles.push_back({{0.01 * i, 0.01 * j, 0.01 * k}, 1, 0.0});
  const FieldFrame frame = make_frame(3, particles);
  SnapshotSettings s = plain(64, 64, 0.01);  // a 0.4 m block in 64 px: about 1.2 px per particle
  s.camera.kind = CameraKind::orbit;
  s.level_of_detail = false;
  const Snapshot all = renderer().render(frame, s);
  EXPECT_EQ(all.drawn_particles, particles.size());
  EXPECT_LT(all.sprite_pixels, 2);
  s.level_of_detail = true;
  const Snapshot fewer = renderer().render(frame, s);
  const double keep = std::pow(all.sprite_pixels / 2, 3);
  EXPECT_NEAR(double(fewer.drawn_particles) / double(particles.size()), keep, 0.02);
  EXPECT_NEAR(fewer.sprite_pixels, 2, 1e-9);
  // Both cover the block alike: the same soil-coloured area within a few per cent.
  auto covered = [](const Snapshot& shot) {
    int n = 0;
    for (std::size_t p = 0; p < shot.image.pixels.size(); p += 3)
      n += shot.image.pixels[p] != 255 || shot.image.pixels[p + 1] != 255 || shot.image.pixels[p + 2] != 255;
    return double(n);
  };
  EXPECT_NEAR(covered(fewer) / covered(all), 1.0, 0.1);
}

TEST(SnapshotRenderer, SizeAbove3840By2160IsRefused) {
  const FieldFrame frame = make_frame(2, {{{0, 0, 0}, 0, 0.0}});
  SnapshotSettings s = plain(3841, 100, 0.5);
  try {
    renderer().render(frame, s);
    FAIL() << "no error for width 3841";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("width 3841"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("3840x2160"), std::string::npos) << e.what();
  }
  s = plain(100, 2161, 0.5);
  EXPECT_THROW(renderer().render(frame, s), RenderError);
  s = plain(3840, 2160, 0.5);
  const Snapshot largest = renderer().render(frame, s);
  EXPECT_EQ(largest.image.width, 3840);
  EXPECT_EQ(largest.image.height, 2160);
}

}  // namespace cascade::render
