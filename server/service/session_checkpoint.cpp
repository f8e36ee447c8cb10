// Session's checkpoints: taking one at a step boundary, and starting from one (SessionConfig::
// restore). Both on the solver thread.
#include <chrono>
#include <cmath>
#include <fstream>

#include "server/scenario/forcing_message.h"
#include "server/scenario/file_text.h"
#include "server/scenario/stage_setup.h"
#include "server/service/checkpoint_store.h"
#include "server/service/session.h"

namespace cascade::service {

namespace {

std::string read_text(const std::filesystem::path& path) {
  if (auto text = file_text(path)) return *text;
  throw std::runtime_error("cannot read " + path.string());
}

// The journal of the run so far replaces journal.jsonl; the file replaced (the commands after the
// checkpoint, which the restore undoes) stays beside it.
void replace_journal(const std::filesystem::path& path, const std::string& text) {
  if (std::filesystem::exists(path)) {
    for (unsigned n = 1;; ++n) {
      auto kept = path;
      kept += ".replaced-" + std::to_string(n);
      if (std::filesystem::exists(kept)) continue;
      std::filesystem::rename(path, kept);
      break;
    }
  }
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out.flush()) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace

std::filesystem::path Session::take_checkpoint(const std::string& caller) {
  const auto path = next_checkpoint_path(config_.directory);
  std::filesystem::create_directories(path.parent_path());
  v1::JournalEntry entry;
  entry.set_command("checkpoint");
  entry.set_caller(caller);
  entry.set_detail(checkpoint_name(config_.name, path));
  journal(entry);  // first, so that the checkpoint's journal ends with it
  Checkpoint checkpoint;
  checkpoint.simulation = config_.name;
  checkpoint.wall_time = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  checkpoint.spec = config_.spec;
  checkpoint.journal = read_text(journal_->path());
  checkpoint.engine = engine_->state();
  write_checkpoint(path, checkpoint);
  add_event("checkpoint", entry.detail(), caller);
  return path;
}

// The fork's engine is this one's clone (one copy of the state, made on the device, at the cost
// of a copy of the arrays to this simulation's step; the fork lists its neighbours itself at its
// first step); the parent's journal
// names the fork first, so that the fork's journal, a copy of the parent's, ends with the entry
// that made it.
std::shared_ptr<RestoreSource> Session::take_fork(const std::string& fork_name, const std::string& caller) {
  v1::JournalEntry entry;
  entry.set_command("fork");
  entry.set_caller(caller);
  entry.set_detail(fork_name);
  journal(entry);
  auto source = std::make_shared<RestoreSource>();
  source->checkpoint_name = config_.name + " at step " + std::to_string(engine_->step_count());
  source->checkpoint.journal = read_text(journal_->path());
  source->engine = engine_->clone();
  {
    std::lock_guard lock(mutex_);
    source->fork = ForkHistory{events_,         probe_samples_, *cascade_events_, next_probe_time_, kinetic_energy_,
                               max_soil_speed_, pore_water_,    forcing_,         rain_};
  }
  add_event("fork", fork_name, caller);
  return source;
}

void Session::restore() {
  RestoreSource& source = *restore_source_;
  try {
    const auto journal_path = config_.directory / "journal.jsonl";
    replace_journal(journal_path, source.checkpoint.journal);
    journal_ = std::make_unique<JournalWriter>(journal_path);
    // The steering of the case's rain so far (a steered intensity, a factor), as advance() goes on:
    // a fork's is its parent's; a checkpoint's is in its journal.
    if (source.fork) rain_ = source.fork->rain;
    else
      for (const auto& entry : read_journal(journal_path))
        if (entry.command() == "update_forcing")
          rain_.steer({entry.update_mask().begin(), entry.update_mask().end()}, entry.new_forcing());
    if (source.engine) {  // a fork: the parent's clone
      engine_ = std::move(source.engine);
    } else {
      engine_ = make_case_engine(config_.spec, config_.engine, *config_.particles, config_.make_engine);
      engine_->restore(source.checkpoint.engine);
    }
    probes_ = std::make_unique<ProbeSampler>(config_.spec, config_.engine.h,
                                             config_.engine.water_density * std::pow(config_.engine.dp, config_.engine.dimensions));
    cascade_events_ = source.fork ? std::make_unique<CascadeEventDetector>(source.fork->cascade_events)
                                  : std::make_unique<CascadeEventDetector>(config_.spec, config_.engine.h, probes_->names());
    if (source.fork) {
      next_probe_time_ = source.fork->next_probe_time;
      kinetic_energy_ = source.fork->kinetic_energy, max_soil_speed_ = source.fork->max_soil_speed;
      pore_water_ = source.fork->pore_water;
    }
    v1::JournalEntry entry;
    entry.set_command(source.fork ? "forked_from" : "restore");
    entry.set_caller(config_.caller);
    entry.set_detail(source.checkpoint_name);
    journal(std::move(entry));
    lost_particles_ = engine_->lost_particles();
    {
      std::lock_guard lock(mutex_);
      forcing_ = forcing_now();
    }
    // A fork has its parent's samples of this very state; a restored one samples it (a frame
    // copy, about a second at 10^6 particles).
    if (!source.fork) sample_outputs(true);
    add_event("state", std::string("paused (") + (source.fork ? "forked from " : "restored from ") + source.checkpoint_name + ")",
              config_.caller);
  } catch (const std::exception& e) {
    engine_.reset();
    stop_running(v1::Simulation::FAILED, std::string("restore failed: ") + e.what());
  }
  restore_source_.reset();  // the engine has the state: no second copy for the session's life
  publish_status();
}

}  // namespace cascade::service
