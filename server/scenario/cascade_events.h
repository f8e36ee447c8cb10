// The moments of a rainfall-landslide-tsunami cascade (scenario.proto, CascadeEvents), detected on
// the frames the run samples its probes on: each criterion fires once, at the first sample that
// meets it. The runner writes the events to run.json, the server to its event list, journal and
// watch streams.
// A run split over processes finds them without gathering its particles: each process takes the
// part of its own particles (part), a few numbers, and process 0 decides on the parts of all
// (observe). A particle an event names is the one of lowest id, as one process names it.
#pragma once

#include <limits>
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

  // A particle that meets a criterion: the one of lowest id among those that do.
  struct Found {
    double id = std::numeric_limits<double>::infinity();  // none
    double position[3] = {0, 0, 0};
    double speed = 0;  // the soil's, of an impact
  };
  // What some particles show of each criterion.
  struct Part {
    double ponding_count = 0;  // free-surface soil particles at p_max
    Found ponding;
    double slide_volume = 0, slide_fastest = 0;  // failed soil moving faster than the onset's speed
    Found impact;                                // moving soil within h of water
    std::vector<Found> overtopping;              // water past each line
  };
  // The part of the rows of `frame` that `owned` marks (null: every row). An impact is looked for
  // from the owned soil to all the water of the frame, so a process's frame must hold the water
  // within h of its soil (a split run's halo, 2h and more, does).
  Part part(const FieldFrame& frame, double ponding_pressure, const std::vector<char>* owned = nullptr) const;

  // The events that fire at this sample, on the parts of every process: `probe_values` sampled at
  // it, `ponding_pressure` the p_max in force (Eq. 39).
  std::vector<CascadeEvent> observe(const std::vector<Part>& parts, const std::vector<double>& probe_values,
                                    double ponding_pressure);
  // The same on the whole run's frame.
  std::vector<CascadeEvent> observe(const FieldFrame& frame, const std::vector<double>& probe_values,
                                    double ponding_pressure) {
    return observe(std::vector<Part>{part(frame, ponding_pressure)}, probe_values, ponding_pressure);
  }

  // A part as numbers for a message, and back (unflatten throws std::invalid_argument on numbers
  // that are not flatten's).
  static std::vector<double> flatten(const Part& part);
  static Part unflatten(const std::vector<double>& numbers);

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

  using Rows = std::vector<char>;
  void ponding(const FieldFrame& frame, const Rows* owned, double ponding_pressure, Part& part) const;
  void landslide(const FieldFrame& frame, const Rows* owned, Part& part) const;
  void impact(const FieldFrame& frame, const Rows* owned, Part& part) const;
  Found overtopped(const FieldFrame& frame, const Rows* owned, const v1::Overtopping& line) const;

  v1::CascadeEvents events_;
  int dimensions_;
  double dp_, h_;
  bool enabled_;
  bool ponding_fired_ = false, landslide_fired_ = false, impact_fired_ = false;
  std::vector<Gauge> gauges_;
  std::vector<Line> lines_;
};

}  // namespace cascade
