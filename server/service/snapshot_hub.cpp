#include "server/service/snapshot_hub.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "render/png_encoder.h"
#include "render/snapshot_renderer.h"
#include "server/scenario/output_schedule.h"
#include "server/service/frame_tap.h"

namespace cascade::service {

namespace {

// How often idle streams are checked for their end (simulation stopped, client gone, shutdown).
constexpr auto kPollInterval = std::chrono::milliseconds(50);

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

const char* camera_name(render::CameraKind kind) {
  switch (kind) {
    case render::CameraKind::side: return "side";
    case render::CameraKind::orbit: return "orbit";
    default: return "look_at";
  }
}

v1::SnapshotImage image_message(const render::Snapshot& snapshot, const render::SnapshotSettings& settings) {
  v1::SnapshotImage image;
  const auto png = render::encode_png(snapshot.image);
  image.set_png(png.data(), png.size());
  image.set_time(snapshot.time);
  image.set_step(snapshot.step);
  image.set_field(snapshot.field);
  image.set_units(snapshot.units);
  image.set_range_min(snapshot.range_min);
  image.set_range_max(snapshot.range_max);
  image.set_camera(camera_name(settings.camera.kind));
  for (int a = 0; a < 3; ++a) image.add_eye(snapshot.camera.eye[a]);
  image.set_width(std::uint32_t(settings.width));
  image.set_height(std::uint32_t(settings.height));
  image.set_drawn_particles(snapshot.drawn_particles);
  return image;
}

}  // namespace

// Owned by the hub's list from StreamSnapshots until OnDone, and shared with render jobs in flight
// and, as a FrameTap, weakly with the session. At most one render or write is in flight, and
// Finish is called only when none is, so the reactor's operations never overlap.
class SnapshotHub::Stream : public grpc::ServerWriteReactor<v1::SnapshotImage>,
                            public FrameTap,
                            public std::enable_shared_from_this<SnapshotHub::Stream> {
 public:
  Stream(SnapshotHub& hub, std::shared_ptr<Session> session, render::SnapshotSettings settings,
         SnapshotInterval interval)
      : hub_(hub), session_(std::move(session)), settings_(std::move(settings)), interval_(interval) {}

  void begin() { session_->tap_frames(weak_from_this()); }

  // The solver thread's: no lock needed for the schedule.
  bool wants_frame(double time) override {
    const double now = interval_.simulated ? time : wall_seconds();
    if (!next_due_) next_due_ = interval_.simulated ? start_time_ + interval_.seconds : now + interval_.seconds;
    if (now < *next_due_ - 1e-12 * interval_.seconds) return false;
    if (interval_.simulated)
      next_due_ = next_due_time(*next_due_, now, interval_.seconds);
    else
      next_due_ = now + interval_.seconds;
    return true;
  }

  void take_frame(std::shared_ptr<const FieldFrame> frame) override {
    if (!next_due_) start_time_ = frame->time;  // the first frame starts the simulated-time schedule
    std::unique_lock lock(mutex_);
    if (finishing_) return;
    latest_ = std::move(frame);  // a frame still waiting is dropped
    if (busy_) return;
    lock.unlock();
    render_latest();
  }

  // From the render thread's poll: ends a stream that has nothing in flight and no more to send.
  void end_if_over(bool server_stopping) {
    std::unique_lock lock(mutex_);
    if (finishing_ || busy_) return;
    grpc::Status status;
    if (server_stopping) status = {grpc::StatusCode::UNAVAILABLE, "server shutting down"};
    else if (cancelled_) status = grpc::Status::CANCELLED;
    else if (!(session_->stopped() && !latest_)) return;
    finishing_ = true;
    lock.unlock();
    Finish(status);
  }

  void OnWriteDone(bool ok) override {
    std::unique_lock lock(mutex_);
    busy_ = false;
    if (!ok) {
      finishing_ = true;  // the client is gone
      lock.unlock();
      return Finish(grpc::Status::CANCELLED);
    }
    if (!latest_ || finishing_) return;
    lock.unlock();
    render_latest();
  }
  void OnCancel() override {
    std::lock_guard lock(mutex_);
    cancelled_ = true;
  }
  void OnDone() override { hub_.remove(this); }

 private:
  void render_latest() {
    std::shared_ptr<const FieldFrame> frame;
    {
      std::lock_guard lock(mutex_);
      if (busy_ || !latest_) return;
      busy_ = true;
      frame = std::move(latest_);
    }
    hub_.render(std::move(frame), settings_, [self = shared_from_this()](const grpc::Status& status, v1::SnapshotImage image) {
      self->rendered(status, std::move(image));
    });
  }

  void rendered(const grpc::Status& status, v1::SnapshotImage image) {
    std::unique_lock lock(mutex_);
    if (!status.ok()) {
      busy_ = false;
      finishing_ = true;
      lock.unlock();
      return Finish(status);
    }
    image_ = std::move(image);
    lock.unlock();
    StartWrite(&image_);  // busy_ stays set until OnWriteDone
  }

  SnapshotHub& hub_;
  const std::shared_ptr<Session> session_;
  const render::SnapshotSettings settings_;
  const SnapshotInterval interval_;
  std::optional<double> next_due_;  // the solver thread's, as is start_time_
  double start_time_ = 0;
  std::mutex mutex_;
  std::shared_ptr<const FieldFrame> latest_;  // waiting to be rendered
  bool busy_ = false, finishing_ = false, cancelled_ = false;
  v1::SnapshotImage image_;
};

SnapshotHub::SnapshotHub() : render_thread_([this] { render_loop(); }) {}

SnapshotHub::~SnapshotHub() {
  shutdown();
  render_thread_.join();
}

void SnapshotHub::shutdown() {
  stopping_ = true;
  wake_.notify_one();
}

void SnapshotHub::render(std::shared_ptr<const FieldFrame> frame, render::SnapshotSettings settings, Rendered done) {
  std::lock_guard lock(mutex_);
  jobs_.push_back({std::move(frame), std::move(settings), std::move(done)});
  wake_.notify_one();
}

grpc::ServerWriteReactor<v1::SnapshotImage>* SnapshotHub::stream(std::shared_ptr<Session> session,
                                                                 render::SnapshotSettings settings,
                                                                 SnapshotInterval interval) {
  auto stream = std::make_shared<Stream>(*this, std::move(session), std::move(settings), interval);
  {
    std::lock_guard lock(mutex_);
    streams_.push_back(stream);
  }
  stream->begin();
  return stream.get();
}

void SnapshotHub::remove(Stream* stream) {
  std::shared_ptr<Stream> last;  // released outside the lock
  std::lock_guard lock(mutex_);
  const auto found = std::find_if(streams_.begin(), streams_.end(), [&](const auto& s) { return s.get() == stream; });
  if (found == streams_.end()) return;
  last = std::move(*found);
  streams_.erase(found);
}

void SnapshotHub::end_idle_streams(bool stopping) {
  std::vector<std::shared_ptr<Stream>> streams;
  {
    std::lock_guard lock(mutex_);
    streams = streams_;
  }
  // Outside the lock: a Finish may run OnDone (remove) at once.
  for (auto& stream : streams) stream->end_if_over(stopping);
}

void SnapshotHub::render_loop() {
  std::unique_ptr<render::SnapshotRenderer> renderer;
  for (;;) {
    std::optional<Job> job;
    {
      std::unique_lock lock(mutex_);
      wake_.wait_for(lock, kPollInterval, [&] { return !jobs_.empty() || stopping_; });
      if (stopping_ && jobs_.empty() && streams_.empty()) return;
      if (!jobs_.empty()) {
        job = std::move(jobs_.front());
        jobs_.pop_front();
      }
    }
    if (job) {
      try {
        // Made here, so that this thread owns it; tried again at the next job if it fails.
        if (!renderer) renderer = std::make_unique<render::SnapshotRenderer>();
      } catch (const std::exception& e) {
        job->done({grpc::StatusCode::UNAVAILABLE,
                   std::string("offscreen rendering is unavailable on this server (no EGL context): ") + e.what()},
                  {});
        continue;
      }
      try {
        job->done(grpc::Status::OK, image_message(renderer->render(*job->frame, job->settings), job->settings));
      } catch (const render::RenderError& e) {
        job->done({grpc::StatusCode::FAILED_PRECONDITION, std::string("snapshot: ") + e.what()}, {});
      }
    }
    end_idle_streams(stopping_);
  }
}

}  // namespace cascade::service
