#include "server/scenario/case_validation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "server/scenario/case_error.h"
#include "server/scenario/case_loader.h"
#include "server/scenario/number_text.h"
#include "server/scenario/snapshot_fields.h"
#include "server/scenario/soil_setup.h"

namespace cascade {

namespace {

using google::protobuf::RepeatedField;
using google::protobuf::RepeatedPtrField;
namespace pb = cascade::v1;

// Fields of every phase, and fields of soil particles only (probe phase soil).
const std::set<std::string> kProbeFields = {
    "pressure",       "density",        "speed",          "velocity_x",     "velocity_y",     "velocity_z",
    "displacement_x", "displacement_y", "displacement_z", "stress_xx",      "stress_yy",      "stress_zz",
    "stress_xy",      "stress_yz",      "stress_zx"};
const std::set<std::string> kSoilProbeFields = {
    "pore_pressure",         "saturation",            "porosity",              "plastic_strain",
    "seepage_x",             "seepage_y",             "seepage_z",             "effective_stress_xx",
    "effective_stress_yy",   "effective_stress_zz",   "effective_stress_xy",   "effective_stress_yz",
    "effective_stress_zx",   "free_surface"};
// Vector components that a 2D (x, z) case does not have.
const std::set<std::string> kThreeDimensionalOnly = {"velocity_y", "displacement_y", "seepage_y"};
const std::set<std::string> kPhases = {"water", "soil", "boundary"};

std::string indexed(const std::string& key, int i) { return key + "[" + std::to_string(i) + "]"; }


// Walks the spec top-down and reports the first problem; `dims_` is trusted once checked.
class SpecChecker {
 public:
  SpecChecker(const pb::ScenarioSpec& spec, const CaseFailure& fail) : spec_(spec), fail_(fail) {}

  void run() {
    check_scalars();
    check_domain();
    check_vector("gravity", spec_.gravity(), dims_, "the body force per unit mass");
    check_materials();
    check_bodies();
    check_numerics();
    check_output();
    check_probes();
    check_hydraulics();
    check_initialisation();
    check_stages();
    check_events();
  }

  // One snapshot of the spec's kind (dimensions, materials), as the snapshot RPCs ask for it.
  void run_snapshot(const std::string& key, const pb::Snapshot& snapshot) {
    dims_ = spec_.dimensions();
    check_snapshot(key, snapshot);
  }

 private:
  [[noreturn]] void error(const std::string& key, const std::string& message) const {
    fail_(key, message);
    throw CaseError(key, message);  // in case `fail_` returned
  }

  std::string axis_name(int axis) const { return dims_ == 2 ? (axis == 0 ? "x" : "z") : std::string(1, "xyz"[axis]); }

  void finite(const std::string& key, double v) const {
    if (!std::isfinite(v)) error(key, "must be a finite number");
  }
  void positive(const std::string& key, double v) const {
    finite(key, v);
    if (v <= 0) error(key, "must be greater than 0 (is " + number_text(v) + ")");
  }
  void non_negative(const std::string& key, double v, const std::string& zero_means = {}) const {
    finite(key, v);
    if (v < 0)
      error(key, "must not be negative (is " + number_text(v) + ")" + (zero_means.empty() ? "" : "; 0 means " + zero_means));
  }

  void check_vector(const std::string& key, const RepeatedField<double>& v, int size, const std::string& what) const {
    if (v.size() != size)
      error(key, "has " + std::to_string(v.size()) + (v.size() == 1 ? " component; " : " components; ") + what +
                     " needs " + std::to_string(size) + (size == dims_ ? " (the case's `dimensions`)" : ""));
    for (int i = 0; i < v.size(); ++i) finite(indexed(key, i), v[i]);
  }

  // max > min on every axis of an axis-aligned box (the domain or a Box shape).
  void check_min_max(const std::string& key, const RepeatedField<double>& min, const RepeatedField<double>& max,
                     const std::string& what) const {
    check_vector(key + ".min", min, dims_, what);
    check_vector(key + ".max", max, dims_, what);
    for (int a = 0; a < dims_; ++a)
      if (!(max[a] > min[a]))
        error(key + ".max", "must be greater than " + key + ".min on axis " + axis_name(a) + " (" + number_text(max[a]) +
                                " <= " + number_text(min[a]) + "): " + what + " would be empty");
  }

  void check_scalars() {
    dims_ = spec_.dimensions();
    if (dims_ != 2 && dims_ != 3) error("dimensions", "must be 2 or 3 (is " + std::to_string(spec_.dimensions()) + ")");
    positive("dp", spec_.dp());
    finite("h_over_dp", spec_.h_over_dp());
    if (spec_.h_over_dp() != 0 && (spec_.h_over_dp() < 1 || spec_.h_over_dp() > 3))
      error("h_over_dp", "must be in [1, 3] (is " + number_text(spec_.h_over_dp()) + "); leave it out for 1.3");
    positive("end_time", spec_.end_time());
  }

  void check_domain() {
    const pb::Domain& d = spec_.domain();
    if (d.min().empty() && d.max().empty()) error("domain", "is missing: give domain.min and domain.max");
    check_min_max("domain", d.min(), d.max(), "the domain");
    double volume = 1;
    for (int a = 0; a < dims_; ++a) volume *= d.max(a) - d.min(a);
    if (!(volume > 0) || !std::isfinite(volume)) error("domain", "must have a positive, finite volume");
    if (!d.periodic().empty() && d.periodic_size() != dims_)
      error("domain.periodic", "has " + std::to_string(d.periodic_size()) + " entries; give none or one per axis (" +
                                   std::to_string(dims_) + ")");
  }

