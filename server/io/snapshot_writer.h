// PNG snapshots of output frames (output.snapshots): DIR/NAME_NNNNNN.png per snapshot and frame,
// NNNNNN counting the frames written from 0 like fields.h5. Renders on the calling thread, from
// the frame it is given; the EGL context is made at the first frame, so a case without snapshots
// never opens one.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cascade/v1/scenario.pb.h"
#include "render/snapshot_renderer.h"
#include "render/snapshot_settings.h"
#include "server/core/field_frame.h"

namespace cascade {

// The renderer's settings for one checked snapshot of a case with defaults applied
// (docs/rendering.md); `dp` is the particles' diameter.
render::SnapshotSettings snapshot_settings(const v1::Snapshot& snapshot, int dimensions, double dp);

class SnapshotWriter {
 public:
  SnapshotWriter(const v1::ScenarioSpec& spec, std::filesystem::path dir);

  // Throws render::RenderError with the snapshot's name when one cannot be drawn or written.
  void write(const FieldFrame& frame);

 private:
  struct Entry {
    std::string name;
    render::SnapshotSettings settings;
  };
  std::vector<Entry> snapshots_;
  std::filesystem::path dir_;
  std::unique_ptr<render::SnapshotRenderer> renderer_;
  int frames_written_ = 0;
};

}  // namespace cascade
