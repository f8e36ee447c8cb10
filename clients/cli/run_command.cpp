#include "clients/cli/run_command.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "clients/cli/progress.h"
#include "server/core/engine.h"
#include "server/core/free_cores.h"
#include "server/core/partition.h"
#include "server/parallel/launched_processes.h"
#include "server/parallel/measured_transport.h"
#include "server/io/hdf5_writer.h"
#include "server/io/journal.h"
#include "server/io/probe_csv_writer.h"
#include "server/io/probe_sampler.h"
#include "server/io/run_summary.h"
#include "server/io/sample_parts.h"
#include "server/io/snapshot_writer.h"
#include "server/io/split_fields_writer.h"
#include "server/io/vtk_writer.h"
#include "server/scenario/cascade_events.h"
#include "server/scenario/case_error.h"
#include "server/scenario/case_loader.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/forcing_message.h"
#include "server/scenario/output_schedule.h"
#include "server/scenario/particle_builder.h"
#include "server/scenario/plausible_ranges.h"
#include "server/scenario/rain_series.h"
#include "server/scenario/soil_setup.h"
#include "server/scenario/stage_setup.h"
#if defined(CASCADE_HAVE_MPI)
#include "server/parallel/distributed_engine.h"
#include "server/parallel/mpi_transport.h"
#endif

namespace cascade::cli {

namespace {

std::atomic<int> g_signal{0};

extern "C" void on_signal(int signal) { g_signal.store(signal); }

struct RunOptions {
  std::string case_path;
  std::filesystem::path out_dir;
  std::vector<CaseOverride> overrides;
  std::optional<double> until;
  std::filesystem::path replay;  // a journal whose forcing changes and stage hand-overs the run repeats
  int threads = 0;
  Precision precision = kBuildPrecision;
};

[[noreturn]] void usage_error(const std::string& message) { throw std::invalid_argument(message); }

double parse_number(const std::string& option, const std::string& text) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used != text.size()) throw std::invalid_argument("trailing characters");
    return v;
  } catch (const std::exception&) {
    usage_error(option + " needs a number, got '" + text + "'");
  }
}

RunOptions parse_options(const std::vector<std::string>& args) {
  RunOptions o;
  for (std::size_t k = 0; k < args.size(); ++k) {
    const std::string& a = args[k];
    auto value = [&]() -> const std::string& {
      if (k + 1 >= args.size()) usage_error(a + " needs a value");
      return args[++k];
    };
    if (a == "--out") o.out_dir = value();
    else if (a == "--set") o.overrides.push_back(parse_override(value()));
    else if (a == "--replay") o.replay = value();
    else if (a == "--until") {
      const double t = parse_number(a, value());
      if (!(t > 0)) usage_error("--until must be a positive time in seconds");
      o.until = t;
    } else if (a == "--threads") {
      const double n = parse_number(a, value());
      if (!(n >= 1 && n <= 1024 && n == std::floor(n))) usage_error("--threads must be a whole number from 1 to 1024");
      o.threads = int(n);
    } else if (a == "--precision") {
      const std::string& p = value();
      if (p == "float") o.precision = Precision::single_precision;
      else if (p == "double") o.precision = Precision::double_precision;
      else usage_error("--precision must be float or double, not '" + p + "'");
    } else if (!a.empty() && a[0] == '-') usage_error("unknown option '" + a + "'");
    else if (o.case_path.empty()) o.case_path = a;
    else usage_error("unexpected argument '" + a + "' (one case file only)");
  }
  if (o.case_path.empty()) usage_error("no case file given");
  if (o.out_dir.empty()) usage_error("--out DIR is required");
  return o;
}

const char* precision_name(Precision p) { return p == Precision::single_precision ? "float" : "double"; }

