// A receiver of frames copied at step boundaries (the snapshot streams). The solver thread asks
// each tap after every step whether it wants this one and, if so, hands it a copy that it shares
// with the other taps; a tap must return at once (queue, never render), so the solver never waits.
#pragma once

#include <memory>

#include "server/core/field_frame.h"

namespace cascade::service {

class FrameTap {
 public:
  virtual ~FrameTap() = default;
  // On the solver thread, after a step that reached `time`.
  virtual bool wants_frame(double time) = 0;
  // On the solver thread: the frame at that step boundary (and the first frame when the tap is added).
  virtual void take_frame(std::shared_ptr<const FieldFrame> frame) = 0;
};

}  // namespace cascade::service
