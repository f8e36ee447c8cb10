// The WatchSimulation streams. One ticker thread samples every watched simulation's published
// status at each watcher's interval and passes on its new events; a watcher whose previous write
// is still in flight (a slow client) skips statuses instead of queueing them, so neither a slow
// nor a vanished client holds memory or the solver.
#pragma once

#include <grpcpp/support/server_callback.h>

#include <atomic>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "cascade/v1/simulation.pb.h"
#include "server/service/session.h"

namespace cascade::service {

class WatchHub {
 public:
  WatchHub();
  ~WatchHub();  // shutdown(), then waits until every stream is gone
  WatchHub(const WatchHub&) = delete;
  WatchHub& operator=(const WatchHub&) = delete;

  // A stream of `session`'s status every `interval` seconds and each of its events, until the
  // simulation stops (COMPLETED, FAILED, deleted) or the client goes away.
  grpc::ServerWriteReactor<v1::WatchSimulationResponse>* watch(std::shared_ptr<Session> session, double interval);

  // Ends every stream with UNAVAILABLE at the next tick (a write in flight first completes, or fails
  // when the server cancels it); new streams end at once.
  void shutdown() { stopping_ = true; }

 private:
  class Watcher;
  void add(Watcher* watcher);
  void remove(Watcher* watcher);
  void tick_loop();

  std::mutex mutex_;
  std::vector<Watcher*> watchers_;
  std::atomic<bool> stopping_{false};
  std::thread ticker_;
};

}  // namespace cascade::service
