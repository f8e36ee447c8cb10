// A soil material as the engine sees it: the constants of the soil and pore-water terms and its
// hydraulic and constitutive models. In double precision on every backend: the models run once
// per particle and step (not per pair), so their cost does not matter, and one copy serves float
// and double engines.
#pragma once

#include "server/physics/soil/soil_model.h"
#include "server/physics/swcc/hydraulic_model.h"

namespace cascade {

struct SoilMaterial {
  double grain_density = 0;           // ρ_s0 (kg/m³), mixture density of Eq. 28a
  double reference_porosity = 0;      // φ0, the porosity at which the retention curve holds
                                      // (grain_bound_water.h): the case's initial porosity
  double saturated_conductivity = 0;  // K_sat (m/s); K = K_sat K_rel(p_c) in Eq. 27b
  double water_bulk_modulus = 0;      // K_w (Pa): pore-water state p_w = K_w/ρ_w0 (ρ_w − ρ_w0)
                                      // (Eq. 6 for the pore water, Eq. 36b) and C_r (Eq. 28b)
  double pore_sound_speed = 0;        // c_pw0 (m/s) of the pore-water δ-term (Eq. 27a)
  double delta = 0.1;                 // δ of the pore-water δ-term
  double viscosity_alpha = 0.1;       // α_μ,s of the soil momentum (Eq. 26b)
  double damping = 0;                 // ξ of the skeleton's velocity damping (soil_damping.h); 0: none
  bool viscosity_switch = false;      // α_μ,s times the compression switch (soil_viscosity_switch.h)
  bool rigid = false;                 // a fixed skeleton (Section 4.1): pore water flows through
                                      // it, the soil neither moves nor changes stress or porosity
  HydraulicModel<double> hydraulic;   // S_w(p_c), K_rel(p_c) (Eqs. 14, 15, 42, 43)
  SoilModel<double> mechanical;       // stress update (Eqs. 8-13)
};

}  // namespace cascade
