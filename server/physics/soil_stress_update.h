// The soil stress and porosity at the Symplectic stages (Section 3.4, symplectic_verlet.h): from
// the state at the start of the step and the rates of the last evaluation,
//   predictor  σ'^{n+½} = update(σ'^n, ε̇^n Δt/2, ω̇^n Δt/2),  φ^{n+½} = φ^n + Δt/2 φ̇^n,
//   corrector  σ'^{n+1} = update(σ'^n, ε̇^{n+½} Δt, ω̇^{n+½} Δt), φ^{n+1} = φ^n + Δt φ̇^{n+½},
// where update is the material's constitutive model with the Jaumann rotation (Eq. 8; linear
// elastic or Drucker-Prager with softening and suction hardening, Eqs. 10-13; soil/soil_model.h),
// ε̇ and ω̇ from the velocity gradient (Eqs. 26c, 26d) and the suction p_c = −p_w of the last
// evaluation. A rigid skeleton keeps its stress and porosity.
#pragma once

#include <cstdint>

#include "server/core/particle_view.h"
#include "server/physics/soil/jaumann_rate.h"
#include "server/physics/soil_view.h"

namespace cascade {

template <typename Real, int Dim>
struct SoilStressUpdate {
  ParticleView<Real, Dim> p;
  SoilView<Real, Dim> soil;
  const Voigt<Real>* start_stress;
  const Real* start_plastic_strain;
  const Real* start_porosity;
  Real dt;  // Δt/2 at the predictor, Δt at the corrector

  CASCADE_HD void operator()(std::uint32_t i) const {
    const SoilMaterial& m = soil.materials[soil.material[i]];
    if (m.rigid) return;
    const Mat<double, 3> gradient = velocity_gradient_3d<Real, Dim>(soil.velocity_gradient[i]).template cast<double>();
    const double step = double(dt);
    const auto updated = m.mechanical.update(tensor_of(start_stress[i]).template cast<double>(),
                                             strain_rate(gradient) * step, spin_rate(gradient) * step,
                                             -double(p.pressure[i]), double(start_plastic_strain[i]));
    soil.effective_stress[i] = voigt_of(updated.stress).template cast<Real>();
    soil.plastic_strain[i] = Real(updated.kappa);
    soil.porosity[i] = start_porosity[i] + dt * soil.porosity_rate[i];
  }
};

}  // namespace cascade
