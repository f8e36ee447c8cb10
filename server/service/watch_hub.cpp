#include "server/service/watch_hub.h"

#include <algorithm>
#include <chrono>

namespace cascade::service {

namespace {

constexpr auto kTick = std::chrono::milliseconds(20);

double seconds_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

// Lives from WatchSimulation until OnDone. Only it calls Finish, and only once no write is in
// flight, so it is alive whenever the ticker acts on it.
class WatchHub::Watcher : public grpc::ServerWriteReactor<v1::WatchSimulationResponse> {
 public:
  enum class Action { none, write, finish };

  Watcher(WatchHub& hub, std::shared_ptr<Session> session, double interval)
      : hub_(hub), session_(std::move(session)), interval_(interval) {}

  // Under the hub's lock: decides this tick's action and prepares its response.
  Action decide(double now, bool server_stopping) {
    std::lock_guard lock(mutex_);
    if (finishing_ || writing_) return Action::none;
    if (cancelled_ || server_stopping) return finish(server_stopping ? grpc::Status(grpc::StatusCode::UNAVAILABLE, "server shutting down")
                                                                     : grpc::Status::CANCELLED);
    const auto events = session_->events(next_event_);
    if (!events.empty()) {
      response_.Clear();
      *response_.mutable_event() = events.front();
      ++next_event_;
      writing_ = true;
      return Action::write;
    }
    if (final_status_sent_) return finish(grpc::Status::OK);
    const bool stopped = session_->stopped();
    if (now - last_status_ >= interval_ || stopped) {
      response_.Clear();
      *response_.mutable_status() = session_->status();
      last_status_ = now;
      final_status_sent_ = stopped;
      writing_ = true;
      return Action::write;
    }
    return Action::none;
  }

  void act(Action action) {
    if (action == Action::write) StartWrite(&response_);
    if (action == Action::finish) Finish(final_);
  }

  void OnWriteDone(bool ok) override {
    std::unique_lock lock(mutex_);
    writing_ = false;
    if (ok) return;
    finishing_ = true;  // the client is gone
    lock.unlock();
    Finish(grpc::Status::CANCELLED);
  }
  void OnCancel() override {
    std::lock_guard lock(mutex_);
    cancelled_ = true;
  }
  void OnDone() override {
    hub_.remove(this);
    delete this;
  }

 private:
  Action finish(grpc::Status status) {
    finishing_ = true;
    final_ = std::move(status);
    return Action::finish;
  }

  WatchHub& hub_;
  const std::shared_ptr<Session> session_;
  const double interval_;
  std::mutex mutex_;
  bool writing_ = false, finishing_ = false, cancelled_ = false, final_status_sent_ = false;
  double last_status_ = -1e300;
  std::size_t next_event_ = 0;
  v1::WatchSimulationResponse response_;
  grpc::Status final_;
};

WatchHub::WatchHub() : ticker_([this] { tick_loop(); }) {}

WatchHub::~WatchHub() {
  shutdown();
  ticker_.join();
}

grpc::ServerWriteReactor<v1::WatchSimulationResponse>* WatchHub::watch(std::shared_ptr<Session> session,
                                                                        double interval) {
  auto* watcher = new Watcher(*this, std::move(session), interval);
  add(watcher);
  return watcher;
}

void WatchHub::add(Watcher* watcher) {
  std::lock_guard lock(mutex_);
  watchers_.push_back(watcher);
}

void WatchHub::remove(Watcher* watcher) {
  std::lock_guard lock(mutex_);
  watchers_.erase(std::remove(watchers_.begin(), watchers_.end(), watcher), watchers_.end());
}

void WatchHub::tick_loop() {
  for (;;) {
    const bool stopping = stopping_.load();
    std::vector<std::pair<Watcher*, Watcher::Action>> actions;
    {
      std::lock_guard lock(mutex_);
      if (stopping && watchers_.empty()) return;
      const double now = seconds_now();
      for (auto* watcher : watchers_) {
        const auto action = watcher->decide(now, stopping);
        if (action != Watcher::Action::none) actions.emplace_back(watcher, action);
      }
    }
    // Outside the lock: a reaction to these (OnDone → remove) takes it.
    for (auto& [watcher, action] : actions) watcher->act(action);
    std::this_thread::sleep_for(kTick);
  }
}

}  // namespace cascade::service
