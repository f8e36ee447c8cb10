// The snapshot RPCs' rendering: one render thread owns the EGL context (made at the first render,
// so a server nobody asks for pictures never opens one) and renders frames that the solver
// threads copied at step boundaries; and the StreamSnapshots streams. A stream holds at most one
// frame waiting to be rendered, the latest: while its previous image is still being rendered or
// written to a slow client, a newer frame replaces the waiting one. Neither rendering nor a client
// ever holds up a solver thread.
#pragma once

#include <grpcpp/support/server_callback.h>

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "cascade/v1/simulation.pb.h"
#include "render/snapshot_settings.h"
#include "server/service/session.h"

namespace cascade::service {

// When a stream wants a frame: every `seconds` of simulated time or of wall time.
struct SnapshotInterval {
  bool simulated = true;
  double seconds = 1;
};

class SnapshotHub {
 public:
  // On the render thread: the image, or UNAVAILABLE when no EGL context can be made here (the
  // message says why), or FAILED_PRECONDITION when the frame cannot be drawn.
  using Rendered = std::function<void(const grpc::Status&, v1::SnapshotImage)>;

  SnapshotHub();
  ~SnapshotHub();  // shutdown(), then waits until every stream is gone
  SnapshotHub(const SnapshotHub&) = delete;
  SnapshotHub& operator=(const SnapshotHub&) = delete;

  void render(std::shared_ptr<const FieldFrame> frame, render::SnapshotSettings settings, Rendered done);

  // A stream of `session`'s frames at `interval` (the first at the next step boundary), until the
  // simulation stops (COMPLETED, FAILED, deleted), the server shuts down or the client goes away.
  grpc::ServerWriteReactor<v1::SnapshotImage>* stream(std::shared_ptr<Session> session,
                                                      render::SnapshotSettings settings, SnapshotInterval interval);

  // Ends every stream with UNAVAILABLE once its image in flight is written; new ones end at once.
  void shutdown();

 private:
  class Stream;
  struct Job {
    std::shared_ptr<const FieldFrame> frame;
    render::SnapshotSettings settings;
    Rendered done;
  };

  void render_loop();
  void end_idle_streams(bool stopping);
  void remove(Stream* stream);

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Job> jobs_;
  std::vector<std::shared_ptr<Stream>> streams_;
  std::atomic<bool> stopping_{false};
  std::thread render_thread_;
};

}  // namespace cascade::service