  void check_materials() {
    if (spec_.materials().empty()) error("materials", "is missing: a case needs a water or a soil material");
    std::map<std::string, int> seen;
    int water = -1, soils = 0;
    for (int i = 0; i < spec_.materials_size(); ++i) {
      const pb::Material& m = spec_.materials(i);
      const std::string key = indexed("materials", i);
      if (m.name().empty()) error(key + ".name", "is missing: bodies refer to a material by its name");
      if (auto [it, added] = seen.emplace(m.name(), i); !added)
        error(key + ".name", "'" + m.name() + "' is already the name of " + indexed("materials", it->second));
      switch (m.model_case()) {
        case pb::Material::kWater:
          // The engine holds one set of water constants (ρ_w0, c_w0, δ, α): a second water
          // material would start in a state its equation of state does not balance.
          if (water >= 0)
            error(key, "a case has one water material; '" + spec_.materials(water).name() + "' is already one");
          water = i;
          check_water(key + ".water", m.water());
          break;
        case pb::Material::kSoil:
          // HostParticles::soil_material is one byte.
          if (++soils > 255) error(key, "a case has at most 255 soil materials");
          break;
        case pb::Material::MODEL_NOT_SET:
          error(key, "has no model: give one of: water, soil");
      }
    }
    // After the water material: a soil's hydraulic model takes γ_w = ρ_w0 |g| from it.
    for (int m : soil_material_indices(spec_)) soil_material(spec_, m, fail_);
  }

  void check_water(const std::string& key, const pb::WaterModel& w) const {
    non_negative(key + ".density", w.density(), "1000");
    non_negative(key + ".sound_speed", w.sound_speed(), "Eq. 24a");
    non_negative(key + ".max_speed", w.max_speed(), "sqrt(2 g H)");
    non_negative(key + ".max_pressure", w.max_pressure(), "rho g H");
    if (w.has_delta()) {
      non_negative(key + ".delta", w.delta());
      if (w.delta() > 1) error(key + ".delta", "must be in [0, 1] (is " + number_text(w.delta()) + "; usually 0.1)");
    }
    if (w.has_viscosity_alpha()) non_negative(key + ".viscosity_alpha", w.viscosity_alpha());
  }

  const pb::Material* material_named(const std::string& name) const {
    for (const pb::Material& m : spec_.materials())
      if (m.name() == name) return &m;
    return nullptr;
  }

  std::string material_names() const {
    std::string names;
    for (const pb::Material& m : spec_.materials()) names += (names.empty() ? "" : ", ") + m.name();
    return names.empty() ? "none are defined" : "defined: " + names;
  }

  void check_bodies() {
    if (spec_.bodies().empty()) error("bodies", "is empty: a case needs at least one body");
    std::map<std::string, int> seen;
    bool has_fluid = false;
    for (int i = 0; i < spec_.bodies_size(); ++i) {
      const pb::Body& b = spec_.bodies(i);
      const std::string key = indexed("bodies", i);
      if (b.name().empty()) error(key + ".name", "is missing");
      if (auto [it, added] = seen.emplace(b.name(), i); !added)
        error(key + ".name", "'" + b.name() + "' is already the name of " + indexed("bodies", it->second));
      if (b.kind() != pb::FLUID && b.kind() != pb::BOUNDARY) error(key + ".kind", "is missing: give fluid or boundary");
      has_fluid = has_fluid || b.kind() == pb::FLUID;
      if (b.kind() == pb::FLUID && b.material().empty())
        error(key + ".material", "is missing: a fluid body is made of a material");
      const pb::Material* material = b.material().empty() ? nullptr : material_named(b.material());
      if (!b.material().empty() && material == nullptr)
        error(key + ".material", "'" + b.material() + "' is not a material (" + material_names() + ")");
      check_shape(key + ".shape", b.shape(), true);
      for (int j = 0; j < b.subtract_size(); ++j) check_shape(indexed(key + ".subtract", j), b.subtract(j), false);
      if (!b.initial().velocity().empty())
        check_vector(key + ".initial.velocity", b.initial().velocity(), dims_, "a velocity");
      const pb::InitialState& initial = b.initial();
      const bool soil_state = initial.pore_pressure_case() != pb::InitialState::PORE_PRESSURE_NOT_SET ||
                              initial.k0() != 0;
      if (b.kind() == pb::BOUNDARY && (initial.hydrostatic() || !initial.velocity().empty() || soil_state))
        error(key + ".initial", "a boundary body is a fixed solid and has no initial state");
      if (b.kind() == pb::FLUID && material != nullptr) {
        if (material->has_soil()) check_soil_initial(key + ".initial", initial, *material);
        else if (soil_state)
          error(key + ".initial." + soil_state_key(initial),
                "is for soil bodies; '" + b.material() + "' is not a soil material");
      }
      if (b.layers() < 0) error(key + ".layers", "must not be negative (0 means enough to cover 2h)");
      if (b.has_pore_pressure()) check_drained_wall(key + ".pore_pressure", b);
    }
    if (!has_fluid) error("bodies", "has no fluid body: at least one body needs `kind: fluid`");
  }

