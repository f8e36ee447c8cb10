// Infiltration into and evaporation from an unsaturated rigid column (paper Section 4.1,
// cases/infiltration_1d.yaml and cases/evaporation_1d.yaml): the SPH pore-pressure profile
// against an independent fine-grid solution of the Richards equation with the same soil, the same
// compressible pore water and the same boundaries (tests/reference/richards_1d.h, a finite-volume
// solver written for the tests), within 3% of the suction range (the tolerance) at four
// times. The cases run here at dp = 0.04 m (h/dp 1.8 as in the paper) to a quarter of a day,
// so that the test takes seconds; the width follows from the periodic axis' minimum (6.3 h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "server/core/engine_state.h"
#include "server/physics/soil_view.h"
#include "tests/reference/richards_1d.h"
#include "tests/validation/case_run.h"
#include "tests/validation/soil_profiles.h"
#include "tests/validation/validation_table.h"

namespace cascade {
namespace {

constexpr double kRho = 1000.0, kG = 9.81, kHeight = 3.0;
constexpr double kSuctionRange = kRho * kG * kHeight;  // initial suction: 0 at the base, 29.4 kPa at the top

// The overrides that coarsen a Section 4.1 case to dp = 0.04 m: 12 particles across (0.48 m,
// above 6.3 h = 0.454 m) and four dummy layers under the base.
std::vector<std::string> coarse() {
  return {"dp=0.04", "domain.min=[0.0, -0.16]", "domain.max=[0.48, 3.1]", "bodies[0].shape.box.min=[0.0, -0.16]",
          "bodies[0].shape.box.max=[0.48, 0.0]", "bodies[1].shape.box.max=[0.48, 3.0]"};
}

// The Richards solution for the case's soil (Eq. 42), K_w and top flux.
reference::Richards1d richards(const EngineConfig& config, double intensity, double p_min) {
  const SoilMaterial& soil = config.soils.at(0);
  const reference::RichardsSoil r = testing::richards_soil(soil, 0.4, kRho, kG);
  reference::RichardsOptions options;
  options.cells = 600;
  options.max_time_step = 30.0;
  return reference::Richards1d(r, kHeight, [](double z) { return -kRho * kG * z; },
                               reference::TopBoundary::adaptive(intensity, 0.0, p_min),
                               reference::BottomBoundary::no_flow(), options);
}

// The surface particles that take the prescribed flux of Eq. 39 (SurfaceState::flux) and those
// held at p_max or p_min instead, from the engine's state.
struct SurfaceCount {
  std::size_t flux = 0, held = 0;
};
SurfaceCount surface_states(const Engine& engine) {
  const EngineState state = engine.state();
  const auto& phase = state.integers.at("phase");
  const auto& free_surface = state.integers.at("free_surface");
  const auto& surface_state = state.integers.at("surface_state");
  SurfaceCount count;
  for (std::size_t i = 0; i < phase.size(); ++i)
    if (phase[i] == std::uint32_t(Phase::soil) && free_surface[i])
      ++(surface_state[i] == std::uint32_t(SurfaceState::flux) ? count.flux : count.held);
  return count;
}

// Runs the case and its Richards solution to each time and records the worst |p_SPH − p_ref| over
// the layers, in units of the suction range.
void compare(const std::string& name, const std::string& case_file, double intensity, double p_min) {
  testing::CaseRun run(case_file, coarse());
  auto solution = richards(run.config, intensity, p_min);
  for (double day : {0.05, 0.1, 0.15, 0.25}) {
    const double t = day * 86400.0;
    run.run_until(t);
    solution.advance_to(run.engine->time());
    const auto reference = solution.snapshot();
    const auto layers = testing::layer_pressures(run.engine->frame());
    // 3.0 m at dp = 0.04 m: 75 layers, every one of them compared.
    EXPECT_EQ(layers.size(), 75u);
    double worst = 0;
    for (const auto& [z, p] : layers)
      worst = testing::worst_of(worst, std::fabs(p - testing::interpolate(reference.z, reference.pore_pressure, z)));
    char metric[128];
    std::snprintf(metric, sizeof metric, "largest layer |p_w − p_Richards| / ρ_w g H at %.2f day", day);
    CASCADE_VALIDATE({.case_name = name + " (cases/" + case_file + ", dp = 0.04 m)",
                      .reference = "fine-grid finite-volume Richards solution, 600 cells, same soil, K_w and "
                                   "boundaries (tests/reference/richards_1d.h)",
                      .metric = metric, .measured = worst / kSuctionRange, .reference_value = 0.03,
                      .bound = testing::Bound::at_most,
                      .tolerance_source = "the issue's tolerance: 3% of the suction range"});
  }
}

// The pore water's balance at the same times: while the whole surface takes the prescribed flux
// (Eq. 39), the water that the column gains (Σ V Θ*, the volume that Eq. 27a conserves:
// soil_profiles.h) is the flux times the surface and the time, the base being impermeable.
void water_balance(const std::string& name, const std::string& case_file, double intensity) {
  testing::CaseRun run(case_file, coarse());
  const SoilMaterial& soil = run.config.soils.at(0);
  const double particle_mass = run.config.water_density * run.config.dp * run.config.dp;  // 2D: m = ρ_w0 dp²
  const double width = run.config.domain_max[0] - run.config.domain_min[0];  // the periodic column's top
  const double initial_volume = testing::pore_water_volume(run.engine->frame(), soil, particle_mass);
  for (double day : {0.05, 0.1, 0.15, 0.25}) {
    run.run_until(day * 86400.0);
    const SurfaceCount surface = surface_states(*run.engine);
    EXPECT_EQ(surface.flux, 12u);  // the top layer at dp = 0.04 m, every particle on the flux condition
    EXPECT_EQ(surface.held, 0u);
    const double came_in = intensity * width * run.engine->time();
    // The engine's own count of the rain (pore_water_account.h): the flux times the top's width
    // and the time, to round-off; nothing else crossed.
    const PoreWaterAccount account = run.engine->pore_water_account();
    EXPECT_NEAR(account.rain, came_in, 1e-9 * std::fabs(came_in));
    EXPECT_EQ(account.walls, 0.0);
    EXPECT_EQ(account.surface, 0.0);
    const double gained = testing::pore_water_volume(run.engine->frame(), soil, particle_mass) - initial_volume;
    char metric[160];
    std::snprintf(metric, sizeof metric, "pore-water volume gained (Σ V Θ*) / flux × surface × time at %.2f day", day);
    CASCADE_VALIDATE({.case_name = name + " (cases/" + case_file + ", dp = 0.04 m)",
                      .reference = "conservation of the pore water (Eq. 27a): through an impermeable base the "
                                   "column gains what its surface takes",
                      .metric = metric, .measured = gained / came_in, .reference_value = 1.0, .tolerance = 0.005,
                      .tolerance_source = "the issue's tolerance: 0.5% of the water that came in or left"});
  }
}

TEST(Infiltration1D, PorePressureAgainstRichards) {
  compare("1D infiltration", "infiltration_1d.yaml", 1.1574e-6, -1e30);
}

TEST(Evaporation1D, PorePressureAgainstRichards) { compare("1D evaporation", "evaporation_1d.yaml", -2.3148e-8, -1e5); }

TEST(Infiltration1D, PoreWaterBalance) { water_balance("1D infiltration", "infiltration_1d.yaml", 1.1574e-6); }
TEST(Evaporation1D, PoreWaterBalance) { water_balance("1D evaporation", "evaporation_1d.yaml", -2.3148e-8); }

}  // namespace
}  // namespace cascade
