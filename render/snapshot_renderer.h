// Frame → PNG-ready image: picks the particles to draw (phase styles, clip box, slab, level of
// detail), colours them, frames the camera, draws them with ParticleDrawer and adds the colour bar
// and the time. The renderer owns its EGL context: construct it, render with it and destroy it on
// one thread (a service's render thread, handed copied frames). Rendering reads the frame only.
#pragma once

#include <cstdint>
#include <string>

#include "render/egl_context.h"
#include "render/particle_drawer.h"
#include "render/rgb_image.h"
#include "render/snapshot_settings.h"
#include "server/core/field_frame.h"

namespace cascade::render {

// The image and what it shows (for a service's reply and for tests).
struct Snapshot {
  RgbImage image;
  double time = 0;
  std::uint64_t step = 0;
  std::string field, units;   // units empty for "phase"
  bool coloured_by_field = false;
  double range_min = 0, range_max = 0;  // used for the colours and the bar
  std::size_t drawn_particles = 0;
  double sprite_pixels = 0;   // diameter of a drawn sprite at the centre of the drawn particles
  FramedCamera camera;
};

class SnapshotRenderer {
 public:
  SnapshotRenderer();  // creates the context on this thread; throws RenderError

  // Throws RenderError for bad settings or a field the frame does not have.
  Snapshot render(const FieldFrame& frame, const SnapshotSettings& settings);

  const EglContext& context() const { return context_; }

 private:
  EglContext context_;
  ParticleDrawer drawer_;
};

}  // namespace cascade::render
