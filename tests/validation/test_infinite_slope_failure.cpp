// The time of failure of an infinite slope under constant rain, and the hand-off to the dynamic
// stage: cases/infinite_slope_2d.yaml (its header has the set-up) through the staged engine
// (geostatic, implicit pore water, dynamic) as the runner runs it.
//
// References, independent of the engine:
//  - Srivastava & Yeh's (1991) transient heads for Gardner's soil on a no-flow base
//    (tests/reference/gardner_analytic.h, ColumnBase::no_flow), mapped onto the slope-normal
//    coordinate. Derivation: with g = |g| (sin β, −cos β) in (x, n) and nothing varying along x,
//    H = ψ + n cos β − x sin β, q_n = −K (∂ψ/∂n + cos β), q_x = K sin β (uniform, divergence-free),
//    so ∂θ/∂t = ∂/∂n [K (∂ψ/∂n + cos β)]. With ζ = n cos β, ∂/∂n = cos β ∂/∂ζ:
//    ∂θ/∂t = ∂/∂ζ [K cos²β (∂ψ/∂ζ + 1)], Richards' vertical equation in ζ with K_eff = K_sat cos²β
//    e^{αψ} (same α, same θ(ψ)), on a column of height H cos β; its downward flux
//    K_eff (∂ψ/∂ζ + 1) = cos β · K (∂ψ/∂n + cos β) is cos β times the normal flux, so the rain per
//    unit slope area i enters as i cos β; the no-flow base stays no-flow.
//  - The infinite-slope factor of safety with suction stress (Lu & Godt 2008,
//    tests/reference/infinite_slope.h) with those heads: the first time its minimum over depth
//    reaches 1. The suction stress is weighted by the engine's Bishop parameter, S_w (Eq. 7,
//    σ' = σ + S_w p_w I), not by Lu & Godt's S_e = (S_w − S_min)/(S_max − S_min): the reference is
//    given the model's χ = S_w, so that it describes the same soil; the S_e time is printed too.
//    The unit weight is the initial state's (Eq. 28a at the initial S_w): the implicit stage
//    holds the total stress (docs/physics.md, "Implicit pore-water stage"), as the reference does.
//
// Checks (the numbers of the last run are in docs/physics.md, "Verification"):
//  1. The stage switch (the yielded band that ends the rain stage) against the Lu & Godt time:
//     within 10% (the brief's tolerance). It does not hold, for a reason in the model: the
//     criterion is Drucker–Prager yield, and Drucker–Prager matched to Mohr–Coulomb in plane strain
//     (Eq. 11 with ERRATA.md) equals Mohr–Coulomb on the slope-parallel plane only at the
//     plane-strain limit state whose failure plane is that plane. The layer's elastic K0 state after
//     the geostatic stage (σ'_xx ≈ σ'_yy ≈ 0.75 σ'_nn measured) has a larger deviator and reaches
//     the cone at Lu & Godt's FS ≈ 1.75, 0.76 h into the rain against 6.6 h. Even at K0 = 1
//     (pure shear on the slope plane) the cone's friction 3α_φ = tan φ'/sqrt(1 + 4/3 tan²φ') is 17%
//     below tan φ' at 30°: the model's own steady sliding (simple shear at constant volume,
//     dilatancy 0) has c = k_c, tan φ = 3α_φ, and Lu & Godt's expression with those gives 5.30 h,
//     −20% (printed). So the 10% check is StageSwitchAgainstLuGodtKnownFailure. What the model
//     does is checked against the same heads: the first time Eqs. 10a/11 reach yield in any particle
//     layer, from the geostatic stresses the test measures shifted by Bishop's Δ(S_w p_w) I (the
//     implicit stage's update) with Srivastava & Yeh's heads, within the same 10%.
//     Also checked: the geostatic stage gives the bedrock's layer the stresses of the infinite
//     slope (σ_nn = −W cos β, τ = W sin β, W the weight of the layer above it per unit slope area)
//     within 5%, and starts inside the yield surface; the rain stage's heads at the switch follow
//     the mapped Srivastava & Yeh heads within 2% of the profile's range (the tolerance of
//     test_implicit_pore_water.cpp) and are the same along x (every x alike).
//     Doubtful: the time of first yield depends on the geostatic state, which is not converged in
//     dp: at dp 0.0125 m the bedrock layer's stresses came out 2.2 (σ_nn) and 1.5 (τ) times the
//     slice's and the rain stage ended at 131 s (docs/physics.md, "Verification").
//  2. The dynamic stage moves the slope: a soil speed above 0.1 m/s within 5 s of the hand-off.
//     Handed over at the case's switch the slope is stable (FS ≈ 1.75) and stays at rest, rightly:
//     DynamicStageMovesTheSlopeKnownFailure, the same reason. A second run ends the rain stage at
//     the latest time check 1 accepts, 1.1 times the Lu & Godt time (FS < 1 there), and the slope
//     must move.
//  3. The explicit scheme at this real K_sat: Eq. 40c's Δt_sp = (γ_w/K_w) h² C_r/(2K) (C_r of
//     Eq. 28b, K = K_sat K_rel at each particle's p_w at the hand-off), its minimum over the soil,
//     against the first step the dynamic stage takes: below half of C0 Δt_sp (Eq. 40d), a margin of
//     2 on the seepage limit, in both runs.
//  4. The failure criterion that asks the model itself (StageEnd.motion, docs/physics.md "Stages"):
//     a third run ends the rain stage when a 1 s trial of the dynamic engine from the stage's state
//     brings soil to 0.1 m/s, tried every 20 min (half the 10% tolerance of the 6.6 h reference)
//     while some soil is at yield; its switch against the model's own strength on the slope
//     plane (the simple-shear time of check 1) within 10%, and against Mohr–Coulomb's strength of
//     a soil that does not dilate (Davis 1968: in steady simple shear at dilatancy 0 the slope
//     plane carries τ = c' cos φ' + σ'_n sin φ', the direct-shear result of Potts, Dounias & Vaughan
//     1987) in Lu & Godt's expression within 10%; the dynamic stage then moves the slope within
//     5 s. Against Lu & Godt with c', tan φ' (the strength of an associated soil, which dilates)
//     within 10% it is a known failure, for check 1's reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "server/physics/swcc/grain_bound_water.h"
#include "tests/reference/gardner_analytic.h"
#include "tests/reference/infinite_slope.h"
#include "tests/validation/case_run.h"
#include "tests/validation/solid_depth.h"
#include "tests/validation/validation_table.h"

