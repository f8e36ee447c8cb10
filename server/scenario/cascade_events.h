// The moments of a rainfall-landslide-tsunami cascade (scenario.proto, CascadeEvents), detected on
// the frames the run samples its probes on: each criterion fires once, at the first sample that
// meets it. The runner writes the events to run.json, the server to its event list, journal and
// watch streams.
#pragma once

#include <string>
#include <vector>

#include "cascade/v1/scenario.pb.h"
#include "server/core/field_frame.h"

namespace cascade {

struct CascadeEvent {
  std::string kind;     // ponding_started, landslide_onset, water_impact, wave_at_gauge, overtopping
  std::string message;  // what met the criterion, with its numbers
};

class CascadeEventDetector {
 public:
  // `probe_names`: the order of the values that observe() is given (ProbeSampler::names()).
  CascadeEventDetector(const v1::ScenarioSpec& spec, double h, const std::vector<std::string>& probe_names);

  // The events that fire at this frame: `probe_values` sampled on it, `ponding_pressure` the
  // p_max in force (Eq. 39).
  std::vector<CascadeEvent> observe(const FieldFrame& frame, const std::vector<double>& probe_values,
                                    double ponding_pressure);

  bool enabled() const { return enabled_; }

 private:
  struct Gauge {
    std::string probe;
    int column;     // index into the probe values
    double rise;    // m above the first sample
    double first;   // the first sample (NaN until taken)
    bool fired = false;
  };
  struct Line {
    v1::Overtopping spec;
    bool fired = false;
  };

  bool ponding(const FieldFrame& frame, double ponding_pressure, std::string& message) const;
  bool landslide(const FieldFrame& frame, std::string& message) const;
  bool impact(const FieldFrame& frame, std::string& message) const;
  bool overtopped(const FieldFrame& frame, const v1::Overtopping& line, std::string& message) const;

  v1::CascadeEvents events_;
  int dimensions_;
  double dp_, h_;
  bool enabled_;
  bool ponding_fired_ = false, landslide_fired_ = false, impact_fired_ = false;
  std::vector<Gauge> gauges_;
  std::vector<Line> lines_;
};

}  // namespace cascade