  // A drained wall (Eqs. 36, 37): a boundary body in a case with soil, whose prescribed pore
  // water keeps a positive density ρ_w0 (1 + p / K_w) in every soil.
  void check_drained_wall(const std::string& key, const pb::Body& b) const {
    if (b.kind() != pb::BOUNDARY)
      error(key, "is the prescribed pore pressure of a drained wall: give it on a boundary body (a soil body starts "
                 "from initial.water_table or initial.suction)");
    if (soil_material_indices(spec_).empty())
      error(key, "acts on the pore water of soil next to the wall, and the case has no soil material");
    above_minus_bulk_modulus(key, b.pore_pressure());
  }

  // The smallest pore-water bulk modulus K_w of the soils (∞ without soil).
  double smallest_bulk_modulus() const {
    double bulk = std::numeric_limits<double>::infinity();
    for (int m : soil_material_indices(spec_)) {
      const double k = spec_.materials(m).soil().water_bulk_modulus();
      bulk = std::min(bulk, k > 0 ? k : kDefaultWaterBulkModulus);
    }
    return bulk;
  }

  // A prescribed pore pressure: finite and above −K_w of every soil.
  void above_minus_bulk_modulus(const std::string& key, double pressure) const {
    finite(key, pressure);
    const double bulk = smallest_bulk_modulus();
    if (!(pressure > -bulk))
      error(key, "must be above -K_w = " + number_text(-bulk) + " Pa, the smallest pore-water bulk modulus of the soils (is " +
                     number_text(pressure) + "): the pore-water density ρ_w0 (1 + p / K_w) must stay positive");
  }

  static std::string soil_state_key(const pb::InitialState& initial) {
    switch (initial.pore_pressure_case()) {
      case pb::InitialState::kSuction: return "suction";
      case pb::InitialState::kWaterTable: return "water_table";
      default: return "k0";
    }
  }

  // The initial state of a soil body: pore pressure (p_w > −K_w everywhere: the water-table case
  // is checked by the particle builder, which knows the body's extent) and K0.
  void check_soil_initial(const std::string& key, const pb::InitialState& initial, const pb::Material& m) const {
    // A horizontal component tilts the layers: gravity |g| (sin β, −cos β) makes a layer along x an
    // infinite slope of angle β (cases/infinite_slope_2d.yaml); the builder then measures the
    // initial state along z with gravity's z component, the slope-normal one.
    bool horizontal = false;
    const double vertical = spec_.gravity_size() == dims_ ? spec_.gravity(dims_ - 1) : 0.0;
    for (int a = 0; a + 1 < dims_ && a < spec_.gravity_size(); ++a) horizontal = horizontal || spec_.gravity(a) != 0;
    if (vertical > 0 || (horizontal && !(vertical < 0)))
      error("gravity", "must have a downward z component (or be zero) in a case with soil: the initial pore pressure "
                       "and geostatic stress of " + key.substr(0, key.find(".initial")) + " are measured along z");
    if (initial.hydrostatic())
      error(key + ".hydrostatic",
            "is for water bodies; a soil body starts from initial.water_table or initial.suction");
    if (initial.has_suction()) {
      finite(key + ".suction", initial.suction());
      if (!(initial.suction() > 0))
        error(key + ".suction", "must be greater than 0 (is " + number_text(initial.suction()) +
                                    "); leave it out for zero pore pressure, or give water_table");
      const double bulk = m.soil().water_bulk_modulus() > 0 ? m.soil().water_bulk_modulus() : kDefaultWaterBulkModulus;
      if (!(initial.suction() < bulk))
        error(key + ".suction", "must be below the pore water's bulk modulus K_w = " + number_text(bulk) +
                                    " Pa: the pore-water density ρ_w0 (1 − suction / K_w) must stay positive");
    }
    if (initial.has_water_table()) finite(key + ".water_table", initial.water_table());
    non_negative(key + ".k0", initial.k0(), "nu / (1 - nu) of the mechanical model, 1 for a rigid soil");
    if (m.soil().rigid())
      for (int a = 0; a < initial.velocity_size(); ++a)
        if (initial.velocity(a) != 0) error(key + ".velocity", "a rigid soil does not move: leave the velocity out");
  }

  // `inside_domain`: the shape bounds a body, so its extent must lie in the domain (subtracted
  // shapes may reach out of it, e.g. the open top of a tank).
  void check_shape(const std::string& key, const pb::Shape& s, bool inside_domain) const {
    switch (s.kind_case()) {
      case pb::Shape::KIND_NOT_SET:
        error(key, "names no shape: give one of box, polygon, extruded_polygon, half_space");
      case pb::Shape::kBox: {
        check_min_max(key + ".box", s.box().min(), s.box().max(), "the box");
        if (inside_domain)
          for (int a = 0; a < dims_; ++a) {
            check_inside(key + ".box.min", s.box().min(a), a);
            check_inside(key + ".box.max", s.box().max(a), a);
          }
        return;
      }
      case pb::Shape::kPolygon:
        if (dims_ != 2) error(key + ".polygon", "is a 2D shape; a 3D case uses extruded_polygon");
        check_vertices(key + ".polygon.vertices", s.polygon().vertices(), inside_domain);
        return;
      case pb::Shape::kExtrudedPolygon: {
        const pb::ExtrudedPolygon& e = s.extruded_polygon();
        if (dims_ != 3) error(key + ".extruded_polygon", "is a 3D shape; a 2D case uses polygon");
        check_vertices(key + ".extruded_polygon.vertices", e.vertices(), inside_domain);
        finite(key + ".extruded_polygon.y_min", e.y_min());
        finite(key + ".extruded_polygon.y_max", e.y_max());
        if (!(e.y_max() > e.y_min()))
          error(key + ".extruded_polygon.y_max",
                "must be greater than y_min (" + number_text(e.y_max()) + " <= " + number_text(e.y_min()) + ")");
        if (inside_domain) {
          check_inside(key + ".extruded_polygon.y_min", e.y_min(), 1);
          check_inside(key + ".extruded_polygon.y_max", e.y_max(), 1);
        }
        return;
      }
      case pb::Shape::kHalfSpace: {
        const pb::HalfSpace& h = s.half_space();
        check_vector(key + ".half_space.point", h.point(), dims_, "a point");
        check_vector(key + ".half_space.normal", h.normal(), dims_, "a normal");
        double length2 = 0;
        for (double c : h.normal()) length2 += c * c;
        if (!(length2 > 0)) error(key + ".half_space.normal", "must not be the zero vector");
        return;
      }
    }
  }