namespace cascade {
namespace {

// The case's soil and layer (cases/infinite_slope_2d.yaml); run_case() checks the soil's against
// the engine's material.
constexpr double kPi = 3.14159265358979323846;
constexpr double kThickness = 0.5;          // H, slope-normal (m)
constexpr double kBaseHead = -3.0;          // ψ at the bedrock at t = 0 (m)
constexpr double kAlpha = 1.0;              // Gardner's α (1/m)
constexpr double kSMin = 0.23, kSMax = 1.0;
constexpr double kPorosity = 0.4, kGrainDensity = 2650.0;
constexpr double kCohesion = 500.0;                       // c' (Pa)
constexpr double kFriction = 30.0 * kPi / 180.0;          // φ'
constexpr double kRain = 5e-6;                            // per unit slope area (m/s)

struct Outcome {
  double beta = 0, gamma_w = 0, dp = 0;
  std::uint64_t geostatic_steps = 0;
  // The bedrock's particle layer after the geostatic stage (layer means).
  double base_n = 0;                                    // its height above the bedrock (m)
  double sxx = 0, syy = 0, snn = 0, tau = 0;            // effective stress (Pa), tension positive
  double total_nn = 0, expected_nn = 0, expected_tau = 0;
  // Every particle layer after the geostatic stage: n and the mean effective stress (xx, yy, nn, xn).
  std::vector<std::array<double, 5>> layers;
  double drucker_prager_n = 0;                          // the layer that yields first
  double yield_ratio_start = 0;                         // largest yield ratio at the start of the rain
  double switch_time = -1;                              // the rain stage's end (s)
  double yielded_low = 0, yielded_high = 0;             // the n range of the yielded particles then (m)
  std::string switch_reason;
  double worst_head = 0, head_range = 0;                // at the switch (m)
  double head_spread = 0;                               // the largest max − min of ψ within a layer (m)
  double lu_godt_time = -1, lu_godt_depth = 0, lu_godt_se_time = -1;
  double switch_factor_of_safety = 0;                   // Lu & Godt's minimum over depth at the switch
  double simple_shear_time = -1;                        // the same with the model's simple-shear strength
  double non_dilatant_time = -1;                        // the same with Davis' (1968) strength at dilatancy 0
  bool reference_valid = false;
  double drucker_prager_time = -1;                      // Eqs. 10a/11 with the analytic heads
  double seepage_dt = 0, first_dynamic_dt = 0, largest_dynamic_dt = 0, cfl = 0;
  double speed = 0, speed_after = -1;                   // largest soil speed, when it passed 0.1 m/s
  double wall_seconds = 0;
  testing::SolidDepth::Count inside{};                  // in the bedrock: the start, hand-off, every dynamic step
};

std::map<double, std::vector<std::size_t>> soil_layers(const FieldFrame& f) {
  std::map<double, std::vector<std::size_t>> layers;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.phase[i] == std::uint8_t(Phase::soil)) layers[std::round(f.position[3 * i + 2] * 1e6) / 1e6].push_back(i);
  return layers;
}

double largest_soil_speed(const FieldFrame& f) {
  const auto* v = f.find("velocity");
  double best = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.phase[i] == std::uint8_t(Phase::soil))
      best = testing::worst_of(best, std::sqrt(v->values[3 * i] * v->values[3 * i] + v->values[3 * i + 1] * v->values[3 * i + 1] +
                                      v->values[3 * i + 2] * v->values[3 * i + 2]));
  return best;
}

