#include "render/snapshot_settings.h"

#include <cmath>
#include <cstdio>

#include "render/egl_context.h"

namespace cascade::render {

namespace {

[[noreturn]] void bad(const std::string& message) { throw RenderError("snapshot " + message); }

std::string text(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%g", v);
  return s;
}

}  // namespace

void check_settings(const SnapshotSettings& s) {
  if (s.width < 1 || s.width > kMaxImageWidth)
    bad("width " + std::to_string(s.width) + " is outside [1, " + std::to_string(kMaxImageWidth) +
        "]: images are at most " + std::to_string(kMaxImageWidth) + "x" + std::to_string(kMaxImageHeight));
  if (s.height < 1 || s.height > kMaxImageHeight)
    bad("height " + std::to_string(s.height) + " is outside [1, " + std::to_string(kMaxImageHeight) +
        "]: images are at most " + std::to_string(kMaxImageWidth) + "x" + std::to_string(kMaxImageHeight));
  if (!(s.particle_diameter > 0) || !std::isfinite(s.particle_diameter))
    bad("particle diameter must be a positive length (the case's dp), is " + text(s.particle_diameter));
  if (s.range_min && s.range_max && !(*s.range_max > *s.range_min))
    bad("range: max " + text(*s.range_max) + " must be greater than min " + text(*s.range_min));
  if (!(s.translucent_opacity > 0 && s.translucent_opacity <= 1)) bad("translucent opacity must be in (0, 1]");
  if (!(s.lod_min_pixels > 0)) bad("level-of-detail pixel size must be positive");
  const CameraSettings& c = s.camera;
  if (!(c.vertical_fov > 0 && c.vertical_fov < 180)) bad("camera field of view must be in (0, 180) degrees");
  if (!(c.zoom > 0)) bad("camera zoom must be positive");
  if (!(std::fabs(c.elevation) <= 90)) bad("camera elevation must be in [-90, 90] degrees");
  if (c.kind == CameraKind::look_at && c.eye == c.target) bad("camera eye and target must differ");
  if (s.clip)
    for (int a = 0; a < 3; ++a)
      if (!(s.clip->max[std::size_t(a)] > s.clip->min[std::size_t(a)])) bad("clip box max must exceed min on every axis");
  if (s.slab && (s.slab->axis < 0 || s.slab->axis > 2 || !(s.slab->thickness > 0)))
    bad("slab needs an axis (x, y or z) and a positive thickness");
}

}  // namespace cascade::render