// Writes frames (with their PNG snapshots) and probes at their intervals. Frames every
// `output.interval`, probes every `output.probe_interval`, both also at the start and at the end
// of the run.
//
// In a run split over processes (`transport`), nothing is gathered for fields.h5 or the probes:
// each process writes its block of rows (in id order) of every dataset that process 0 lays out in
// fields.h5 (split_fields_writer.h), and sends process 0 the parts of the probes and events of its own
// particles (a few numbers per probe: sample_parts.h), which combines them. VTK files and snapshots, drawn by process 0, gather the frame there
// (Engine::frame_at_process_0). Whether every process could write is agreed on by all, so that a
// failed write stops every process.
class Outputs {
 public:
  Outputs(const v1::ScenarioSpec& spec, const std::filesystem::path& dir, double h, double mass,
          Transport* transport = nullptr)
      : spec_(spec),
        mass_(mass),
        sampler_(spec, h, mass),
        frame_interval_(stage_frame_interval(spec, 0)),
        probe_interval_(stage_probe_interval(spec, 0)),
        events_(spec, h, sampler_.names()),
        transport_(transport),
        fields_path_(dir / "fields.h5"),
        write_fields_(!spec.output().has_hdf5() || spec.output().hdf5()),
        gather_frames_(!transport_ || spec.output().vtk() || spec.output().snapshots_size() > 0) {
    if (transport_ && transport_->process() != 0) return;
    std::filesystem::create_directories(dir);
    if (write_fields_) hdf5_ = std::make_unique<Hdf5FieldWriter>(fields_path_);
    if (spec.output().vtk()) vtk_ = std::make_unique<VtkSeriesWriter>(dir / "vtk");
    probes_ = std::make_unique<ProbeCsvWriter>(dir / "probes.csv", sampler_.names());
    snapshots_ = std::make_unique<SnapshotWriter>(spec, dir / "snapshots");
  }

  // A new stage: its own intervals, counted from now.
  void enter_stage(int stage, double t) {
    frame_interval_ = stage_frame_interval(spec_, stage);
    probe_interval_ = stage_probe_interval(spec_, stage);
    next_frame_ = t + frame_interval_;
    next_probe_ = t + probe_interval_;
  }

  // `force` (the start and the end of the run) writes each output unless it already holds this time.
  // Returns the cascade's events (cascade_events.h) that fire at this probe sample.
  std::vector<CascadeEvent> observe(const Engine& engine, bool force) {
    const double t = engine.time();
    const double frame_slack = 1e-12 * frame_interval_, probe_slack = 1e-12 * probe_interval_;
    const bool frame_due = force ? t != last_frame_time_ : t >= next_frame_ - frame_slack;
    const bool probe_due = force ? t != last_probe_time_ : t >= next_probe_ - probe_slack;
    if (!frame_due && !probe_due) return {};
    const auto started = std::chrono::steady_clock::now();
    std::vector<CascadeEvent> fired;
    std::string failure;
    const bool gather = frame_due && gather_frames_;
    FieldFrame frame;  // the whole run's, on process 0
    if (gather) frame = engine.frame_at_process_0();
    if (probe_due) {
      fired = sample_probes(engine, gather && !transport_ ? &frame : nullptr, failure);
      next_probe_ = next_due_time(next_probe_, t, probe_interval_);
      last_probe_time_ = t;
    }
    if (frame_due) {
      if (transport_ && write_fields_) {
        const std::string written = write_split_frame(*transport_, hdf5_.get(), fields_path_, engine.frame_block(),
                                                      engine.particle_count());
        if (failure.empty()) failure = written;
      }
      try {
        if (hdf5_ && !transport_) hdf5_->write(frame);
        if (vtk_) vtk_->write(frame);
        if (snapshots_ && gather) snapshots_->write(frame);
      } catch (const std::exception& e) {
        if (!transport_) throw;
        if (failure.empty()) failure = e.what();
      }
      next_frame_ = next_due_time(next_frame_, t, frame_interval_);
      last_frame_time_ = t;
      ++frames_;
    }
    if (transport_ && transport_->maximum(failure.empty() ? 0.0 : 1.0) > 0)
      throw std::runtime_error(failure.empty() ? "another process could not write its outputs" : failure);
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return fired;
  }

  std::uint64_t frames() const { return frames_; }
  double seconds() const { return seconds_; }  // in observe: taking the frames, sampling, writing

