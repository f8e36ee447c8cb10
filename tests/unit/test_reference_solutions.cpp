// Tests of the independent reference solutions in tests/reference/: each is checked against
// what it must satisfy on its own (equation, boundary conditions, mass, published values) and,
// where two of them describe the same problem, against each other (the Richards solver against
// the Gardner closed forms and against Terzaghi's series).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "tests/reference/column_collapse.h"
#include "tests/reference/gardner_analytic.h"
#include "tests/reference/gardner_layered.h"
#include "tests/reference/infinite_slope.h"
#include "tests/reference/liakopoulos_reference.h"
#include "tests/reference/richards_1d.h"
#include "tests/reference/terzaghi.h"

namespace cascade::reference {
namespace {

constexpr double kDay = 86400.0;
constexpr double kRhoG = 1000.0 * 9.81;

// The Eq. 42 soil for the Richards solver. capped: S_w = S_max, K_rel = 1 for p_c <= 0 (the
// physical soil); uncapped: the exponentials continue into p_c < 0, which is the problem the
// linear closed form solves there.
RichardsSoil section_4_1_richards_soil(bool capped) {
  RichardsSoil soil;
  soil.porosity = 0.4;
  soil.saturated_conductivity = 1.0 / kDay;
  soil.saturation = [capped](double pc) {
    if (capped && pc <= 0) return 1.0;
    return 0.23 + 0.77 * std::exp(-2.0 * pc / kRhoG);
  };
  soil.relative_conductivity = [capped](double pc) {
    if (capped && pc <= 0) return 1.0;
    return std::exp(-2.0 * pc / kRhoG);
  };
  return soil;
}

double hydrostatic(double z) { return -kRhoG * z; }  // the paper's Section 4.1 initial state

struct ProfileError {
  double max_abs = 0;  // Pa
  double range = 0;    // max − min of the reference pressure over the column (Pa)
  double relative() const { return max_abs / range; }
};

ProfileError compare(const Richards1d& solver, const GardnerColumnSolution& exact, double t) {
  ProfileError e;
  double lo = 1e300, hi = -1e300;
  for (std::size_t i = 0; i < solver.cell_centres().size(); ++i) {
    const double z = solver.cell_centres()[i];
    const double p = exact.pore_pressure(z, t, 1000.0, 9.81);
    e.max_abs = std::max(e.max_abs, std::fabs(solver.pore_pressure()[i] - p));
    lo = std::min(lo, p);
    hi = std::max(hi, p);
  }
  e.range = hi - lo;
  return e;
}

double mass_balance_error(const Richards1d& solver) {
  const RichardsSnapshot s = solver.snapshot();
  const double inflow = s.cumulative_top_inflow + s.cumulative_bottom_inflow;
  return std::fabs(s.water_storage - solver.initial_storage() - inflow) / std::fabs(inflow);
}

RichardsOptions fine_options(int cells = 300) {
  RichardsOptions o;
  o.cells = cells;
  o.max_time_step = 30.0;
  o.time_weight = 0.5;
  return o;
}

// ---------------------------------------------------------------------------------------------
// Gardner closed forms on their own.

GardnerColumn section_4_1_column(ColumnBase base, double flux_in) {
  GardnerColumn c;
  c.soil = section_4_1_soil();
  c.height = kSection41Height;
  c.base = base;
  c.flux_in = flux_in;
  return c;
}

TEST(GardnerAnalytic, Section41SoilIsEq42) {
  const GardnerSoil s = section_4_1_soil();
  // θ(ψ) = φ S_w with S_w of Eq. 42 and ψ = −p_c/(ρ g): check at p_c = 5 kPa.
  const double pc = 5000.0, psi = -pc / kRhoG;
  EXPECT_NEAR(s.theta_r + (s.theta_s - s.theta_r) * std::exp(s.alpha * psi),
              0.4 * (0.23 + 0.77 * std::exp(-2.0 * pc / kRhoG)), 1e-15);
  EXPECT_DOUBLE_EQ(s.saturated_conductivity * kDay, 1.0);
}

// The solution satisfies its PDE, its boundary conditions and its water balance, for both bases
// and both fluxes of Section 4.1.
TEST(GardnerAnalytic, SatisfiesEquationBoundariesAndMass) {
  for (ColumnBase base : {ColumnBase::water_table, ColumnBase::no_flow}) {
    for (double q : {kSection41Infiltration, kSection41Evaporation}) {
      const GardnerColumn column = section_4_1_column(base, q);
      const GardnerColumnSolution s(column);
      const double ks = column.soil.saturated_conductivity, dtheta = 0.4 - 0.092, a = 2.0;
      for (double t : {0.01 * kDay, 0.1 * kDay, 1.0 * kDay}) {
        SCOPED_TRACE(testing::Message() << "base " << int(base) << " q " << q * kDay << " t " << t);
        // Dimensional PDE: (Δθ/K_s) ∂K/∂t = ∂²K/∂z²/α + ∂K/∂z (K relative), centred differences.
        const double z = 1.3, h = 2e-3, dt = 1e-3 * t;
        auto k = [&](double zz, double tt) { return s.relative_conductivity(zz, tt); };
        const double kt = (k(z, t + dt) - k(z, t - dt)) / (2 * dt);
        const double kz = (k(z + h, t) - k(z - h, t)) / (2 * h);
        const double kzz = (k(z + h, t) - 2 * k(z, t) + k(z - h, t)) / (h * h);
        EXPECT_NEAR(dtheta / ks * kt, kzz / a + kz, 1e-6 * (std::fabs(kz) + std::fabs(kzz)));
        // Top flux is the prescribed one.
        EXPECT_NEAR(s.downward_flux(kSection41Height, t), q, 1e-12 * std::fabs(q));
        // Flux is also ∂K/∂z/α + K in the interior (consistency of the two series).
        EXPECT_NEAR(s.downward_flux(z, t) / ks, kz / a + k(z, t), 1e-6);
        if (base == ColumnBase::no_flow) {
          EXPECT_NEAR(s.downward_flux(0.0, t), 0.0, 1e-13 * std::fabs(q));
          // Water balance: Δ∫θ dz = q t (midpoint rule on a fine grid).
          double gain = 0;
          const int n = 6000;
          for (int i = 0; i < n; ++i) {
            const double zz = (i + 0.5) * kSection41Height / n;
            gain += (s.water_content(zz, t) - s.water_content(zz, 0.0)) * kSection41Height / n;
          }
          EXPECT_NEAR(gain, q * t, 2e-6 * std::fabs(q * t));  // midpoint rule on the steep front
        } else {
          EXPECT_NEAR(s.pressure_head(0.0, t), 0.0, 1e-12);  // the water table stays put
        }
      }
    }
  }
}

// Small times: the solution leaves the initial state continuously; long times, water table:
// the steady profile for q_B.
TEST(GardnerAnalytic, InitialAndSteadyLimits) {
  const GardnerColumnSolution inf(
      section_4_1_column(ColumnBase::water_table, kSection41Infiltration));
  for (double z : {0.5, 1.5, 2.5}) {
    EXPECT_NEAR(inf.pressure_head(z, 1.0), -z, 1e-6);  // 1 s after the flux starts
    const double qb = 0.1, steady = std::log(qb - (qb - 1.0) * std::exp(-2.0 * z)) / 2.0;
    EXPECT_NEAR(inf.pressure_head(z, 100.0 * kDay), steady, 1e-12);
  }
  // Both bases agree while the base has not felt the flux (early times, upper column).
  const GardnerColumnSolution nf(section_4_1_column(ColumnBase::no_flow, kSection41Infiltration));
  EXPECT_NEAR(nf.pressure_head(2.5, 0.05 * kDay), inf.pressure_head(2.5, 0.05 * kDay), 1e-9);
  // No-flow infiltration raises the base above saturation eventually (K > 1): valid() says so.
  EXPECT_TRUE(nf.valid(0.0, 0.05 * kDay));
  EXPECT_FALSE(nf.valid(0.0, 2.0 * kDay));
  EXPECT_TRUE(nf.valid(0.0, 2.0 * kDay, /*require_unsaturated=*/false));
}

// ---------------------------------------------------------------------------------------------
// Richards solver against the Gardner closed forms (the same mathematical problem).

TEST(Richards1d, MatchesGardnerWaterTableInfiltration) {
  const GardnerColumnSolution exact(
      section_4_1_column(ColumnBase::water_table, kSection41Infiltration));
  Richards1d solver(section_4_1_richards_soil(false), kSection41Height, hydrostatic,
                    TopBoundary::constant_flux(kSection41Infiltration),
                    BottomBoundary::fixed_pressure(0.0), fine_options());
  for (double t : {0.05 * kDay, 0.25 * kDay, 1.0 * kDay}) {
    solver.advance_to(t);
    const ProfileError e = compare(solver, exact, t);
    EXPECT_LT(e.relative(), 5e-3) << "t = " << t / kDay << " day, max error " << e.max_abs << " Pa";
    EXPECT_LT(e.relative(), 1e-4);  // what this grid actually achieves
  }
  EXPECT_LT(mass_balance_error(solver), 1e-8);
}

TEST(Richards1d, MatchesGardnerNoFlowInfiltrationAndEvaporation) {
  for (double q : {kSection41Infiltration, kSection41Evaporation}) {
    const GardnerColumnSolution exact(section_4_1_column(ColumnBase::no_flow, q));
    Richards1d solver(section_4_1_richards_soil(false), kSection41Height, hydrostatic,
                      TopBoundary::constant_flux(q), BottomBoundary::no_flow(), fine_options());
    for (double t : {0.05 * kDay, 0.5 * kDay, 2.0 * kDay}) {
      solver.advance_to(t);
      const ProfileError e = compare(solver, exact, t);
      EXPECT_LT(e.relative(), 5e-3) << "q " << q * kDay << " t " << t / kDay << " day";
      EXPECT_LT(e.relative(), 3e-4);
    }
    EXPECT_LT(mass_balance_error(solver), 1e-8);
    // No flow through the base: all the change came through the top, q t.
    const RichardsSnapshot s = solver.snapshot();
    EXPECT_EQ(s.cumulative_bottom_inflow, 0.0);
    EXPECT_NEAR(s.cumulative_top_inflow, q * 2.0 * kDay, 1e-12 * std::fabs(q) * kDay);
  }
}

// The paper's physical soil (S_w capped at S_max) is the linear problem as long as the column
// stays unsaturated; early in the infiltration run it does.
TEST(Richards1d, CappedSoilMatchesGardnerWhileUnsaturated) {
  const GardnerColumnSolution exact(
      section_4_1_column(ColumnBase::no_flow, kSection41Infiltration));
  Richards1d solver(section_4_1_richards_soil(true), kSection41Height, hydrostatic,
                    TopBoundary::constant_flux(kSection41Infiltration), BottomBoundary::no_flow(),
                    fine_options());
  const double t = 0.1 * kDay;
  // The linear solution lifts the base above saturation at once, but by a negligible amount:
  ASSERT_LT(exact.relative_conductivity(0.0, t) - 1.0, 1e-6);
  solver.advance_to(t);
  EXPECT_LT(compare(solver, exact, t).relative(), 1e-4);
}

// Halving dz reduces the error (second order in space; Crank–Nicolson with small steps so that
// the time error does not hide it).
TEST(Richards1d, GridConvergence) {
  const GardnerColumnSolution exact(
      section_4_1_column(ColumnBase::no_flow, kSection41Infiltration));
  const double t = 0.05 * kDay;
  std::vector<double> errors;
  for (int cells : {60, 120, 240}) {
    RichardsOptions o = fine_options(cells);
    o.max_time_step = 5.0;
    Richards1d solver(section_4_1_richards_soil(false), kSection41Height, hydrostatic,
                      TopBoundary::constant_flux(kSection41Infiltration), BottomBoundary::no_flow(),
                      o);
    solver.advance_to(t);
    errors.push_back(compare(solver, exact, t).max_abs);
  }
  EXPECT_GT(errors[0] / errors[1], 3.0);
  EXPECT_GT(errors[1] / errors[2], 3.0);
}

// Backward Euler converges to the same solution (first order in time).
TEST(Richards1d, BackwardEulerConvergesInTime) {
  const GardnerColumnSolution exact(section_4_1_column(ColumnBase::no_flow, kSection41Evaporation));
  const double t = 0.2 * kDay;
  std::vector<double> errors;
  for (double dt : {240.0, 120.0, 60.0}) {
    RichardsOptions o = fine_options(300);
    o.time_weight = 1.0;
    o.max_time_step = dt;
    Richards1d solver(section_4_1_richards_soil(false), kSection41Height, hydrostatic,
                      TopBoundary::constant_flux(kSection41Evaporation), BottomBoundary::no_flow(),
                      o);
    solver.advance_to(t);
    errors.push_back(compare(solver, exact, t).max_abs);
  }
  EXPECT_GT(errors[0] / errors[1], 1.6);
  EXPECT_GT(errors[1] / errors[2], 1.6);
}

// ---------------------------------------------------------------------------------------------
// Richards solver: boundary switching and mass balance with the compressible storage.

// Rain faster than K_sat ponds the surface: the switch to p = p_max happens, the surface holds
// p_max, less than the rain enters, and water is conserved with a compressible pore water.
TEST(Richards1d, AdaptiveTopPondsUnderHeavyRain) {
  RichardsSoil soil = section_4_1_richards_soil(true);
  soil.water_bulk_modulus = 2e6;
  const double rain = 2.0 / kDay;
  RichardsOptions o = fine_options(200);
  o.time_weight = 1.0;
  Richards1d solver(soil, kSection41Height, hydrostatic, TopBoundary::adaptive(rain, 0.0, -1e6),
                    BottomBoundary::no_flow(), o);
  solver.advance_to(60.0);
  EXPECT_EQ(solver.top_state(), TopState::flux);  // a dry surface first takes all the rain
  solver.advance_to(0.5 * kDay);
  EXPECT_EQ(solver.top_state(), TopState::ponded);
  const RichardsSnapshot s = solver.snapshot();
  EXPECT_DOUBLE_EQ(s.surface_pressure, 0.0);
  EXPECT_LT(s.cumulative_top_inflow, rain * 0.5 * kDay);
  EXPECT_GT(s.cumulative_top_inflow, 0.0);
  EXPECT_LT(mass_balance_error(solver), 1e-8);
  // The saturated zone under the pond stores water by compression: storage exceeds φ S_w alone.
  EXPECT_GT(solver.storage(1e4), 0.4 * 1.0);
  EXPECT_NEAR(solver.storage(1e4) - solver.storage(0.0), 0.4 * 1e4 / 2e6, 1e-12);
}

// Strong evaporation dries the surface to p_min, which then holds; when rain follows, the
// surface goes back to the prescribed flux.
TEST(Richards1d, AdaptiveTopDryingLimitAndRecovery) {
  const double p_min = -40e3;
  TopBoundary top = TopBoundary::adaptive(0.0, 0.0, p_min);
  top.flux_in = [](double t) { return t < 0.5 * kDay ? -0.5 / kDay : 0.05 / kDay; };
  RichardsOptions o = fine_options(200);
  o.time_weight = 1.0;
  Richards1d solver(section_4_1_richards_soil(true), kSection41Height, hydrostatic, top,
                    BottomBoundary::no_flow(), o);
  solver.advance_to(0.4 * kDay);
  EXPECT_EQ(solver.top_state(), TopState::drying_limit);
  RichardsSnapshot s = solver.snapshot();
  EXPECT_DOUBLE_EQ(s.surface_pressure, p_min);
  EXPECT_GT(s.cumulative_top_inflow, -0.5 * 0.4);  // less than the demand left the soil
  for (double p : s.pore_pressure) EXPECT_GE(p, p_min - 1.0);
  solver.advance_to(0.6 * kDay);
  EXPECT_EQ(solver.top_state(), TopState::flux);
  EXPECT_LT(mass_balance_error(solver), 1e-8);
}

// With a fixed surface pressure the top flux is whatever the soil takes; the balance holds too.
TEST(Richards1d, FixedPressureTopConservesWater) {
  Richards1d solver(section_4_1_richards_soil(true), kSection41Height, hydrostatic,
                    TopBoundary::constant_pressure(-5e3), BottomBoundary::fixed_pressure(0.0),
                    fine_options(150));
  solver.advance_to(0.3 * kDay);
  const RichardsSnapshot s = solver.snapshot();
  EXPECT_GT(s.cumulative_top_inflow, 0.0);
  EXPECT_LT(s.cumulative_bottom_inflow, 0.0);  // the water table drains the wetted column
  EXPECT_LT(mass_balance_error(solver), 1e-8);
  EXPECT_DOUBLE_EQ(solver.pore_pressure_at(kSection41Height), -5e3);
  EXPECT_DOUBLE_EQ(solver.pore_pressure_at(0.0), 0.0);
}

// The convenience driver returns one profile per requested time, in order.
TEST(Richards1d, SolveReturnsRequestedProfiles) {
  const std::vector<RichardsSnapshot> out =
      solve_richards_1d(section_4_1_richards_soil(true), kSection41Height, hydrostatic,
                        TopBoundary::constant_flux(kSection41Infiltration),
                        BottomBoundary::no_flow(), {0.1 * kDay, 0.2 * kDay}, fine_options(100));
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].time, 0.1 * kDay);
  EXPECT_EQ(out[1].time, 0.2 * kDay);
  ASSERT_EQ(out[1].pore_pressure.size(), 100u);
  EXPECT_NEAR(out[1].z.back(), kSection41Height - 0.5 * kSection41Height / 100, 1e-12);
  EXPECT_NEAR(out[1].cumulative_top_inflow, kSection41Infiltration * 0.2 * kDay, 1e-15);
  EXPECT_GT(out[1].pore_pressure.back(), out[0].pore_pressure.back());  // the top wets
}