  void check_vertices(const std::string& key, const RepeatedPtrField<pb::Point2>& vertices, bool inside_domain) const {
    if (vertices.size() < 3)
      error(key, "has " + std::to_string(vertices.size()) + " vertices; a polygon needs at least 3");
    double twice_area = 0;
    for (int i = 0; i < vertices.size(); ++i) {
      const pb::Point2& p = vertices[i];
      const pb::Point2& q = vertices[(i + 1) % vertices.size()];
      finite(indexed(key, i), p.x());
      finite(indexed(key, i), p.z());
      if (inside_domain) {
        check_inside(indexed(key, i), p.x(), 0);
        check_inside(indexed(key, i), p.z(), dims_ - 1);
      }
      twice_area += p.x() * q.z() - q.x() * p.z();
    }
    if (twice_area == 0) error(key, "encloses no area");
  }

  void check_inside(const std::string& key, double v, int axis) const {
    const double lo = spec_.domain().min(axis), hi = spec_.domain().max(axis);
    if (v < lo || v > hi)
      error(key, "lies outside the domain on axis " + axis_name(axis) + " (" + number_text(v) + " not in [" + number_text(lo) +
                     ", " + number_text(hi) + "])");
  }

  void check_numerics() const {
    const pb::Numerics& n = spec_.numerics();
    finite("numerics.cfl", n.cfl());
    if (n.cfl() < 0 || n.cfl() > 1)
      error("numerics.cfl", "must be in (0, 1] (is " + number_text(n.cfl()) + "; 0 means 0.2)");
    non_negative("numerics.max_dt", n.max_dt(), "no upper bound");
    non_negative("numerics.min_dt", n.min_dt(), "1e-12");
    if (n.max_dt() > 0 && n.min_dt() > n.max_dt())
      error("numerics.min_dt",
            "must not exceed numerics.max_dt (" + number_text(n.min_dt()) + " > " + number_text(n.max_dt()) + ")");
  }

  void check_output() const {
    non_negative("output.interval", spec_.output().interval(), "end_time / 100");
    std::map<std::string, int> names;
    for (int i = 0; i < spec_.output().snapshots_size(); ++i) {
      const pb::Snapshot& snapshot = spec_.output().snapshots(i);
      const std::string key = indexed("output.snapshots", i);
      check_snapshot(key, snapshot);
      const std::string name = !snapshot.name().empty() ? snapshot.name() : !snapshot.field().empty() ? snapshot.field() : "phase";
      if (auto [it, added] = names.emplace(name, i); !added)
        error(key + ".name", "'" + name + "' is already the name of " + indexed("output.snapshots", it->second) +
                                 ": give each snapshot of the same field its own name");
    }
  }

  // A picture of output.snapshots (docs/rendering.md).
  void check_snapshot(const std::string& key, const pb::Snapshot& s) const {
    const std::string& field = s.field();
    const bool soil_field = is_soil_snapshot_field(field);
    const bool y_component = field.size() > 2 && field.compare(field.size() - 2, 2, "_y") == 0;
    if ((!field.empty() && !kSnapshotFields.count(field) && !soil_field) || (dims_ == 2 && y_component))
      error(key + ".field", "'" + field + "' is not a field a snapshot can show (phase, pressure, density, velocity" +
                                (dims_ == 2 ? "" : "/_x/_y/_z") +
                                "; of soil: pore_pressure, saturation, porosity, plastic_strain, seepage, "
                                "displacement, stress_xx/yy/zz/xy/yz/zx, effective_stress_xx/...)");
    if (soil_field && soil_material_indices(spec_).empty())
      error(key + ".field", "'" + field + "' is a field of soil particles, and the case has no soil material");
    if (!s.phase().empty() && s.phase() != "all" && !kPhases.count(s.phase()))
      error(key + ".phase", "'" + s.phase() + "' is not a phase (water, soil, boundary, all)");
    for (int i = 0; i < s.translucent_size(); ++i)
      if (!kPhases.count(s.translucent(i)))
        error(indexed(key + ".translucent", i), "'" + s.translucent(i) + "' is not a phase (water, soil, boundary)");
    if (!s.colour_map().empty() && s.colour_map() != "viridis" && s.colour_map() != "cool_warm")
      error(key + ".colour_map", "'" + s.colour_map() + "' is not a colour map (viridis, cool_warm)");
    if (s.has_min()) finite(key + ".min", s.min());
    if (s.has_max()) finite(key + ".max", s.max());
    if (s.has_min() && s.has_max() && !(s.max() > s.min()))
      error(key + ".max", "must be greater than min (" + number_text(s.max()) + " <= " + number_text(s.min()) + ")");
    check_snapshot_camera(key, s);
    if (s.has_clip()) check_min_max(key + ".clip", s.clip().min(), s.clip().max(), "the clip box");
    if (s.has_slab()) {
      const pb::SnapshotSlab& slab = s.slab();
      if (slab.axis().size() != 1 || axes().find(slab.axis()) == std::string::npos)
        error(key + ".slab.axis", "'" + slab.axis() + "' is not an axis of this case (" + axes() + ")");
      finite(key + ".slab.position", slab.position());
      positive(key + ".slab.thickness", slab.thickness());
    }
    if (s.width() < 0 || s.width() > 3840)
      error(key + ".width", "must be in [1, 3840] pixels (is " + std::to_string(s.width()) + "); 0 means 1280");
    if (s.height() < 0 || s.height() > 2160)
      error(key + ".height", "must be in [1, 2160] pixels (is " + std::to_string(s.height()) + "); 0 means 720");
    if (!s.background().empty()) {
      check_vector(key + ".background", s.background(), 3, "a colour (red, green, blue in [0, 1])");
      for (int c = 0; c < 3; ++c)
        if (s.background(c) < 0 || s.background(c) > 1)
          error(indexed(key + ".background", c), "must be in [0, 1] (is " + number_text(s.background(c)) + ")");
    }
  }

