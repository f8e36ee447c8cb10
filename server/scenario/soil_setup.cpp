#include "server/scenario/soil_setup.h"

#include <cmath>

#include "server/physics/swcc/hydraulic_model_check.h"
#include "server/scenario/case_error.h"
#include "server/scenario/number_text.h"
#include "server/scenario/plausible_ranges.h"

namespace cascade {

namespace {

namespace pb = cascade::v1;

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadiansPerDegree = kPi / 180.0;


// The first word of a model check's message: the parameter it names.
std::string first_word(const std::string& message) { return message.substr(0, message.find(' ')); }

// Reports through `fail` and makes sure the report does not return.
class Reporter {
 public:
  explicit Reporter(const CaseFailure& fail) : fail_(fail) {}

  [[noreturn]] void error(const std::string& key, const std::string& message) const {
    fail_(key, message);
    throw CaseError(key, message);
  }
  void finite(const std::string& key, double v) const {
    if (!std::isfinite(v)) error(key, "must be a finite number");
  }
  void positive(const std::string& key, double v) const {
    finite(key, v);
    if (!(v > 0)) error(key, "must be greater than 0 (is " + number_text(v) + ")");
  }
  void non_negative(const std::string& key, double v, const std::string& zero_means) const {
    finite(key, v);
    if (v < 0) error(key, "must not be negative (is " + number_text(v) + "); 0 means " + zero_means);
  }
  void plausible(const std::string& key, const PlausibleRange& range, double v) const {
    if (const auto message = implausible(range, v)) error(key, *message);
  }