Outcome run_case(const std::vector<std::string>& overrides) {
  const auto wall_start = std::chrono::steady_clock::now();
  testing::CaseRun run("infinite_slope_2d.yaml", overrides);
  Outcome out;
  const EngineConfig& config = run.config;
  const SoilMaterial& soil = config.soils.at(0);
  const double g = std::hypot(config.gravity[0], config.gravity[1]);
  out.beta = std::atan2(config.gravity[0], -config.gravity[1]);
  out.gamma_w = config.water_density * g;
  out.dp = config.dp;
  out.cfl = config.cfl;
  const double cb = std::cos(out.beta), sb = std::sin(out.beta);
  // Bishop's χ = S_w of the engine's soil (Eq. 42a); the test's constants must be the case's.
  const auto saturation = [](double psi) { return psi >= 0 ? kSMax : kSMin + (kSMax - kSMin) * std::exp(kAlpha * psi); };
  EXPECT_NEAR(soil.hydraulic.saturation(0.7 * out.gamma_w), saturation(-0.7), 1e-12) << "the case's soil";
  EXPECT_NEAR(soil.hydraulic.relative_conductivity(0.7 * out.gamma_w), std::exp(-0.7 * kAlpha), 1e-12);
  EXPECT_EQ(soil.mechanical.peak_cohesion, kCohesion);
  EXPECT_NEAR(soil.mechanical.peak_friction_angle, kFriction, 1e-12);

  // Srivastava & Yeh in ζ = n cos β (header).
  reference::GardnerColumn column;
  column.soil = {kAlpha, kPorosity * kSMax, kPorosity * kSMin, soil.saturated_conductivity * cb * cb};
  column.height = kThickness * cb;
  column.base = reference::ColumnBase::no_flow;
  column.base_pressure_head = kBaseHead;
  column.flux_in = kRain * cb;
  const reference::GardnerColumnSolution heads(column);
  const auto head_at = [&](double n, double t) { return heads.pressure_head(n * cb, t); };

  const testing::SolidDepth bedrock(run.spec);
  out.inside = bedrock.inside(run.engine->frame(), 0.5 * out.dp);
  // Geostatic stage.
  while (run.engine->stage() == 0) run.engine->step();
  out.geostatic_steps = run.engine->step_count();
  const FieldFrame start = run.engine->frame();
  {
    const auto layers = soil_layers(start);
    const auto& base = layers.begin()->second;
    out.base_n = layers.begin()->first;
    const auto* effective = start.find("effective_stress");
    const auto* total = start.find("stress");
    for (const std::size_t i : base) {
      out.sxx += effective->values[6 * i] / base.size();
      out.syy += effective->values[6 * i + 1] / base.size();
      out.snn += effective->values[6 * i + 2] / base.size();
      out.tau += effective->values[6 * i + 5] / base.size();  // zx
      out.total_nn += total->values[6 * i + 2] / base.size();
    }
    // The weight of the soil above the layer's centre per unit slope area, Eq. 28a at the initial S_w.
    double w = 0;
    const int pieces = 2000;
    for (int k = 0; k < pieces; ++k) {
      const double n = out.base_n + (kThickness - out.base_n) * (k + 0.5) / pieces;
      w += g * ((1 - kPorosity) * kGrainDensity + saturation(head_at(n, 0.0)) * kPorosity * config.water_density) *
           (kThickness - out.base_n) / pieces;
    }
    out.expected_nn = -w * cb;
    out.expected_tau = w * sb;
    for (const auto& [n, members] : layers) {
      std::array<double, 5> mean{n, 0, 0, 0, 0};
      for (const std::size_t i : members)
        for (int c = 0; c < 4; ++c) mean[1 + c] += effective->values[6 * i + (c < 3 ? c : 5)] / members.size();
      out.layers.push_back(mean);
    }
    const auto* ratio = start.find("yield_ratio");
    for (std::size_t i = 0; i < start.size(); ++i)
      if (start.phase[i] == std::uint8_t(Phase::soil)) out.yield_ratio_start = std::max(out.yield_ratio_start, ratio->values[i]);
  }
  run.engine->take_stage_changes();

  // Rain stage, to the switch.
  while (run.engine->stage() == 1) run.engine->step();
  for (const StageChange& c : run.engine->take_stage_changes())
    if (c.to == 2) out.switch_time = c.time, out.switch_reason = c.reason;
  const FieldFrame handoff = run.engine->frame();
  out.inside.keep_worst(bedrock.inside(handoff, 0.5 * out.dp));
  {
    const auto* p = handoff.find("pore_pressure");
    double lo = 1e300, hi = -1e300;
    for (const auto& [n, members] : soil_layers(handoff)) {
      double mean = 0, low = 1e300, high = -1e300;
      for (const std::size_t i : members) {
        mean += p->values[i] / members.size();
        low = std::min(low, p->values[i]), high = std::max(high, p->values[i]);
      }
      out.head_spread = testing::worst_of(out.head_spread, (high - low) / out.gamma_w);
      const double expected = head_at(n, out.switch_time);
      lo = std::min(lo, expected), hi = std::max(hi, expected);
      out.worst_head = testing::worst_of(out.worst_head, std::fabs(mean / out.gamma_w - expected));
    }
    out.head_range = hi - lo;
    const auto* ratio = handoff.find("yield_ratio");
    out.yielded_low = 1e300, out.yielded_high = -1e300;
    for (std::size_t i = 0; i < handoff.size(); ++i)
      if (handoff.phase[i] == std::uint8_t(Phase::soil) && ratio->values[i] >= 1)
        out.yielded_low = std::min(out.yielded_low, handoff.position[3 * i + 2]),
        out.yielded_high = std::max(out.yielded_high, handoff.position[3 * i + 2]);
    // Eq. 40c at the hand-off: Δt_sp = (γ_w/K_w) h² C_r / (2K), C_r of Eq. 28b, K = K_sat K_rel.
    out.seepage_dt = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < handoff.size(); ++i) {
      if (handoff.phase[i] != std::uint8_t(Phase::soil)) continue;
      const double p_c = -p->values[i];
      const double c_r =
          pore_water_capacity(soil.hydraulic, soil.reference_porosity, p_c, kPorosity, soil.water_bulk_modulus);
      const double k = soil.saturated_conductivity * soil.hydraulic.relative_conductivity(p_c);
      out.seepage_dt = std::min(out.seepage_dt, out.gamma_w / soil.water_bulk_modulus * config.h * config.h * c_r / (2 * k));
    }
  }

  // Dynamic stage: until a soil particle moves faster than 0.1 m/s, at most 5 s.
  while (run.engine->time() < out.switch_time + 5.0) {
    run.engine->step();
    if (out.first_dynamic_dt == 0) out.first_dynamic_dt = run.engine->last_dt();
    out.largest_dynamic_dt = std::max(out.largest_dynamic_dt, run.engine->last_dt());
    const FieldFrame now = run.engine->frame();
    out.speed = largest_soil_speed(now);
    out.inside.keep_worst(bedrock.inside(now, 0.5 * out.dp));
    if (out.speed > 0.1) {
      out.speed_after = run.engine->time() - out.switch_time;
      break;
    }
  }

  // Lu & Godt with Srivastava & Yeh's heads: d is the vertical depth (infinite_slope.h), the
  // slope-normal height above the bedrock n = H − d cos β.
  const reference::HeadField field = [&](double d, double t) { return head_at(kThickness - d * cb, t); };
  const auto stability = [&](std::function<double(double)> chi, double cohesion, double friction) {
    reference::InfiniteSlope slope;
    slope.slope_angle = out.beta;
    slope.cohesion = cohesion;
    slope.friction_angle = friction;
    slope.unit_weight_profile = [&](double d) {
      return g * ((1 - kPorosity) * kGrainDensity +
                  saturation(head_at(kThickness - d * cb, 0.0)) * kPorosity * config.water_density);
    };
    slope.effective_saturation = std::move(chi);
    slope.water_unit_weight = out.gamma_w;
    return reference::InfiniteSlopeStability(slope);
  };
  reference::SlopeSearchOptions options;
  options.time_samples = 400;
  const auto critical = [&](const reference::InfiniteSlopeStability& s) {
    return s.critical_depth_and_time(field, 1e-3, kThickness / cb, 0.0, 2 * 86400.0, options);
  };
  const reference::InfiniteSlopeStability lu_godt = stability(saturation, kCohesion, kFriction);
  out.switch_factor_of_safety = lu_godt.minimum_over_depth(field, out.switch_time, 1e-3, kThickness / cb).factor_of_safety;
  const reference::SlopeCriticalState bishop = critical(lu_godt);
  if (bishop.found) {
    out.lu_godt_time = bishop.time;
    out.lu_godt_depth = bishop.depth;
    out.reference_valid = heads.valid(0.0, bishop.time) && heads.valid(kThickness * cb, bishop.time);
  }
  const reference::SlopeCriticalState effective_saturation =
      critical(stability(reference::gardner_effective_saturation(kAlpha), kCohesion, kFriction));
  if (effective_saturation.found) out.lu_godt_se_time = effective_saturation.time;
  // The model's own sliding strength on the slope plane: steady simple shear at constant volume
  // (dilatancy 0) needs s_xx = s_yy = 0 (ε^p ∥ s with ε_xx = ε_yy = 0), so σ'_xx = σ'_yy = σ'_nn
  // and Eq. 10a gives τ = k_c + 3α_φ σ'_n (compression positive): Lu & Godt's expression with
  // c = k_c and tan φ = 3α_φ of Eq. 11 (ERRATA.md).
  {
    const double t = std::tan(kFriction), root = std::sqrt(9 + 12 * t * t);
    const reference::SlopeCriticalState sliding =
        critical(stability(saturation, 3 * kCohesion / root, std::atan(3 * t / root)));
    if (sliding.found) out.simple_shear_time = sliding.time;
  }
  // Mohr–Coulomb's strength on the slope plane for the case's soil, which does not dilate: in
  // steady simple shear at dilatancy ψ the plane of zero extension carries
  // τ = c* + σ'_n tan φ* with tan φ* = sin φ cos ψ / (1 − sin φ sin ψ) and
  // c* = c cos φ cos ψ / (1 − sin φ sin ψ) (Davis 1968, "Theories of plasticity and the failure of
  // soil masses", in I. K. Lee (ed.), Soil Mechanics: Selected Topics, Butterworths; for ψ = 0
  // τ/σ'_n = sin φ', as Potts, Dounias & Vaughan 1987, Géotechnique 37(1), found in the direct shear
  // box). Lu & Godt's expression with c*, φ* is the infinite slope of a non-dilatant Mohr–Coulomb
  // soil; independent of Eq. 11's Drucker–Prager match.
  {
    const reference::SlopeCriticalState non_dilatant =
        critical(stability(saturation, kCohesion * std::cos(kFriction), std::atan(std::sin(kFriction))));
    if (non_dilatant.found) out.non_dilatant_time = non_dilatant.time;
  }

  // Eqs. 10a and 11 (ERRATA.md) in each particle layer: the measured geostatic stress, shifted by
  // Δ(S_w p_w) I as the implicit stage does, with the analytic pressure there; the first time any
  // layer yields.
  for (const auto& layer : out.layers) {
    const double t = std::tan(kFriction), root = std::sqrt(9 + 12 * t * t);
    const double alpha_phi = t / root, k_c = 3 * kCohesion / root;
    const double n = layer[0];
    const double p0 = out.gamma_w * head_at(n, 0.0);
    const double s0 = saturation(p0 / out.gamma_w) * p0;
    const auto ratio = [&](double time) {
      const double p = out.gamma_w * head_at(n, time);
      const double shift = saturation(p / out.gamma_w) * p - s0;
      const double a = layer[1] + shift, b = layer[2] + shift, c = layer[3] + shift;
      const double j2 = ((a - b) * (a - b) + (b - c) * (b - c) + (c - a) * (c - a)) / 6 + layer[4] * layer[4];
      return std::sqrt(j2) / (k_c - alpha_phi * (a + b + c));
    };
    double lo = 0, hi = -1;
    for (double time = 0; time <= 2 * 86400.0; time += 60.0) {
      if (ratio(time) >= 1) {
        hi = time;
        break;
      }
      lo = time;
    }
    if (hi < 0) continue;
    while (hi - lo > 1.0) (ratio(0.5 * (lo + hi)) >= 1 ? hi : lo) = 0.5 * (lo + hi);
    if (out.drucker_prager_time < 0 || hi < out.drucker_prager_time) out.drucker_prager_time = hi, out.drucker_prager_n = n;
  }
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  std::printf("infinite slope: beta %.1f deg, H %.2f m, dp %.3f m; geostatic %llu steps; bedrock layer at n = %.4f m: "
              "sigma'_xx %.1f, sigma'_yy %.1f, sigma'_nn %.1f, tau %.1f Pa; sigma_nn %.1f (slice -W cos b = %.1f), "
              "|tau| %.1f (W sin b = %.1f); largest yield ratio at the start of the rain %.3f\n",
              out.beta * 180 / kPi, kThickness, out.dp, (unsigned long long)out.geostatic_steps, out.base_n, out.sxx, out.syy,
              out.snn, out.tau, out.total_nn, out.expected_nn, std::fabs(out.tau), out.expected_tau, out.yield_ratio_start);
  std::printf("  rain stage ends at %.0f s (%.2f h), yielded particles at n = %.4f to %.4f m: %s\n", out.switch_time,
              out.switch_time / 3600, out.yielded_low, out.yielded_high, out.switch_reason.c_str());
  std::printf("  Lu & Godt FS = 1 (chi = S_w): %.0f s (%.2f h) at vertical depth %.3f m (normal %.3f m), heads valid %d; "
              "with chi = S_e: %.0f s (%.2f h); FS at the switch %.3f; with the model's simple-shear strength (k_c, "
              "3 alpha_phi): %.0f s (%.2f h); with Davis' non-dilatant strength (c cos phi, atan sin phi): %.0f s (%.2f h)\n",
              out.lu_godt_time, out.lu_godt_time / 3600, out.lu_godt_depth, out.lu_godt_depth * cb, int(out.reference_valid),
              out.lu_godt_se_time, out.lu_godt_se_time / 3600, out.switch_factor_of_safety, out.simple_shear_time,
              out.simple_shear_time / 3600, out.non_dilatant_time, out.non_dilatant_time / 3600);
  std::printf("  Drucker-Prager yield from the measured geostatic stress and SY heads: %.0f s (%.2f h), first in the "
              "layer at n = %.4f m; model switch %+.1f%% of it, %+.1f%% of Lu & Godt\n",
              out.drucker_prager_time, out.drucker_prager_time / 3600, out.drucker_prager_n,
              100 * (out.switch_time - out.drucker_prager_time) / out.drucker_prager_time,
              100 * (out.switch_time - out.lu_godt_time) / out.lu_godt_time);
  std::printf("  dynamic stage: largest soil speed %.3f m/s after %.3f s; steps: first %.3g s, largest %.3g s, seepage limit "
              "Eq. 40c %.3g s (C0 Delta t_sp = %.3g s); run time %.0f s\n",
              out.speed, out.speed_after, out.first_dynamic_dt, out.largest_dynamic_dt, out.seepage_dt,
              out.cfl * out.seepage_dt, out.wall_seconds);
  return out;
}

