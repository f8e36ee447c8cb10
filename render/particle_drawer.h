// Draws particles as shaded sphere impostors into a framebuffer object and reads the image back.
// Each particle is one point sprite; its fragment shader discards outside the circle, shades with
// a headlight and writes the depth of the sphere's surface, so spheres intersect correctly.
// Needs the GL context current on the calling thread (EglContext).
#pragma once

#include <cstdint>
#include <vector>

#include "render/camera.h"
#include "render/rgb_image.h"

namespace cascade::render {

struct SpriteVertex {
  float position[3];
  std::uint8_t colour[4];  // sRGB and opacity
};

class ParticleDrawer {
 public:
  ParticleDrawer();  // compiles the shaders; throws RenderError
  ~ParticleDrawer();
  ParticleDrawer(const ParticleDrawer&) = delete;
  ParticleDrawer& operator=(const ParticleDrawer&) = delete;

  // Clears `image` (its size is the framebuffer's) to `background`, draws `opaque`, then
  // `translucent` (expected back to front) blended over it without writing depth, into the
  // viewport of `camera` at the image's left; reads the pixels into `image`.
  void draw(const std::vector<SpriteVertex>& opaque, const std::vector<SpriteVertex>& translucent,
            const FramedCamera& camera, double radius, Rgb8 background, RgbImage& image);

 private:
  void resize(int width, int height);
  void upload_and_draw(const std::vector<SpriteVertex>& sprites);

  unsigned program_ = 0, vertex_array_ = 0, buffer_ = 0;
  unsigned framebuffer_ = 0, colour_buffer_ = 0, depth_buffer_ = 0;
  int width_ = 0, height_ = 0;
  int view_location_ = -1, projection_location_ = -1, radius_location_ = -1, pixel_scale_location_ = -1,
      perspective_location_ = -1;
};

}  // namespace cascade::render
