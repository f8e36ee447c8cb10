#include "render/snapshot_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/overlay.h"
#include "render/scalar_field.h"

namespace cascade::render {

namespace {

// A well-mixed 32-bit hash of a particle id (the finaliser of MurmurHash3): level of detail
// keeps the same particles from frame to frame, spread evenly over the body.
std::uint32_t mix(std::uint32_t h) {
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return h;
}

bool inside_section(const SnapshotSettings& s, const double* p) {
  if (s.clip)
    for (std::size_t a = 0; a < 3; ++a)
      if (p[a] < s.clip->min[a] || p[a] > s.clip->max[a]) return false;
  if (s.slab && std::fabs(p[s.slab->axis] - s.slab->position) > s.slab->thickness / 2) return false;
  return true;
}

// The colour range: the given ends, the others from the values of the particles the field colours.
void colour_range(const SnapshotSettings& s, const FieldFrame& frame, const std::vector<std::uint32_t>& drawn,
                  const ScalarField& field, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (std::uint32_t i : drawn) {
    if (!s.field_phases[frame.phase[i]] || !std::isfinite(field.values[i])) continue;
    lo = std::min(lo, field.values[i]);
    hi = std::max(hi, field.values[i]);
  }
  if (lo > hi) lo = hi = 0;  // nothing coloured by the field
  if (s.colour_map == ColourMapKind::cool_warm && !s.range_min && !s.range_max) {
    const double m = std::max(std::fabs(lo), std::fabs(hi));
    lo = -m;
    hi = m;
  }
  if (s.range_min) lo = *s.range_min;
  if (s.range_max) hi = *s.range_max;
  if (!(hi > lo)) {  // a constant field: its value at the middle of a small range
    const double pad = std::max(std::fabs(lo) * 1e-6, 1e-12);
    if (s.range_max) lo = hi - 2 * pad;
    else if (s.range_min) hi = lo + 2 * pad;
    else lo -= pad, hi += pad;
  }
}

}  // namespace

SnapshotRenderer::SnapshotRenderer() = default;

Snapshot SnapshotRenderer::render(const FieldFrame& frame, const SnapshotSettings& s) {
  check_settings(s);
  Snapshot out;
  out.time = frame.time;
  out.step = frame.step;
  out.field = s.field;
  out.coloured_by_field = s.field != "phase";
  ScalarField field;
  if (out.coloured_by_field) {
    field = scalar_field(frame, s.field);
    out.units = field.units;
  }

  std::vector<std::uint32_t> drawn;
  Bounds bounds;
  bounds.min.setConstant(std::numeric_limits<double>::infinity());
  bounds.max = -bounds.min;
  for (std::uint32_t i = 0; i < std::uint32_t(frame.size()); ++i) {
    if (frame.phase[i] > 2 || s.phases[frame.phase[i]] == PhaseStyle::hidden) continue;
    const double* p = &frame.position[3 * std::size_t(i)];
    if (!inside_section(s, p)) continue;
    drawn.push_back(i);
    for (int a = 0; a < 3; ++a) {
      bounds.min[a] = std::min(bounds.min[a], p[a]);
      bounds.max[a] = std::max(bounds.max[a], p[a]);
    }
  }
  if (drawn.empty()) bounds.min = bounds.max = Eigen::Vector3d::Zero();
  if (out.coloured_by_field) colour_range(s, frame, drawn, field, out.range_min, out.range_max);

  const bool bar = out.coloured_by_field && s.colour_bar;
  const ColourBarLayout layout = colour_bar_layout(s.width, s.height);
  double radius = s.particle_diameter / 2;
  out.camera = frame_camera(s.camera, bounds, radius, bar ? layout.scene_width : s.width, s.height);

  // Level of detail: a fraction `keep` of the particles, drawn larger so that they cover as much
  // of the picture (area in 2D, volume in 3D) as all of them would.
  const Eigen::Vector3d centre = (bounds.min + bounds.max) / 2;
  out.sprite_pixels = out.camera.pixels_across(s.particle_diameter, centre);
  double keep = 1;
  if (s.level_of_detail && out.sprite_pixels < s.lod_min_pixels) {
    const int dims = frame.dimensions == 2 ? 2 : 3;
    keep = std::max(std::pow(out.sprite_pixels / s.lod_min_pixels, dims), 1e-6);
    radius /= std::pow(keep, 1.0 / dims);
    out.sprite_pixels = out.camera.pixels_across(2 * radius, centre);
  }
  const double keep_below = keep * 4294967296.0;

  const ColourMap& map = ColourMap::get(s.colour_map);
  const double scale = out.coloured_by_field ? 1 / (out.range_max - out.range_min) : 0;
  const std::uint8_t translucent_alpha = std::uint8_t(std::lround(s.translucent_opacity * 255));
  std::vector<SpriteVertex> opaque, translucent;
  opaque.reserve(drawn.size());
  for (std::uint32_t i : drawn) {
    if (keep < 1 && double(mix(frame.id[i])) >= keep_below) continue;
    const std::uint8_t phase = frame.phase[i];
    const Rgb8 c = out.coloured_by_field && s.field_phases[phase] ? map.at((field.values[i] - out.range_min) * scale)
                                                                  : phase_colour(phase);
    const bool see_through = s.phases[phase] == PhaseStyle::translucent;
    const double* p = &frame.position[3 * std::size_t(i)];
    (see_through ? translucent : opaque)
        .push_back({{float(p[0]), float(p[1]), float(p[2])}, {c.r, c.g, c.b, see_through ? translucent_alpha : std::uint8_t(255)}});
  }
  out.drawn_particles = opaque.size() + translucent.size();
  if (!translucent.empty()) {  // back to front: the farthest (most negative view z) first
    const Eigen::Matrix4d& v = out.camera.view;
    auto depth = [&](const SpriteVertex& a) {
      return v(2, 0) * a.position[0] + v(2, 1) * a.position[1] + v(2, 2) * a.position[2];
    };
    std::stable_sort(translucent.begin(), translucent.end(),
                     [&](const SpriteVertex& a, const SpriteVertex& b) { return depth(a) < depth(b); });
  }

  out.image = RgbImage(s.width, s.height);
  drawer_.draw(opaque, translucent, out.camera, radius, s.background, out.image);
  if (bar) {
    const std::string title = field.name + (field.units.empty() ? "" : " [" + field.units + "]");
    draw_colour_bar(out.image, layout, map, out.range_min, out.range_max, title, s.background);
  }
  if (s.time_label) draw_time_label(out.image, frame.time, s.background);
  return out;
}

}  // namespace cascade::render
