// What a snapshot shows and how: the field and its colour map, the phases drawn, the camera, the
// section and the image. Plain values, so that a service can copy them across threads.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "render/colour_map.h"

namespace cascade::render {

inline constexpr int kMaxImageWidth = 3840;
inline constexpr int kMaxImageHeight = 2160;

// How each phase (FieldFrame::phase 0 water, 1 soil, 2 boundary) is drawn.
enum class PhaseStyle { hidden, opaque, translucent };

enum class CameraKind {
  side,     // orthographic, looking along +y at the x-z plane (x right, z up); 2D cases
  orbit,    // perspective, around the centre of the drawn particles
  look_at,  // perspective, from `eye` towards `target`
};

struct CameraSettings {
  CameraKind kind = CameraKind::side;
  // orbit: azimuth about z in degrees (0 looks along +y like the side view, 90 along -x),
  // elevation above the x-y plane in degrees, zoom > 1 moves closer.
  double azimuth = 30, elevation = 20, zoom = 1;
  // look_at
  std::array<double, 3> eye{0, -1, 0}, target{0, 0, 0}, up{0, 0, 1};
  double vertical_fov = 40;  // degrees, orbit and look_at
};

// Particles whose centre lies outside the box, or farther than thickness / 2 from the slab's
// plane, are not drawn: a section through a 3D case.
struct ClipBox {
  std::array<double, 3> min{}, max{};
};
struct Slab {
  int axis = 1;  // 0 x, 1 y, 2 z
  double position = 0, thickness = 0;
};

struct SnapshotSettings {
  // A scalar field, a vector (its magnitude), a component (velocity_z, stress_zz), or "phase" for
  // the fixed phase colours.
  std::string field = "phase";
  ColourMapKind colour_map = ColourMapKind::viridis;
  // Unset ends come from the drawn particles coloured by the field; with cool_warm an automatic
  // range is symmetric about zero, so that zero is the white midpoint.
  std::optional<double> range_min, range_max;
  std::array<PhaseStyle, 3> phases{PhaseStyle::opaque, PhaseStyle::opaque, PhaseStyle::hidden};
  // Phases coloured by the field; the others drawn take their phase colour (soil-only fields
  // such as pore_pressure leave the water blue).
  std::array<bool, 3> field_phases{true, true, true};
  double translucent_opacity = 0.35;

  CameraSettings camera;
  std::optional<ClipBox> clip;
  std::optional<Slab> slab;

  int width = 1280, height = 720;
  Rgb8 background{255, 255, 255};
  double particle_diameter = 0;  // metres, > 0: the case's dp
  bool colour_bar = true;        // with the field name and units; only when coloured by a field
  bool time_label = true;        // the simulated time, top left
  // Fewer, larger sprites when a particle would cover less than `lod_min_pixels` across.
  bool level_of_detail = true;
  double lod_min_pixels = 2;
};

// Throws RenderError naming the bad setting (size above 3840×2160, diameter not positive, ...).
void check_settings(const SnapshotSettings& settings);

}  // namespace cascade::render
