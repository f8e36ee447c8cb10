// The cascade's event criteria (server/scenario/cascade_events.h) on hand-made frames: each fires
// when its criterion is met and not before, and once only; the parts that the processes of a split
// run take (CascadeEventDetector::part) fire the same events, with the same words.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "server/scenario/cascade_events.h"
#include "server/scenario/case_loader.h"
#include "tests/unit/process_frames.h"

namespace cascade {
namespace {

// A 2D frame of particles (x, z, phase), with velocity, pore pressure and κ.
struct FrameBuilder {
  FieldFrame frame;
  FrameBuilder() {
    frame.dimensions = 2;
    for (const char* name : {"velocity", "pore_pressure", "plastic_strain"})
      frame.fields.push_back({name, "", std::string(name) == "velocity" ? 3 : 1, {}});
  }
  std::size_t add(double x, double z, std::uint8_t phase, double vx = 0, double p_w = 0, double kappa = 0,
                  bool surface = false) {
    frame.position.insert(frame.position.end(), {x, 0.0, z});
    frame.phase.push_back(phase);
    frame.id.push_back(std::uint32_t(frame.id.size()));
    frame.free_surface.push_back(surface ? 1 : 0);
    frame.fields[0].values.insert(frame.fields[0].values.end(), {vx, 0.0, 0.0});
    frame.fields[1].values.push_back(p_w);
    frame.fields[2].values.push_back(kappa);
    return frame.id.size() - 1;
  }
};

v1::ScenarioSpec spec_with_events(const std::string& events) {
  return load_case_text(
      "dimensions: 2\ndp: 0.01\nend_time: 1\ndomain: {min: [0, 0], max: [2, 1]}\ngravity: [0, -9.81]\n"
      "materials:\n  - name: water\n    water: {density: 1000}\n"
      "  - name: sand\n    soil: {grain_density: 2650, porosity: 0.4, saturated_conductivity: 1e-4,\n"
      "           hydraulic: {gardner: {s_min: 0.2, alpha: 1}},\n"
      "           mechanical: {drucker_prager: {youngs_modulus: 1e7, poisson_ratio: 0.3, friction_angle: 30}}}\n"
      "bodies:\n  - {name: w, kind: fluid, material: water, shape: {box: {min: [1, 0], max: [2, 0.5]}}}\n"
      "  - {name: s, kind: fluid, material: sand, shape: {box: {min: [0, 0], max: [0.5, 0.5]}}}\n"
      "probes:\n  - {name: gauge1, kind: elevation, position: [1.5]}\n"
      "events: " + events + "\n",
      {}, "events.yaml");
}

TEST(CascadeEvents, PondingFiresAtTheFirstSurfaceParticleAtPmax) {
  CascadeEventDetector detector(spec_with_events("{ponding_started: true}"), 0.013, {"gauge1"});
  FrameBuilder f;
  f.add(0.1, 0.5, 1, 0, -500, 0, true);  // a surface particle under suction
  f.add(0.2, 0.4, 1, 0, 0, 0, false);    // at p_max but inside the soil: not the surface
  EXPECT_TRUE(detector.observe(f.frame, {0.5}, 0.0).empty());
  f.frame.fields[1].values[0] = 0.0;     // the surface particle reaches p_max = 0
  const auto fired = detector.observe(f.frame, {0.5}, 0.0);
  ASSERT_EQ(fired.size(), 1u);
  EXPECT_EQ(fired[0].kind, "ponding_started");
  EXPECT_NE(fired[0].message.find("1 free-surface"), std::string::npos) << fired[0].message;
  EXPECT_TRUE(detector.observe(f.frame, {0.5}, 0.0).empty());  // once
}

TEST(CascadeEvents, LandslideOnsetNeedsPlasticStrainSpeedAndVolumeTogether) {
  // 3 particles of dp² = 1e-4 m² make 3e-4 m² > 2.5e-4.
  CascadeEventDetector detector(
      spec_with_events("{landslide_onset: {plastic_strain: 0.05, speed: 0.1, volume: 2.5e-4}}"), 0.013, {"gauge1"});
  FrameBuilder f;
  for (int k = 0; k < 3; ++k) f.add(0.1 + 0.01 * k, 0.3, 1, 0.5, 0, 0.01);  // fast, little κ
  f.add(0.3, 0.3, 1, 0.01, 0, 0.2);                                           // κ, slow
  EXPECT_TRUE(detector.observe(f.frame, {0.5}, 0.0).empty());
  for (int k = 0; k < 2; ++k) f.frame.fields[2].values[std::size_t(k)] = 0.1;  // 2e-4 m²: not yet
  EXPECT_TRUE(detector.observe(f.frame, {0.5}, 0.0).empty());
  f.frame.fields[2].values[2] = 0.1;
  const auto fired = detector.observe(f.frame, {0.5}, 0.0);
  ASSERT_EQ(fired.size(), 1u);
  EXPECT_EQ(fired[0].kind, "landslide_onset");
}

TEST(CascadeEvents, WaterImpactIsMovingSoilWithinHOfWater) {
  const double h = 0.013;
  CascadeEventDetector detector(spec_with_events("{water_impact: {speed: 0.1}}"), h, {"gauge1"});
  FrameBuilder f;
  f.add(1.0, 0.1, 0);                              // water
  const std::size_t soil = f.add(1.0 - 1.5 * h, 0.1, 1, 1.0);  // fast soil 1.5 h away
  f.add(1.0 - 0.5 * h, 0.2, 1, 0.05);              // slow soil within h (0.1 above): too slow
  EXPECT_TRUE(detector.observe(f.frame, {0.5}, 0.0).empty());
  f.frame.position[3 * soil] = 1.0 - 0.9 * h;      // the fast one within h
  const auto fired = detector.observe(f.frame, {0.5}, 0.0);
  ASSERT_EQ(fired.size(), 1u);
  EXPECT_EQ(fired[0].kind, "water_impact");
}

TEST(CascadeEvents, WaveAtGaugeIsARiseAboveTheFirstSampleAndOvertoppingIsWaterPastTheLine) {
  CascadeEventDetector detector(
      spec_with_events("{wave_at_gauge: [{probe: gauge1, rise: 0.01}], "
                       "overtopping: [{name: far_bank, axis: x, position: 1.8, above: 0.55}]}"),
      0.013, {"gauge1"});
  FrameBuilder f;
  const std::size_t water = f.add(1.7, 0.6, 0);
  EXPECT_TRUE(detector.observe(f.frame, {0.50}, 0.0).empty());   // the still level
  EXPECT_TRUE(detector.observe(f.frame, {0.505}, 0.0).empty());  // 5 mm: below the rise
  auto fired = detector.observe(f.frame, {0.515}, 0.0);
  ASSERT_EQ(fired.size(), 1u);
  EXPECT_EQ(fired[0].kind, "wave_at_gauge");
  f.frame.position[3 * water] = 1.85;                             // past the line, above the crest
  fired = detector.observe(f.frame, {0.52}, 0.0);
  ASSERT_EQ(fired.size(), 1u);
  EXPECT_EQ(fired[0].kind, "overtopping");
  EXPECT_NE(fired[0].message.find("far_bank"), std::string::npos);
}

TEST(CascadeEvents, NoEventsBlockMeansNoDetection) {
  v1::ScenarioSpec spec = spec_with_events("{ponding_started: true}");
  spec.clear_events();
  CascadeEventDetector detector(spec, 0.013, {"gauge1"});
  EXPECT_FALSE(detector.enabled());
  FrameBuilder f;
  f.add(0.1, 0.5, 1, 0, 0, 0, true);
  EXPECT_TRUE(detector.observe(f.frame, {0.5}, 0.0).empty());
}

TEST(CascadeEvents, PartsOfProcessesFireWhatTheWholeFrameFires) {
  const std::string events =
      "{ponding_started: true, landslide_onset: {plastic_strain: 0.05, speed: 0.1, volume: 2.5e-4}, "
      "water_impact: {speed: 0.1}, overtopping: [{name: far_bank, axis: x, position: 1.8, above: 0.55}, "
      "{name: near_bank, axis: x, position: 0.05, above: 0.9, below: true}]}";
  const double h = 0.013;
  FrameBuilder f;
  f.add(1.9, 0.6, 0);                        // water past the far bank
  f.add(1.85, 0.7, 0);                       // and more of it
  f.add(1.0, 0.1, 0);                        // water the slide reaches
  for (int k = 0; k < 4; ++k) f.add(1.0 - (0.5 + 0.1 * k) * h, 0.1, 1, 0.5 + k, 0, 0.1);  // failed soil, moving
  f.add(0.1, 0.5, 1, 0, 0, 0, true);         // two surface particles at p_max
  f.add(0.2, 0.5, 1, 0, 0, 0, true);
  f.add(0.3, 0.5, 1, 0, -100, 0, true);      // and one under suction
  CascadeEventDetector whole(spec_with_events(events), h, {"gauge1"});
  const auto expected = whole.observe(f.frame, {0.5}, 0.0);
  ASSERT_EQ(expected.size(), 4u);  // the near bank holds

  for (int processes : {1, 2, 3, 4}) {
    CascadeEventDetector detector(spec_with_events(events), h, {"gauge1"});
    std::vector<int> owner(f.frame.size());
    for (std::size_t i = 0; i < owner.size(); ++i) owner[i] = int((i + 1) % std::size_t(processes));
    std::vector<CascadeEventDetector::Part> parts;
    int process = 0;
    for (const FieldFrame& local : frames_of_processes(f.frame, owner, processes)) {
      const std::vector<char> owned = owned_rows(local, process++);
      parts.push_back(CascadeEventDetector::unflatten(CascadeEventDetector::flatten(detector.part(local, 0.0, &owned))));
    }
    const auto fired = detector.observe(parts, {0.5}, 0.0);
    ASSERT_EQ(fired.size(), expected.size()) << processes << " processes";
    for (std::size_t k = 0; k < fired.size(); ++k) {
      EXPECT_EQ(fired[k].kind, expected[k].kind);
      EXPECT_EQ(fired[k].message, expected[k].message) << processes << " processes";
    }
    EXPECT_THROW(CascadeEventDetector::unflatten({1.0, 2.0}), std::invalid_argument);
  }
}

}  // namespace
}  // namespace cascade
