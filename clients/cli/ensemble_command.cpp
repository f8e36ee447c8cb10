#include "clients/cli/ensemble_command.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>

#include "server/scenario/case_units.h"
#include "server/scenario/file_text.h"
#include "server/scenario/hyetograph.h"

namespace cascade::cli {

namespace {

// One what-if branch: how its rain differs, and what the fork returned.
struct Branch {
  std::string label;                           // "rain x2", or the hyetograph's file name
  std::optional<double> factor;                // rainfall.factor
  std::vector<v1::RainfallPoint> hyetograph;   // in SI, times as the case's clock
  v1::Simulation simulation;                   // the fork, then its state at the end
};

// What a branch's run showed: its events' times (NaN: never) and the wave at each gauge.
struct Outcome {
  double ponding = NAN, onset = NAN, impact = NAN, overtopping = NAN;
  std::map<std::string, std::pair<double, double>> gauges;  // probe: arrival time, largest rise (m)
};

const CaseUnit& unit_option(const Remote& remote, const std::string& key, const char* fallback) {
  const std::string name = remote.args().option(key, fallback);
  const CaseUnit* unit = find_case_unit(name);
  if (!unit) throw UsageError(key + ": unknown unit '" + name + "'");
  return *unit;
}

std::vector<Branch> branches_of(const Remote& remote) {
  std::vector<Branch> branches;
  const std::string factors = remote.args().option("--rain-factors");
  const std::vector<std::string> files = remote.args().all("--hyetograph");
  if (factors.empty() && files.empty()) throw UsageError("ensemble needs --rain-factors F,F,... or --hyetograph FILE... (or both)");
  for (double f : factors.empty() ? std::vector<double>{} : number_list("--rain-factors", factors)) {
    char label[40];
    std::snprintf(label, sizeof label, "rain x%g", f);
    branches.push_back({label, f, {}, {}});
  }
  const CaseUnit& time_unit = unit_option(remote, "--time-unit", "s");
  const CaseUnit& intensity_unit = unit_option(remote, "--intensity-unit", "m/s");
  if (std::string(time_unit.si) != "s") throw UsageError("--time-unit: '" + std::string(time_unit.name) + "' is not a time");
  if (std::string(intensity_unit.si) != "m/s")
    throw UsageError("--intensity-unit: '" + std::string(intensity_unit.name) + "' is not a rain intensity");
  for (const auto& file : files) {
    const auto text = file_text(file);
    if (!text) throw UsageError("--hyetograph: cannot read " + file);
    try {
      branches.push_back({std::filesystem::path(file).filename().string(), {}, read_hyetograph(*text, time_unit, intensity_unit), {}});
    } catch (const HyetographError& e) {
      throw UsageError("--hyetograph " + file + ", line " + std::to_string(e.line()) + ": " + e.what());
    }
  }
  if (branches.size() < 1 || branches.size() > 32) throw UsageError("ensemble takes 1 to 32 branches");
  return branches;
}

// The fork of `parent` for one branch: the factor at the fork, or the hyetograph's intensity at the
// fork's time there and each later row scheduled at its time.
bool fork_branch(Remote& remote, const v1::Simulation& parent, Branch& branch) {
  using Stub = v1::SimulationService::Stub;
  v1::ForkSimulationRequest request;
  request.set_name(parent.name());
  const double t0 = parent.status().time();
  if (branch.factor) {
    request.mutable_forcing()->mutable_rainfall()->set_factor(*branch.factor);
  } else {
    double at_fork = 0;  // before the first row: no rain
    for (const auto& row : branch.hyetograph)
      if (row.time() <= t0) at_fork = row.intensity();
    request.mutable_forcing()->mutable_rainfall()->set_intensity(at_fork);
  }
  request.mutable_update_mask()->add_paths(branch.factor ? "rainfall.factor" : "rainfall.intensity");
  return call(remote, &Stub::ForkSimulation, request, branch.simulation);
}

// A branch to `end`: a hyetograph's later rows each applied at the first step boundary at or
// after its time (as a scheduled UpdateForcing would be), by running to that time and then
// changing the rain, so that nothing depends on when a request arrives.
// With `stop`, each run ends early STOP seconds after the branch's first event of its kind (the
// server's RunSimulationUntil.stop_after_event), and the branch goes no further.
void run_branch(Remote& remote, Branch& branch, double end, const std::optional<v1::EventStop>& stop) {
  using Stub = v1::SimulationService::Stub;
  const auto run_until = [&](double time) {
    if (!(time > branch.simulation.status().time())) return true;
    v1::RunSimulationUntilRequest request;
    request.set_name(branch.simulation.name());
    request.set_time(time);
    if (stop) *request.mutable_stop_after_event() = *stop;
    return call(remote, &Stub::RunSimulationUntil, request, branch.simulation) &&
           branch.simulation.state() == v1::Simulation::PAUSED && branch.simulation.status().time() >= time;
  };
  for (const auto& row : branch.hyetograph) {
    if (row.time() <= branch.simulation.status().time()) continue;
    if (row.time() >= end) break;
    if (!run_until(row.time())) return;  // ended, failed, or stopped after its event
    v1::UpdateForcingRequest change;
    change.set_name(branch.simulation.name());
    change.mutable_forcing()->mutable_rainfall()->set_intensity(row.intensity());
    change.mutable_update_mask()->add_paths("rainfall.intensity");
    v1::UpdateForcingResponse reply;
    if (!call(remote, &Stub::UpdateForcing, change, reply)) return;
  }
  run_until(end);
}

Outcome outcome_of(Remote& remote, const std::string& name) {
  using Stub = v1::SimulationService::Stub;
  Outcome o;
  v1::ListEventsRequest events_request;
  events_request.set_name(name);
  events_request.set_since_time(-INFINITY);
  v1::ListEventsResponse events;
  if (!call(remote, &Stub::ListEvents, events_request, events)) return o;
  for (const auto& e : events.events()) {
    if (e.kind() == "ponding_started" && std::isnan(o.ponding)) o.ponding = e.time();
    if (e.kind() == "landslide_onset" && std::isnan(o.onset)) o.onset = e.time();
    if (e.kind() == "water_impact" && std::isnan(o.impact)) o.impact = e.time();
    if (e.kind() == "overtopping" && std::isnan(o.overtopping)) o.overtopping = e.time();
    if (e.kind() == "wave_at_gauge") o.gauges[e.message().substr(0, e.message().find(':'))] = {e.time(), NAN};
  }
  v1::ListProbesRequest probes_request;
  probes_request.set_name(name);
  probes_request.set_since_time(-INFINITY);
  v1::ListProbesResponse probes;
  if (!call(remote, &Stub::ListProbes, probes_request, probes) || probes.samples().empty()) return o;
  for (auto& [probe, gauge] : o.gauges) {
    const auto k = std::find(probes.probe_names().begin(), probes.probe_names().end(), probe) - probes.probe_names().begin();
    if (k >= probes.probe_names_size()) continue;
    // The rise over the first sample, the still water level (as the wave_at_gauge event measures it).
    const double first = probes.samples(0).values(int(k));
    double highest = first;
    for (const auto& s : probes.samples()) highest = std::max(highest, s.values(int(k)));
    gauge.second = highest - first;
  }
  return o;
}

std::string cell(double v) {
  if (std::isnan(v)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

}  // namespace

int ensemble(Remote& remote) {
  using Stub = v1::SimulationService::Stub;
  std::vector<Branch> branches = branches_of(remote);
  v1::GetSimulationRequest get;
  get.set_name(remote.simulation());
  v1::Simulation parent;
  if (!call(remote, &Stub::GetSimulation, get, parent)) return 1;
  // Every branch from the same step: a running parent pauses for the forks.
  const bool was_running = parent.state() == v1::Simulation::RUNNING;
  if (was_running) {
    v1::PauseSimulationRequest pause;
    pause.set_name(parent.name());
    if (!call(remote, &Stub::PauseSimulation, pause, parent)) return 1;
  }
  bool forked = true;
  for (auto& b : branches) forked = forked && fork_branch(remote, parent, b);
  if (was_running) {
    v1::ResumeSimulationRequest resume;
    resume.set_name(parent.name());
    v1::Simulation ignored;
    if (!call(remote, &Stub::ResumeSimulation, resume, ignored)) return 1;
  }
  if (!forked) return 1;
  const std::string until = remote.args().option("--until");
  const double end = until.empty() ? parent.end_time() : number("--until", until);
  std::fprintf(stderr, "cascade ensemble: %zu branches of %s from t = %.9g s (step %llu) to t = %.9g s\n", branches.size(),
               parent.name().c_str(), parent.status().time(), static_cast<unsigned long long>(parent.status().step()), end);

  // Side by side: one RunSimulationUntil per branch, each on its own thread (the server shares the
  // cores among the simulations that step).
  std::vector<std::thread> runs;
  const std::optional<v1::EventStop> stop = event_stop(remote.args());
  for (auto& b : branches) runs.emplace_back([&remote, &b, end, &stop] { run_branch(remote, b, end, stop); });
  for (auto& t : runs) t.join();

  std::vector<Outcome> outcomes;
  std::vector<std::string> gauges;
  for (auto& b : branches) {
    v1::GetSimulationRequest request;
    request.set_name(b.simulation.name());
    call(remote, &Stub::GetSimulation, request, b.simulation);
    outcomes.push_back(outcome_of(remote, b.simulation.name()));
    for (const auto& [probe, gauge] : outcomes.back().gauges)
      if (std::find(gauges.begin(), gauges.end(), probe) == gauges.end()) gauges.push_back(probe);
  }
  std::vector<std::string> header = {"branch", "simulation", "state", "time_s", "ponding_s", "landslide_onset_s",
                                     "landslide_onset_h", "water_impact_s", "overtopping_s"};
  for (const auto& g : gauges) header.insert(header.end(), {g + "_arrival_s", g + "_rise_m"});
  std::vector<std::vector<std::string>> rows;
  for (std::size_t k = 0; k < branches.size(); ++k) {
    const Outcome& o = outcomes[k];
    const v1::Simulation& s = branches[k].simulation;
    std::vector<std::string> row = {branches[k].label, s.name(),      state_name(s.state()), cell(s.status().time()),
                                    cell(o.ponding),   cell(o.onset), cell(o.onset / 3600),  cell(o.impact),
                                    cell(o.overtopping)};
    for (const auto& g : gauges) {
      const auto found = o.gauges.find(g);
      row.push_back(cell(found == o.gauges.end() ? NAN : found->second.first));
      row.push_back(cell(found == o.gauges.end() ? NAN : found->second.second));
    }
    rows.push_back(std::move(row));
  }

  if (const std::string out = remote.args().option("--out"); !out.empty()) {
    std::ofstream csv(out);
    for (std::size_t c = 0; c < header.size(); ++c) csv << (c ? "," : "") << header[c];
    csv << '\n';
    for (const auto& row : rows) {
      for (std::size_t c = 0; c < row.size(); ++c) csv << (c ? "," : "") << row[c];
      csv << '\n';
    }
    if (!csv.flush()) throw std::runtime_error("cannot write " + out);
  }
  if (remote.args().json) {
    std::string text = "{\"parent\": \"" + parent.name() + "\", \"fork_time\": " + cell(parent.status().time()) +
                       ", \"branches\": [";
    for (std::size_t r = 0; r < rows.size(); ++r) {
      text += r ? ", {" : "{";
      for (std::size_t c = 0; c < header.size(); ++c) {
        const bool numeric = c >= 3;
        const std::string value = numeric ? (rows[r][c] == "-" ? "null" : rows[r][c]) : "\"" + rows[r][c] + "\"";
        text += (c ? ", \"" : "\"") + header[c] + "\": " + value;
      }
      text += "}";
    }
    std::puts((text + "]}").c_str());
    return 0;
  }
  std::vector<std::size_t> width(header.size());
  for (std::size_t c = 0; c < header.size(); ++c) {
    width[c] = header[c].size();
    for (const auto& row : rows) width[c] = std::max(width[c], row[c].size());
  }
  rows.insert(rows.begin(), header);
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < row.size(); ++c)
      std::printf(c + 1 < row.size() ? "%-*s  " : "%-*s\n", c + 1 < row.size() ? int(width[c]) : 0, row[c].c_str());
  }
  return 0;
}

}  // namespace cascade::cli
