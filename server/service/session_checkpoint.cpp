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

void Session::restore() {
  const RestoreSource& source = *config_.restore;
  try {
    const auto journal_path = config_.directory / "journal.jsonl";
    replace_journal(journal_path, source.checkpoint.journal);
    journal_ = std::make_unique<JournalWriter>(journal_path);
    // A steered intensity replaced the case's rain series for the rest of the run (advance()).
    for (const auto& entry : read_journal(journal_path))
      for (const auto& field : entry.update_mask()) intensity_steered_ |= field == "rainfall.intensity";
    engine_ = make_case_engine(config_.spec, config_.engine, config_.particles, config_.make_engine);
    engine_->restore(source.checkpoint.engine);
    probes_ = std::make_unique<ProbeSampler>(config_.spec, config_.engine.h,
                                             config_.engine.water_density * std::pow(config_.engine.dp, config_.engine.dimensions));
    cascade_events_ = std::make_unique<CascadeEventDetector>(config_.spec, config_.engine.h, probes_->names());
    v1::JournalEntry entry;
    entry.set_command("restore");
    entry.set_caller(config_.caller);
    entry.set_detail(source.checkpoint_name);
    journal(std::move(entry));
    lost_particles_ = engine_->lost_particles();
    sample_outputs(true);
    add_event("state", "paused (restored from " + source.checkpoint_name + ")", config_.caller);
  } catch (const std::exception& e) {
    engine_.reset();
    stop_running(v1::Simulation::FAILED, std::string("restore failed: ") + e.what());
  }
  publish_status();
}

}  // namespace cascade::service