  void check_snapshot_camera(const std::string& key, const pb::Snapshot& s) const {
    const std::string& camera = s.camera();
    if (!camera.empty() && camera != "side" && camera != "orbit" && camera != "look_at")
      error(key + ".camera", "'" + camera + "' is not a camera (side, orbit, look_at)");
    if (dims_ == 2 && !camera.empty() && camera != "side")
      error(key + ".camera", "a 2D case is drawn in its x-z plane: give side or leave camera out");
    const bool orbit = camera == "orbit" || (camera.empty() && dims_ == 3);
    if (s.has_orbit() && !orbit) error(key + ".orbit", "is used by the orbit camera only");
    if (s.has_look_at() != (camera == "look_at"))
      error(key + (s.has_look_at() ? ".look_at" : ".camera"),
            s.has_look_at() ? "is used by the look_at camera only" : "look_at needs look_at: {eye: ..., target: ...}");
    auto fov = [&](const std::string& k, bool has, double v) {
      if (has && !(v > 0 && v < 180)) error(k, "must be in (0, 180) degrees (is " + number_text(v) + ")");
    };
    if (s.has_orbit()) {
      const pb::SnapshotOrbit& o = s.orbit();
      if (o.has_azimuth()) finite(key + ".orbit.azimuth", o.azimuth());
      if (o.has_elevation() && !(std::fabs(o.elevation()) <= 90))
        error(key + ".orbit.elevation", "must be in [-90, 90] degrees (is " + number_text(o.elevation()) + ")");
      if (o.has_zoom()) positive(key + ".orbit.zoom", o.zoom());
      fov(key + ".orbit.fov", o.has_fov(), o.fov());
    }
    if (s.has_look_at()) {
      const pb::SnapshotLookAt& l = s.look_at();
      check_vector(key + ".look_at.eye", l.eye(), 3, "a point in 3D");
      check_vector(key + ".look_at.target", l.target(), 3, "a point in 3D");
      if (!l.up().empty()) check_vector(key + ".look_at.up", l.up(), 3, "a direction in 3D");
      if (l.eye(0) == l.target(0) && l.eye(1) == l.target(1) && l.eye(2) == l.target(2))
        error(key + ".look_at.target", "must differ from eye");
      fov(key + ".look_at.fov", l.has_fov(), l.fov());
    }
  }

  void check_probes() const {
    std::map<std::string, int> seen;
    for (int i = 0; i < spec_.probes_size(); ++i) {
      const pb::Probe& p = spec_.probes(i);
      const std::string key = indexed("probes", i);
      if (p.name().empty()) error(key + ".name", "is missing: it heads the probe's column in probes.csv");
      if (auto [it, added] = seen.emplace(p.name(), i); !added)
        error(key + ".name", "'" + p.name() + "' is already the name of " + indexed("probes", it->second));
      if (!p.phase().empty() && !kPhases.count(p.phase()))
        error(key + ".phase", "'" + p.phase() + "' is not a phase (water, soil, boundary)");
      const bool uses_field = p.kind() == pb::POINT || p.kind() == pb::MAX || p.kind() == pb::MEAN;
      switch (p.kind()) {
        case pb::POINT:
          check_vector(key + ".position", p.position(), dims_, "a point probe");
          for (int a = 0; a < dims_; ++a) check_inside(key + ".position", p.position(a), a);
          break;
        case pb::ELEVATION:
          // The vertical line at x (2D) or (x, y) (3D).
          check_vector(key + ".position", p.position(), dims_ - 1, "an elevation probe (the horizontal coordinates)");
          for (int a = 0; a < dims_ - 1; ++a) check_inside(key + ".position", p.position(a), a);
          if (!p.phase().empty() && p.phase() != "water")
            error(key + ".phase", "an elevation probe measures the water surface; leave phase out or give water");
          break;
        case pb::FRONT:
          if (p.axis().empty()) error(key + ".axis", "is missing: a front probe needs an axis (" + axes() + ")");
          if (p.axis().size() != 1 || axes().find(p.axis()) == std::string::npos)
            error(key + ".axis", "'" + p.axis() + "' is not an axis of this case (" + axes() + ")");
          finite(key + ".origin", p.origin());
          break;
        case pb::MAX:
        case pb::MEAN:
          if (!p.position().empty()) error(key + ".position", "is not used by max and mean probes");
          break;
        default:
          error(key + ".kind", "is missing: give one of point, elevation, front, max, mean");
      }
      if (uses_field) {
        if (p.field().empty()) error(key + ".field", "is missing: give one of " + field_names());
        const bool soil_field = kSoilProbeFields.count(p.field()) > 0;
        if ((!kProbeFields.count(p.field()) && !soil_field) || (dims_ == 2 && kThreeDimensionalOnly.count(p.field())))
          error(key + ".field", "'" + p.field() + "' is not a field (" + field_names() + ")");
        if (soil_field && p.phase() != "soil")
          error(key + ".phase", "'" + p.field() + "' is a field of soil particles: give phase: soil");
      } else if (!p.field().empty()) {
        error(key + ".field", "is not used by this kind of probe");
      }
      if (p.kind() != pb::FRONT && (!p.axis().empty() || p.minimum() || p.origin() != 0))
        error(key + (p.axis().empty() ? (p.minimum() ? ".minimum" : ".origin") : ".axis"),
              "is used by front probes only");
    }
  }

