// Host-side validation of hydraulic-model parameters. Kept out of hydraulic_model.h so that
// device code does not include <string>. The case loader prefixes the YAML key to the message.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

#include "server/physics/swcc/hydraulic_model.h"

namespace cascade {

namespace hydraulic_check {

// "name must be <rule> (got value)"; every rule is written so that NaN fails it.
template <typename Real>
std::string error(const char* name, const char* rule, Real value) {
  std::ostringstream out;
  out << name << " must be " << rule << " (got " << value << ")";
  return out.str();
}

// The saturation range shared by Eqs. 14 and 42: 0 <= S_min < S_max <= 1 (an infinite S_min or
// S_max fails one of the comparisons).
template <typename Real>
std::string saturation_range(Real s_min, Real s_max) {
  if (!(s_min >= Real(0))) return error("s_min", ">= 0", s_min);
  if (!(s_max <= Real(1))) return error("s_max", "<= 1", s_max);
  if (!(s_min < s_max)) {
    std::ostringstream out;
    out << "s_min must be less than s_max (got s_min " << s_min << ", s_max " << s_max << ")";
    return out.str();
  }
  return {};
}

template <typename Real>
std::string positive(const char* name, const char* unit, Real value) {
  if (value > Real(0) && std::isfinite(value)) return {};
  return error(name, (std::string("a finite number > 0 ") + unit).c_str(), value);
}

}  // namespace hydraulic_check

template <typename Real>
std::string check_hydraulic_model(const VanGenuchten<Real>& m) {
  if (auto e = hydraulic_check::saturation_range(m.s_min, m.s_max); !e.empty()) return e;
  // λ = 1 − 1/n with n > 1 (Eq. 14): λ <= 0 gives no decay, λ >= 1 an infinite exponent.
  if (!(m.lambda > Real(0) && m.lambda < Real(1))) return hydraulic_check::error("lambda", "in (0, 1)", m.lambda);
  return hydraulic_check::positive("p_ref", "Pa", m.p_ref);
}

template <typename Real>
std::string check_hydraulic_model(const Gardner<Real>& m) {
  if (auto e = hydraulic_check::saturation_range(m.s_min, m.s_max); !e.empty()) return e;
  if (auto e = hydraulic_check::positive("alpha", "1/m", m.alpha); !e.empty()) return e;
  return hydraulic_check::positive("unit_weight", "Pa/m", m.unit_weight);
}

template <typename Real>
std::string check_hydraulic_model(const Liakopoulos<Real>& m) {
  return hydraulic_check::positive("unit_weight", "Pa/m", m.unit_weight);
}

// Empty when the model can be used; otherwise a message that starts with the offending
// parameter's name (s_min, s_max, lambda, p_ref, alpha, unit_weight, or model).
template <typename Real>
std::string check_hydraulic_model(const HydraulicModel<Real>& m) {
  using Kind = typename HydraulicModel<Real>::Kind;
  switch (m.kind) {
    case Kind::van_genuchten: return check_hydraulic_model(m.van_genuchten);
    case Kind::gardner: return check_hydraulic_model(m.gardner);
    case Kind::liakopoulos: return check_hydraulic_model(m.liakopoulos);
  }
  return "model must be van_genuchten, gardner or liakopoulos (got kind " + std::to_string(int(m.kind)) + ")";
}

}  // namespace cascade