// The case as it is: the rain stage ends at the yielded band.
const Outcome& outcome() {
  static const Outcome o = run_case({});
  return o;
}

// The rain stage ended instead at the latest time check 1 accepts, 1.1 times the Lu & Godt time:
// does the dynamic stage move a slope handed over failed?
const Outcome& late_handoff() {
  static const Outcome o = run_case({"stages[1].end={time: " + std::to_string(1.1 * outcome().lu_godt_time) + "}"});
  return o;
}

// The rain stage ended by the slope's own motion (check 4): trials every 20 min.
const Outcome& motion_switch() {
  static const Outcome o = run_case({"stages[1].end={motion: {speed: 0.1, duration: 1, interval: 1200}}"});
  return o;
}

const std::string kCase = "Infinite slope under rain, 35° (cases/infinite_slope_2d.yaml)";
const std::string kLuGodt = "Lu & Godt (2008) factor of safety with suction stress (χ = S_w), with Srivastava & Yeh's "
                            "(1991) heads (tests/reference/infinite_slope.h): the time FS reaches 1";
const char* const kTimeBound = "issue 12's bound: 10% of the time of failure";

// A soil speed above 0.1 m/s within 5 s of the hand-off (header, check 2); `run` names the hand-off.
void validate_motion(const Outcome& o, const std::string& run) {
  const std::string reference = "the dynamic stage moves the slope after the hand-off (the file's check 2)";
  const std::string source = "the test's criterion of motion: 0.1 m/s within 5 s (no independent source)";
  CASCADE_VALIDATE({.case_name = kCase, .reference = reference,
                    .metric = "soil speed when it passed 0.1 m/s, else 5 s after the hand-off, " + run + " (m/s)",
                    .measured = o.speed, .reference_value = 0.1, .bound = testing::Bound::at_least,
                    .tolerance_source = source});
  CASCADE_VALIDATE({.case_name = kCase, .reference = reference,
                    .metric = "time from the hand-off to a soil speed above 0.1 m/s (never: no value), " + run + " (s)",
                    .measured = o.speed_after >= 0 ? o.speed_after : INFINITY, .reference_value = 5.0,
                    .bound = testing::Bound::at_most, .tolerance_source = source});
  testing::validate_outside_solids(kCase + ", " + run, o.inside, 0.5 * o.dp,
                                   "at the start, the hand-off and every step of the dynamic stage");
}