  std::string axes() const { return dims_ == 2 ? "x, z" : "x, y, z"; }
  std::string field_names() const {
    const std::string y = dims_ == 2 ? "" : "/_y";
    return "pressure, density, speed, velocity_x" + y + "/_z, displacement_x" + y +
           "/_z, stress_xx/yy/zz/xy/yz/zx; of soil: pore_pressure, saturation, porosity, plastic_strain, "
           "seepage_x" + y + "/_z, effective_stress_xx/yy/zz/xy/yz/zx, free_surface";
  }

  // The free-surface conditions (Eq. 39) of the case and of its initialisation stage. The pore
  // water at p_max, p_min and a held surface pressure must keep a positive density
  // ρ_w0 (1 + p / K_w) in every soil.
  void check_hydraulics() const {
    if (spec_.has_hydraulics()) check_hydraulic_boundary("hydraulics", spec_.hydraulics());
  }

  void check_initialisation() const {
    if (!spec_.has_initialisation()) return;
    const pb::Initialisation& init = spec_.initialisation();
    finite("initialisation.duration", init.duration());
    if (!(init.duration() > 0))
      error("initialisation.duration", "must be greater than 0 (is " + number_text(init.duration()) +
                                           "): the simulated seconds the stage runs before t = 0");
    if (!init.has_hydraulics()) return;
    if (init.hydraulics().rainfall_size() > 0)
      error("initialisation.hydraulics.rainfall", "is a time series; the initialisation stage holds constant "
                                                  "conditions: give rainfall_intensity");
    if (init.hydraulics().has_hyetograph())
      error("initialisation.hydraulics.hyetograph",
            "is a time series; the initialisation stage holds constant "
            "conditions: give rainfall_intensity");
    check_hydraulic_boundary("initialisation.hydraulics", init.hydraulics());
  }

  // The stages (docs/physics.md, "Stages"): a geostatic start only first, the pore-water stage only
  // with soil, end times increasing, every number finite and of its sign.
  void check_stages() const {
    if (spec_.stages_size() == 0) return;
    if (spec_.has_initialisation())
      error("initialisation", "a case with stages starts with its first stage (e.g. geostatic), not an initialisation");
    bool soil = false;
    for (const auto& m : spec_.materials()) soil |= m.has_soil();
    double last_end = -1;
    for (int k = 0; k < spec_.stages_size(); ++k) {
      const pb::Stage& stage = spec_.stages(k);
      const std::string key = "stages[" + std::to_string(k) + "]";
      if (stage.kind_case() == pb::Stage::KIND_NOT_SET)
        error(key, "names no kind: give one of geostatic, pore_water, dynamic");
      if (stage.has_geostatic()) {
        if (k != 0) error(key + ".geostatic", "the geostatic start can only be the first stage");
        if (!soil) error(key + ".geostatic", "needs soil: the case has no soil material");
        const auto& g = stage.geostatic();
        non_negative(key + ".geostatic.force_ratio", g.force_ratio());
        non_negative(key + ".geostatic.speed", g.speed());
        finite(key + ".geostatic.local_damping", g.local_damping());
        if (!(g.local_damping() >= 0 && g.local_damping() < 1))
          error(key + ".geostatic.local_damping", "must lie in [0, 1) (0 means 0.8), is " + number_text(g.local_damping()));
        if (stage.end().has_time() || stage.end().has_yield_band() || stage.end().has_motion())
          error(key + ".end", "the geostatic stage ends at equilibrium; it takes no end criterion");
      }
      if (stage.has_pore_water()) {
        if (!soil) error(key + ".pore_water", "needs soil: the case has no soil material");
        const auto& w = stage.pore_water();
        for (const auto& [name, value] : {std::pair<const char*, double>{"initial_dt", w.initial_dt()},
                                          {"min_dt", w.min_dt()},
                                          {"max_dt", w.max_dt()},
                                          {"pressure_tolerance", w.pressure_tolerance()},
                                          {"water_content_change", w.water_content_change()}})
          non_negative(key + ".pore_water." + name, value);
        if (w.max_iterations() < 0) error(key + ".pore_water.max_iterations", "must be >= 0 (0 means 20)");
        if (w.max_dt() > 0 && w.min_dt() > w.max_dt())
          error(key + ".pore_water.min_dt", "must not exceed max_dt (" + number_text(w.max_dt()) + " s)");
      }
      non_negative(key + ".output_interval", stage.output_interval());
      non_negative(key + ".probe_interval", stage.probe_interval());
      if (stage.end().has_time()) {
        finite(key + ".end.time", stage.end().time());
        if (!(stage.end().time() > last_end && stage.end().time() >= 0))
          error(key + ".end.time", "must be >= 0 and later than the previous stage's end (is " +
                                       number_text(stage.end().time()) + " s)");
        last_end = stage.end().time();
      }
      if (stage.end().has_yield_band()) {
        const auto& band = stage.end().yield_band();
        if (!stage.has_pore_water()) error(key + ".end.yield_band", "ends a pore-water stage only");
        non_negative(key + ".end.yield_band.ratio", band.ratio());
        non_negative(key + ".end.yield_band.volume", band.volume());
        non_negative(key + ".end.yield_band.span", band.span());
      }
      if (stage.end().has_motion()) {
        const auto& m = stage.end().motion();
        if (!stage.has_pore_water()) error(key + ".end.motion", "ends a pore-water stage only");
        non_negative(key + ".end.motion.speed", m.speed());
        non_negative(key + ".end.motion.duration", m.duration());
        non_negative(key + ".end.motion.interval", m.interval());
      }
    }
  }

