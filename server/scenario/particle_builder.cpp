#include "server/scenario/particle_builder.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <sstream>
#include <unordered_set>
#include <utility>

#include "cascade/v1/scenario.pb.h"
#include "server/scenario/case_error.h"
#include "server/scenario/geometry.h"
#include "server/scenario/soil_setup.h"

namespace cascade {
namespace {

constexpr double kDefaultHOverDp = 1.3;

std::string body_key(int i) { return "bodies[" + std::to_string(i) + "]"; }

std::string format_point(const Vec3& x, int dimensions) {
  std::ostringstream s;
  if (dimensions == 2) s << "(" << x.x() << ", " << x.z() << ")";
  else s << "(" << x.x() << ", " << x.y() << ", " << x.z() << ")";
  return s.str();
}

double water_density(const v1::Material& m) {
  return m.water().density() > 0.0 ? m.water().density() : kDefaultWaterDensity;
}

// The axes a case uses in the 3D embedding: (x, z) in 2D.
std::vector<int> axes(int dimensions) { return dimensions == 2 ? std::vector<int>{0, 2} : std::vector<int>{0, 1, 2}; }

// Lattice index range [first, last] per axis (y: a single layer at y = 0 in 2D).
struct LatticeBox {
  std::int64_t first[3] = {0, 0, 0};
  std::int64_t last[3] = {-1, -1, -1};

  double count() const {
    double n = 1.0;
    for (int a = 0; a < 3; ++a) n *= std::max<double>(0.0, double(last[a] - first[a] + 1));
    return n;
  }
};

// The wetted pieces by the cells of a uniform grid over a box: each piece is listed in every
// cell its bounding box, widened by `reach`, overlaps, so that the cell of a point lists every
// piece within `reach` of it. A terrain's bedrock has 10⁵ pieces and 10⁵ dummy particles: a
// search over all pieces for each particle is 10¹⁰ box tests.
class WettedIndex {
 public:
  WettedIndex(const std::vector<Aabb>& pieces, const Aabb& box, double reach) : box_(box), cell_(reach) {
    for (int a = 0; a < 3; ++a)
      cells_[a] = box.empty() ? 1 : std::max<std::int64_t>(1, std::int64_t(std::ceil((box.hi[a] - box.lo[a]) / cell_)));
    // A coarser grid where this one would be large (a thin wall's pieces span a whole side).
    while (double(cells_[0]) * double(cells_[1]) * double(cells_[2]) > 4e6) {
      cell_ *= 2.0;
      for (int a = 0; a < 3; ++a) cells_[a] = std::max<std::int64_t>(1, (cells_[a] + 1) / 2);
    }
    lists_.resize(std::size_t(cells_[0] * cells_[1] * cells_[2]));
    if (box.empty()) return;
    for (std::size_t f = 0; f < pieces.size(); ++f) {
      const Aabb b = pieces[f].expanded(reach).intersection(box);
      if (b.empty()) continue;
      std::int64_t lo[3], hi[3];
      for (int a = 0; a < 3; ++a) lo[a] = cell_of(b.lo[a], a), hi[a] = cell_of(b.hi[a], a);
      for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
        for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
          for (std::int64_t i = lo[0]; i <= hi[0]; ++i) lists_[std::size_t((k * cells_[1] + j) * cells_[0] + i)].push_back(f);
    }
  }

  // The pieces listed in x's cell, in increasing order (x within the box).
  const std::vector<std::size_t>& near(const Vec3& x) const {
    std::int64_t c[3];
    for (int a = 0; a < 3; ++a) c[a] = cell_of(x[a], a);
    return lists_[std::size_t((c[2] * cells_[1] + c[1]) * cells_[0] + c[0])];
  }

 private:
  std::int64_t cell_of(double t, int a) const {
    if (!(t > box_.lo[a])) return 0;
    return std::min<std::int64_t>(cells_[a] - 1, std::int64_t((t - box_.lo[a]) / cell_));
  }

  Aabb box_;
  double cell_;
  std::int64_t cells_[3] = {1, 1, 1};
  std::vector<std::vector<std::size_t>> lists_;
};

class Builder {
 public:
  explicit Builder(const v1::ScenarioSpec& spec) : spec_(spec) {}

  ParticleSet build();