TEST(InfiniteSlopeFailure, GeostaticStageCarriesTheSlopesStresses) {
  const Outcome& o = outcome();
  const std::string reference = "the infinite-slope slice, W the layer's weight above (Eq. 28a at the initial S_w)";
  const std::string source = "the test's choice (no stated source; the geostatic state is not converged in dp)";
  CASCADE_VALIDATE({.case_name = kCase, .reference = reference + ", σ_nn = −W cos β",
                    .metric = "bedrock layer's total σ_nn after the geostatic stage (Pa)", .measured = o.total_nn,
                    .reference_value = o.expected_nn, .tolerance = 0.05, .relative = true,
                    .tolerance_source = source});
  CASCADE_VALIDATE({.case_name = kCase, .reference = reference + ", τ = W sin β",
                    .metric = "bedrock layer's |τ| after the geostatic stage (Pa)", .measured = std::fabs(o.tau),
                    .reference_value = o.expected_tau, .tolerance = 0.05, .relative = true,
                    .tolerance_source = source});
  EXPECT_LT(o.yield_ratio_start, 1.0) << "the layer must start inside the yield surface";
}

TEST(InfiniteSlopeFailure, RainStageHeadsFollowSrivastavaYehOnTheSlope) {
  const Outcome& o = outcome();
  ASSERT_GT(o.switch_time, 0);
  CASCADE_VALIDATE({.case_name = kCase,
                    .reference = "Srivastava & Yeh (1991) mapped to the slope normal (reference/gardner_analytic.h)",
                    .metric = "worst |ψ − ψ_SY| of the layer means at the rain stage's end / the profile's range",
                    .measured = o.worst_head / o.head_range, .reference_value = 0.02, .bound = testing::Bound::at_most,
                    .tolerance_source = "issue 12's bound: 2% of the profile's range"});
  // Every x alike on an infinite slope: the same head along each particle layer, to a hundredth of
  // the tolerance above (a pair across the periodic seam that took the stored positions' elevations,
  // 0.14 m apart there, spread it by 129 mm, 24% of the range, at the switch).
  CASCADE_VALIDATE({.case_name = kCase, .reference = "an infinite slope: nothing varies along x",
                    .metric = "largest spread of ψ along x in a layer at the rain stage's end / the profile's range",
                    .measured = o.head_spread / o.head_range, .reference_value = 2e-4, .bound = testing::Bound::at_most,
                    .tolerance_source = "a hundredth of the 2% head tolerance (the test's choice)"});
}