 private:
  const CaseFailure& fail_;
};

// The hydraulic model of a soil, γ_w = ρ_w0 |g| included, checked by hydraulic_model_check.h.
HydraulicModel<double> hydraulic_model(const pb::HydraulicModel& h, double unit_weight, const std::string& key,
                                       const Reporter& report) {
  HydraulicModel<double> model;
  std::string sub;
  const google::protobuf::Descriptor* fields = nullptr;
  switch (h.model_case()) {
    case pb::HydraulicModel::MODEL_NOT_SET:
      report.error(key, "has no model: give one of van_genuchten, gardner, liakopoulos");
    case pb::HydraulicModel::kVanGenuchten: {
      const pb::VanGenuchtenModel& v = h.van_genuchten();
      sub = key + ".van_genuchten";
      fields = pb::VanGenuchtenModel::descriptor();
      model = HydraulicModel<double>(VanGenuchten<double>{v.s_min(), v.has_s_max() ? v.s_max() : 1.0, v.lambda(),
                                                          v.p_ref()});
      break;
    }
    case pb::HydraulicModel::kGardner: {
      const pb::GardnerModel& g = h.gardner();
      sub = key + ".gardner";
      fields = pb::GardnerModel::descriptor();
      model = HydraulicModel<double>(
          Gardner<double>{g.s_min(), g.has_s_max() ? g.s_max() : 1.0, g.alpha(), unit_weight});
      break;
    }
    case pb::HydraulicModel::kLiakopoulos:
      sub = key + ".liakopoulos";
      fields = pb::LiakopoulosModel::descriptor();
      model = HydraulicModel<double>(Liakopoulos<double>{unit_weight});
      break;
  }
  const std::string message = check_hydraulic_model(model);
  if (message.empty()) return model;
  const std::string name = first_word(message);
  if (fields->FindFieldByName(name) != nullptr) report.error(sub + "." + name, message);
  if (name == "unit_weight")
    report.error(sub, message + ": the model reads the suction head p_c / (ρ_w0 |g|), so the case needs gravity");
  report.error(sub, message);
}

// A soil model's parameter name (as SoilModel::validate() reports it) → its key in the case file.
std::string drucker_prager_key(const std::string& name) {
  if (name == "peak_cohesion") return "cohesion";
  if (name == "peak_friction_angle") return "friction_angle";
  return name;
}

SoilModel<double> mechanical_model(const pb::SoilModel& s, const std::string& key, const Reporter& report) {
  SoilModel<double> model;
  std::string sub;
  switch (s.mechanical().model_case()) {
    case pb::MechanicalModel::MODEL_NOT_SET:
      if (!s.rigid())
        report.error(key, "has no model: give one of linear_elastic, drucker_prager (only a rigid soil may leave "
                          "it out)");
      // A rigid skeleton never deforms: a placeholder that validates and that nothing uses.
      model.kind = SoilModel<double>::Kind::linear_elastic;
      model.youngs_modulus = 1.0;
      model.poisson_ratio = 0.0;
      return model;
    case pb::MechanicalModel::kLinearElastic: {
      const pb::LinearElasticModel& e = s.mechanical().linear_elastic();
      sub = key + ".linear_elastic";
      model.kind = SoilModel<double>::Kind::linear_elastic;
      model.youngs_modulus = e.youngs_modulus();
      model.poisson_ratio = e.poisson_ratio();
      break;
    }
    case pb::MechanicalModel::kDruckerPrager: {
      const pb::DruckerPragerModel& d = s.mechanical().drucker_prager();
      sub = key + ".drucker_prager";
      // In degrees first, so the message shows the number the file has.
      report.finite(sub + ".friction_angle", d.friction_angle());
      if (!(d.friction_angle() >= 0 && d.friction_angle() < 90))
        report.error(sub + ".friction_angle", "must be in [0, 90) degrees (is " + number_text(d.friction_angle()) + ")");
      model.kind = SoilModel<double>::Kind::drucker_prager;
      model.youngs_modulus = d.youngs_modulus();
      model.poisson_ratio = d.poisson_ratio();
      model.peak_cohesion = d.cohesion();
      model.residual_cohesion = d.has_residual_cohesion() ? d.residual_cohesion() : d.cohesion();
      model.peak_friction_angle = d.friction_angle() * kRadiansPerDegree;
      model.residual_friction_angle =
          (d.has_residual_friction_angle() ? d.residual_friction_angle() : d.friction_angle()) * kRadiansPerDegree;
      model.dilatancy_angle = d.dilatancy_angle() * kRadiansPerDegree;
      model.softening_coefficient = d.softening_coefficient();
      model.suction_cohesion = d.suction_cohesion();
      model.suction_cohesion_rate = d.suction_cohesion_rate();
      model.suction_friction_rate = d.suction_friction_rate() * kRadiansPerDegree;
      model.atmospheric_pressure =
          d.atmospheric_pressure() != 0 ? d.atmospheric_pressure() : kDefaultAtmosphericPressure;
      break;
    }
  }
  const std::string message = model.validate();
  if (!message.empty()) {
    const std::string name = first_word(message);
    report.error(name == "kind" ? sub : sub + "." + drucker_prager_key(name), message);
  }
  report.plausible(sub + ".youngs_modulus", kYoungsModulus, model.youngs_modulus);
  return model;
}

}  // namespace

double reference_water_density(const pb::ScenarioSpec& spec) {
  for (const pb::Material& m : spec.materials())
    if (m.has_water()) return m.water().density() > 0 ? m.water().density() : kDefaultWaterDensity;
  return kDefaultWaterDensity;
}

double gravity_magnitude(const pb::ScenarioSpec& spec) {
  double g2 = 0.0;
  for (double g : spec.gravity()) g2 += g * g;
  return std::sqrt(g2);
}

std::vector<int> soil_material_indices(const pb::ScenarioSpec& spec) {
  std::vector<int> indices;
  for (int m = 0; m < spec.materials_size(); ++m)
    if (spec.materials(m).has_soil()) indices.push_back(m);
  return indices;
}

SoilMaterial soil_material(const pb::ScenarioSpec& spec, int material_index, const CaseFailure& fail) {
  const Reporter report(fail);
  const std::string key = "materials[" + std::to_string(material_index) + "].soil";
  const pb::Material& material = spec.materials(material_index);
  if (!material.has_soil()) report.error("materials[" + std::to_string(material_index) + "]", "is not a soil");
  const pb::SoilModel& s = material.soil();
  report.positive(key + ".grain_density", s.grain_density());
  report.plausible(key + ".grain_density", kGrainDensity, s.grain_density());
  report.finite(key + ".porosity", s.porosity());
  if (!(s.porosity() > 0 && s.porosity() < 1))
    report.error(key + ".porosity", "must be in (0, 1) (is " + number_text(s.porosity()) + ")");
  report.positive(key + ".saturated_conductivity", s.saturated_conductivity());
  report.plausible(key + ".saturated_conductivity", kSaturatedConductivity, s.saturated_conductivity());
  report.non_negative(key + ".water_bulk_modulus", s.water_bulk_modulus(), "2e6 Pa");
  if (s.water_bulk_modulus() > 0) report.plausible(key + ".water_bulk_modulus", kWaterBulkModulus, s.water_bulk_modulus());
  report.non_negative(key + ".pore_sound_speed", s.pore_sound_speed(), "10 saturated_conductivity");
  if (s.has_delta()) {
    report.finite(key + ".delta", s.delta());
    if (!(s.delta() >= 0 && s.delta() <= 1))
      report.error(key + ".delta", "must be in [0, 1] (is " + number_text(s.delta()) + "; usually 0.1)");
  }
  if (s.has_viscosity_alpha()) {
    report.finite(key + ".viscosity_alpha", s.viscosity_alpha());
    if (s.viscosity_alpha() < 0)
      report.error(key + ".viscosity_alpha", "must not be negative (is " + number_text(s.viscosity_alpha()) + ")");
  }
  report.finite(key + ".damping", s.damping());
  if (s.damping() < 0) report.error(key + ".damping", "must not be negative (is " + number_text(s.damping()) + "); 0 means none");
  if (s.damping() > 0 && s.rigid())
    report.error(key + ".damping", "damps the skeleton's motion, and a rigid soil does not move: leave it out");
  if (s.viscosity_switch() && s.rigid())
    report.error(key + ".viscosity_switch", "switches the skeleton's artificial viscosity, and a rigid soil does not "
                                             "move: leave it out");

  SoilMaterial out;
  out.grain_density = s.grain_density();
  out.reference_porosity = s.porosity();
  out.saturated_conductivity = s.saturated_conductivity();
  out.water_bulk_modulus = s.water_bulk_modulus() > 0 ? s.water_bulk_modulus() : kDefaultWaterBulkModulus;
  out.pore_sound_speed =
      s.pore_sound_speed() > 0 ? s.pore_sound_speed() : kPoreSoundSpeedFactor * s.saturated_conductivity();
  out.delta = s.has_delta() ? s.delta() : kDefaultPoreDelta;
  out.viscosity_alpha = s.has_viscosity_alpha() ? s.viscosity_alpha() : kDefaultSoilViscosityAlpha;
  out.rigid = s.rigid();
  out.damping = s.damping();
  out.viscosity_switch = s.viscosity_switch();
  out.hydraulic = hydraulic_model(s.hydraulic(), reference_water_density(spec) * gravity_magnitude(spec),
                                  key + ".hydraulic", report);
  out.mechanical = mechanical_model(s, key + ".mechanical", report);
  return out;
}

SoilMaterial soil_material(const pb::ScenarioSpec& spec, int material_index) {
  return soil_material(spec, material_index,
                       [](const std::string& key, const std::string& message) { throw CaseError(key, message); });
}

double initial_pore_pressure(const pb::InitialState& initial, double water_density, double gravity, double z) {
  switch (initial.pore_pressure_case()) {
    case pb::InitialState::kSuction:
      return -initial.suction();
    case pb::InitialState::kWaterTable:
      return water_density * gravity * (initial.water_table() - z);
    case pb::InitialState::PORE_PRESSURE_NOT_SET:
      break;
  }
  return 0.0;
}

double earth_pressure_coefficient(const SoilMaterial& soil, const pb::InitialState& initial) {
  if (initial.k0() > 0) return initial.k0();
  if (soil.rigid) return 1.0;
  const double nu = soil.mechanical.poisson_ratio;
  return nu / (1.0 - nu);
}

HydraulicForcing hydraulic_forcing(const pb::ScenarioSpec& spec, double time) {
  return hydraulic_forcing(spec.hydraulics(), time);
}

HydraulicForcing initialisation_forcing(const pb::ScenarioSpec& spec) {
  return hydraulic_forcing(spec.initialisation().hydraulics(), 0.0);
}

HydraulicForcing hydraulic_forcing(const pb::HydraulicBoundary& h, double time) {
  HydraulicForcing f;
  f.rainfall_intensity = h.rainfall_intensity();
  if (h.rainfall_size() > 0) {
    // Piecewise constant; a point counts from its own time on, whatever rounding the step sum has.
    const double slack = 1e-12 * std::abs(time);
    f.rainfall_intensity = 0.0;
    for (const pb::RainfallPoint& p : h.rainfall()) {
      if (p.time() > time + slack) break;
      f.rainfall_intensity = p.intensity();
    }
  }
  f.ponding_pressure = h.ponding_pressure();
  if (h.has_drying_pressure()) f.drying_pressure = h.drying_pressure();
  f.has_surface_pressure = h.has_surface_pressure();
  f.surface_pressure = h.surface_pressure();
  if (h.has_region()) {
    f.has_region = true;
    for (int a = 0; a < h.region().min_size() && a < 3; ++a) f.region_min[a] = h.region().min(a);
    for (int a = 0; a < h.region().max_size() && a < 3; ++a) f.region_max[a] = h.region().max(a);
  }
  return f;
}

}  // namespace cascade