// ---------------------------------------------------------------------------------------------
// Terzaghi.

TEST(Terzaghi, ClassicalDegreeOfConsolidation) {
  EXPECT_NEAR(degree_of_consolidation(0.197), 0.5, 1e-3);
  EXPECT_NEAR(degree_of_consolidation(0.848), 0.9, 1e-3);
  // Small times: U ≈ 2 √(T_v/π); late: U → 1; monotone in between.
  EXPECT_NEAR(degree_of_consolidation(1e-4), 2.0 * std::sqrt(1e-4 / 3.14159265358979), 1e-12);
  EXPECT_NEAR(degree_of_consolidation(5.0), 1.0, 1e-5);
  double last = 0;
  for (double tv = 1e-5; tv < 3; tv *= 1.3) {
    const double u = degree_of_consolidation(tv);
    EXPECT_GT(u, last);
    last = u;
  }
}

TEST(Terzaghi, SeriesAgreeAndSatisfyTheProblem) {
  for (double tv : {0.002, 0.01, 0.05, 0.2}) {
    EXPECT_NEAR(terzaghi_degree_fourier(tv), terzaghi_degree_images(tv), 1e-12) << tv;
    for (double zeta : {0.0, 0.3, 0.7, 0.95}) {
      EXPECT_NEAR(terzaghi_pressure_fourier(zeta, tv), terzaghi_pressure_images(zeta, tv), 1e-12);
    }
    // Drained top, impermeable base (even in ζ about the base).
    EXPECT_NEAR(excess_pore_pressure_ratio(1.0, tv), 0.0, 1e-14);
    EXPECT_NEAR(excess_pore_pressure_ratio(1e-3, tv), excess_pore_pressure_ratio(0.0, tv),
                1e-5 * excess_pore_pressure_ratio(0.0, tv) + 1e-15);
    // 1 − U is the average of u/u_0 (midpoint rule).
    double mean = 0;
    for (int i = 0; i < 2000; ++i) mean += excess_pore_pressure_ratio((i + 0.5) / 2000, tv) / 2000;
    EXPECT_NEAR(mean, 1.0 - degree_of_consolidation(tv), 1e-6);
  }
  // Just after loading the interior carries the whole load.
  for (double zeta : {0.0, 0.5, 0.9})
    EXPECT_NEAR(excess_pore_pressure_ratio(zeta, 1e-8), 1.0, 1e-12);
}

