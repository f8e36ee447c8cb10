// The view and projection of a snapshot: the camera settings framed on the drawn particles.
#pragma once

#include <Eigen/Core>
#include <array>

#include "render/snapshot_settings.h"

namespace cascade::render {

// Axis-aligned bounds of particle centres.
struct Bounds {
  Eigen::Vector3d min{0, 0, 0}, max{0, 0, 0};
};

struct FramedCamera {
  Eigen::Matrix4d view, projection;
  bool perspective = false;
  // Sprite size: orthographic, pixels per metre; perspective, pixels per metre at unit distance.
  double pixel_scale = 1;
  Eigen::Vector3d eye{0, 0, 0};
  int viewport_width = 1, viewport_height = 1;

  // (column, row) of a world point in the viewport, row 0 at the top; pixel centres at +0.5.
  Eigen::Vector2d pixel_of(const Eigen::Vector3d& point) const;
  // How many pixels across a sphere of `diameter` at `point` covers.
  double pixels_across(double diameter, const Eigen::Vector3d& point) const;
};

// side: the x-z extent of the spheres (centres ± radius), 5% larger on each side, fills the
// viewport's width or height and is centred. orbit: the bounding sphere of the spheres fills the
// narrower field of view at zoom 1. look_at: as given; near and far planes hold the bounds.
FramedCamera frame_camera(const CameraSettings& camera, const Bounds& bounds, double radius, int viewport_width,
                          int viewport_height);

}  // namespace cascade::render