  // The cascade's events: each criterion's thresholds, and what it needs of the case.
  void check_events() const {
    if (!spec_.has_events()) return;
    const pb::CascadeEvents& e = spec_.events();
    const bool soil = !soil_material_indices(spec_).empty();
    bool water = false;
    for (const pb::Material& m : spec_.materials()) water = water || m.has_water();
    if (e.ponding_started() && !soil) error("events.ponding_started", "watches the soil's free surface, and the case has no soil material");
    if (e.has_landslide_onset()) {
      const pb::LandslideOnset& l = e.landslide_onset();
      if (!soil) error("events.landslide_onset", "watches the soil, and the case has no soil material");
      positive("events.landslide_onset.plastic_strain", l.plastic_strain());
      positive("events.landslide_onset.speed", l.speed());
      positive("events.landslide_onset.volume", l.volume());
    }
    if (e.has_water_impact()) {
      if (!soil || !water) error("events.water_impact", "needs soil and water in the case");
      positive("events.water_impact.speed", e.water_impact().speed());
    }
    for (int i = 0; i < e.wave_at_gauge_size(); ++i) {
      const pb::WaveAtGauge& w = e.wave_at_gauge(i);
      const std::string key = indexed("events.wave_at_gauge", i);
      const pb::Probe* probe = nullptr;
      for (const pb::Probe& p : spec_.probes())
        if (p.name() == w.probe()) probe = &p;
      if (!probe || probe->kind() != pb::ELEVATION)
        error(key + ".probe", "'" + w.probe() + "' is not the name of an elevation probe of the case");
      positive(key + ".rise", w.rise());
    }
    for (int i = 0; i < e.overtopping_size(); ++i) {
      const pb::Overtopping& o = e.overtopping(i);
      const std::string key = indexed("events.overtopping", i);
      if (!water) error(key, "watches the water, and the case has no water material");
      if (o.name().empty()) error(key + ".name", "is missing: it names the line in the event");
      if (o.axis() != "x" && !(dims_ == 3 && o.axis() == "y"))
        error(key + ".axis", "'" + o.axis() + "' is not a horizontal axis of this case (" + (dims_ == 2 ? "x" : "x, y") + ")");
      finite(key + ".position", o.position());
      finite(key + ".above", o.above());
    }
  }

  void check_hydraulic_boundary(const std::string& key, const pb::HydraulicBoundary& h) const {
    if (soil_material_indices(spec_).empty())
      error(key, "acts on the free surface of soil, and the case has no soil material");
    finite(key + ".rainfall_intensity", h.rainfall_intensity());
    if (h.rainfall_size() > 0 && h.rainfall_intensity() != 0)
      error(key + ".rainfall", "cannot be given together with rainfall_intensity: give a constant intensity or a "
                               "time series");
    // The case loader replaces the hyetograph of a case file with its series; any other names a
    // file that nobody reads here (the server reads no files that a request names).
    if (h.has_hyetograph())
      error(key + ".hyetograph",
            "names a file, which only the loader of a case file reads (cascade run, cascade "
            "create): a case sent as text, or a spec, carries the rainfall series instead");
    if (!h.rainfall_file().empty() && h.rainfall_size() == 0)
      error(key + ".rainfall_file", "names the hyetograph file of the rainfall series, and there is no series");
    for (int i = 0; i < h.rainfall_size(); ++i) {
      const std::string point_key = indexed(key + ".rainfall", i);
      const pb::RainfallPoint& point = h.rainfall(i);
      finite(point_key + ".time", point.time());
      finite(point_key + ".intensity", point.intensity());
      if (point.time() < 0) error(point_key + ".time", "must not be negative (is " + number_text(point.time()) + ")");
      if (i > 0 && !(point.time() > h.rainfall(i - 1).time()))
        error(point_key + ".time", "must be later than the time of the point before (" + number_text(point.time()) +
                                       " <= " + number_text(h.rainfall(i - 1).time()) + ")");
    }
    finite(key + ".ponding_pressure", h.ponding_pressure());
    const double bulk = smallest_bulk_modulus();
    if (!(h.ponding_pressure() > -bulk))
      error(key + ".ponding_pressure", "must be above -K_w = " + number_text(-bulk) + " Pa (is " +
                                           number_text(h.ponding_pressure()) + ")");
    if (h.has_drying_pressure()) {
      finite(key + ".drying_pressure", h.drying_pressure());
      if (!(h.drying_pressure() < h.ponding_pressure()))
        error(key + ".drying_pressure", "must be below ponding_pressure (" + number_text(h.drying_pressure()) +
                                            " >= " + number_text(h.ponding_pressure()) + ")");
      above_minus_bulk_modulus(key + ".drying_pressure", h.drying_pressure());
    }
    if (h.has_surface_pressure()) {
      if (h.rainfall_intensity() != 0 || h.rainfall_size() > 0)
        error(key + ".surface_pressure",
              "holds the pore pressure of the whole free surface and cannot be given "
              "together with rain: leave out rainfall_intensity, rainfall and hyetograph");
      above_minus_bulk_modulus(key + ".surface_pressure", h.surface_pressure());
    }
    if (h.has_region()) check_min_max(key + ".region", h.region().min(), h.region().max(), "the rain region");
  }