 private:
  // The probes' row and the events that fire, from every process's part of them
  // (sample_parts.h). `whole`: the whole run's frame, where one process has taken it already.
  std::vector<CascadeEvent> sample_probes(const Engine& engine, const FieldFrame* whole, std::string& failure) {
    const double ponding = engine.forcing().ponding_pressure;
    const Engine::SamplePart part = [&](const FieldFrame& local, const std::vector<char>& owned) {
      return sample_part(sampler_, events_, mass_, ponding, true, local, owned);
    };
    try {
      const std::vector<std::vector<char>> parts =
          whole ? std::vector<std::vector<char>>{part(*whole, owned_rows(*whole, 0))}
                : engine.parts_at_process_0(part, sample_request(true));
      if (transport_ && transport_->process() != 0) return {};
      const OutputSample sample = combine_sample_parts(sampler_, true, parts);
      if (probes_) probes_->write_row(engine.time(), sample.probe_values);
      return events_.observe(sample.event_parts, sample.probe_values, ponding);
    } catch (const std::exception& e) {
      if (!transport_) throw;
      if (failure.empty()) failure = e.what();
      return {};
    }
  }

  const v1::ScenarioSpec& spec_;
  double mass_;  // of a particle, for the probes' volumes and the energy
  ProbeSampler sampler_;
  double frame_interval_, probe_interval_;
  double next_frame_ = 0, next_probe_ = 0, last_frame_time_ = -1, last_probe_time_ = -1;
  std::unique_ptr<Hdf5FieldWriter> hdf5_;
  std::unique_ptr<VtkSeriesWriter> vtk_;
  std::unique_ptr<ProbeCsvWriter> probes_;
  std::unique_ptr<SnapshotWriter> snapshots_;
  CascadeEventDetector events_;
  Transport* transport_;
  std::filesystem::path fields_path_;
  bool write_fields_;   // fields.h5
  bool gather_frames_;  // one process, or VTK files or snapshots of a split run
  std::uint64_t frames_ = 0;
  double seconds_ = 0;
};

std::string format_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

// A forcing change of the engine, recorded in run.json.
void set_forcing(Engine& engine, const HydraulicForcing& next, const std::string& what, RunSummary& summary) {
  summary.events.push_back({engine.time(), engine.step_count(), "forcing", what});
  engine.set_forcing(next);
}

// The case's rain at the engine's time (a change applies at a step boundary), as a replayed
// journal has steered it (rain_series.h).
void apply_case_rain(const v1::ScenarioSpec& spec, const CaseRain& rain, Engine& engine, RunSummary& summary) {
  const auto due = rain.due(spec, engine);
  if (!due) return;
  HydraulicForcing next = engine.forcing();  // keeps whatever else the engine holds
  next.rainfall_intensity = *due;
  set_forcing(engine, next,
              "rainfall_intensity " + format_number(engine.forcing().rainfall_intensity) + " -> " +
                  format_number(*due) + " m/s" + rain_series_origin(spec),
              summary);
}

// The steering of a run's journal (forcing changes and the operator's stage hand-overs), each
// applied before the step that followed it there, in the journal's order: the same case and build
// then give the same bits.
class JournalReplay {
 public:
  // Refuses, before the first step, a journal written for another case and forcing that
  // UpdateForcing would have refused (a hand-edited NaN rain was applied): the ranges of
  // plausible_ranges.h, as for a case file and a request.
  JournalReplay(const std::filesystem::path& path, const std::string& case_name) {
    for (auto& entry : read_journal(path)) {
      const std::string where = path.filename().string() + ", step " + std::to_string(entry.step()) + ": ";
      if (entry.command() == "create" && entry.case_name() != case_name)
        throw std::runtime_error(where + "the journal is of case '" + entry.case_name() + "', not '" + case_name + "'");
      if (entry.command() == "update_forcing") check_forcing(where, entry);
      if (entry.command() == "update_forcing" || entry.command() == "advance_stage") changes_.push_back(std::move(entry));
    }
  }