TEST(Terzaghi, ConsolidationCoefficientWithCompressibleWater) {
  const double e_oed = oedometric_modulus(1.3e6, 0.4);
  EXPECT_NEAR(e_oed, 1.3e6 * 0.6 / (1.4 * 0.2), 1e-6);
  const double k = 4.41e-6, phi = 0.2975;
  // Incompressible water: c_v = k E_oed / γ_w.
  EXPECT_NEAR(consolidation_coefficient(k, e_oed, phi, INFINITY), k * e_oed / kRhoG, 1e-15);
  // Table 1's K_w = 2 MPa: the water takes a good part of the storage.
  const double cv = consolidation_coefficient(k, e_oed, phi, 2e6);
  EXPECT_NEAR(cv, k / (kRhoG * (1 / e_oed + phi / 2e6)), 1e-15);
  EXPECT_NEAR(loading_efficiency(e_oed, phi, 2e6), 1.0 / (1.0 + phi * e_oed / 2e6), 1e-15);
  EXPECT_NEAR(loading_efficiency(e_oed, phi, INFINITY), 1.0, 1e-15);
  // Settlement: instantaneous part at T_v = 0, all of m_v H Δσ at the end.
  const double load = 1e4, h = 1.0, u0 = load * loading_efficiency(e_oed, phi, 2e6);
  EXPECT_NEAR(consolidation_settlement(0.0, load, h, e_oed, phi, 2e6), h / e_oed * (load - u0),
              1e-15);
  EXPECT_NEAR(consolidation_settlement(10.0, load, h, e_oed, phi, 2e6), h * load / e_oed, 1e-12);
}