// The model's criterion (Drucker–Prager yield) with the analytic heads: the stage switch within 10%.
TEST(InfiniteSlopeFailure, StageSwitchAgainstDruckerPragerYieldWithAnalyticHeads) {
  const Outcome& o = outcome();
  ASSERT_GT(o.drucker_prager_time, 0) << "Drucker–Prager must not hold at the start";
  CASCADE_VALIDATE({.case_name = kCase,
                    .reference = "first Drucker–Prager yield (Eqs. 10a/11) of a layer, from its measured geostatic "
                                 "stress with Srivastava & Yeh's (1991) heads",
                    .metric = "rain stage's end at the yielded band (s)", .measured = o.switch_time,
                    .reference_value = o.drucker_prager_time, .tolerance = 0.1, .relative = true,
                    .tolerance_source = kTimeBound});
}

// Known failure, a reason in the model (header, check 1): the switch is Drucker–Prager yield of the
// bedrock's layer from its elastic K0 state, which comes long before the slope-parallel plane's
// Mohr–Coulomb factor of safety reaches 1. The printed numbers give both times.
TEST(InfiniteSlopeFailure, StageSwitchAgainstLuGodtKnownFailure) {
  const Outcome& o = outcome();
  ASSERT_GT(o.lu_godt_time, 0) << "the reference slope must fail within the rain";
  EXPECT_TRUE(o.reference_valid) << "Srivastava & Yeh's heads must be unsaturated (K <= K_sat) there";
  CASCADE_VALIDATE({.case_name = kCase, .reference = kLuGodt, .metric = "rain stage's end at the yielded band (s)",
                    .measured = o.switch_time, .reference_value = o.lu_godt_time, .tolerance = 0.1, .relative = true,
                    .tolerance_source = kTimeBound});
}

