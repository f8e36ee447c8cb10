// Issue 14, item 5: the explicit pore water's balance with its boundaries. The water that the
// soil holds, Σ V_i Θ*_i (the volume Eq. 27a conserves, soil_profiles.h: pore_water_volume), changes
// by what the engine counts entering through each boundary (Engine::pore_water_account,
// server/physics/pore_water_account.h): rain through the flux surface (Eq. 39), drained walls
// (Eq. 36), and surfaces that hold a prescribed pressure (ponded, seepage faces). The storage is
// measured on the frames, the boundary exchange summed by the engine step by step, so the check
// holds only if the pairs inside conserve, the rain and boundary terms are what the continuity
// applies, and the time integration keeps them together. The columns of infiltration and
// evaporation, whose only boundary is the flux surface, are checked against the analytic
// rain × area × time in test_infiltration_1d.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "tests/validation/case_run.h"
#include "tests/validation/liakopoulos_case.h"
#include "tests/validation/soil_profiles.h"
#include "tests/validation/validation_table.h"

namespace cascade {
namespace {

double stored_pore_water(const testing::CaseRun& run) {
  const double particle_mass = run.config.water_density * std::pow(run.config.dp, run.config.dimensions);
  return testing::pore_water_volume(run.engine->frame(), run.config.soils.at(0), particle_mass);
}

// (ΔΣ V Θ* − what the boundaries let in) / `scale`: 0 for a conserving scheme.
void validate_balance(const testing::CaseRun& run, double initial, const std::string& case_name,
                      const std::string& when, double scale, const std::string& scale_name) {
  const PoreWaterAccount in = run.engine->pore_water_account();
  const double stored = stored_pore_water(run) - initial;
  CASCADE_VALIDATE({.case_name = case_name,
                    .reference = "conservation of the pore water (Eq. 27a): the storage changes by what enters "
                                 "through rain, drained walls and seepage faces",
                    .metric = "(Σ V Θ* gained − rain − drained walls − seepage faces) / " + scale_name + ", " + when,
                    .measured = (stored - (in.rain + in.walls + in.surface)) / scale, .reference_value = 0.0,
                    .tolerance = 0.005,
                    .tolerance_source = "the issue's tolerance: 0.5% of the water that came in or left"});
}

// The accelerated demo's slope under rain at K_sat (Section 5's i/K_sat = 1; the demo script
// raises it to that at 5 s), deforming on impermeable bedrock, to 19 s, before it fails
// (landslide_onset at 19.5 s). From about 14 s particles of its surface pond at p_w = 0 and take
// water through it.
TEST(PoreWaterBalance, CascadeDemoSlope) {
  testing::CaseRun run("cascade_demo_2d.yaml", {"hydraulics.rainfall_intensity=1e-2"});
  const std::string name = "Cascade demo 2D, its slope before failure (cases/cascade_demo_2d.yaml, i = K_sat)";
  const double initial = stored_pore_water(run);
  for (double t : {5.0, 10.0, 15.0, 19.0}) {
    run.run_until(t);
    const PoreWaterAccount in = run.engine->pore_water_account();
    EXPECT_GT(in.rain, 0.0);
    EXPECT_EQ(in.walls, 0.0);  // no drained wall
    validate_balance(run, initial, name, "t = " + std::to_string(int(t)) + " s", in.rain, "rain in");
  }
  // The ponded surface took part, by more than the tolerance: the check has the power to see it.
  const PoreWaterAccount in = run.engine->pore_water_account();
  EXPECT_GT(std::fabs(in.surface), 0.005 * in.rain);
}

// Known failure: the same slope after it fails, at 22 and 25 s, the slide in the channel. Measured
// when written: the soil holds 10.4% and 11.6% of the rain more than came in. In development runs
// (2026-12-06) the balance still held at 20 s (−0.05%), when the slide reached the water
// (water_impact at 20.0 s), and with the skeleton rigid it holds past 19 s (−0.17% at 22 s, −0.21%
// at 25 s, the ponded surfaces taking 5% of the rain): the gain comes where the moving soil meets
// the free water. Suspects, not yet measured apart: a particle's volume follows Eq. 22's divergence
// over every neighbour, free water included, while its pore water takes Eq. 26c's ε̇_v over the
// soil and the walls plus S_w times the free water's volume change (soil_interaction.h); and the
// grains' residual water (grain_bound_water.h), which Θ* counts in a pore volume that changes.
// Letting the porosity (Eq. 26a) follow the free water's volume change as the particle's volume
// does, so that the grains keep their volume, broke the run down 0.13 s after the impact
// (development run): the interface needs its own derivation (issue 13, item 3).
TEST(PoreWaterBalance, CascadeDemoAfterFailureKnownFailure) {
  testing::CaseRun run("cascade_demo_2d.yaml", {"hydraulics.rainfall_intensity=1e-2"});
  const std::string name = "Cascade demo 2D, its slope after failure (cases/cascade_demo_2d.yaml, i = K_sat)";
  const double initial = stored_pore_water(run);
  for (double t : {22.0, 25.0}) {
    run.run_until(t);
    validate_balance(run, initial, name, "t = " + std::to_string(int(t)) + " s",
                     run.engine->pore_water_account().rain, "rain in");
  }
}

// Liakopoulos' column (Section 4.2), deforming, drains through its base, a drained wall at
// p_w = 0 (Eq. 36); its top takes no rain.
TEST(PoreWaterBalance, LiakopoulosColumn) {
  constexpr double kAlpha = 100.0;
  testing::CaseRun run("liakopoulos.yaml", testing::accelerated_liakopoulos(kAlpha));
  const std::string name = "Liakopoulos drainage (cases/liakopoulos.yaml, dp = 0.05 m, K_sat × 100)";
  const double initial = stored_pore_water(run);
  for (double t : {300.0, 1200.0}) {
    run.run_until(t / kAlpha);
    const PoreWaterAccount in = run.engine->pore_water_account();
    EXPECT_EQ(in.rain, 0.0);
    EXPECT_LT(in.walls, 0.0);  // it drains
    validate_balance(run, initial, name, "t = " + std::to_string(int(t)) + " s", -in.walls,
                     "outflow through the drained base");
  }
}

}  // namespace
}  // namespace cascade