// The Richards solver's compressible storage on a rigid saturated column is Terzaghi's problem
// with m_v = 0: c = K_sat K_w/(γ_w φ). Two independent references, one answer.
TEST(Terzaghi, RichardsStorageOnRigidSaturatedColumn) {
  const double height = 1.0, k = 1e-5, kw = 2e6, phi = 0.3, u0 = 1e4;
  RichardsSoil soil;
  soil.porosity = phi;
  soil.saturated_conductivity = k;
  soil.saturation = [](double) { return 1.0; };
  soil.relative_conductivity = [](double) { return 1.0; };
  soil.water_bulk_modulus = kw;
  const double cv = consolidation_coefficient(k, INFINITY, phi, kw, kRhoG);
  EXPECT_NEAR(cv, k * kw / (kRhoG * phi), 1e-15);
  RichardsOptions o;  // backward Euler: Crank–Nicolson rings on the jump from u_0 to 0 at the top
  o.cells = 100;
  o.time_weight = 1.0;
  o.max_time_step = 2e-4 * height * height / cv;
  auto hydro = [&](double z) { return kRhoG * (height - z); };  // water table at the top
  Richards1d solver(
      soil, height, [&](double z) { return hydro(z) + u0; }, TopBoundary::constant_pressure(0.0),
      BottomBoundary::no_flow(), o);
  for (double tv : {0.05, 0.2, 0.6}) {
    solver.advance_to(tv * height * height / cv);
    double worst = 0;
    for (std::size_t i = 0; i < solver.cell_centres().size(); ++i) {
      const double z = solver.cell_centres()[i];
      const double u = solver.pore_pressure()[i] - hydro(z);
      worst = std::max(worst, std::fabs(u / u0 - excess_pore_pressure_ratio(z / height, tv)));
    }
    EXPECT_LT(worst, 2e-3) << "T_v = " << tv;
    const RichardsSnapshot s = solver.snapshot();
    // Water expelled through the top = storage lost = φ/K_w ∫ (u0 − u) dz = φ u0 H U / K_w.
    EXPECT_NEAR(-s.cumulative_top_inflow, phi * u0 * height * degree_of_consolidation(tv) / kw,
                2e-3 * phi * u0 * height / kw);
  }
  EXPECT_LT(mass_balance_error(solver), 1e-8);
}

// ---------------------------------------------------------------------------------------------
// Column collapse.

TEST(ColumnCollapse, Lube2005RegimesAndPublishedDiscontinuity) {
  EXPECT_EQ(collapse_regime(1.0), CollapseRegime::linear);
  EXPECT_EQ(collapse_regime(2.0), CollapseRegime::transition);
  EXPECT_EQ(collapse_regime(4.0), CollapseRegime::power_law);
  EXPECT_DOUBLE_EQ(lube2005_runout_band(1.0).low, 1.2);
  EXPECT_NEAR(lube2005_runout_band(8.0).high, 1.9 * 4.0, 1e-12);
  // As published the fit is not continuous: the branches differ at both ends of the transition
  // and meet only at a = (1.9/1.2)^3, beyond it.
  EXPECT_NEAR(lube2005_linear_runout(1.8), 2.16, 1e-12);
  EXPECT_NEAR(lube2005_power_runout(1.8), 1.9 * std::pow(1.8, 2.0 / 3.0), 1e-12);
  EXPECT_GT(lube2005_power_runout(1.8) - lube2005_linear_runout(1.8), 0.6);
  EXPECT_GT(lube2005_power_runout(2.8) - lube2005_linear_runout(2.8), 0.4);
  const double meet = std::pow(1.9 / 1.2, 3.0);
  EXPECT_NEAR(lube2005_linear_runout(meet), lube2005_power_runout(meet), 1e-12);
  EXPECT_GT(meet, Lube2005Planar::power_lower_aspect);
  // The band spans both branches inside the transition and is continuous at its ends from inside.
  const RunoutBand b = lube2005_runout_band(2.3);
  EXPECT_DOUBLE_EQ(b.low, lube2005_linear_runout(2.3));
  EXPECT_DOUBLE_EQ(b.high, lube2005_power_runout(2.3));
  // Run-out grows with a in every regime.
  double last = 0;
  for (double a = 0.2; a < 12; a += 0.1) {
    EXPECT_GE(lube2005_runout_band(a).low, last);
    last = lube2005_runout_band(a).low;
  }
  EXPECT_DOUBLE_EQ(balmforth_kerswell_2005_runout_exponent(ChannelWidth::narrow).value, 0.65);
  EXPECT_DOUBLE_EQ(balmforth_kerswell_2005_runout_exponent(ChannelWidth::wide).uncertainty, 0.1);
}

// ---------------------------------------------------------------------------------------------
// Liakopoulos.

TEST(Liakopoulos, CurvesAgreeWithOgsForm) {
  // Eq. 43a is the OGS curve 1 − 1.9722e-11 p_c^2.4279 exactly when ρ_w0 g = 10^4 Pa/m.
  for (double pc : {1e3, 5e3, 1e4}) {
    EXPECT_NEAR(liakopoulos_saturation_eq43(pc, 10.0), liakopoulos_saturation_ogs(pc), 2e-4);
  }
  // With g = 9.81 the deficit 1 − S_w is larger by (10^4/9810)^2.4279.
  EXPECT_NEAR(
      (1 - liakopoulos_saturation_eq43(5e3, 9.81)) / (1 - liakopoulos_saturation_eq43(5e3, 10.0)),
      std::pow(1e4 / 9810.0, 2.4279), 1e-12);
  // Eq. 43b reproduces the OGS k_rel table (liakopoulos.prj, curve k_rel) to its rounding.
  EXPECT_NEAR(liakopoulos_relative_conductivity(0.8), 0.56711275277159, 2e-4);
  EXPECT_NEAR(liakopoulos_relative_conductivity(0.6), 0.126933648878653, 2e-4);
  EXPECT_NEAR(liakopoulos_relative_conductivity(0.92), 0.828754286640385, 2e-4);
  EXPECT_DOUBLE_EQ(liakopoulos_relative_conductivity(0.3), 0.0);
  // K_sat of Table 1 is the OGS permeability 4.5e-13 m² at μ_w = 1e-3 Pa s.
  EXPECT_NEAR(LiakopoulosMaterial::saturated_conductivity, 4.5e-13 * kRhoG / 1e-3, 1e-8);
}