  // Applies the changes due at the engine's step, as the server did: a factor of the rain sets the
  // intensity at once (Session::apply_forcing_change). A hand-over leaves its stage change in the
  // engine (Engine::take_stage_changes).
  void apply(const v1::ScenarioSpec& spec, Engine& engine, int dimensions, RunSummary& summary) {
    while (next_ < changes_.size() && changes_[next_].step() <= engine.step_count()) {
      const auto& entry = changes_[next_++];
      if (entry.step() < engine.step_count())
        throw std::runtime_error("journal change at step " + std::to_string(entry.step()) +
                                 " lies before the replay's step " + std::to_string(engine.step_count()));
      if (entry.command() == "advance_stage") {
        try {
          engine.advance_stage(entry.caller());
        } catch (const std::invalid_argument& e) {
          throw std::runtime_error("journal's advance_stage at step " + std::to_string(entry.step()) + ": " + e.what());
        }
        continue;
      }
      const std::vector<std::string> mask(entry.update_mask().begin(), entry.update_mask().end());
      HydraulicForcing next = updated_forcing(engine.forcing(), entry.new_forcing(), mask, dimensions);
      rain_.steer(mask, entry.new_forcing());
      if (const auto due = rain_.due(spec, engine.time(), next.rainfall_intensity)) next.rainfall_intensity = *due;
      set_forcing(engine, next, "replayed " + join(mask) + " from the journal", summary);
    }
  }

  const CaseRain& rain() const { return rain_; }

 private:
  static void check_forcing(const std::string& where, const v1::JournalEntry& entry) {
    const v1::Forcing& f = entry.new_forcing();
    const auto check = [&](const std::string& field, const PlausibleRange& range, double value) {
      if (const auto message = implausible(range, value)) throw std::runtime_error(where + field + " " + *message);
    };
    for (const auto& field : entry.update_mask()) {
      if (field == "rainfall.intensity") check(field, kRainfallIntensity, f.rainfall().intensity());
      if (field == "rainfall.factor") check(field, kRainFactor, f.rainfall().factor());
      if (field == "ponding.p_max") check(field, kSurfacePressure, f.ponding().p_max());
      if (field == "ponding.p_min" && f.ponding().has_p_min()) check(field, kSurfacePressure, f.ponding().p_min());
    }
  }

  static std::string join(const std::vector<std::string>& fields) {
    std::string text;
    for (const auto& f : fields) text += (text.empty() ? "" : ", ") + f;
    return text;
  }

  std::vector<v1::JournalEntry> changes_;
  std::size_t next_ = 0;
  CaseRain rain_;
};

}  // namespace

