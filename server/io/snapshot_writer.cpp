#include "server/io/snapshot_writer.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "render/png_encoder.h"
#include "server/scenario/snapshot_fields.h"

namespace cascade {

namespace {

using render::PhaseStyle;

int phase_index(const std::string& phase) { return phase == "water" ? 0 : phase == "soil" ? 1 : 2; }
int axis_index(const std::string& axis) { return axis == "x" ? 0 : axis == "y" ? 1 : 2; }

std::array<double, 3> point3(const google::protobuf::RepeatedField<double>& v) { return {v[0], v[1], v[2]}; }

// A case's point of `dimensions` components as frame coordinates; 2D cases are (x, z) with y = 0.
std::array<double, 3> frame_point(const google::protobuf::RepeatedField<double>& v, int dimensions, double y) {
  return dimensions == 2 ? std::array<double, 3>{v[0], y, v[1]} : point3(v);
}

}  // namespace

render::SnapshotSettings snapshot_settings(const v1::Snapshot& s, int dimensions, double dp) {
  render::SnapshotSettings r;
  r.field = s.field();
  r.colour_map = s.colour_map() == "cool_warm" ? render::ColourMapKind::cool_warm : render::ColourMapKind::viridis;
  if (s.has_min()) r.range_min = s.min();
  if (s.has_max()) r.range_max = s.max();
  if (s.phase().empty()) r.phases = {PhaseStyle::opaque, PhaseStyle::opaque, PhaseStyle::hidden};
  else if (s.phase() == "all") r.phases = {PhaseStyle::opaque, PhaseStyle::opaque, PhaseStyle::opaque};
  else {
    r.phases = {PhaseStyle::hidden, PhaseStyle::hidden, PhaseStyle::hidden};
    r.phases[std::size_t(phase_index(s.phase()))] = PhaseStyle::opaque;
  }
  for (const std::string& p : s.translucent()) r.phases[std::size_t(phase_index(p))] = PhaseStyle::translucent;
  // The frame holds soil fields on soil particles only; other particles keep their phase colour.
  if (is_soil_snapshot_field(s.field())) r.field_phases = {false, true, false};

  if (s.camera() == "side") r.camera.kind = render::CameraKind::side;
  else if (s.camera() == "look_at") {
    r.camera.kind = render::CameraKind::look_at;
    r.camera.eye = point3(s.look_at().eye());
    r.camera.target = point3(s.look_at().target());
    if (!s.look_at().up().empty()) r.camera.up = point3(s.look_at().up());
    if (s.look_at().has_fov()) r.camera.vertical_fov = s.look_at().fov();
  } else {
    r.camera.kind = render::CameraKind::orbit;
    const v1::SnapshotOrbit& o = s.orbit();
    if (o.has_azimuth()) r.camera.azimuth = o.azimuth();
    if (o.has_elevation()) r.camera.elevation = o.elevation();
    if (o.has_zoom()) r.camera.zoom = o.zoom();
    if (o.has_fov()) r.camera.vertical_fov = o.fov();
  }
  if (s.has_clip()) {
    const double everything = std::numeric_limits<double>::max();
    r.clip = render::ClipBox{frame_point(s.clip().min(), dimensions, -everything),
                             frame_point(s.clip().max(), dimensions, everything)};
  }
  if (s.has_slab()) r.slab = render::Slab{axis_index(s.slab().axis()), s.slab().position(), s.slab().thickness()};
  r.width = s.width();
  r.height = s.height();
  if (!s.background().empty()) {
    auto byte = [](double v) { return std::uint8_t(std::lround(v * 255)); };
    r.background = {byte(s.background(0)), byte(s.background(1)), byte(s.background(2))};
  }
  r.particle_diameter = dp;
  return r;
}

SnapshotWriter::SnapshotWriter(const v1::ScenarioSpec& spec, std::filesystem::path dir) : dir_(std::move(dir)) {
  for (const v1::Snapshot& s : spec.output().snapshots())
    snapshots_.push_back({s.name(), snapshot_settings(s, spec.dimensions(), spec.dp())});
  if (!snapshots_.empty()) std::filesystem::create_directories(dir_);
}

void SnapshotWriter::write(const FieldFrame& frame) {
  if (snapshots_.empty()) return;
  if (!renderer_) renderer_ = std::make_unique<render::SnapshotRenderer>();
  char index[16];
  std::snprintf(index, sizeof index, "_%06d.png", frames_written_);
  for (const Entry& e : snapshots_) {
    try {
      render::write_png(dir_ / (e.name + index), renderer_->render(frame, e.settings).image);
    } catch (const render::RenderError& error) {
      throw render::RenderError("snapshot '" + e.name + "': " + error.what());
    }
  }
  ++frames_written_;
}

}  // namespace cascade