TEST(Liakopoulos, OgsProfilesAreConsistent) {
  using P = LiakopoulosOgsProfiles;
  for (int k = 0; k < 3; ++k) {
    const double* p = P::pressure(k);
    const double* u = P::displacement(k);
    EXPECT_EQ(p[0], 0.0);  // drained base
    EXPECT_EQ(u[0], 0.0);  // fixed base
    for (int i = 1; i < P::points; ++i) {
      EXPECT_LT(p[i], p[i - 1]);               // suction grows upwards
      EXPECT_LT(u[i], u[i - 1]);               // settlement grows upwards
      EXPECT_GT(p[i], -kRhoG * P::height[i]);  // never beyond the final hydrostatic state
      if (k > 0) {
        EXPECT_LT(p[i], P::pressure(k - 1)[i]);  // drainage proceeds in time
        EXPECT_LT(u[i], P::displacement(k - 1)[i]);
      }
    }
  }
  EXPECT_NEAR(P::interpolate(P::pressure(2), 1.0), -9171.73, 1e-9);
  EXPECT_NEAR(P::interpolate(P::pressure(0), 0.0125), 0.5 * -56.64, 1e-9);
}

// A rigid-skeleton Richards run of the same test drains faster than the coupled OGS solution,
// because the compacting skeleton feeds water to the drainage (storage m_v ~ 3.6e-7 1/Pa against
// a capillary capacity φ dS_w/dp ~ 2e-6 1/Pa early on); the difference fades as the column
// approaches equilibrium. A check that the decoded numbers mean what the header says they mean.
TEST(Liakopoulos, RigidRichardsBracketsOgs) {
  RichardsSoil soil;
  soil.porosity = LiakopoulosMaterial::porosity;
  soil.saturated_conductivity = 4.5e-13 * kRhoG / 1e-3;
  soil.saturation = [](double pc) { return liakopoulos_saturation_ogs(pc); };
  soil.relative_conductivity = [](double pc) {
    return liakopoulos_relative_conductivity(liakopoulos_saturation_ogs(pc));
  };
  soil.water_bulk_modulus = 2e9;
  RichardsOptions o;
  o.cells = 200;
  o.time_weight = 0.5;
  o.max_time_step = 10.0;
  Richards1d solver(
      soil, 1.0, [](double) { return 0.0; }, TopBoundary::constant_flux(0.0),
      BottomBoundary::fixed_pressure(0.0), o);
  const double tolerance[3] = {0.25, 0.15, 0.03};  // of the OGS top suction
  for (int k = 0; k < 3; ++k) {
    solver.advance_to(LiakopoulosOgsProfiles::times[k]);
    const double* p = LiakopoulosOgsProfiles::pressure(k);
    for (int i = 4; i < LiakopoulosOgsProfiles::points; i += 4) {
      const double rigid = solver.pore_pressure_at(LiakopoulosOgsProfiles::height[i]);
      EXPECT_LT(rigid, p[i]) << "t " << LiakopoulosOgsProfiles::times[k] << " z " << 0.025 * i;
      EXPECT_NEAR(rigid, p[i], tolerance[k] * std::fabs(p[40]));
    }
  }
  EXPECT_LT(mass_balance_error(solver), 1e-8);
}


// ---------------------------------------------------------------------------------------------
// Two-layer Srivastava–Yeh solution (gardner_layered.h).

// A coarse layer over a fine one would perch water; here a slower, wetter-holding upper layer over
// the Eq. 42 soil: K_s2 = 0.2 m/day, θ_s2 = 0.45, θ_r2 = 0.1, one α = 2 1/m; water table at the
// base; surface flux 0.01 → 0.1 m/day.
LayeredGardnerColumn layered_column(double lower = 1.5, double upper = 1.5) {
  LayeredGardnerColumn c;
  c.lower = section_4_1_soil();
  c.upper = GardnerSoil{2.0, 0.45, 0.10, 0.2 / kDay};
  c.lower_thickness = lower;
  c.upper_thickness = upper;
  c.base_pressure_head = 0.0;
  c.initial_flux_in = 0.01 / kDay;
  c.flux_in = 0.1 / kDay;
  return c;
}

// Steady head for a flux q by integrating dψ/dz = q/K_i(ψ) − 1 upwards from the water table with
// classical RK4 (step 1 mm; error ~1e-12 m here): independent of the closed forms.
double steady_head_rk4(const GardnerSoil& lower, const GardnerSoil& upper, double l1, double psi0,
                       double q, double z) {
  auto rhs = [&](double zz, double psi) {
    const GardnerSoil& s = zz < l1 ? lower : upper;
    return q / (s.saturated_conductivity * std::exp(s.alpha * psi)) - 1.0;
  };
  double psi = psi0, zz = 0;
  auto advance = [&](double to) {  // never steps across the interface
    const int n = std::max(1, int(std::ceil((to - zz) / 1e-3)));
    const double h = (to - zz) / n;
    const double zc = 0.5 * (zz + to);  // the layer of this stretch
    auto f = [&](double, double p) { return rhs(zc, p); };
    for (int i = 0; i < n; ++i) {
      const double k1 = f(zz, psi), k2 = f(zz + h / 2, psi + h / 2 * k1);
      const double k3 = f(zz + h / 2, psi + h / 2 * k2), k4 = f(zz + h, psi + h * k3);
      psi += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      zz += h;
    }
    zz = to;
  };
  if (z > l1) {
    advance(l1);
    advance(z);
  } else {
    advance(z);
  }
  return psi;
}

// Equal layers: the two-layer series is the homogeneous one (gardner_analytic.h), for infiltration
// and evaporation. Both series are summed to 1e-13 or better, so 1e-8 has a wide margin.
TEST(GardnerLayered, EqualLayersReproduceHomogeneousSolution) {
  for (double q : {kSection41Infiltration, kSection41Evaporation}) {
    LayeredGardnerColumn c = layered_column(1.2, 1.8);
    c.upper = c.lower;
    c.flux_in = q;
    GardnerColumn h = section_4_1_column(ColumnBase::water_table, q);
    h.initial_flux_in = c.initial_flux_in;
    const LayeredGardnerSolution layered(c);
    const GardnerColumnSolution homogeneous(h);
    double worst_k = 0, worst_q = 0;
    for (double t : {0.001 * kDay, 0.01 * kDay, 0.1 * kDay, 1.0 * kDay, 5.0 * kDay})
      for (int i = 0; i <= 60; ++i) {
        const double z = 0.05 * i;
        worst_k = std::max(worst_k, std::fabs(layered.relative_conductivity(z, t) -
                                              homogeneous.relative_conductivity(z, t)));
        worst_q = std::max(worst_q, std::fabs(layered.downward_flux(z, t) -
                                              homogeneous.downward_flux(z, t)));
      }
    EXPECT_LT(worst_k, 1e-8) << "q " << q * kDay;
    EXPECT_LT(worst_q / c.lower.saturated_conductivity, 1e-8) << "q " << q * kDay;
    // The eigenvalues are the homogeneous ones, σ = λ² + ¼ with tan λL + 2λ = 0.
    for (int n = 1; n <= 5; ++n) {
      const double lam = std::sqrt(layered.mode(n).sigma - 0.25), L = 2.0 * kSection41Height;
      EXPECT_NEAR(std::tan(lam * L) + 2 * lam, 0.0, 1e-9) << n;
    }
  }
}

