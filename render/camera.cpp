#include "render/camera.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace cascade::render {

namespace {

constexpr double kPi = 3.14159265358979323846;
double radians(double degrees) { return degrees * kPi / 180; }

// A right-handed view: the camera at `eye` looks along -z of its own frame.
Eigen::Matrix4d look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target, const Eigen::Vector3d& up) {
  const Eigen::Vector3d forward = (target - eye).normalized();
  Eigen::Vector3d right = forward.cross(up);
  if (right.norm() < 1e-9) right = forward.cross(Eigen::Vector3d(0, 1, 0));  // looking along `up`
  right.normalize();
  const Eigen::Vector3d true_up = right.cross(forward);
  Eigen::Matrix4d v = Eigen::Matrix4d::Identity();
  v.block<1, 3>(0, 0) = right.transpose();
  v.block<1, 3>(1, 0) = true_up.transpose();
  v.block<1, 3>(2, 0) = -forward.transpose();
  v(0, 3) = -right.dot(eye);
  v(1, 3) = -true_up.dot(eye);
  v(2, 3) = forward.dot(eye);
  return v;
}

// glOrtho and gluPerspective.
Eigen::Matrix4d orthographic(double half_width, double half_height, double near, double far) {
  Eigen::Matrix4d p = Eigen::Matrix4d::Identity();
  p(0, 0) = 1 / half_width;
  p(1, 1) = 1 / half_height;
  p(2, 2) = -2 / (far - near);
  p(2, 3) = -(far + near) / (far - near);
  return p;
}

Eigen::Matrix4d perspective(double vertical_fov, double aspect, double near, double far) {
  const double f = 1 / std::tan(vertical_fov / 2);
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = f / aspect;
  p(1, 1) = f;
  p(2, 2) = (far + near) / (near - far);
  p(2, 3) = 2 * far * near / (near - far);
  p(3, 2) = -1;
  return p;
}

}  // namespace

Eigen::Vector2d FramedCamera::pixel_of(const Eigen::Vector3d& point) const {
  const Eigen::Vector4d clip = projection * view * point.homogeneous();
  const double x = clip.x() / clip.w(), y = clip.y() / clip.w();
  return {(x + 1) / 2 * viewport_width, (1 - y) / 2 * viewport_height};
}

double FramedCamera::pixels_across(double diameter, const Eigen::Vector3d& point) const {
  if (!perspective) return diameter * pixel_scale;
  const double depth = -(view * point.homogeneous()).z();
  return diameter * pixel_scale / std::max(depth, 1e-12);
}

FramedCamera frame_camera(const CameraSettings& camera, const Bounds& bounds, double radius, int viewport_width,
                          int viewport_height) {
  FramedCamera f;
  f.viewport_width = viewport_width;
  f.viewport_height = viewport_height;
  const double aspect = double(viewport_width) / double(viewport_height);
  const Eigen::Vector3d centre = (bounds.min + bounds.max) / 2;
  const Eigen::Vector3d half = (bounds.max - bounds.min) / 2 + Eigen::Vector3d::Constant(radius);
  const double sphere_radius = half.norm();
  if (camera.kind == CameraKind::side) {
    const double half_x = 1.05 * half.x(), half_z = 1.05 * half.z();
    f.pixel_scale = std::min(viewport_width / (2 * half_x), viewport_height / (2 * half_z));
    f.eye = centre;
    f.view = look_at(centre, centre + Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 1));
    const double depth = 1.01 * half.y();  // the view-space z of the particles lies in [-depth, depth]
    f.projection = orthographic(viewport_width / (2 * f.pixel_scale), viewport_height / (2 * f.pixel_scale), -depth, depth);
    return f;
  }
  f.perspective = true;
  const double fovy = radians(camera.vertical_fov);
  const double fovx = 2 * std::atan(std::tan(fovy / 2) * aspect);
  Eigen::Vector3d target = centre;
  if (camera.kind == CameraKind::orbit) {
    const double az = radians(camera.azimuth), el = radians(camera.elevation);
    const Eigen::Vector3d direction(std::sin(az) * std::cos(el), -std::cos(az) * std::cos(el), std::sin(el));
    const double distance = sphere_radius / std::sin(std::min(fovx, fovy) / 2) / camera.zoom;
    f.eye = centre + distance * direction;
  } else {
    f.eye = Eigen::Vector3d(camera.eye[0], camera.eye[1], camera.eye[2]);
    target = Eigen::Vector3d(camera.target[0], camera.target[1], camera.target[2]);
  }
  const Eigen::Vector3d up = camera.kind == CameraKind::look_at ? Eigen::Vector3d(camera.up[0], camera.up[1], camera.up[2])
                                                                 : Eigen::Vector3d(0, 0, 1);
  f.view = look_at(f.eye, target, up);
  const double to_centre = (centre - f.eye).norm();
  const double far = to_centre + sphere_radius;
  const double near = std::max(far * 1e-4, to_centre - sphere_radius);
  f.projection = perspective(fovy, aspect, near, far);
  f.pixel_scale = viewport_height / 2.0 / std::tan(fovy / 2);
  return f;
}

}  // namespace cascade::render