  const pb::ScenarioSpec& spec_;
  const CaseFailure& fail_;
  int dims_ = 0;
};

}  // namespace

void check_spec(const pb::ScenarioSpec& spec, const CaseFailure& fail) { SpecChecker(spec, fail).run(); }

void check_snapshot(const pb::ScenarioSpec& spec, const std::string& key, const pb::Snapshot& snapshot,
                    const CaseFailure& fail) {
  SpecChecker(spec, fail).run_snapshot(key, snapshot);
}

void apply_snapshot_defaults(pb::Snapshot& snapshot, int dimensions) {
  if (snapshot.field().empty()) snapshot.set_field("phase");
  if (snapshot.name().empty()) snapshot.set_name(snapshot.field());
  if (snapshot.camera().empty()) snapshot.set_camera(dimensions == 2 ? "side" : "orbit");
  if (snapshot.colour_map().empty())
    snapshot.set_colour_map(is_signed_snapshot_field(snapshot.field()) ? "cool_warm" : "viridis");
  if (snapshot.width() == 0) snapshot.set_width(1280);
  if (snapshot.height() == 0) snapshot.set_height(720);
}

void validate_spec(const pb::ScenarioSpec& spec) {
  check_spec(spec, [](const std::string& key, const std::string& message) { throw CaseError(key, message); });
}

void apply_defaults(pb::ScenarioSpec& spec) {
  if (spec.h_over_dp() == 0) spec.set_h_over_dp(1.3);
  pb::Numerics& numerics = *spec.mutable_numerics();
  if (numerics.cfl() == 0) numerics.set_cfl(0.2);
  if (numerics.min_dt() == 0) numerics.set_min_dt(1e-12);
  pb::Output& output = *spec.mutable_output();
  if (output.interval() == 0) output.set_interval(spec.end_time() / 100);
  if (!output.has_hdf5()) output.set_hdf5(true);
  for (pb::Snapshot& snapshot : *output.mutable_snapshots()) apply_snapshot_defaults(snapshot, spec.dimensions());
  for (pb::Material& m : *spec.mutable_materials()) {
    if (m.model_case() == pb::Material::kWater) {
      pb::WaterModel& w = *m.mutable_water();
      if (w.density() == 0) w.set_density(1000);
      if (!w.has_delta()) w.set_delta(0.1);
      if (!w.has_viscosity_alpha()) w.set_viscosity_alpha(0.01);
    }
    if (m.model_case() != pb::Material::kSoil) continue;
    pb::SoilModel& s = *m.mutable_soil();
    if (s.water_bulk_modulus() == 0) s.set_water_bulk_modulus(kDefaultWaterBulkModulus);
    if (s.pore_sound_speed() == 0) s.set_pore_sound_speed(kPoreSoundSpeedFactor * s.saturated_conductivity());
    if (!s.has_delta()) s.set_delta(kDefaultPoreDelta);
    if (!s.has_viscosity_alpha()) s.set_viscosity_alpha(kDefaultSoilViscosityAlpha);
    pb::HydraulicModel& h = *s.mutable_hydraulic();
    if (h.has_van_genuchten() && !h.van_genuchten().has_s_max()) h.mutable_van_genuchten()->set_s_max(1);
    if (h.has_gardner() && !h.gardner().has_s_max()) h.mutable_gardner()->set_s_max(1);
    if (s.mechanical().has_drucker_prager()) {
      pb::DruckerPragerModel& d = *s.mutable_mechanical()->mutable_drucker_prager();
      if (!d.has_residual_cohesion()) d.set_residual_cohesion(d.cohesion());
      if (!d.has_residual_friction_angle()) d.set_residual_friction_angle(d.friction_angle());
      if (d.atmospheric_pressure() == 0) d.set_atmospheric_pressure(kDefaultAtmosphericPressure);
    }
  }
  for (pb::Probe& p : *spec.mutable_probes())
    if (p.phase().empty()) p.set_phase("water");
}

}  // namespace cascade