// t = 0 is the steady profile for q_A, t → ∞ the one for q_B; both against the RK4 profile. The
// closed-form steady profile also holds for unequal α (only the transient needs one α).
TEST(GardnerLayered, InitialAndFinalSteadyStates) {
  const LayeredGardnerColumn c = layered_column();
  const LayeredGardnerSolution s(c);
  for (int i = 0; i <= 30; ++i) {
    const double z = 0.1 * i;
    const double psi_a = steady_head_rk4(c.lower, c.upper, 1.5, 0.0, c.initial_flux_in, z);
    const double psi_b = steady_head_rk4(c.lower, c.upper, 1.5, 0.0, c.flux_in, z);
    EXPECT_NEAR(s.pressure_head(z, 0.0), psi_a, 1e-9) << z;
    EXPECT_NEAR(s.pressure_head(z, 200.0 * kDay), psi_b, 1e-9) << z;
    EXPECT_NEAR(s.downward_flux(z, 200.0 * kDay), c.flux_in, 1e-12 * c.flux_in);
    GardnerSoil upper = c.upper;
    upper.alpha = 0.7;
    EXPECT_NEAR(layered_gardner_steady_pressure_head(c.lower, upper, 1.5, -0.2, c.flux_in, z),
                steady_head_rk4(c.lower, upper, 1.5, -0.2, c.flux_in, z), 1e-9)
        << z;
  }
  // The two steady states differ (the test above is not vacuous).
  EXPECT_GT(s.pressure_head(3.0, 200.0 * kDay) - s.pressure_head(3.0, 0.0), 0.5);
  GardnerSoil different = c.upper;
  different.alpha = 1.0;
  LayeredGardnerColumn bad = c;
  bad.upper = different;
  EXPECT_THROW(LayeredGardnerSolution{bad}, std::invalid_argument);
}

// Completeness of the eigenfunctions found by the root scan: Parseval's identity
// Σ a_n² N_n = ∫ρ v_0² dz. The terms fall as n^−4: the tail after 4000 modes is 1.4e-11 (K_s2/K_s1
// = 0.2) and 3.2e-11 (5) of the sum (summed to n = 40000 once), and the quadrature of the right
// side is exact to round-off, so 1e-10 holds; a root missed among the first ~400 (terms > 1e-10
// of the sum; 1.5e-9 at n = 200) would break it.
TEST(GardnerLayered, ModesAreCompleteParseval) {
  for (double ratio : {0.2, 5.0}) {
    LayeredGardnerColumn c = layered_column(1.0, 2.0);
    c.upper.saturated_conductivity = ratio * c.lower.saturated_conductivity;
    const LayeredGardnerSolution s(c);
    double sum = 0;
    for (int n = 1; n <= 4000; ++n) {
      const auto& m = s.mode(n);
      sum += m.coefficient * m.coefficient * m.norm;
      if (n > 1) ASSERT_GT(m.sigma, s.mode(n - 1).sigma);
    }
    EXPECT_NEAR(sum, s.initial_energy(), 1e-10 * s.initial_energy()) << "K_s2/K_s1 " << ratio;
  }
}

// The eigenvalues solve the two-layer characteristic equation of the paper as coded by Bandai &
// Ghezzehei (DD-PINNs-RRE, Srivastava1991_heterogeneous.ipynb), written here from its formula,
// on their example (α = 1 1/cm, L1* = L2* = 10 cm, K_s2/K_s1 = 10, equal θ), for the modes where
// its λ and μ are real. It was derived independently (gardner_layered.h), so agreement to
// round-off tests both.
TEST(GardnerLayered, RootsSolvePublishedCharacteristicEquation) {
  for (double ratio : {10.0, 0.1}) {
    LayeredGardnerColumn c;
    c.lower = GardnerSoil{100.0, 0.40, 0.06, 1e-5};
    c.upper = GardnerSoil{100.0, 0.40, 0.06, ratio * 1e-5};
    c.lower_thickness = c.upper_thickness = 0.1;
    c.initial_flux_in = 1e-7;
    c.flux_in = 5e-7;
    const LayeredGardnerSolution s(c);
    const double beta = 1.0 / ratio, l1 = 10.0, l2 = 10.0;
    int checked = 0;
    for (int n = 1; n <= 60; ++n) {
      const double lam2 = s.mode(n).sigma - 0.25, mu2 = beta * lam2 + (beta - 1.0) / 4.0;
      if (lam2 <= 0 || mu2 <= 0) continue;
      const double lam = std::sqrt(lam2), mu = std::sqrt(mu2);
      const double a = std::sin(lam * l1) + 2 * lam * std::cos(lam * l1);
      const double b = std::sin(mu * l2) + 2 * mu * std::cos(mu * l2);
      const double cc = (1 + 4 * mu2) * ratio * std::sin(lam * l1) * std::sin(mu * l2);
      EXPECT_NEAR(a * b - cc, 0.0, 1e-9 * (std::fabs(a * b) + std::fabs(cc))) << "n " << n;
      ++checked;
    }
    EXPECT_GT(checked, 40) << ratio;
  }
}

// The equation in each layer, the boundary conditions and continuity of head and flux at the
// interface (both sides' expressions evaluated at z = L1). The PDE residual is that of centred
// differences, O(h²) + O(δt²): with h = 0.5 mm and δt = 1e-4 t it is below 4e-7 of the scale
// (it falls fourfold per halving of h, measured), 1e-6 leaves margin.
TEST(GardnerLayered, EquationBoundariesAndInterface) {
  const LayeredGardnerColumn c = layered_column();
  const LayeredGardnerSolution s(c);
  for (double t : {0.02 * kDay, 0.2 * kDay, 2.0 * kDay}) {
    SCOPED_TRACE(testing::Message() << "t " << t / kDay << " day");
    for (double z : {0.7, 2.3}) {
      const GardnerSoil& soil = z < 1.5 ? c.lower : c.upper;
      const double h = 5e-4, dt = 1e-4 * t, a = soil.alpha;
      auto k = [&](double zz, double tt) { return s.relative_conductivity(zz, tt); };
      const double kt = (k(z, t + dt) - k(z, t - dt)) / (2 * dt);
      const double kz = (k(z + h, t) - k(z - h, t)) / (2 * h);
      const double kzz = (k(z + h, t) - 2 * k(z, t) + k(z - h, t)) / (h * h);
      const double dtheta = soil.theta_s - soil.theta_r, ks = soil.saturated_conductivity;
      EXPECT_NEAR(dtheta / ks * kt, kzz / a + kz, 1e-6 * (std::fabs(kz) + std::fabs(kzz)));
      EXPECT_NEAR(s.downward_flux(z, t) / ks, kz / a + k(z, t), 1e-6);
    }
    EXPECT_NEAR(s.pressure_head(0.0, t), 0.0, 1e-12);
    EXPECT_NEAR(s.downward_flux(3.0, t), c.flux_in, 1e-12 * c.flux_in);
    EXPECT_NEAR(s.relative_conductivity(1.5, t, 1), s.relative_conductivity(1.5, t, 2), 1e-12);
    EXPECT_NEAR(s.downward_flux(1.5, t, 1), s.downward_flux(1.5, t, 2), 1e-11 * c.flux_in);
    // The head gradient jumps at the interface (K_s differs), so the check above is not trivial.
    const double below = s.pressure_head(1.5 - 1e-4, t), above = s.pressure_head(1.5 + 1e-4, t);
    const double centre = s.pressure_head(1.5, t);
    EXPECT_GT(std::fabs((above - centre) - (centre - below)), 1e-6);
  }
}

