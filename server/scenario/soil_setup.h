// Scenario → the soil side of the engine: SoilMaterial from a soil material of the case (defaults,
// degrees → radians, the host-side checks of the hydraulic and constitutive models), the case's
// reference water density, the soil initial state (pore pressure, geostatic effective stress) and
// the free-surface hydraulic forcing at a given time. The validator, the particle builder, the
// engine set-up and the runner all use these, so a case means the same thing everywhere.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "cascade/v1/scenario.pb.h"
#include "server/core/hydraulic_forcing.h"
#include "server/core/soil_material.h"
#include "server/scenario/case_validation.h"

namespace cascade {

constexpr double kDefaultWaterDensity = 1000.0;       // ρ_w0 (kg/m³) without a water material
constexpr double kDefaultWaterBulkModulus = 2e6;      // K_w (Pa), Tables 1-3
constexpr double kDefaultPoreDelta = 0.1;             // δ of Eq. 27a
constexpr double kDefaultSoilViscosityAlpha = 0.1;    // α_μ,s of Eq. 26b (Bui and Nguyen 2021)
constexpr double kDefaultAtmosphericPressure = 101e3;  // p_atm of Eq. 13 (Pa)
constexpr double kPoreSoundSpeedFactor = 10.0;        // c_pw0 = 10 q_w,max, q_w,max = K_sat

// ρ_w0 of the case: the water material's density (0 means 1000), or 1000 without one.
double reference_water_density(const v1::ScenarioSpec& spec);

// |g| (m/s²).
double gravity_magnitude(const v1::ScenarioSpec& spec);

// The indices in spec.materials of the soil materials, in spec order: EngineConfig::soils[k] and
// HostParticles::soil_material == k stand for materials[soil_material_indices(spec)[k]].
std::vector<int> soil_material_indices(const v1::ScenarioSpec& spec);

// The engine's SoilMaterial for materials[material_index] (a soil): "0 / unset means" defaults
// applied, angles converted to radians, γ_w = ρ_w0 |g| in the hydraulic model. Reports the first
// problem through `fail` with the dotted key (`materials[1].soil.hydraulic.gardner.s_min`), then
// throws CaseError should `fail` return.
SoilMaterial soil_material(const v1::ScenarioSpec& spec, int material_index, const CaseFailure& fail);
// As above; problems throw CaseError (no line).
SoilMaterial soil_material(const v1::ScenarioSpec& spec, int material_index);

// The initial pore pressure p_w (Pa) at height z of a soil body with this initial state.
double initial_pore_pressure(const v1::InitialState& initial, double water_density, double gravity, double z);

// K0 of the geostatic stress: initial.k0, or ν/(1 − ν) of the mechanical model, 1 when rigid.
double earth_pressure_coefficient(const SoilMaterial& soil, const v1::InitialState& initial);

// The free-surface conditions of `spec.hydraulics` at simulated time t: the rain series is
// piecewise constant (a point's intensity holds from its time on; none before the first point).
HydraulicForcing hydraulic_forcing(const v1::ScenarioSpec& spec, double time);
// The same for one HydraulicBoundary: the case's own or its initialisation stage's.
HydraulicForcing hydraulic_forcing(const v1::HydraulicBoundary& hydraulics, double time);
// The conditions of the initialisation stage (spec.initialisation.hydraulics, constant in time).
HydraulicForcing initialisation_forcing(const v1::ScenarioSpec& spec);

}  // namespace cascade