// Known failure, the same reason in the model: handed over at the first Drucker–Prager yield, the
// slope is stable (Lu & Godt's factor of safety is printed: above 1), and the dynamic stage keeps it
// at rest, rightly.
TEST(InfiniteSlopeFailure, DynamicStageMovesTheSlopeKnownFailure) {
  validate_motion(outcome(), "handed over at the yielded band");
}

TEST(InfiniteSlopeFailure, DynamicStageMovesTheSlopeHandedOverFailed) {
  const Outcome& o = late_handoff();
  ASSERT_GT(o.switch_time, 1.05 * o.lu_godt_time) << "handed over after the reference failure";
  EXPECT_LT(o.switch_factor_of_safety, 1.0);
  validate_motion(o, "handed over at 1.1 × the Lu & Godt time");
}

// The model's own failure against two strengths on the slope plane for a soil that does not dilate,
// each within the same 10%: the model's own (Lu & Godt's expression with c = k_c, tan φ = 3α_φ:
// steady simple shear at constant volume, header check 1), and Mohr–Coulomb's (Lu & Godt's
// expression with Davis' c*, φ*: run_case), independent of Eq. 11's match. The dynamic stage then
// moves the slope within 5 s.
TEST(InfiniteSlopeFailure, StageSwitchByMotionAgainstNonDilatantSlopeStrengths) {
  const Outcome& o = motion_switch();
  ASSERT_GT(o.simple_shear_time, 0);
  ASSERT_GT(o.non_dilatant_time, 0);
  CASCADE_VALIDATE({.case_name = kCase,
                    .reference = "Lu & Godt's (2008) expression with the model's simple-shear strength (c = k_c, "
                                 "tan φ = 3α_φ) and Srivastava & Yeh's (1991) heads: the time FS reaches 1",
                    .metric = "rain stage's end by motion trials (s)", .measured = o.switch_time,
                    .reference_value = o.simple_shear_time, .tolerance = 0.1, .relative = true,
                    .tolerance_source = kTimeBound});
  CASCADE_VALIDATE({.case_name = kCase,
                    .reference = "Lu & Godt's (2008) factor of safety with Davis' (1968) strength of a non-dilatant "
                                 "Mohr–Coulomb soil (c' cos φ', tan φ* = sin φ') and Srivastava & Yeh's (1991) heads: "
                                 "the time FS reaches 1",
                    .metric = "rain stage's end by motion trials (s)", .measured = o.switch_time,
                    .reference_value = o.non_dilatant_time, .tolerance = 0.1, .relative = true,
                    .tolerance_source = kTimeBound});
  validate_motion(o, "handed over by motion trials");
}