// Water balance: d/dt ∫θ dz = q_B − q(0, t) (the base is the outflow). Storage by the trapezoid
// rule on 4000 intervals per layer (error ~1e-7 relative, and mostly the same at t ± δ), time
// derivative by a central difference with δ = 1e-3 t (error ~1e-6 relative).
TEST(GardnerLayered, MassBalance) {
  const LayeredGardnerColumn c = layered_column();
  const LayeredGardnerSolution s(c);
  auto storage = [&](double t) {
    double sum = 0;
    for (int layer = 1; layer <= 2; ++layer) {
      const GardnerSoil& soil = layer == 1 ? c.lower : c.upper;
      const double a = layer == 1 ? 0.0 : 1.5, b = layer == 1 ? 1.5 : 3.0;
      const int n = 4000;
      const double h = (b - a) / n;
      for (int i = 0; i <= n; ++i) {
        const double w = (i == 0 || i == n) ? 0.5 : 1.0;
        const double k = s.relative_conductivity(a + i * h, t, layer);
        sum += w * h * (soil.theta_r + (soil.theta_s - soil.theta_r) * k);
      }
    }
    return sum;
  };
  for (double t : {0.05 * kDay, 0.5 * kDay, 2.0 * kDay}) {
    const double dt = 1e-3 * t;
    const double rate = (storage(t + dt) - storage(t - dt)) / (2 * dt);
    const double expected = c.flux_in - s.downward_flux(0.0, t);
    EXPECT_NEAR(rate, expected, 1e-4 * std::fabs(expected)) << "t " << t / kDay << " day";
  }
}