 private:
  void read_case();
  LatticeBox lattice_box(const Aabb& box) const;
  // The box spanned by a lattice box's points.
  Aabb lattice_box_bounds(const LatticeBox& l) const {
    return {lattice_point(l.first[0], l.first[1], l.first[2]), lattice_point(l.last[0], l.last[1], l.last[2])};
  }
  Vec3 lattice_point(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return {(double(i) + 0.5) * dp_, dims_ == 2 ? 0.0 : (double(j) + 0.5) * dp_, (double(k) + 0.5) * dp_};
  }
  // The body's region within the domain: infinite sides (half-spaces) and periodic axes are clipped.
  Aabb clipped_bounds(const Region& region) const;
  std::vector<Face> wetted_surface(int body) const;
  void estimate_count() const;
  void add_fluid(int body);
  void add_boundary(int body);
  void add_particle(const Vec3& x, const Vec3& ghost, Phase phase, const Vec3& velocity, int body);
  void check_inside_domain(int body) const;
  void set_densities();
  void set_soil_state(int body);

  const v1::ScenarioSpec& spec_;
  int dims_ = 3;
  double dp_ = 0.0;
  Aabb domain_;
  bool periodic_[3] = {false, false, false};
  std::vector<Region> regions_;            // per body
  std::vector<bool> is_fluid_;             // per body
  std::vector<int> material_;              // per body: material index, -1 for BOUNDARY
  std::vector<int> soil_;                  // per body: index into soils_, -1 unless a soil body
  std::vector<SoilMaterial> soils_;        // the soil materials, as EngineConfig::soils
  std::vector<std::vector<Face>> wetted_;  // per body: its wetted surface pieces (BOUNDARY)
  std::vector<Face> all_wetted_;           // every BOUNDARY body's wetted pieces
  std::vector<Aabb> all_wetted_bounds_;
  std::unordered_set<std::uint64_t> dummy_sites_;  // lattice points taken by BOUNDARY bodies
  ParticleSet out_;
};

void Builder::read_case() {
  dims_ = spec_.dimensions();
  if (dims_ != 2 && dims_ != 3) throw CaseError("dimensions", "must be 2 or 3");
  dp_ = spec_.dp();
  if (!(dp_ > 0.0) || !std::isfinite(dp_)) throw CaseError("dp", "must be a positive number");
  if (spec_.h_over_dp() < 0.0) throw CaseError("h_over_dp", "must not be negative");
  if (spec_.gravity_size() != 0 && spec_.gravity_size() != dims_)
    throw CaseError("gravity", "needs " + std::to_string(dims_) + " components");

  const auto& d = spec_.domain();
  if (d.min_size() != dims_ || d.max_size() != dims_)
    throw CaseError("domain", "min and max need " + std::to_string(dims_) + " components each");
  if (d.periodic_size() != 0 && d.periodic_size() != dims_)
    throw CaseError("domain.periodic", "needs " + std::to_string(dims_) + " entries or none");
  const std::vector<int> ax = axes(dims_);
  domain_ = {Vec3::Zero(), Vec3::Zero()};
  for (int c = 0; c < dims_; ++c) {
    if (!(d.min(c) < d.max(c))) throw CaseError("domain.max", "every component must exceed the one of min");
    domain_.lo[ax[c]] = d.min(c);
    domain_.hi[ax[c]] = d.max(c);
    periodic_[ax[c]] = d.periodic_size() ? d.periodic(c) : false;
  }

  for (int m : soil_material_indices(spec_)) soils_.push_back(soil_material(spec_, m));

  // Half-space faces reach well beyond the domain, so closest points inside it are exact.
  const Aabb face_bounds = domain_.expanded((domain_.hi - domain_.lo).norm() + 10.0 * dp_);
  for (int i = 0; i < spec_.bodies_size(); ++i) {
    const v1::Body& b = spec_.bodies(i);
    const std::string key = body_key(i);
    if (b.kind() != v1::FLUID && b.kind() != v1::BOUNDARY) throw CaseError(key + ".kind", "must be FLUID or BOUNDARY");
    const v1::TerrainGrid& terrain = spec_.terrain().grid();
    Shape shape = shape_from_spec(b.shape(), dims_, face_bounds, terrain, dp_, key + ".shape");
    std::vector<Shape> sub;
    for (int k = 0; k < b.subtract_size(); ++k)
      sub.push_back(shape_from_spec(b.subtract(k), dims_, face_bounds, terrain, dp_,
                                    key + ".subtract[" + std::to_string(k) + "]"));
    regions_.emplace_back(std::move(shape), std::move(sub));
    is_fluid_.push_back(b.kind() == v1::FLUID);

    int material = -1, soil = -1;
    if (b.kind() == v1::FLUID) {
      for (int m = 0; m < spec_.materials_size() && material < 0; ++m)
        if (spec_.materials(m).name() == b.material()) material = m;
      if (material < 0) throw CaseError(key + ".material", "no material named '" + b.material() + "'");
      const v1::Material& m = spec_.materials(material);
      if (m.model_case() != v1::Material::kWater && m.model_case() != v1::Material::kSoil)
        throw CaseError(key + ".material", "material '" + b.material() + "' is neither water nor soil");
      if (m.has_soil()) {
        const std::vector<int> soils = soil_material_indices(spec_);
        soil = static_cast<int>(std::find(soils.begin(), soils.end(), material) - soils.begin());
      }
    } else if (b.layers() < 0) {
      throw CaseError(key + ".layers", "must not be negative");
    }
    material_.push_back(material);
    soil_.push_back(soil);
    if (b.initial().velocity_size() != 0 && b.initial().velocity_size() != dims_)
      throw CaseError(key + ".initial.velocity", "needs " + std::to_string(dims_) + " components");
  }
}

LatticeBox Builder::lattice_box(const Aabb& box) const {
  LatticeBox l;
  for (int a : axes(dims_)) {
    l.first[a] = static_cast<std::int64_t>(std::ceil(box.lo[a] / dp_ - 0.5));
    // Along a periodic axis the point at the domain's upper end is the image of the lower one.
    l.last[a] = periodic_[a] && box.hi[a] >= domain_.hi[a]
                    ? static_cast<std::int64_t>(std::ceil(domain_.hi[a] / dp_ - 0.5)) - 1
                    : static_cast<std::int64_t>(std::floor(box.hi[a] / dp_ - 0.5));
  }
  if (dims_ == 2) l.first[1] = l.last[1] = 0;
  return l;
}

Aabb Builder::clipped_bounds(const Region& region) const {
  Aabb b = region.bounds();
  for (int a : axes(dims_)) {
    if (!std::isfinite(b.lo[a]) || periodic_[a]) b.lo[a] = std::max(b.lo[a], domain_.lo[a]);
    if (!std::isfinite(b.hi[a]) || periodic_[a]) b.hi[a] = std::min(b.hi[a], domain_.hi[a]);
  }
  if (dims_ == 2) b.lo.y() = b.hi.y() = 0.0;
  return b;
}

// The body's surface that fluid can touch: the parts of its region's surface where points just
// outside lie in the domain (its non-periodic extent) and in no other BOUNDARY body's solid,
// including the periodic images of every solid (its own as well).
std::vector<Face> Builder::wetted_surface(int body) const {
  const double gap = 1e-6 * dp_, tolerance = 1e-9 * dp_;
  ConvexCell domain_cell;
  for (int a : axes(dims_)) {
    if (periodic_[a]) continue;
    domain_cell.planes.push_back({Vec3::Unit(a), domain_.hi[a]});
    domain_cell.planes.push_back({-Vec3::Unit(a), -domain_.lo[a]});
  }
  std::vector<Vec3> images;  // shifts of the periodic images, the identity first
  images.push_back(Vec3::Zero());
  for (int a : axes(dims_)) {
    if (!periodic_[a]) continue;
    const Vec3 period = (domain_.hi[a] - domain_.lo[a]) * Vec3::Unit(a);
    const std::size_t n = images.size();
    for (std::size_t m = 0; m < n; ++m)
      for (double side : {-1.0, 1.0}) images.push_back(images[m] + side * period);
  }

  std::vector<Face> wetted;
  for (const Face& f : regions_[body].surface(gap)) {
    std::vector<Face> pieces = clip_to_cell(f.translated(gap * f.normal), domain_cell, tolerance);
    for (int other = 0; other < static_cast<int>(regions_.size()) && !pieces.empty(); ++other) {
      if (is_fluid_[other]) continue;
      for (const Vec3& shift : images) {
        if (other == body && shift.isZero()) continue;
        const Region solid = shift.isZero() ? regions_[other] : regions_[other].translated(shift);
        pieces = cut_by_region(pieces, solid, tolerance);
      }
    }
    for (const Face& p : pieces) wetted.push_back(p.translated(-gap * f.normal));
  }
  return wetted;
}

void Builder::estimate_count() const {
  const double cell = std::pow(dp_, dims_);
  double total = 0.0;
  for (std::size_t i = 0; i < regions_.size(); ++i) {
    const Aabb box = clipped_bounds(regions_[i]);
    double n = lattice_box(box).count();
    if (!is_fluid_[i]) {
      double area = 0.0;
      for (const Face& f : wetted_[i]) area += f.measure();
      n = std::min(n, area * boundary_thickness(spec_, static_cast<int>(i)) / cell + 1.0);
    }
    total += n;
  }
  if (total > kMaxParticles) {
    std::ostringstream s;
    s << "about " << total << " particles at this spacing, more than the limit of " << kMaxParticles
      << "; increase dp or shrink the bodies";
    throw CaseError("dp", s.str());
  }
}

void Builder::add_particle(const Vec3& x, const Vec3& ghost, Phase phase, const Vec3& velocity, int body) {
  HostParticles& p = out_.particles;
  for (int a : axes(dims_)) {
    p.position.push_back(x[a]);
    p.ghost.push_back(ghost[a]);
    p.velocity.push_back(velocity[a]);
  }
  p.phase.push_back(phase);
  p.water_density.push_back(0.0);  // set_densities
  p.porosity.push_back(0.0);       // set_soil_state, for soil particles
  p.soil_material.push_back(0);
  p.effective_stress.insert(p.effective_stress.end(), 6, 0.0);
  p.body.push_back(static_cast<std::uint32_t>(body));
}

void Builder::add_fluid(int body) {
  const Region& region = regions_[body];
  const LatticeBox l = lattice_box(clipped_bounds(region));
  std::vector<const Region*> excluded;  // BOUNDARY solids and earlier FLUID bodies
  for (int other = 0; other < static_cast<int>(regions_.size()); ++other)
    if (!is_fluid_[other] || other < body) excluded.push_back(&regions_[other]);
  Vec3 velocity = Vec3::Zero();
  const auto& v = spec_.bodies(body).initial().velocity();
  for (int c = 0; c < v.size(); ++c) velocity[axes(dims_)[c]] = v[c];
  const Phase phase = soil_[body] >= 0 ? Phase::soil : Phase::water;

  for (std::int64_t k = l.first[2]; k <= l.last[2]; ++k)
    for (std::int64_t j = l.first[1]; j <= l.last[1]; ++j)
      for (std::int64_t i = l.first[0]; i <= l.last[0]; ++i) {
        const Vec3 x = lattice_point(i, j, k);
        if (!region.contains(x)) continue;
        bool taken = false;
        for (const Region* r : excluded)
          if ((taken = r->contains(x))) break;
        if (!taken) add_particle(x, x, phase, velocity, body);
      }
}

void Builder::add_boundary(int body) {
  const Region& region = regions_[body];
  const double thickness = boundary_thickness(spec_, body);
  out_.bodies[body].thickness = thickness;
  if (all_wetted_.empty()) return;
  // Only points within `thickness` of some wetted piece can become dummy particles.
  Aabb near;
  for (const Aabb& b : all_wetted_bounds_) near.extend(b);
  const LatticeBox l = lattice_box(clipped_bounds(region).intersection(near.expanded(thickness)));
  const double limit2 = thickness * thickness;
  constexpr std::int64_t kOffset = std::int64_t(1) << 20;
  const WettedIndex index(all_wetted_bounds_, lattice_box_bounds(l), thickness);

  for (std::int64_t k = l.first[2]; k <= l.last[2]; ++k)
    for (std::int64_t j = l.first[1]; j <= l.last[1]; ++j)
      for (std::int64_t i = l.first[0]; i <= l.last[0]; ++i) {
        const Vec3 x = lattice_point(i, j, k);
        if (!region.contains(x)) continue;
        // Closest wetted point over the pieces within `thickness` (in piece order, so that ties
        // go to the first piece as in a search over all), skipping those whose box is too far.
        double best2 = limit2;
        Vec3 surface_point = Vec3::Zero();
        bool found = false;
        for (std::size_t f : index.near(x)) {
          if (all_wetted_bounds_[f].squared_distance(x) >= best2) continue;
          const Vec3 s = all_wetted_[f].closest_point(x);
          const double d2 = (s - x).squaredNorm();
          if (d2 < best2) best2 = d2, surface_point = s, found = true;
        }
        if (!found) continue;  // deeper than `thickness` below the wetted surface
        const std::uint64_t site = (std::uint64_t(i + kOffset) << 42) | (std::uint64_t(j + kOffset) << 21) |
                                   std::uint64_t(k + kOffset);
        if (!dummy_sites_.insert(site).second) continue;  // an earlier BOUNDARY body has it
        add_particle(x, 2.0 * surface_point - x, Phase::boundary, Vec3::Zero(), body);
      }
}

void Builder::check_inside_domain(int body) const {
  const HostParticles& p = out_.particles;
  const BodyReport& r = out_.bodies[body];
  const double slack = 1e-9 * dp_;
  for (std::size_t n = r.first; n < r.first + r.count; ++n) {
    for (int c = 0; c < dims_; ++c) {
      const double x = p.position[n * dims_ + c];
      if (x < spec_.domain().min(c) - slack || x > spec_.domain().max(c) + slack) {
        Vec3 pos = Vec3::Zero();
        for (int a = 0; a < dims_; ++a) pos[axes(dims_)[a]] = p.position[n * dims_ + a];
        throw CaseError(body_key(body), "body '" + r.name + "' has a particle at " + format_point(pos, dims_) +
                                            " outside the domain; enlarge domain or move the body");
      }
    }
  }
}

void Builder::set_densities() {
  HostParticles& p = out_.particles;
  const double boundary_density = reference_water_density(spec_);
  const double g = gravity_magnitude(spec_);
  const int z = dims_ - 1;
  for (std::size_t b = 0; b < out_.bodies.size(); ++b) {
    const BodyReport& r = out_.bodies[b];
    if (!is_fluid_[b]) {
      std::fill_n(p.water_density.begin() + r.first, r.count, boundary_density);
      continue;
    }
    if (soil_[b] >= 0) {
      set_soil_state(static_cast<int>(b));
      continue;
    }
    const v1::Material& m = spec_.materials(material_[b]);
    const double rho0 = water_density(m);
    if (!spec_.bodies(static_cast<int>(b)).initial().hydrostatic()) {
      std::fill_n(p.water_density.begin() + r.first, r.count, rho0);
      continue;
    }
    const double c0 = water_sound_speed(spec_, material_[b], p);
    double top = -std::numeric_limits<double>::infinity();
    for (std::size_t n = r.first; n < r.first + r.count; ++n) top = std::max(top, p.position[n * dims_ + z]);
    top += 0.5 * dp_;
    for (std::size_t n = r.first; n < r.first + r.count; ++n) {
      const double pressure = rho0 * g * (top - p.position[n * dims_ + z]);
      p.water_density[n] = rho0 + pressure / (c0 * c0);  // Eq. 6 with K_w = ρ_w0 c_w0²
    }
  }
}

// ρ_s = (1 − φ) ρ_s0 + S_w φ ρ_w0 (Eq. 28a) integrated over [z0, z1] by 5-point Gauss–Legendre,
// split at the water table, where S_w has its kink (p_c = 0).
double mixture_weight(const SoilMaterial& soil, double porosity, double rho_w0, double g,
                      const v1::InitialState& initial, double z0, double z1) {
  static constexpr double kNodes[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                                       0.9061798459386640};
  static constexpr double kWeights[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                         0.2369268850561891, 0.2369268850561891};
  const auto integrate = [&](double a, double b) {
    double sum = 0.0;
    for (int q = 0; q < 5; ++q) {
      const double zq = 0.5 * (a + b) + 0.5 * (b - a) * kNodes[q];
      const double s_w = soil.hydraulic.saturation(-initial_pore_pressure(initial, rho_w0, g, zq));
      sum += kWeights[q] * ((1.0 - porosity) * soil.grain_density + s_w * porosity * rho_w0);
    }
    return 0.5 * (b - a) * sum;
  };
  if (initial.has_water_table() && initial.water_table() > z0 && initial.water_table() < z1)
    return integrate(z0, initial.water_table()) + integrate(initial.water_table(), z1);
  return integrate(z0, z1);
}

// Pore pressure, pore-water density, porosity and the geostatic effective stress of a soil body
// (scenario.proto, InitialState). Each particle's vertical stress integrates the mixture's weight
// down its lattice column from the column's top (its highest particle of this body + dp/2).
void Builder::set_soil_state(int body) {
  HostParticles& p = out_.particles;
  const BodyReport& r = out_.bodies[body];
  const v1::InitialState& initial = spec_.bodies(body).initial();
  const SoilMaterial& soil = soils_[soil_[body]];
  const double porosity = spec_.materials(material_[body]).soil().porosity();
  // Along z with gravity's z component: |g| for vertical gravity, |g| cos β for gravity tilted by
  // β (an infinite slope along x, scenario.proto InitialState; the slope's shear stress is left to
  // the geostatic stage).
  const double rho_w0 = reference_water_density(spec_), g = spec_.gravity_size() == dims_ ? -spec_.gravity(dims_ - 1) : 0.0;
  const double k0 = earth_pressure_coefficient(soil, initial);
  const int z = dims_ - 1;
  const auto level = [&](std::size_t n, int c) { return std::llround(p.position[n * dims_ + c] / dp_ - 0.5); };

  // The top lattice level of each column, and the levels the body spans.
  std::map<std::pair<long long, long long>, long long> top;
  long long lowest = std::numeric_limits<long long>::max(), highest = std::numeric_limits<long long>::min();
  for (std::size_t n = r.first; n < r.first + r.count; ++n) {
    const long long k = level(n, z);
    const auto column = std::make_pair(level(n, 0), dims_ == 3 ? level(n, 1) : 0LL);
    const auto [it, added] = top.emplace(column, k);
    if (!added) it->second = std::max(it->second, k);
    lowest = std::min(lowest, k), highest = std::max(highest, k);
  }
  // weight[m] = ∫ ρ_s dz from the bottom of the body's lowest particles, lowest · dp, up to the half
  // level lowest · dp + m dp/2: particle centres (odd m) and column tops (even m) are such levels.
  const double bottom = double(lowest) * dp_;
  std::vector<double> weight(2 * std::size_t(highest - lowest + 1) + 1, 0.0);
  for (std::size_t m = 1; m < weight.size(); ++m)
    weight[m] = weight[m - 1] + mixture_weight(soil, porosity, rho_w0, g, initial, bottom + 0.5 * dp_ * double(m - 1),
                                               bottom + 0.5 * dp_ * double(m));

  const std::string key = body_key(body) + ".initial";
  for (std::size_t n = r.first; n < r.first + r.count; ++n) {
    const long long k = level(n, z);
    const long long k_top = top.at(std::make_pair(level(n, 0), dims_ == 3 ? level(n, 1) : 0LL));
    const double zn = p.position[n * dims_ + z], z_top = (double(k_top) + 1.0) * dp_;
    const double p_w = initial_pore_pressure(initial, rho_w0, g, zn);
    if (!(p_w > -soil.water_bulk_modulus)) {
      std::ostringstream message;
      message << "gives the pore pressure " << p_w << " Pa at z = " << zn << " m, at or below -K_w = "
              << -soil.water_bulk_modulus << " Pa, where the pore-water density ρ_w0 (1 + p_w / K_w) is no longer "
              << "positive";
      throw CaseError(key + (initial.has_water_table() ? ".water_table" : ".suction"), message.str());
    }
    // Water standing on the body when the table is above its top: the column carries it.
    const double surcharge = std::max(0.0, initial_pore_pressure(initial, rho_w0, g, z_top));
    const double total = -surcharge - g * (weight[2 * std::size_t(k_top - lowest + 1)] -
                                           weight[2 * std::size_t(k - lowest) + 1]);
    const double effective = total + soil.hydraulic.saturation(-p_w) * p_w;  // Bishop, Eq. 7
    double* stress = &p.effective_stress[6 * n];
    stress[0] = stress[1] = k0 * effective;
    stress[2] = effective;
    stress[3] = stress[4] = stress[5] = 0.0;
    p.water_density[n] = rho_w0 * (1.0 + p_w / soil.water_bulk_modulus);  // Eq. 36b
    p.porosity[n] = porosity;
    p.soil_material[n] = static_cast<std::uint8_t>(soil_[body]);
  }
}

ParticleSet Builder::build() {
  read_case();
  const int n_bodies = static_cast<int>(regions_.size());
  wetted_.resize(n_bodies);
  for (int b = 0; b < n_bodies; ++b) {
    if (is_fluid_[b]) continue;
    wetted_[b] = wetted_surface(b);
    for (const Face& f : wetted_[b]) {
      all_wetted_.push_back(f);
      all_wetted_bounds_.push_back(f.bounds());
    }
  }
  estimate_count();
  for (int a : axes(dims_)) {
    const double reach = std::max(std::abs(domain_.lo[a]), std::abs(domain_.hi[a])) / dp_;
    if (reach >= double(1 << 19)) throw CaseError("dp", "the domain spans more than 2^19 spacings from the origin");
  }

  out_.particles.dimensions = dims_;
  const std::vector<int> ax = axes(dims_);
  std::vector<double> lo, hi;
  for (int a : ax) lo.push_back(domain_.lo[a]), hi.push_back(domain_.hi[a]);
  const Shape domain_box = Shape::box(lo, hi, dims_, "domain");
  for (int b = 0; b < n_bodies; ++b) {
    BodyReport r;
    r.name = spec_.bodies(b).name();
    r.first = out_.particles.size();
    for (const Face& f : wetted_[b])  // the part in the domain (a periodic axis may cut a face)
      for (const Face& piece : clip_to_cell(f, domain_box.cells()[0], 1e-9 * dp_)) r.wetted_surface += piece.measure();
    out_.bodies.push_back(r);
    if (is_fluid_[b]) add_fluid(b);
    else add_boundary(b);
    out_.bodies[b].count = out_.particles.size() - out_.bodies[b].first;
    if (is_fluid_[b] && out_.bodies[b].count == 0)
      throw CaseError(body_key(b), "body '" + r.name + "' has no particles: region empty or covered by solids");
    // A solid with no dummy particles would let water through without a word.
    if (!is_fluid_[b] && out_.bodies[b].count == 0)
      throw CaseError(body_key(b), "boundary body '" + r.name +
                                       "' has no dummy particles: none of its surface faces the fluid inside the domain");
    check_inside_domain(b);
  }
  if (out_.particles.size() == 0) throw CaseError("domain", "the case has no particles");
  set_densities();
  return std::move(out_);
}

}  // namespace

ParticleSet build_particle_set(const v1::ScenarioSpec& spec) { return Builder(spec).build(); }

HostParticles build_particles(const v1::ScenarioSpec& spec) { return build_particle_set(spec).particles; }

double smoothing_length(const v1::ScenarioSpec& spec) {
  return (spec.h_over_dp() > 0.0 ? spec.h_over_dp() : kDefaultHOverDp) * spec.dp();
}

double boundary_thickness(const v1::ScenarioSpec& spec, int body_index) {
  const int layers = spec.bodies(body_index).layers();
  if (layers > 0) return layers * spec.dp();
  // Whole layers covering the support 2h; the small slack keeps 2h = 3 dp at 3 layers.
  return std::ceil(2.0 * smoothing_length(spec) / spec.dp() - 1e-9) * spec.dp();
}

double water_sound_speed(const v1::ScenarioSpec& spec, int material_index, const HostParticles& particles) {
  const std::string key = "materials[" + std::to_string(material_index) + "].water";
  const v1::WaterModel& w = spec.materials(material_index).water();
  if (w.sound_speed() > 0.0) return w.sound_speed();
  const double rho0 = w.density() > 0.0 ? w.density() : kDefaultWaterDensity;
  const double g = gravity_magnitude(spec);
  const int dims = particles.dimensions;
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  for (std::size_t n = 0; n < particles.size(); ++n) {
    if (particles.phase[n] != Phase::water) continue;
    const double z = particles.position[n * dims + dims - 1];
    lowest = std::min(lowest, z), highest = std::max(highest, z);
  }
  const double height = highest >= lowest ? highest - lowest + spec.dp() : 0.0;
  const double v_max = w.max_speed() > 0.0 ? w.max_speed() : std::sqrt(2.0 * g * height);
  const double dp_max = w.max_pressure() > 0.0 ? w.max_pressure() : rho0 * g * height;
  const double c0 = 10.0 * std::max(v_max, std::sqrt(dp_max / rho0));
  if (!(c0 > 0.0))
    throw CaseError(key + ".sound_speed",
                    "Eq. 24a gives no sound speed (no gravity or no water height): set sound_speed or max_speed");
  return c0;
}

}  // namespace cascade