// Known failure, a reason in the model (header, checks 1 and 4): the case's soil does not dilate,
// and in simple shear its strength on the slope plane is below c' + σ'_n tan φ' (Davis' sin φ' for
// Mohr–Coulomb, 4% below that the cone's 3α_φ of Eq. 11): the slope fails by the model's strength,
// 18% before Lu & Godt's time with c', tan φ', which assumes a dilating (associated) soil.
TEST(InfiniteSlopeFailure, StageSwitchByMotionAgainstLuGodtKnownFailure) {
  const Outcome& o = motion_switch();
  ASSERT_GT(o.lu_godt_time, 0);
  CASCADE_VALIDATE({.case_name = kCase, .reference = kLuGodt, .metric = "rain stage's end by motion trials (s)",
                    .measured = o.switch_time, .reference_value = o.lu_godt_time, .tolerance = 0.1, .relative = true,
                    .tolerance_source = kTimeBound});
}

TEST(InfiniteSlopeFailure, ExplicitStepIsNotSetBySeepage) {
  for (const auto& [o, run] : {std::pair{&outcome(), "handed over at the yielded band"},
                                std::pair{&late_handoff(), "handed over at 1.1 × the Lu & Godt time"}}) {
    ASSERT_GT(o->first_dynamic_dt, 0);
    CASCADE_VALIDATE({.case_name = kCase, .reference = "½ C0 Δt_sp, Eq. 40c's seepage limit at the hand-off (Eq. 40d)",
                      .metric = std::string("first dynamic step, ") + run + " (s)", .measured = o->first_dynamic_dt,
                      .reference_value = 0.5 * o->cfl * o->seepage_dt, .bound = testing::Bound::at_most,
                      .tolerance_source = "a margin of 2 on the seepage limit (the test's choice)"});
  }
}

}  // namespace
}  // namespace cascade