// The fine-grid Richards solver with a two-layer soil (richards_1d.h, layered constructor)
// against the closed form, uncapped curves as in the homogeneous comparison. The interface sits
// on a cell face.
TEST(Richards1d, LayeredMatchesLayeredGardner) {
  const LayeredGardnerColumn c = layered_column();
  const LayeredGardnerSolution exact(c);
  auto richards_soil = [](const GardnerSoil& g) {
    RichardsSoil soil;
    soil.porosity = g.theta_s;
    soil.saturated_conductivity = g.saturated_conductivity;
    soil.saturation = [g](double pc) {
      return (g.theta_r + (g.theta_s - g.theta_r) * std::exp(-g.alpha * pc / kRhoG)) / g.theta_s;
    };
    soil.relative_conductivity = [g](double pc) { return std::exp(-g.alpha * pc / kRhoG); };
    return soil;
  };
  Richards1d solver({{1.5, richards_soil(c.lower)}, {3.0, richards_soil(c.upper)}}, 3.0,
                    [&](double z) { return kRhoG * exact.pressure_head(z, 0.0); },
                    TopBoundary::constant_flux(c.flux_in), BottomBoundary::fixed_pressure(0.0),
                    fine_options(300));
  for (double t : {0.25 * kDay, 1.0 * kDay, 3.0 * kDay}) {
    solver.advance_to(t);
    double worst = 0, lo = 1e300, hi = -1e300;
    for (std::size_t i = 0; i < solver.cell_centres().size(); ++i) {
      const double z = solver.cell_centres()[i], p = kRhoG * exact.pressure_head(z, t);
      worst = std::max(worst, std::fabs(solver.pore_pressure()[i] - p));
      lo = std::min(lo, p);
      hi = std::max(hi, p);
    }
    EXPECT_LT(worst / (hi - lo), 5e-3) << "t " << t / kDay << " day, max error " << worst;
    EXPECT_LT(worst / (hi - lo), 5e-4);  // what this grid achieves (second order in dz)
  }
  EXPECT_LT(mass_balance_error(solver), 1e-8);
  // The layers hold different water at the same pressure.
  EXPECT_NEAR(solver.storage(-1e4, 0), 0.4 * (0.23 + 0.77 * std::exp(-2.0 * 1e4 / kRhoG)), 1e-15);
  EXPECT_NEAR(solver.storage(-1e4, 299), 0.10 + 0.35 * std::exp(-2.0 * 1e4 / kRhoG), 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Infinite slope with suction stress (infinite_slope.h).

constexpr double kDeg = 3.14159265358979323846 / 180.0;

InfiniteSlope sand_slope(double beta_deg, double phi_deg, double cohesion, double gamma) {
  InfiniteSlope s;
  s.slope_angle = beta_deg * kDeg;
  s.friction_angle = phi_deg * kDeg;
  s.cohesion = cohesion;
  s.unit_weight = gamma;
  s.effective_saturation = van_genuchten_effective_saturation(1.0, 2.0);
  return s;
}

// Dry (u_w = 0), no cohesion: FS = tan φ'/tan β at every depth.
TEST(InfiniteSlope, DryCohesionless) {
  const InfiniteSlopeStability slope(sand_slope(30, 35, 0, 18e3));
  for (double h : {0.3, 1.0, 4.0})
    EXPECT_NEAR(slope.factor_of_safety(h, 0.0), std::tan(35 * kDeg) / std::tan(30 * kDeg), 1e-14);
}

// Seepage parallel to the slope with the water table on the surface: equipotentials are normal to
// the slope, so ψ = H cos²β at vertical depth H, and FS = (1 − γ_w/γ_sat) tan φ'/tan β.
TEST(InfiniteSlope, SlopeParallelSeepage) {
  const double gamma = 20e3, beta = 25 * kDeg;
  const InfiniteSlopeStability slope(sand_slope(25, 36, 0, gamma));
  for (double h : {0.5, 2.0, 6.0}) {
    const double psi = h * std::cos(beta) * std::cos(beta);
    EXPECT_NEAR(slope.factor_of_safety(h, psi),
                (1.0 - 9810.0 / gamma) * std::tan(36 * kDeg) / std::tan(beta), 1e-14);
  }
}

// Cohesion term by hand: β = 35°, φ' = 30°, c' = 5 kPa, γ = 19 kN/m³, H = 1.5 m, u_w = 0:
// tan 30°/tan 35° = 0.577350/0.700208 = 0.824542; 2c'/(γ H sin 2β) = 10000/(28500 · 0.939693)
// = 0.373396; FS = 1.197938 (six-figure tables, hence the 2e-6).
TEST(InfiniteSlope, CohesionByHand) {
  const InfiniteSlopeStability slope(sand_slope(35, 30, 5e3, 19e3));
  EXPECT_NEAR(slope.factor_of_safety(1.5, 0.0), 1.197938, 2e-6);
  // Halving the depth doubles the cohesion term.
  EXPECT_NEAR(slope.factor_of_safety(0.75, 0.0), 0.824542 + 2 * 0.373396, 4e-6);
}

// Suction stress by hand and its effect: van Genuchten α = 1 1/m, n = 2 at ψ = −1 m:
// S_e = 2^{−1/2}, σ^s = −9810/√2 = −6936.7 Pa; Gardner α = 1 1/m: σ^s = −9810 e^{−1} = −3608.9 Pa.
// Suction (ψ < 0) raises FS above the u_w = 0 value; positive pressure lowers it.
TEST(InfiniteSlope, SuctionRaisesFactorOfSafety) {
  InfiniteSlope vg = sand_slope(35, 30, 0, 18e3);
  InfiniteSlope gardner = vg;
  gardner.effective_saturation = gardner_effective_saturation(1.0);
  const InfiniteSlopeStability a(vg), b(gardner);
  EXPECT_NEAR(a.suction_stress(-1.0), -6936.7, 0.05);
  EXPECT_NEAR(b.suction_stress(-1.0), -3608.9, 0.05);
  EXPECT_DOUBLE_EQ(a.suction_stress(0.5), 9810.0 * 0.5);  // saturated: Terzaghi
  const double dry = a.factor_of_safety(1.0, 0.0);
  for (double psi : {-0.1, -1.0, -3.0}) {
    EXPECT_GT(a.factor_of_safety(1.0, psi), dry) << psi;
    EXPECT_GT(b.factor_of_safety(1.0, psi), dry) << psi;
  }
  EXPECT_LT(a.factor_of_safety(1.0, 0.2), dry);
  // Hand value: FS = 0.824542 + 6936.7 · 0.577350/(18000 · 0.573576 · 0.819152)
  //                = 0.824542 + 0.473548.
  EXPECT_NEAR(a.factor_of_safety(1.0, -1.0), 0.824542 + 0.473548, 5e-6);
}

// A depth-dependent unit weight enters through the overburden W(H) = ∫γ dd.
TEST(InfiniteSlope, DepthDependentUnitWeight) {
  InfiniteSlope s = sand_slope(30, 33, 4e3, 0.0);
  s.unit_weight = std::numeric_limits<double>::quiet_NaN();
  s.unit_weight_profile = [](double d) { return 16e3 + 2e3 * d; };
  const InfiniteSlopeStability slope(s);
  const double h = 2.5, w = 16e3 * h + 1e3 * h * h;
  EXPECT_NEAR(slope.overburden(h), w, 1e-9 * w);
  const double beta = 30 * kDeg, tan_phi = std::tan(33 * kDeg), psi = -0.4;
  const double sigma_s = 9810.0 * psi / std::sqrt(1.0 + 0.16);  // vG α = 1, n = 2
  EXPECT_NEAR(slope.factor_of_safety(h, psi),
              tan_phi / std::tan(beta) +
                  (4e3 - sigma_s * tan_phi) / (w * std::sin(beta) * std::cos(beta)),
              1e-12);
}

// Earliest failure time against a closed form: a water table rising from depth 2 m to
// the surface in 10 days, seepage parallel to the slope, ψ = (d − d_w(t)) cos²β (suction above
// it). With c' = 0 the minimum over depth is on the deepest plane H, and FS(H) = 1 when
// d_w = H [1 − (1 − tan β/tan φ') γ/γ_w].
TEST(InfiniteSlope, CriticalTimeForRisingWaterTable) {
  const double beta = 30 * kDeg, phi = 40 * kDeg, gamma = 20e3, depth = 2.0, rise = 10 * kDay;
  const InfiniteSlopeStability slope(sand_slope(30, 40, 0, gamma));
  const HeadField field = [&](double d, double t) {
    const double water_table = depth * (1.0 - t / rise);
    return (d - water_table) * std::cos(beta) * std::cos(beta);
  };
  const double d_w = depth * (1.0 - (1.0 - std::tan(beta) / std::tan(phi)) * gamma / 9810.0);
  const double t_exact = rise * (1.0 - d_w / depth);
  SlopeSearchOptions o;
  o.time_tolerance = 10.0;
  const SlopeCriticalState c = slope.critical_depth_and_time(field, 0.05, depth, 0.0, rise, o);
  ASSERT_TRUE(c.found);
  EXPECT_GE(c.time, t_exact - 1e-6);
  EXPECT_LE(c.time, t_exact + o.time_tolerance);
  EXPECT_NEAR(c.depth, depth, 1e-6);
  EXPECT_LE(c.factor_of_safety, 1.0);
  EXPECT_NEAR(c.factor_of_safety, 1.0, 1e-4);
}

// The layered Srivastava–Yeh infiltration as the head field (d = L − z): a cohesive sand slope
// that stands under the initial suction and loses it. The search returns a bracket: FS <= 1 at
// the returned time, > 1 one tolerance earlier.
TEST(InfiniteSlope, CriticalTimeUnderLayeredInfiltration) {
  LayeredGardnerColumn c;
  c.lower = GardnerSoil{1.0, 0.40, 0.10, 0.5 / kDay};
  c.upper = GardnerSoil{1.0, 0.35, 0.05, 2.0 / kDay};
  c.lower_thickness = 2.0;
  c.upper_thickness = 2.0;
  c.initial_flux_in = 0.001 / kDay;
  c.flux_in = 0.4 / kDay;
  const LayeredGardnerSolution column(c);
  const HeadField field = [&](double d, double t) {
    return column.pressure_head(c.height() - d, t);
  };
  InfiniteSlope s = sand_slope(35, 33, 1e3, 19e3);
  s.effective_saturation = gardner_effective_saturation(1.0);  // the column's own S_e = e^{αψ}
  const InfiniteSlopeStability slope(s);
  const double d_min = 0.05, d_max = 3.5;
  ASSERT_GT(slope.minimum_over_depth(field, 0.0, d_min, d_max).factor_of_safety, 1.0);
  ASSERT_LT(slope.minimum_over_depth(field, 30 * kDay, d_min, d_max).factor_of_safety, 1.0);
  SlopeSearchOptions o;
  o.time_tolerance = 60.0;
  const SlopeCriticalState critical =
      slope.critical_depth_and_time(field, d_min, d_max, 0.0, 10 * kDay, o);
  ASSERT_TRUE(critical.found);
  EXPECT_LE(critical.factor_of_safety, 1.0);
  EXPECT_GT(slope.minimum_over_depth(field, critical.time - o.time_tolerance, d_min, d_max)
                .factor_of_safety,
            1.0);
  EXPECT_GT(critical.depth, d_min);
  EXPECT_LE(critical.depth, d_max);
  std::printf("layered infiltration: failure at t = %.4f day, depth %.3f m\n",
              critical.time / kDay, critical.depth);
}

}  // namespace
}  // namespace cascade::reference