int run_command(const std::vector<std::string>& args) {
  RunOptions options;
  v1::ScenarioSpec spec;
  ParticleSet set;
  try {
    options = parse_options(args);
    spec = load_case_file(options.case_path, options.overrides);
    try {
      set = build_particle_set(spec);
    } catch (const CaseError& e) {
      // The particle builder's errors name the key but neither file nor line: name the file.
      std::fprintf(stderr, "cascade run: %s: %s\n", options.case_path.c_str(), e.what());
      return 2;
    }
  } catch (const CaseError& e) {
    std::fprintf(stderr, "cascade run: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cascade run: %s\n", e.what());
    return 2;
  }
  // Launched by mpirun as several processes: the run is split over them (issue 17,
  // server/parallel/); process 0 writes the outputs and the console.
  const int processes = launched_processes();
#if defined(CASCADE_HAVE_MPI)
  std::unique_ptr<MpiSession> mpi;
  std::unique_ptr<MpiTransport> transport;
  std::unique_ptr<MeasuredTransport> meter;  // the steps' exchanges, for run.json
  if (processes > 1) {
    mpi = std::make_unique<MpiSession>(nullptr, nullptr);
    transport = std::make_unique<MpiTransport>();
    meter = std::make_unique<MeasuredTransport>(*transport);
  }
  Transport* const split = meter.get();
#else
  if (processes > 1) {
    std::fprintf(stderr, "cascade run: launched as %d processes, but this build has no MPI (configure with -DCASCADE_MPI=ON)\n",
                 processes);
    return 2;
  }
  Transport* const split = nullptr;
  MeasuredTransport* const meter = nullptr;
#endif
  const bool root = !split || split->process() == 0;
  std::FILE* const log = root ? stderr : std::fopen("/dev/null", "w");
  if (!log) return 1;

  if (options.threads > 0) omp_set_num_threads(options.threads);
  // Without --threads, the team takes the cores that other processes leave free, measured again
  // about once a second while the run steps (free_cores.h).
  const CoreShare::Running running;
  int team = omp_get_max_threads();
  auto size_team = [&] {
    if (options.threads > 0) return;
    const int threads = CoreShare::of_this_process().threads_per_simulation();
    if (threads != team) omp_set_num_threads(team = threads);
  };
  size_team();

  RunSummary summary;
  summary.case_name = spec.name();
  summary.precision = precision_name(options.precision);
  summary.processes = processes;
  const auto& particles = set.particles;
  summary.particles = {particles.size(), particles.count(Phase::water), particles.count(Phase::soil),
                       particles.count(Phase::boundary)};
  if (spec.terrain().has_grid()) {
    const v1::TerrainGrid& grid = spec.terrain().grid();
    summary.terrain.present = true;
    for (int a = 0; a < grid.origin_size() && a < 2; ++a) summary.terrain.origin[a] = grid.origin(a);
    summary.terrain.crs = grid.crs();
    summary.terrain.surface = grid.surface_source();
    summary.terrain.base = grid.base_source();
    for (const v1::MapPoint& p : grid.section()) summary.terrain.section.push_back({p.x(), p.y()});
  }
  const double end_time = options.until ? *options.until : spec.end_time();
  const auto json_path = options.out_dir / "run.json";

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<Engine> engine;
  int exit_code = 0;
  try {
    const EngineConfig config = engine_config(spec, particles, options.precision);
    EngineMaker make = &make_engine;
#if defined(CASCADE_HAVE_MPI)
    if (split)
      make = [split](const EngineConfig& c, const HostParticles& p) -> std::unique_ptr<Engine> {
        return std::make_unique<DistributedEngine>(c, p, *split);
      };
#endif
    engine = make_case_engine(spec, config, particles, make);
    Outputs outputs(spec, options.out_dir, config.h, config.water_density * std::pow(config.dp, config.dimensions),
                    split);
#if defined(CASCADE_HAVE_MPI)
    if (split)
      std::fprintf(log, "cascade run: split over %d processes (mpirun): slabs along axis %d, halo %g m\n", processes,
                   slabs_for(config, particles, processes).axis, halo_width(config));
#endif
    std::fprintf(log,
                 "cascade run: %s, %zu particles (%zu water, %zu soil, %zu boundary), dp = %g m, h = %g m, "
                 "c0 = %.3f m/s, %s on %s with %d threads%s, until t = %g s\n",
                 spec.name().c_str(), particles.size(), std::size_t(summary.particles.water),
                 std::size_t(summary.particles.soil), std::size_t(summary.particles.boundary), config.dp, config.h,
                 config.sound_speed,
                 summary.precision.c_str(), engine->device_name(), omp_get_max_threads(),
                 options.threads > 0 ? "" : " (the cores that other processes leave free)", end_time);
    if (spec.has_initialisation()) {
      // Before t = 0, without outputs: the main stage and every output start at its end.
      std::fprintf(log, "cascade run: initialisation stage of %g s\n", spec.initialisation().duration());
      const std::uint64_t steps = run_initialisation(spec, *engine);
      summary.events.push_back({0.0, engine->step_count(), "initialisation",
                                "stage of " + format_number(spec.initialisation().duration()) + " s in " +
                                    std::to_string(steps) + " steps; clock and displacement restart at t = 0"});
    }
    std::optional<JournalReplay> replay;
    if (!options.replay.empty()) replay.emplace(options.replay, spec.name());
    const CaseRain unsteered;  // the case's rain as it is, without a journal
    Progress progress(end_time, log);
    const auto record = [&](const std::vector<CascadeEvent>& fired) {
      for (const CascadeEvent& e : fired) {
        std::fprintf(log, "\ncascade run: t = %g s, step %llu: %s: %s\n", engine->time(),
                     static_cast<unsigned long long>(engine->step_count()), e.kind.c_str(), e.message.c_str());
        summary.events.push_back({engine->time(), engine->step_count(), e.kind, e.message});
      }
    };
    // The stage switches since the last step: run.json's events, and every output at the switch.
    const auto record_stages = [&]() {
      for (const StageChange& c : engine->take_stage_changes()) {
        const std::string message = (c.from < 0 ? std::string("start: ") : c.from_name + " -> ") + c.to_name + ": " + c.reason;
        std::fprintf(log, "\ncascade run: t = %g s, step %llu: stage_changed: %s\n", c.time,
                     static_cast<unsigned long long>(c.step), message.c_str());
        summary.events.push_back({c.time, c.step, "stage_changed", message});
        outputs.enter_stage(c.to, c.time);
        record(outputs.observe(*engine, true));
      }
    };
    record_stages();
    record(outputs.observe(*engine, true));
    std::size_t lost = 0;
    while (engine->time() < end_time * (1 - 1e-12)) {
      size_team();
      // Split over processes, all stop at the same step when any was signalled.
      const int signal = split ? int(split->maximum(double(g_signal.load()))) : g_signal.load();
      if (signal != 0) {
        outputs.observe(*engine, true);
        throw SimulationFailure("interrupted by signal " + std::to_string(signal) + " at t = " +
                                std::to_string(engine->time()) + " s; outputs hold the run up to there");
      }
      if (replay) replay->apply(spec, *engine, config.dimensions, summary);
      record_stages();  // a replayed hand-over
      apply_case_rain(spec, replay ? replay->rain() : unsteered, *engine, summary);
      const double exchange_seconds = meter ? meter->seconds() : 0.0;
      const std::uint64_t exchange_bytes = meter ? meter->bytes_sent() : 0;
      engine->step();
      if (meter) {
        summary.exchange_seconds += meter->seconds() - exchange_seconds;
        summary.exchange_bytes += meter->bytes_sent() - exchange_bytes;
      }
      record_stages();
      record(outputs.observe(*engine, false));
      progress.update(engine->time(), engine->step_count(), engine->last_dt());
      if (engine->lost_particles() != lost) {
        summary.events.push_back({engine->time(), engine->step_count(), "particles_lost",
                                  std::to_string(engine->lost_particles() - lost) +
                                      " particles left the domain (" + std::to_string(engine->lost_particles()) +
                                      " in all)"});
        lost = engine->lost_particles();
      }
    }
    record(outputs.observe(*engine, true));
    summary.frames_written = outputs.frames(), summary.output_seconds = outputs.seconds();
    progress.finish(engine->time(), engine->step_count(), engine->last_dt());
    summary.status = RunSummary::Status::completed;
  } catch (const std::exception& e) {
    summary.status = RunSummary::Status::failed;
    summary.error = e.what();
    std::fprintf(split && !root ? stderr : log, "\ncascade run: %sfailed: %s\n",
                 split && !root ? ("process " + std::to_string(split->process()) + ": ").c_str() : "", e.what());
    exit_code = 1;
  }
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  LoadBalance balance;
  if (engine) {
    summary.sim_time = engine->time();
    summary.steps = engine->step_count();
    summary.lost_particles = engine->lost_particles();
    if (summary.particles.soil > 0) {
      const PoreWaterAccount account = engine->pore_water_account();
      summary.pore_water = {true, account.rain, account.walls, account.surface};
    }
    summary.bytes_per_particle = double(engine->device_bytes()) / double(std::max<std::size_t>(1, particles.size()));
#if defined(CASCADE_HAVE_MPI)
    if (const auto* distributed = dynamic_cast<const DistributedEngine*>(engine.get()))
      for (std::size_t held : distributed->share_sizes()) summary.process_particles.push_back(held);
#endif
    balance = engine->load_balance();
    summary.balance = {balance.last(), balance.mean(), balance.largest(), balance.rebuilds.size(),
                       balance.repartitions()};
    if (split) {  // the slowest process's time in the steps' exchanges, and every process's bytes
      summary.exchange_seconds = split->maximum(summary.exchange_seconds);
      summary.exchange_bytes = std::uint64_t(split->sum(double(summary.exchange_bytes)));
    }
    summary.particle_steps_per_second =
        summary.wall_seconds > 0 ? double(particles.size()) * double(summary.steps) / summary.wall_seconds : 0.0;
  }
  if (!root) return exit_code;
  try {
    std::filesystem::create_directories(options.out_dir);
    if (split) write_balance_csv(options.out_dir / "balance.csv", balance);
    write_run_json(json_path, summary);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cascade run: cannot write %s: %s\n", json_path.c_str(), e.what());
    return 1;
  }
  std::fprintf(stderr, "cascade run: %s: t = %g s, %llu steps, %.1f s wall, %.3g particle-steps/s; outputs in %s\n",
               exit_code == 0 ? "completed" : "failed", summary.sim_time, static_cast<unsigned long long>(summary.steps),
               summary.wall_seconds, summary.particle_steps_per_second, options.out_dir.c_str());
  return exit_code;
}

}  // namespace cascade::cli
