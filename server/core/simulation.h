// Simulation<Real, Dim, Backend>: particle arrays on one backend and the step that calls the
// physical terms in order. Included only by the backend files (engine_cpu.cpp, engine_cuda.cu).
#pragma once

#include <cstdio>
#include <cstring>

#include <thrust/copy.h>
#include <thrust/fill.h>
#include <thrust/for_each.h>
#include <thrust/functional.h>
#include <thrust/host_vector.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/reduce.h>
#include <thrust/replace.h>
#include <thrust/transform.h>
#include <thrust/transform_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "server/core/backend.h"
#include "server/core/engine.h"
#include "server/core/cell_sort.h"
#include "server/core/neighbour_list.h"
#include "server/core/particle_rows.h"
#include "server/core/particle_view.h"
#include "server/core/engine_state_rows.h"
#include "server/core/partition.h"
#include "server/physics/free_surface.h"
#include "server/physics/local_damping.h"
#include "server/physics/soil_interaction.h"
#include "server/physics/soil_stress_update.h"
#include "server/physics/pore_water_state.h"
#include "server/physics/renormalised_gradient.h"
#include "server/physics/seepage.h"
#include "server/physics/seepage_inertia.h"
#include "server/physics/soil_view.h"
#include "server/physics/solid_boundary_soil.h"
#include "server/physics/solid_boundary.h"
#include "server/physics/symplectic_verlet.h"
#include "server/physics/time_step.h"
#include "server/physics/wall_contact.h"
#include "server/physics/water_interaction.h"

namespace cascade {

template <typename Real, int Dim, typename Backend>
class Simulation final : public Engine {
  template <typename T>
  using Vector = typename Backend::template Vector<T>;
  using V = Vec<Real, Dim>;

 public:
  // With a partition, `host` holds this process's share of the run (partition.h): the particles it
  // owns, the copies of the others' within its halo, and the dummies there.
  Simulation(const EngineConfig& config, const HostParticles& host, const PartitionSetup* partition = nullptr)
      : config_(config),
        forcing_(config.forcing),
        cells_(config.domain_min, config.domain_max, config.periodic, 2.0 * kListRadius * config.h),
        neighbours_(config.h / config.dp) {
    const std::size_t n = host.size();
    if (host.dimensions != Dim) throw std::invalid_argument("particle set dimensions do not match the engine");
    std::vector<V> position(n), velocity(n), ghost(n);
    std::vector<Real> water_density(n);
    std::vector<std::uint32_t> id(n);
    for (std::size_t i = 0; i < n; ++i) {
      for (int a = 0; a < Dim; ++a) {
        position[i][a] = Real(host.position[i * Dim + a]);
        velocity[i][a] = Real(host.velocity[i * Dim + a]);
        ghost[i][a] = Real(host.ghost[i * Dim + a]);
      }
      water_density[i] = Real(host.water_density[i]);
      id[i] = partition ? partition->global_id[i] : std::uint32_t(i);
    }
    if (partition) {
      transport_ = partition->transport;
      slabs_ = partition->slabs;
      owner_ = partition->owner;
    }
    position_ = position;
    velocity_ = velocity;
    ghost_ = ghost;
    water_density_ = water_density;
    density_ = std::vector<Real>(n, Real(config.water_density));  // one initial numerical density (Section 3.2)
    phase_ = host.phase;
    id_ = id;
    // Zeros, not Eigen's uninitialised default.
    for (auto* v : {&pressure_, &density_rate_, &water_density_rate_, &step_limit_, &start_density_, &start_water_density_})
      v->assign(n, Real(0));
    for (auto* v : {&acceleration_, &water_density_gradient_, &start_position_, &start_velocity_, &listed_position_})
      v->assign(n, V::Zero());
    dummy_flags_.resize(n);
    scratch_phase_.resize(n);
    scratch_index_.resize(n);
    set_up_soil(host, partition);
    const EngineState* start = partition ? partition->start : nullptr;
    if (start) take_state(*start);

    sph_.h = Real(config.h);
    // The kernel gradient normalised on the lattice the builder places the particles on
    // (kernel.h, docs/physics.md "Lattice moment"): every gradient and divergence is then exact
    // for a linear field in the bulk, as the renormalised pore-pressure gradient is.
    sph_.kernel = WendlandC2<Real, Dim>(Real(config.h), Real(1.0 / lattice_gradient_moment<Dim>(config.h, config.dp)));
    sph_.eta2 = Real(0.01 * config.h * config.h);
    sph_.laplacian_scale = Real(lattice_gradient_moment<Dim>(config.h, config.dp) /
                                lattice_gradient_moment<Dim>(config.h, config.dp, 0.01 * config.h * config.h));
    sph_.dp = Real(config.dp);
    sph_.mass = Real(config.water_density * std::pow(config.dp, Dim));
    for (int a = 0; a < Dim; ++a) sph_.gravity[a] = Real(config.gravity[a]);
    water_ = WaterConstants<Real>{Real(config.water_density), Real(config.sound_speed), Real(config.delta),
                                  Real(config.viscosity_alpha)};
    // Pressures of the initial state (Eq. 6, the pore-water state and the boundary
    // extrapolation), so that frame 0 has them. A share of a split run first settles which copies
    // each process holds by the engine's own rule (share_particles), in its own precision. A
    // share that starts from a checkpoint keeps the checkpoint's values, as restore() does.
    if (transport_) share_particles(false);
    sort_by_cell();
    if (start) return;
    boundary_values(false);
    density_gradients();
  }

  // A member-wise copy (device arrays copied on the device) without the neighbour lists, which
  // the copy builds again at its first step as restore() does (half of a 3D engine's bytes: the
  // parent's step boundary then waits for the state only); grid_ holds pointers into cells_'
  // arrays, so the copy's view is taken again from its own.
  std::unique_ptr<Engine> clone() const override {
    refuse_when_partitioned("a fork");
    auto copy = std::make_unique<Simulation>(*this);
    copy->grid_ = copy->cells_.view();
    return copy;
  }

  // Split over processes, the copies of other processes' particles take their owners' values at
  // the half step and at the end of the step (refresh_halo), so that every evaluation and every
  // frame between steps reads the whole run's state.
  void step() override {
    update_lists();
    evaluate_rates(false);
    dt_ = next_time_step();
    save_step_start();
    launch(SymplecticPredictor<Real, Dim>{view(), start_view(), grid_, Real(dt_)}, 0, moving_);
    update_soil_stress(0.5 * dt_);
    refresh_halo();
    evaluate_rates(true);
    account_pore_water();
    if (has_soil_ && !relaxing())  // a_s is part of the seepage, held while relaxing
      launch(SeepageInertiaFilter<Real, Dim>{view(), soil_view(), sph_.h, Real(dt_)}, grid_.water_end, moving_);
    launch(SymplecticCorrector<Real, Dim>{view(), start_view(), grid_, Real(dt_)}, 0, moving_);
    if (active_ > moving_) launch(WallContact<Real, Dim>{view(), grid_, neighbours_.view()}, 0, moving_);
    update_soil_stress(dt_);
    refresh_halo();
    time_ += dt_;
    ++steps_;
  }

  // The seepage discharge at the present state, for a state whose pore water another solver
  // advanced with the skeleton at rest (the implicit stage), so that its frames carry the Darcy
  // flux of its pore pressures: the dummies' soil side, the pore-water gradient and Eq. 27b as a
  // step's first evaluation forms them, nothing else. It writes no carried array but `seepage`, so
  // a state taken after it continues as the engine does; the next step's surface switch (Eq. 39)
  // reads the discharge of the state it starts from.
  void refresh_seepage() override {
    if (!has_soil_ || relaxing()) return;
    update_lists();
    refresh_halo();
    launch_owned(SolidBoundarySoil<Real, Dim>{view(), soil_view(), grid_, sph_, raw(dummy_flags_)}, moving_, active_);
    send_dummy_values();
    pore_water_gradients();
    seepage_discharge();
    send_pore_water_gradients();
  }

  double time() const override { return time_; }
  std::uint64_t step_count() const override { return steps_; }
  double last_dt() const override { return dt_; }
  std::size_t particle_count() const override { return phase_.size(); }
  std::size_t lost_particles() const override { return phase_.size() - active_; }
  LoadBalance load_balance() const override { return balance_; }
  PoreWaterAccount pore_water_account() const override {
    const thrust::host_vector<double> totals(pore_water_totals_.begin(), pore_water_totals_.end());
    return {totals[0], totals[1], totals[2]};
  }
  const char* device_name() const override { return Backend::name; }
  void set_forcing(const HydraulicForcing& forcing) override { forcing_ = forcing; }
  HydraulicForcing forcing() const override { return forcing_; }

  void set_relaxation(double local_damping) override {
    if (!(local_damping >= 0 && local_damping < 1))
      throw std::invalid_argument("the local damping coefficient must be in [0, 1), not " + number(local_damping));
    local_damping_ = local_damping;
  }

  // Split over processes: of the particles each owns, combined over all (collective).
  Equilibrium equilibrium() const override {
    if (!has_soil_) return {};
    const std::uint32_t water = grid_.water_end;
    const EquilibriumOfParticle<Real, Dim> term{raw(soil_materials_), raw(soil_material_), raw(porosity_),
                                                raw(saturation_), raw(density_), raw(velocity_),
                                                raw(unbalanced_acceleration_), sph_.mass, sph_.gravity.norm(),
                                                water_.rho0};
    const EquilibriumSums<Real> none{Real(0), Real(0), Real(0), Real(0)};
    const auto first = thrust::counting_iterator<std::uint32_t>(water);
    const auto last = thrust::counting_iterator<std::uint32_t>(std::uint32_t(moving_));
    EquilibriumSums<Real> sums =
        transport_ ? thrust::transform_reduce(Backend::policy(), first, last,
                                              OwnedTerm<decltype(term), EquilibriumSums<Real>>{term, raw(owner_),
                                                                                              process(), none},
                                              none, CombineEquilibriumSums<Real>())
                   : thrust::transform_reduce(Backend::policy(), first, last, term, none, CombineEquilibriumSums<Real>());
    double max_force = double(sums.max_force), weight = double(sums.weight), particles = double(sums.particles),
           max_speed = double(sums.max_speed);
    if (transport_) {
      max_force = transport_->maximum(max_force), weight = transport_->sum(weight);
      particles = transport_->sum(particles), max_speed = transport_->maximum(max_speed);
    }
    if (!(particles > 0)) return {};
    return {max_force / (weight / particles), max_speed};
  }

  void zero_velocities() override {
    thrust::fill(Backend::policy(), velocity_.begin(), velocity_.begin() + moving_, V(V::Zero()));
  }

  void restart_clock() override {
    time_ = 0;
    thrust::fill(pore_water_totals_.begin(), pore_water_totals_.end(), 0.0);  // from the clock's start, as the displacement
    if (!has_soil_) return;
    const FieldFrame now = frame();
    initial_position_ = transport_ ? whole_run_positions(now) : now.position;
  }

  // Split over processes: the positions of the whole run by id (N × 3, as a frame's), from the
  // particles each process owns in its share's frame `own` (collective).
  std::vector<double> whole_run_positions(const FieldFrame& own) const {
    const auto* owner = own.find("process");
    std::vector<char> message;
    for (std::size_t k = 0; k < own.size(); ++k) {
      if (owner->values[k] != double(process())) continue;
      const char* id = reinterpret_cast<const char*>(&own.id[k]);
      const char* x = reinterpret_cast<const char*>(&own.position[3 * k]);
      message.insert(message.end(), id, id + sizeof(std::uint32_t));
      message.insert(message.end(), x, x + 3 * sizeof(double));
    }
    std::vector<double> whole(initial_position_.size(), 0.0);
    constexpr std::size_t row = sizeof(std::uint32_t) + 3 * sizeof(double);
    for (const auto& in : transport_->exchange(std::vector<std::vector<char>>(transport_->processes(), message)))
      for (std::size_t at = 0; at + row <= in.size(); at += row) {
        std::uint32_t id = 0;
        std::memcpy(&id, in.data() + at, sizeof id);
        if (3 * std::size_t(id) + 3 > whole.size()) throw std::logic_error("a process owns an unknown particle");
        std::memcpy(&whole[3 * std::size_t(id)], in.data() + at + sizeof id, 3 * sizeof(double));
      }
    return whole;
  }

  // Split over processes: the rows of the particles this process owns (DistributedEngine puts
  // the processes' rows together).
  EngineState state() const override {
    EngineState s;
    s.dimensions = Dim;
    s.single_precision = std::is_same_v<Real, float>;
    s.particles = phase_.size();
    s.time = time_, s.last_dt = dt_, s.steps = steps_;
    s.forcing = forcing_;
    s.displacement_reference = initial_position_;
    s.pore_water = pore_water_account();
    for_each_carried_array(*this, [&s](const char* name, const auto& array) { export_array(array, name, s); });
    if (!transport_) return s;
    const thrust::host_vector<std::uint32_t> owner(owner_.begin(), owner_.end());
    std::vector<std::size_t> owned;
    for (std::size_t k = 0; k < owner.size(); ++k)
      if (owner[k] == process()) owned.push_back(k);
    return state_rows(s, owned);
  }

  void restore(const EngineState& s) override {
    refuse_when_partitioned("a restore");  // DistributedEngine::restore builds the shares anew instead
    take_state(s);
    list_at_listed_positions();
  }

  // The carried arrays and counters of `s`, whose particles are this engine's (a restore, or a
  // share of a split run that starts from its rows of a checkpoint).
  void take_state(const EngineState& s) {
    if (s.dimensions != Dim || s.single_precision != std::is_same_v<Real, float> || s.particles != phase_.size())
      throw std::invalid_argument("the state is of a " + std::to_string(s.dimensions) + "D engine in " +
                                  (s.single_precision ? "float" : "double") + " with " + std::to_string(s.particles) +
                                  " particles; this one is " + std::to_string(Dim) + "D, " +
                                  (std::is_same_v<Real, float> ? "float" : "double") + ", " +
                                  std::to_string(phase_.size()) + " particles");
    for_each_carried_array(*this, [&s](const char* name, auto& array) { import_array(s, name, array); });
    time_ = s.time, dt_ = s.last_dt, steps_ = s.steps;
    forcing_ = s.forcing;
    if (has_soil_) initial_position_ = s.displacement_reference;
    pore_water_totals_ = std::vector<double>{s.pore_water.rain, s.pore_water.walls, s.pore_water.surface};
  }

  std::size_t device_bytes() const override {
    std::size_t bytes = 0;
    auto add = [&](const auto& v) { bytes += v.capacity() * sizeof(typename std::decay_t<decltype(v)>::value_type); };
    add(position_), add(velocity_), add(ghost_), add(acceleration_), add(water_density_gradient_);
    add(start_position_), add(start_velocity_), add(listed_position_);
    add(density_), add(water_density_), add(pressure_), add(density_rate_), add(water_density_rate_);
    add(step_limit_), add(start_density_), add(start_water_density_);
    add(phase_), add(scratch_phase_), add(dummy_flags_), add(id_), add(scratch_index_);
    add(soil_materials_), add(soil_material_), add(free_surface_), add(surface_state_);
    add(porosity_), add(saturation_), add(conductivity_), add(seepage_), add(skeleton_acceleration_);
    add(effective_stress_), add(start_stress_);
    add(dummy_pore_pressure_), add(dummy_stress_), add(dummy_velocity_), add(wall_), add(wall_pore_pressure_);
    add(velocity_gradient_), add(porosity_rate_), add(plastic_strain_), add(start_plastic_strain_), add(start_porosity_);
    add(unbalanced_acceleration_), add(pore_water_inflow_), add(pore_water_blocks_), add(pore_water_totals_);
    add(owner_);
    return bytes + cells_.bytes() + neighbours_.bytes();
  }

  FieldFrame frame() const override {
    const std::size_t n = phase_.size();
    std::vector<V> position(n), velocity(n);
    std::vector<Real> pressure(n), water_density(n), density(n);
    std::vector<Phase> phase(n);
    std::vector<std::uint32_t> id(n);
    thrust::copy(position_.begin(), position_.end(), position.begin());
    thrust::copy(velocity_.begin(), velocity_.end(), velocity.begin());
    thrust::copy(pressure_.begin(), pressure_.end(), pressure.begin());
    thrust::copy(water_density_.begin(), water_density_.end(), water_density.begin());
    thrust::copy(density_.begin(), density_.end(), density.begin());
    thrust::copy(phase_.begin(), phase_.end(), phase.begin());
    thrust::copy(id_.begin(), id_.end(), id.begin());
    show_unlisted_dummies(velocity, pressure, water_density);

    FieldFrame f;
    f.time = time_;
    f.step = steps_;
    f.dimensions = Dim;
    f.position.resize(3 * n);
    f.phase.resize(n);
    f.id.resize(n);
    FieldFrame::RealField vel{"velocity", "m/s", 3, std::vector<double>(3 * n)};
    FieldFrame::RealField pres{"pressure", "Pa", 1, std::vector<double>(n)};
    FieldFrame::RealField dens{"density", "kg/m^3", 1, std::vector<double>(n)};
    FieldFrame::RealField num{"numerical_density", "kg/m^3", 1, std::vector<double>(n)};
    // 2D cases are (x, z): written as (x, 0, z).
    const int axis3[3] = {0, Dim == 2 ? -1 : 1, Dim == 2 ? 1 : 2};
    const std::vector<std::uint32_t> slot = slots_by_id(id);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = slot[k];  // ordered by id
      for (int c = 0; c < 3; ++c) {
        f.position[3 * i + c] = axis3[c] < 0 ? 0.0 : double(position[k][axis3[c]]);
        vel.values[3 * i + c] = axis3[c] < 0 ? 0.0 : double(velocity[k][axis3[c]]);
      }
      f.phase[i] = std::uint8_t(phase[k]);
      f.id[i] = id[k];
      pres.values[i] = double(pressure[k]);
      dens.values[i] = double(water_density[k]);
      num.values[i] = double(density[k]);
    }
    // Particles past active_ left the domain along a non-periodic axis (cell_sort.h): they keep
    // their phase and last state in the frame, flagged here, so that no count of a phase can
    // hide them (docs/output.md).
    FieldFrame::RealField lost{"lost", "1", 1, std::vector<double>(n)};
    for (std::size_t k = active_; k < n; ++k) lost.values[slot[k]] = 1.0;
    f.fields = {std::move(vel), std::move(pres), std::move(dens), std::move(num), std::move(lost)};
    if (transport_) {
      // The process that owns each particle: the one whose values of it count (partition.h).
      const thrust::host_vector<std::uint32_t> owner(owner_.begin(), owner_.end());
      FieldFrame::RealField process{"process", "1", 1, std::vector<double>(n)};
      for (std::size_t k = 0; k < n; ++k) process.values[slot[k]] = double(owner[k]);
      f.fields.push_back(std::move(process));
    }
    if (has_soil_) add_soil_fields(f, id, slot, pressure, axis3);
    return f;
  }

 private:
  // Where each particle goes in a frame ordered by id: its id, or, in a process's share of a
  // split run (whose ids are those of the whole run), the rank of its id among the share's.
  std::vector<std::uint32_t> slots_by_id(const std::vector<std::uint32_t>& id) const {
    if (!transport_) return id;
    std::vector<std::uint32_t> order(id.size()), slot(id.size());
    for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return id[a] < id[b]; });
    for (std::uint32_t k = 0; k < order.size(); ++k) slot[order[k]] = k;
    return slot;
  }

  // The steps give no water values to the dummies that no particle lists (they rest at ρ_w0,
  // SolidBoundaryWater): a frame shows those the values their ghost nodes give now, computed
  // into copies, so that taking a frame changes nothing in the run.
  void show_unlisted_dummies(std::vector<V>& velocity, std::vector<Real>& pressure,
                             std::vector<Real>& water_density) const {
    if (active_ == moving_) return;
    Vector<Real> shown_pressure = pressure_, shown_water_density = water_density_;
    Vector<V> shown_velocity = velocity_;
    ParticleView<Real, Dim> shown = const_cast<Simulation*>(this)->view();  // read only, but for these:
    shown.pressure = raw(shown_pressure), shown.water_density = raw(shown_water_density);
    shown.velocity = raw(shown_velocity);
    launch(SolidBoundaryWater<Real, Dim>{shown, grid_, sph_, water_, nullptr, false}, moving_, active_);
    const std::size_t n = active_ - moving_;
    std::vector<std::uint8_t> flags(n);
    std::vector<Real> dummy_pressure(n), dummy_water_density(n);
    std::vector<V> dummy_velocity(n);
    thrust::copy(dummy_flags_.begin() + moving_, dummy_flags_.begin() + active_, flags.begin());
    thrust::copy(shown_pressure.begin() + moving_, shown_pressure.begin() + active_, dummy_pressure.begin());
    thrust::copy(shown_water_density.begin() + moving_, shown_water_density.begin() + active_,
                 dummy_water_density.begin());
    thrust::copy(shown_velocity.begin() + moving_, shown_velocity.begin() + active_, dummy_velocity.begin());
    for (std::size_t k = 0; k < n; ++k) {
      if (flags[k] & kListed) continue;
      pressure[moving_ + k] = dummy_pressure[k], water_density[moving_ + k] = dummy_water_density[k];
      velocity[moving_ + k] = dummy_velocity[k];
    }
  }

  // The arrays that hold state from one step to the next (sort_by_cell's reordered ones, and the
  // listed positions that decide the next list rebuild), with the pressures and surface values
  // the frames report; every other array is recomputed in a step before it is read.
  template <typename Self, typename F>
  static void for_each_carried_array(Self& self, F&& f) {
    f("position", self.position_), f("velocity", self.velocity_), f("ghost", self.ghost_);
    f("listed_position", self.listed_position_), f("density", self.density_);
    f("water_density", self.water_density_), f("pressure", self.pressure_), f("phase", self.phase_);
    f("id", self.id_);
    if (!self.has_soil_) return;
    f("soil_material", self.soil_material_), f("surface_state", self.surface_state_), f("wall", self.wall_);
    f("free_surface", self.free_surface_), f("porosity", self.porosity_), f("saturation", self.saturation_);
    f("plastic_strain", self.plastic_strain_), f("seepage", self.seepage_);
    f("skeleton_acceleration", self.skeleton_acceleration_), f("effective_stress", self.effective_stress_);
  }

  // Scalars of Real or an integer type, or Eigen fixed-size vectors and tensors of Real.
  template <typename T>
  static constexpr int components_of() {
    if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) return 1;
    else return int(T::SizeAtCompileTime);
  }
  template <typename T>
  static constexpr bool is_integer() {
    return std::is_integral_v<T> || std::is_enum_v<T>;
  }

  template <typename T>
  static void export_array(const Vector<T>& array, const char* name, EngineState& s) {
    std::vector<T> host(array.size());
    thrust::copy(array.begin(), array.end(), host.begin());
    constexpr int c = components_of<T>();
    if constexpr (is_integer<T>()) {
      auto& out = s.integers[name];
      for (const T& v : host) out.push_back(std::uint32_t(v));
    } else {
      auto& out = s.reals[name];
      out.reserve(host.size() * c);
      for (const T& v : host)
        for (int k = 0; k < c; ++k) {
          if constexpr (c == 1) out.push_back(double(v));
          else out.push_back(double(v(k)));
        }
    }
  }

  template <typename Arrays>
  static const typename Arrays::mapped_type& stored(const Arrays& arrays, const char* name, std::size_t size) {
    const auto found = arrays.find(name);
    if (found == arrays.end() || found->second.size() != size)
      throw std::invalid_argument(std::string("the state's array '") + name + "' is missing or has the wrong size");
    return found->second;
  }

  template <typename T>
  static void import_array(const EngineState& s, const char* name, Vector<T>& array) {
    constexpr int c = components_of<T>();
    std::vector<T> host(s.particles);
    if constexpr (is_integer<T>()) {
      const auto& values = stored(s.integers, name, s.particles);
      for (std::size_t i = 0; i < s.particles; ++i) host[i] = T(values[i]);
    } else {
      const auto& values = stored(s.reals, name, s.particles * c);
      for (std::size_t i = 0; i < s.particles; ++i) {
        if constexpr (c == 1) host[i] = T(values[i]);
        else
          for (int k = 0; k < c; ++k) host[i](k) = typename T::Scalar(values[i * c + k]);
      }
    }
    array = host;
  }

  // The soil fields of docs/output.md, ordered by id like the others.
  void add_soil_fields(FieldFrame& f, const std::vector<std::uint32_t>& id, const std::vector<std::uint32_t>& slot,
                       const std::vector<Real>& pressure, const int* axis3) const {
    const std::size_t n = id.size();
    std::vector<Real> porosity(n), saturation(n);
    std::vector<V> seepage(n), position(n);
    std::vector<std::uint8_t> free_surface(n);
    std::vector<Voigt<Real>> stress(n);
    std::vector<Real> plastic_strain(n);
    thrust::copy(effective_stress_.begin(), effective_stress_.end(), stress.begin());
    thrust::copy(plastic_strain_.begin(), plastic_strain_.end(), plastic_strain.begin());
    thrust::copy(porosity_.begin(), porosity_.end(), porosity.begin());
    thrust::copy(saturation_.begin(), saturation_.end(), saturation.begin());
    thrust::copy(seepage_.begin(), seepage_.end(), seepage.begin());
    thrust::copy(position_.begin(), position_.end(), position.begin());
    thrust::copy(free_surface_.begin(), free_surface_.end(), free_surface.begin());
    FieldFrame::RealField pore{"pore_pressure", "Pa", 1, std::vector<double>(n)};
    FieldFrame::RealField sat{"saturation", "1", 1, std::vector<double>(n)};
    FieldFrame::RealField phi{"porosity", "1", 1, std::vector<double>(n)};
    FieldFrame::RealField kappa{"plastic_strain", "1", 1, std::vector<double>(n)};
    FieldFrame::RealField q{"seepage", "m/s", 3, std::vector<double>(3 * n)};
    FieldFrame::RealField u{"displacement", "m", 3, std::vector<double>(3 * n)};
    FieldFrame::RealField total{"stress", "Pa", 6, std::vector<double>(6 * n)};
    FieldFrame::RealField effective{"effective_stress", "Pa", 6, std::vector<double>(6 * n)};
    FieldFrame::RealField yield{"yield_ratio", "1", 1, std::vector<double>(n)};
    std::vector<std::uint8_t> material(n);
    thrust::copy(soil_material_.begin(), soil_material_.end(), material.begin());
    f.free_surface.assign(n, 0);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = slot[k];
      if (f.phase[i] != std::uint8_t(Phase::soil)) continue;
      pore.values[i] = double(pressure[k]);
      sat.values[i] = double(saturation[k]);
      phi.values[i] = double(porosity[k]);
      f.free_surface[i] = free_surface[k];
      for (int c = 0; c < 3; ++c) {
        q.values[3 * i + c] = axis3[c] < 0 ? 0.0 : double(seepage[k][axis3[c]]);
        u.values[3 * i + c] = f.position[3 * i + c] - initial_position_[3 * std::size_t(id[k]) + c];
      }
      kappa.values[i] = double(plastic_strain[k]);
      // σ = σ' − S_w p_w I (Bishop, Eq. 7)
      for (int c = 0; c < 6; ++c) {
        effective.values[6 * i + c] = double(stress[k](c));
        total.values[6 * i + c] = double(stress[k](c)) - (c < 3 ? sat.values[i] * pore.values[i] : 0.0);
      }
      yield.values[i] = config_.soils[material[k]].mechanical.yield_ratio(tensor_of(Voigt<double>(stress[k].template cast<double>())),
                                                                         -pore.values[i], kappa.values[i]);
    }
    for (auto* field : {&pore, &sat, &phi, &kappa, &q, &u, &total, &effective, &yield}) f.fields.push_back(std::move(*field));
  }

  // Runs f on particles [begin, end): the moving particles are [0, moving_), the dummy particles
  // [moving_, active_) (cell_sort.h), so each pass runs on its own particles. On the CPU, over
  // many particles, the threads take blocks of kLaunchBlock particles as they finish the last: a
  // pass's cost is uneven along the particles (only the dummies near water interpolate, a splash
  // has few neighbours), and an even split left one thread waiting (3D dam break: 216 → 206 ms
  // per step). Over a few blocks an even split is faster (the 2D demo's 1265 particles: 0.68
  // against 0.64 ms per step). Each particle's result is the same whichever thread computes it.
  template <typename F>
  static void launch(const F& f, std::size_t begin, std::size_t end) {
#if defined(_OPENMP) && !defined(__CUDACC__)
    if constexpr (std::is_same_v<Backend, OmpBackend>) {
      if (end - begin >= kDynamicLaunchFrom) {
        const std::int64_t first = std::int64_t(begin), last = std::int64_t(end);
#pragma omp parallel for schedule(dynamic, kLaunchBlock)
        for (std::int64_t i = first; i < last; ++i) f(std::uint32_t(i));
        return;
      }
    }
#endif
    thrust::for_each(Backend::policy(), thrust::counting_iterator<std::uint32_t>(std::uint32_t(begin)),
                     thrust::counting_iterator<std::uint32_t>(std::uint32_t(end)), f);
  }
  static constexpr int kLaunchBlock = 256;

  // A pass that reads its particle's neighbours, run on the particles this process owns: a copy
  // near the halo's edge lacks some of its neighbours, so in a share of a split run the copies
  // skip it and take their owners' results where a later pass reads them (send_to_copies), or
  // at the next refresh_halo.
  template <typename F>
  void launch_owned(const F& f, std::size_t begin, std::size_t end) const {
    if (transport_) launch(OwnedOnly<F>{f, raw(owner_), process()}, begin, end);
    else launch(f, begin, end);
  }
  static constexpr std::size_t kDynamicLaunchFrom = 64 * kLaunchBlock;

  ParticleView<Real, Dim> view() {
    return {raw(position_), raw(velocity_), raw(density_), raw(water_density_), raw(pressure_),
            raw(phase_), raw(ghost_), raw(acceleration_), raw(density_rate_), raw(water_density_rate_),
            raw(water_density_gradient_), raw(step_limit_)};
  }
  StepStartState<Real, Dim> start_view() {
    return {raw(start_position_), raw(start_velocity_), raw(start_density_), raw(start_water_density_)};
  }

  // Sort particles by cell so that the neighbours of a cell row are contiguous (DESIGN.md), then
  // list each moving particle's neighbours for the rate evaluations of this and later steps.
  void sort_by_cell() {
    cells_.sort(position_, phase_);
    // The step-start copies and the dummies' flags are free while the sort runs (save_step_start
    // and DummyVisibility write them after it): they serve as the gathers' scratch.
    cells_.reorder(position_, start_position_);
    cells_.reorder(velocity_, start_position_);
    cells_.reorder(ghost_, start_position_);
    cells_.reorder(density_, start_density_);
    cells_.reorder(water_density_, start_density_);
    // Recomputed by every evaluation, but carried by a checkpoint (state()): what a frame taken
    // right after a restore in another order (a split run's) shows.
    cells_.reorder(pressure_, start_density_);
    cells_.reorder(phase_, scratch_phase_);
    cells_.reorder(id_, scratch_index_);
    if (transport_) cells_.reorder(owner_, scratch_index_);
    if (has_soil_) {
      // Carried from step to step: the material, the porosity, the surface state and the last
      // seepage discharge that decides it (pore_water_state.h). The rest is recomputed.
      cells_.reorder(soil_material_, dummy_flags_);
      cells_.reorder(surface_state_, dummy_flags_);
      cells_.reorder(wall_, dummy_flags_);
      cells_.reorder(porosity_, start_density_);
      cells_.reorder(plastic_strain_, start_density_);
      cells_.reorder(seepage_, start_position_);
      cells_.reorder(skeleton_acceleration_, start_position_);
      cells_.reorder(effective_stress_, start_stress_);
      cells_.reorder(free_surface_, dummy_flags_);  // carried by a checkpoint, as the pressure
      cells_.reorder(saturation_, start_density_);
      // The dummies' soil side is recomputed at every evaluation, for the dummy block only (at
      // least one slot, so that a vectorised loop may load it unused).
      const std::size_t dummies = std::max<std::size_t>(cells_.active() - cells_.moving(), 1);
      dummy_pore_pressure_.resize(dummies);
      dummy_stress_.resize(dummies);
      dummy_velocity_.resize(dummies);
    }
    grid_ = cells_.view();
    active_ = cells_.active();
    moving_ = cells_.moving();
    neighbours_.build(grid_, position_, moving_, transport_ ? raw(owner_) : nullptr, transport_ ? process() : 0);
    launch(DummyVisibility<Real, Dim>{grid_, raw(position_), raw(dummy_flags_)}, moving_, active_);
    thrust::copy(Backend::policy(), position_.begin(), position_.end(), listed_position_.begin());
    if (transport_) map_halo();
  }

  // The neighbour lists of the coming steps are those built at the listed positions, in the
  // order the arrays are in (sorted by those positions' cells): sorting again there keeps that
  // order (the sort is stable) and lists the same neighbours; the particles then go back to
  // where they are now. For a restored state and a clone. A state in another order (a split
  // run's, in id order: DistributedEngine::state) is sorted here, its positions with it.
  void list_at_listed_positions() {
    Vector<V> now = position_;
    position_ = listed_position_;
    sort_by_cell();
    cells_.reorder(now, start_position_);
    position_ = now;
  }

  // The cell sort and neighbour lists for the coming evaluations: a clone's first (it has none),
  // then kept while they hold and rebuilt at the current positions when they do not.
  void update_lists() {
    if (!neighbours_.built()) list_at_listed_positions();
    if (lists_hold()) return;
    if (transport_) share_particles(cut_where_balanced());
    sort_by_cell();
  }

  // Whether the cell sort and the neighbour lists of the last build still hold for the coming
  // step: no particle can be farther than half the skin from where it was listed by the half
  // step (neighbour_list.h). Δt <= C0 h / c_w0 (Eq. 40b with μ = 0, 40d), or max_dt.
  bool lists_hold() {
    // Without water nothing bounds the step by a sound speed; only a rigid skeleton is there
    // then (set_up_soil), whose particles do not move: v = 0, and the bound does not matter.
    const double max_dt =
        config_.sound_speed > 0 ? std::max(config_.cfl * config_.h / config_.sound_speed, config_.max_dt) : 0.0;
    const Real half_skin = Real((kListRadius - 1.0) * config_.h);
    const Real drift = thrust::transform_reduce(
        Backend::policy(), thrust::counting_iterator<std::uint32_t>(0),
        thrust::counting_iterator<std::uint32_t>(std::uint32_t(moving_)),
        ListDrift<Real, Dim>{grid_, raw(position_), raw(listed_position_), raw(velocity_), Real(0.5 * max_dt)},
        Real(0), MaximumOf<Real>());
    // Split over processes, all rebuild together: the halos change with the lists.
    if (transport_)
      return transport_->maximum(drift == drift ? double(drift) : std::numeric_limits<double>::infinity()) <
             double(half_skin);
    return drift < half_skin;  // false for NaN
  }

  // Right-hand sides at the current state: boundary values and states first (Eqs. 30-35, 38,
  // 39), then pressures and renormalised density gradients (Eqs. 6, 25), the seepage discharge
  // (Eq. 27b), then the interactions (Eqs. 22-24, 27a, 40) and the soil's local damping
  // (local_damping.h). While relaxing, the pore water is held: no pore-water gradient or seepage
  // pass, and a zero pore-water density rate.
  void evaluate_rates(bool half_step) {
    boundary_values(half_step);
    density_gradients();
    const std::uint32_t water = grid_.water_end;
    if (has_soil_ && !relaxing()) seepage_discharge(), send_pore_water_gradients();
    launch_owned(WaterInteraction<Real, Dim>{view(), grid_, neighbours_.view(), sph_, water_,
                                             has_soil_ ? raw(saturation_) : nullptr},
                 0, water);
    if (!has_soil_) return;
    launch_owned(SoilInteraction<Real, Dim>{view(), soil_view(), grid_, neighbours_.view(), sph_, surface_forcing(),
                                            water_.rho0, relaxing()},
                 water, moving_);
    // While relaxing the free water is damped too: its sloshing would load the soil it rests on.
    launch(LocalDamping<Real, Dim>{view(), raw(unbalanced_acceleration_), Real(local_damping_)},
           relaxing() ? 0u : water, moving_);
  }

  // With soil, the free surface (Eq. 38, at the step's first evaluation) and the pore-water state
  // and surface conditions (Eqs. 6, 39); then the dummy particles' water values (Eqs. 30-35a) and,
  // with soil, their soil side (Eqs. 32a, 32b, 35a), which read the pore-water state. The water
  // side reads the water only, so its place after the soil's states changes nothing. The pore-water
  // state reads its own particle only: a copy computes it from its owner's values as the owner does.
  void boundary_values(bool half_step) {
    if (has_soil_) {
      const std::uint32_t water = grid_.water_end;
      if (!half_step) {
        launch_owned(FreeSurfaceDetection<Real, Dim>{view(), soil_view(), grid_, neighbours_.view(), sph_}, water,
                     moving_);
        send_to_copies([&](auto&& send) { send(free_surface_, soil_halo_); });
      }
      // Held pore water keeps its surface states too.
      launch(PoreWaterState<Real, Dim>{view(), soil_view(), surface_forcing(), water_.rho0, !half_step && !relaxing()},
             water, moving_);
    }
    launch_owned(SolidBoundaryWater<Real, Dim>{view(), grid_, sph_, water_, raw(dummy_flags_), half_step}, moving_,
                 active_);
    if (has_soil_)
      launch_owned(SolidBoundarySoil<Real, Dim>{view(), soil_view(), grid_, sph_, raw(dummy_flags_)}, moving_, active_);
    send_dummy_values();
  }

  // The seepage discharge (Eq. 27b), for the frames and the surface states (pore_water_state.h).
  void seepage_discharge() {
    launch_owned(SeepageDischarge<Real, Dim>{view(), soil_view(), sph_, surface_forcing()}, grid_.water_end, moving_);
  }

  // Water pressure (Eq. 6) and the renormalised gradients of the water and pore-water densities
  // (Eq. 25), each over its own particles. The pore water's reads the free water's pressure.
  void density_gradients() {
    const std::uint32_t water = grid_.water_end;
    launch_owned(RenormalisedDensityGradient<Real, Dim>{view(), grid_, neighbours_.view(), sph_, water_}, 0, water);
    send_to_copies([&](auto&& send) { send(pressure_, water_halo_), send(water_density_gradient_, water_halo_); });
    if (has_soil_ && !relaxing()) pore_water_gradients();
  }

  // The soil's renormalised gradients of the pore-water density and pressure (Eq. 25).
  void pore_water_gradients() {
    launch_owned(RenormalisedDensityGradient<Real, Dim, true>{view(), grid_, neighbours_.view(), sph_, water_,
                                                              soil_view(), water_.rho0},
                 grid_.water_end, moving_);
  }

  SoilView<Real, Dim> soil_view() {
    return {raw(soil_materials_), raw(soil_material_), raw(porosity_), raw(saturation_), raw(conductivity_),
            raw(seepage_),
            raw(dummy_pore_pressure_), raw(dummy_stress_), raw(dummy_velocity_),
            raw(free_surface_), raw(surface_state_), raw(effective_stress_), raw(velocity_gradient_),
            raw(porosity_rate_), raw(plastic_strain_), raw(skeleton_acceleration_), raw(wall_),
            raw(wall_pore_pressure_), raw(pore_water_inflow_)};
  }

  // Adds what crossed the soil's boundaries over the step (pore_water_account.h) at the rates of
  // the half step, those the corrector advances the pore water with: block sums in parallel, then
  // the blocks in order, the same bits for any number of threads.
  void account_pore_water() {
    if (!has_soil_ || relaxing()) return;
    using BlockSum = PoreWaterInflowBlockSum<Real>;
    const std::uint32_t begin = grid_.water_end, end = std::uint32_t(moving_);
    const std::uint32_t blocks = (end - begin + BlockSum::kBlock - 1) / BlockSum::kBlock;
    if (transport_)  // the copies of other processes' particles: their owners account for them
      thrust::replace_if(Backend::policy(), pore_water_inflow_.begin() + begin, pore_water_inflow_.begin() + end,
                         owner_.begin() + begin, OwnedElsewhere{process()},
                         PoreWaterInflow<Real>{Real(0), Real(0), Real(0)});
    pore_water_blocks_.resize(std::max<std::uint32_t>(blocks, 1));
    thrust::transform(Backend::policy(), thrust::counting_iterator<std::uint32_t>(0),
                      thrust::counting_iterator<std::uint32_t>(blocks), pore_water_blocks_.begin(),
                      BlockSum{raw(pore_water_inflow_), begin, end});
    launch(AddPoreWaterBlocks<Real>{raw(pore_water_blocks_), blocks, dt_, raw(pore_water_totals_)}, 0, 1);
  }

  // σ', κ and φ at a Symplectic stage (soil_stress_update.h), from the step's start.
  void update_soil_stress(double increment) {
    if (!has_soil_) return;
    launch(SoilStressUpdate<Real, Dim>{view(), soil_view(), raw(start_stress_), raw(start_plastic_strain_),
                                       raw(start_porosity_), Real(increment)},
           grid_.water_end, moving_);
  }
  // The geostatic stage (set_relaxation): the soil takes local damping and its pore water is held.
  bool relaxing() const { return local_damping_ > 0; }

  SurfaceForcing<Real, Dim> surface_forcing() const { return SurfaceForcing<Real, Dim>::from(forcing_); }

  // The soil arrays, only for a case with soil particles.
  // A process's share of a split run has the soil arrays when the run has soil, whether or not
  // its share holds any, so that every process lists the same arrays (particle_rows.h).
  void set_up_soil(const HostParticles& host, const PartitionSetup* partition) {
    has_soil_ = partition ? partition->soil : host.count(Phase::soil) > 0;
    if (!has_soil_) return;
    const std::size_t n = host.size();
    // The initial positions by id, on the host, for the displacement.
    initial_position_.assign(3 * n, 0.0);
    const int axis3[3] = {0, Dim == 2 ? -1 : 1, Dim == 2 ? 1 : 2};
    for (std::size_t i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) initial_position_[3 * i + c] = axis3[c] < 0 ? 0.0 : host.position[i * Dim + axis3[c]];
    }
    if (partition) initial_position_ = partition->initial_position;
    std::vector<std::uint8_t> material(n, 0);
    std::vector<Real> porosity(n, Real(0));
    std::vector<Voigt<Real>> stress(n, Voigt<Real>::Zero());
    for (std::size_t i = 0; i < n; ++i) {
      if (host.phase[i] != Phase::soil) continue;
      if (host.effective_stress.size() == 6 * n)
        for (int c = 0; c < 6; ++c) stress[i](c) = Real(host.effective_stress[6 * i + c]);
      if (i >= host.soil_material.size() || host.soil_material[i] >= config_.soils.size())
        throw std::invalid_argument("soil particle " + std::to_string(i) + " has no soil material");
      material[i] = host.soil_material[i];
      porosity[i] = Real(host.porosity[i]);
    }
    // The drained walls: per particle the 1-based index of its wall's entry, 0 for the rest.
    if (config_.drained_walls.size() > 255) throw std::invalid_argument("a case has at most 255 drained walls");
    std::vector<std::uint8_t> wall(n, 0);
    std::vector<Real> wall_pressure(std::max<std::size_t>(config_.drained_walls.size(), 1), Real(0));
    for (std::size_t k = 0; k < config_.drained_walls.size(); ++k) {
      wall_pressure[k] = Real(config_.drained_walls[k].pore_pressure);
      for (std::size_t i = 0; i < n; ++i)
        if (host.phase[i] == Phase::boundary && i < host.body.size() && host.body[i] == config_.drained_walls[k].body)
          wall[i] = std::uint8_t(k + 1);
    }
    wall_ = wall;
    wall_pore_pressure_ = wall_pressure;
    for (std::size_t k = 0; k < config_.soils.size(); ++k)
      if (!(config_.soils[k].reference_porosity > 0 && config_.soils[k].reference_porosity < 1))
        throw std::invalid_argument("soil material " + std::to_string(k) +
                                    " has no reference porosity in (0, 1) for its retention curve");
    soil_materials_ = config_.soils;
    soil_material_ = material;
    porosity_ = porosity;
    effective_stress_ = stress;
    velocity_gradient_.assign(n, Mat<Real, Dim>::Zero());
    porosity_rate_.assign(n, Real(0));
    plastic_strain_.assign(n, Real(0));
    start_stress_.assign(n, Voigt<Real>::Zero());
    start_plastic_strain_.assign(n, Real(0));
    start_porosity_.assign(n, Real(0));
    saturation_.assign(n, Real(0));
    conductivity_.assign(n, Real(0));
    seepage_.assign(n, V::Zero());
    skeleton_acceleration_.assign(n, V::Zero());  // at rest
    unbalanced_acceleration_.assign(n, Real(0));
    pore_water_inflow_.assign(n, PoreWaterInflow<Real>{Real(0), Real(0), Real(0)});
    free_surface_.assign(n, 0);
    surface_state_.assign(n, std::uint8_t(SurfaceState::flux));
  }

  double next_time_step() {
    Real limit = thrust::reduce(Backend::policy(), step_limit_.begin(), step_limit_.begin() + moving_,
                                std::numeric_limits<Real>::max(), MinimumOf<Real>());
    if (transport_) {  // the owned particles of every process: one step for the whole run
      limit = thrust::transform_reduce(Backend::policy(), thrust::counting_iterator<std::uint32_t>(0),
                                       thrust::counting_iterator<std::uint32_t>(std::uint32_t(moving_)),
                                       OwnedStepLimit<Real>{raw(step_limit_), raw(owner_), process()},
                                       std::numeric_limits<Real>::max(), MinimumOf<Real>());
      limit = Real(transport_->minimum(double(limit)));
    }
    if (limit < Real(0))
      throw SimulationFailure("the state holds NaN or infinity at t = " + number(time_) + " s, step " +
                              std::to_string(steps_) + ": a rate of change is not finite at " +
                              describe_particle(first_particle_where([](Real l) { return l < Real(0); })));
    double dt = config_.cfl * double(limit);
    // No particle limits the step (no water, only dry soil): max_dt, or no step at all.
    if (limit >= std::numeric_limits<Real>::max()) dt = config_.max_dt > 0 ? config_.max_dt : 0.0;
    else if (config_.max_dt > 0 && dt > config_.max_dt) dt = config_.max_dt;
    if (dt < config_.min_dt)
      throw SimulationFailure("time step " + number(dt) + " s fell below min_dt " +
                              number(config_.min_dt) + " s at t = " + number(time_) + " s, step " +
                              std::to_string(steps_) + ", set by " +
                              describe_particle(first_particle_where([limit](Real l) { return l == limit; })));
    return dt;
  }

  // The failure's diagnosis, read back to the host only when a run fails: the first moving
  // particle whose step limit meets `condition`, or moving_ for none.
  template <typename Condition>
  std::size_t first_particle_where(Condition condition) const {
    const thrust::host_vector<Real> limits(step_limit_.begin(), step_limit_.begin() + moving_);
    for (std::size_t i = 0; i < limits.size(); ++i)
      if (condition(limits[i])) return i;
    return moving_;
  }
  static std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", v);
    return text;
  }
  std::string describe_particle(std::size_t i) const {
    if (i >= moving_) return "no particle found";
    static const char* const kPhases[] = {"water", "soil", "boundary"};
    const V x = position_[i], v = velocity_[i];
    const Phase phase = phase_[i];
    std::string where = "(";
    for (int a = 0; a < Dim; ++a) where += (a ? ", " : "") + number(double(x[a]));
    where += ") m";
    return std::string(kPhases[std::size_t(phase) < 3 ? std::size_t(phase) : 2]) + " particle id " +
           std::to_string(std::uint32_t(id_[i])) + " at " + where + ", speed " + number(double(v.norm())) +
           " m/s, density " + number(double(water_density_[i])) + " kg/m³";
  }

  // A run split over processes (partition.h). Each process steps its share: the particles it
  // owns, copies of the other processes' particles within its halo, and the dummies there. The
  // copies take their owners' values at the half step and at the end of every step (refresh_halo),
  // and the results of each pass that reads neighbours as a later pass needs them (the free
  // surface, the dummies' values, the gradients: send_to_copies), so that each owned particle's
  // rates are those of the whole run; the copies' own passes over neighbours are not computed
  // (launch_owned) and what they integrate is replaced. The halo is one list radius and the skin
  // (DistributedEngine's halo_width).
  std::uint32_t process() const { return std::uint32_t(transport_->process()); }

  void refuse_when_partitioned(const char* what) const {
    if (transport_)
      throw std::invalid_argument(std::string(what) + " of a run split over processes is not supported yet (issue 17)");
  }

  // Every array with one value per particle, in the same order on every process: what a
  // particle that changes process takes along and what a copy starts from at a rebuild
  // (share_particles). The dummies' soil-side arrays and the lists are each process's own.
  template <typename F>
  void for_each_particle_array(F&& f) {
    f(position_), f(velocity_), f(ghost_), f(acceleration_), f(water_density_gradient_);
    f(start_position_), f(start_velocity_), f(listed_position_);
    f(density_), f(water_density_), f(pressure_), f(density_rate_), f(water_density_rate_), f(step_limit_);
    f(start_density_), f(start_water_density_), f(phase_), f(id_), f(owner_), f(dummy_flags_);
    if (!has_soil_) return;
    f(soil_material_), f(free_surface_), f(surface_state_), f(wall_), f(porosity_), f(saturation_);
    f(conductivity_), f(seepage_), f(skeleton_acceleration_), f(effective_stress_), f(start_stress_);
    f(velocity_gradient_), f(porosity_rate_), f(plastic_strain_), f(start_plastic_strain_), f(start_porosity_);
    f(unbalanced_acceleration_), f(pore_water_inflow_);
  }

  // A message of whole particles: their count, then every array's values at `rows`.
  std::vector<char> pack_particles(const std::vector<std::uint32_t>& rows) {
    std::vector<char> bytes(sizeof(std::uint64_t));
    const std::uint64_t count = rows.size();
    std::memcpy(bytes.data(), &count, sizeof count);
    const Vector<std::uint32_t> on_backend(rows.begin(), rows.end());
    for_each_particle_array([&](auto& array) { ParticleRows<Backend>::pack(array, on_backend, bytes); });
    return bytes;
  }

  // Keeps the particles at `kept` (in that order) and appends those of the messages.
  void keep_and_receive(const std::vector<std::uint32_t>& kept, const std::vector<std::vector<char>>& messages) {
    std::vector<std::size_t> offset(messages.size(), sizeof(std::uint64_t)), count(messages.size(), 0);
    for (std::size_t m = 0; m < messages.size(); ++m) {
      if (messages[m].empty()) continue;
      std::uint64_t c = 0;
      std::memcpy(&c, messages[m].data(), sizeof c);
      count[m] = std::size_t(c);
    }
    const Vector<std::uint32_t> on_backend(kept.begin(), kept.end());
    for_each_particle_array([&](auto& array) {
      using T = typename std::decay_t<decltype(array)>::value_type;
      std::vector<T> received;
      for (std::size_t m = 0; m < messages.size(); ++m) {
        if (messages[m].empty()) continue;
        const std::vector<T> part = ParticleRows<Backend>::template read<T>(messages[m], offset[m], count[m]);
        received.insert(received.end(), part.begin(), part.end());
      }
      ParticleRows<Backend>::keep_and_append(array, on_backend, received);
    });
  }

  // At a list rebuild, before the sort: an owned particle that has crossed into another slab goes
  // to that slab's process; then the copies are dropped and each process sends every other the
  // particles it owns within that process's halo. Dummies never move and stay where they are,
  // unless the slabs were `cut_again`: then each process sends the dummies of its old slab to
  // those whose new halo holds them and keeps them where its own does; the rest it drops. The
  // particles that left the domain stay (their owner counts them lost).
  void share_particles(bool cut_again) {
    const std::uint32_t me = process();
    const int processes = transport_->processes();
    const GridView<Real, Dim> domain = cells_.view();
    auto moving_inside = [&](const thrust::host_vector<V>& x, const thrust::host_vector<Phase>& phase, std::size_t k) {
      return phase[k] != Phase::boundary && domain.contains(x[k]);
    };
    {
      const thrust::host_vector<V> position(position_.begin(), position_.end());
      const thrust::host_vector<V> ghost(ghost_.begin(), ghost_.end());
      const thrust::host_vector<Phase> phase(phase_.begin(), phase_.end());
      thrust::host_vector<std::uint32_t> owner(owner_.begin(), owner_.end());
      std::vector<std::uint32_t> kept;
      std::vector<std::vector<std::uint32_t>> leaving(processes);
      for (std::uint32_t k = 0; k < phase.size(); ++k) {
        if (phase[k] == Phase::boundary && cut_again) {
          if (owner[k] != me) continue;  // its old owner sends it where it is needed
          const double x = double(position[k][slabs_.axis]), ghost_x = double(ghost[k][slabs_.axis]);
          owner[k] = std::uint32_t(slabs_.owner_of(ghost_x));
          for (int r = 0; r < processes; ++r)
            if (r != int(me) && slabs_.holds_dummy(r, x, ghost_x)) leaving[r].push_back(k);
          if (slabs_.holds_dummy(int(me), x, ghost_x)) kept.push_back(k);
          continue;
        }
        if (phase[k] != Phase::boundary && owner[k] != me) continue;  // a copy
        const int to = moving_inside(position, phase, k) ? slabs_.owner_of(double(position[k][slabs_.axis])) : int(me);
        if (to == int(me)) {
          kept.push_back(k);
        } else {
          leaving[to].push_back(k);
          owner[k] = std::uint32_t(to);
        }
      }
      owner_ = owner;
      std::vector<std::vector<char>> send(processes);
      for (int r = 0; r < processes; ++r)
        if (!leaving[r].empty()) send[r] = pack_particles(leaving[r]);
      keep_and_receive(kept, transport_->exchange(send));
    }
    if (cut_again) {  // the dummies received: their new owners
      const thrust::host_vector<V> ghost(ghost_.begin(), ghost_.end());
      const thrust::host_vector<Phase> phase(phase_.begin(), phase_.end());
      thrust::host_vector<std::uint32_t> owner(owner_.begin(), owner_.end());
      for (std::size_t k = 0; k < phase.size(); ++k)
        if (phase[k] == Phase::boundary) owner[k] = std::uint32_t(slabs_.owner_of(double(ghost[k][slabs_.axis])));
      owner_ = owner;
    }
    const thrust::host_vector<V> position(position_.begin(), position_.end());
    const thrust::host_vector<Phase> phase(phase_.begin(), phase_.end());
    const thrust::host_vector<std::uint32_t> owner(owner_.begin(), owner_.end());
    std::vector<std::vector<std::uint32_t>> copies(processes);
    for (std::uint32_t k = 0; k < phase.size(); ++k) {
      if (owner[k] != me || !moving_inside(position, phase, k)) continue;
      for (int r = 0; r < processes; ++r)
        if (r != int(me) && slabs_.distance_to(r, double(position[k][slabs_.axis])) < slabs_.halo) copies[r].push_back(k);
    }
    std::vector<std::vector<char>> send(processes);
    for (int r = 0; r < processes; ++r)
      if (!copies[r].empty()) send[r] = pack_particles(copies[r]);
    std::vector<std::uint32_t> all(phase.size());
    for (std::uint32_t k = 0; k < all.size(); ++k) all[k] = k;
    keep_and_receive(all, transport_->exchange(send));
  }

  // Rows of one kind of copy (moving particles, dummies): per process, the rows of this
  // process's own particles that it sends there and the rows of its copies that it fills from
  // there, both in the order of the particles' ids. `first` is subtracted from every row, for the
  // arrays of the dummy block (dummy_pore_pressure_ and the like).
  struct HaloRows {
    std::vector<Vector<std::uint32_t>> send, receive;
    static HaloRows of(const std::vector<std::vector<std::uint32_t>>& send,
                       const std::vector<std::vector<std::uint32_t>>& receive, std::uint32_t first = 0) {
      HaloRows rows;
      for (std::size_t r = 0; r < send.size(); ++r) {
        std::vector<std::uint32_t> out(send[r]), in(receive[r]);
        for (auto& k : out) k -= first;
        for (auto& k : in) k -= first;
        rows.send.emplace_back(out.begin(), out.end());
        rows.receive.emplace_back(in.begin(), in.end());
      }
      return rows;
    }
  };

  // After the sort: the rows that send_to_copies sends to each process and those it fills from
  // each. Process r holds copies of this process's moving particles that were within r's halo at
  // share_particles (the sort moved none) and of the dummies it owns within that halo
  // (Slabs::holds_dummy). The ids are exchanged once per rebuild to check that both sides agree.
  void map_halo() {
    const std::uint32_t me = process();
    const int processes = transport_->processes();
    const thrust::host_vector<V> position(position_.begin(), position_.begin() + active_);
    const thrust::host_vector<std::uint32_t> owner(owner_.begin(), owner_.begin() + active_);
    const thrust::host_vector<std::uint32_t> id(id_.begin(), id_.begin() + active_);
    std::vector<std::vector<std::uint32_t>> send(processes), receive(processes);
    std::vector<std::vector<std::uint32_t>> dummy_send(processes), dummy_receive(processes);
    for (std::uint32_t k = 0; k < active_; ++k) {
      const bool dummy = k >= moving_;
      if (owner[k] != me) {
        (dummy ? dummy_receive : receive)[owner[k]].push_back(k);
        continue;
      }
      for (int r = 0; r < processes; ++r)
        if (r != int(me) && slabs_.distance_to(r, double(position[k][slabs_.axis])) < slabs_.halo)
          (dummy ? dummy_send : send)[r].push_back(k);
    }
    agree_on_copies(send, receive, id);
    agree_on_copies(dummy_send, dummy_receive, id);
    moving_halo_ = HaloRows::of(send, receive);
    auto of_phase = [&](const std::vector<std::vector<std::uint32_t>>& rows, bool water) {
      std::vector<std::vector<std::uint32_t>> picked(processes);
      for (int r = 0; r < processes; ++r)
        for (std::uint32_t k : rows[r])
          if ((k < grid_.water_end) == water) picked[r].push_back(k);
      return picked;
    };
    water_halo_ = HaloRows::of(of_phase(send, true), of_phase(receive, true));
    soil_halo_ = HaloRows::of(of_phase(send, false), of_phase(receive, false));
    dummy_halo_ = HaloRows::of(dummy_send, dummy_receive);
    dummy_block_halo_ = HaloRows::of(dummy_send, dummy_receive, std::uint32_t(moving_));
    gather_listed_dummies();
    measure_balance();
  }

  // Orders each process's rows by id and checks that every process fills from this one the copies
  // this one sends it.
  void agree_on_copies(std::vector<std::vector<std::uint32_t>>& send, std::vector<std::vector<std::uint32_t>>& receive,
                       const thrust::host_vector<std::uint32_t>& id) {
    const int processes = transport_->processes();
    auto by_id = [&](std::uint32_t a, std::uint32_t b) { return id[a] < id[b]; };
    std::vector<std::vector<char>> sent_ids(processes);
    for (int r = 0; r < processes; ++r) {
      std::sort(send[r].begin(), send[r].end(), by_id);
      std::sort(receive[r].begin(), receive[r].end(), by_id);
      for (std::uint32_t k : send[r]) {
        const char* bytes = reinterpret_cast<const char*>(&id[k]);
        sent_ids[r].insert(sent_ids[r].end(), bytes, bytes + sizeof(std::uint32_t));
      }
    }
    const auto received_ids = transport_->exchange(sent_ids);
    for (int r = 0; r < processes; ++r) {
      bool same = received_ids[r].size() == receive[r].size() * sizeof(std::uint32_t);
      for (std::size_t m = 0; same && m < receive[r].size(); ++m) {
        std::uint32_t sent = 0;
        std::memcpy(&sent, received_ids[r].data() + m * sizeof sent, sizeof sent);
        same = sent == id[receive[r][m]];
      }
      if (!same)
        throw std::logic_error("process " + std::to_string(process()) + " holds other copies of process " +
                               std::to_string(r) + "'s particles than that process refreshes");
    }
  }

  // A dummy is listed (kListed, DummyVisibility) where some moving particle of the whole run lists
  // it; that particle's owner holds the dummy, which lies within one list radius of its slab. So
  // each process sends its flags of the dummies it holds to their owners, which add them up: the
  // owner computes the dummy's values (SolidBoundaryWater, SolidBoundarySoil) where one process
  // would, and a frame shows the same.
  void gather_listed_dummies() {
    const int processes = transport_->processes();
    std::vector<std::vector<char>> send(processes);
    for (int r = 0; r < processes; ++r)
      if (!dummy_halo_.receive[r].empty()) ParticleRows<Backend>::pack(dummy_flags_, dummy_halo_.receive[r], send[r]);
    const auto received = transport_->exchange(send);
    thrust::host_vector<std::uint8_t> flags(dummy_flags_.begin(), dummy_flags_.end());
    for (int r = 0; r < processes; ++r) {
      const thrust::host_vector<std::uint32_t> rows(dummy_halo_.send[r].begin(), dummy_halo_.send[r].end());
      std::size_t offset = 0;
      const auto listed = ParticleRows<Backend>::template read<std::uint8_t>(received[r], offset, rows.size());
      for (std::size_t m = 0; m < rows.size(); ++m) flags[rows[m]] |= std::uint8_t(listed[m] & kListed);
    }
    dummy_flags_ = flags;
  }

  // The work of every process at this rebuild (LoadBalance, partition.h): the list entries of the
  // particles it owns, summed on the backend.
  void measure_balance() {
    const double work = double(thrust::transform_reduce(
        Backend::policy(), thrust::counting_iterator<std::uint32_t>(0),
        thrust::counting_iterator<std::uint32_t>(std::uint32_t(moving_)),
        OwnedTerm<ListLength, std::uint64_t>{ListLength{raw(neighbours_.counts())}, raw(owner_), process(), 0},
        std::uint64_t(0), thrust::plus<std::uint64_t>()));
    const double largest = transport_->maximum(work), total = transport_->sum(work);
    const double imbalance = total > 0 ? largest / (total / double(transport_->processes())) : 1.0;
    balance_.rebuilds.push_back({steps_, time_, imbalance, cut_again_});
    cut_again_ = false;
  }

  // At a rebuild, before share_particles: where the last rebuild's imbalance exceeds
  // kRepartitionImbalance, new cuts that even out the work of its lists (balanced_cuts, from the
  // histogram of every process's owned work along the axis at the current positions).
  bool cut_where_balanced() {
    if (balance_.last() <= kRepartitionImbalance) return false;
    constexpr std::size_t bins = 4096;
    const thrust::host_vector<V> position(position_.begin(), position_.begin() + moving_);
    const thrust::host_vector<std::uint32_t> owner(owner_.begin(), owner_.begin() + moving_);
    const thrust::host_vector<std::uint32_t> count(neighbours_.counts().begin(), neighbours_.counts().end());
    const GridView<Real, Dim> domain = cells_.view();
    std::vector<std::uint32_t> owned;
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (std::uint32_t k = 0; k < moving_; ++k) {
      if (owner[k] != process() || !domain.contains(position[k])) continue;
      owned.push_back(k);
      low = std::min(low, double(position[k][slabs_.axis])), high = std::max(high, double(position[k][slabs_.axis]));
    }
    low = transport_->minimum(low), high = transport_->maximum(high);
    if (!(high > low)) return false;
    std::vector<double> histogram(bins, 0.0);
    for (std::uint32_t k : owned) {
      const double x = (double(position[k][slabs_.axis]) - low) / (high - low) * double(bins);
      histogram[std::min(bins - 1, std::size_t(std::max(0.0, x)))] += double(count[k]);
    }
    std::vector<char> message(bins * sizeof(double));
    std::memcpy(message.data(), histogram.data(), message.size());
    const auto received = transport_->exchange(std::vector<std::vector<char>>(transport_->processes(), message));
    std::vector<double> whole(bins, 0.0), part(bins);
    for (const auto& in : received) {  // in the order of the processes, the same sums on each
      std::memcpy(part.data(), in.data(), message.size());
      for (std::size_t b = 0; b < bins; ++b) whole[b] += part[b];
    }
    slabs_.cut = balanced_cuts(whole, low, high, transport_->processes());
    return cut_again_ = true;
  }

  // Sends the owners' values of some arrays to their copies: for_each_array(f) calls
  // f(array, rows) for each array with the HaloRows of its copies. Every process makes the same
  // calls in the same order.
  template <typename ForEach>
  void send_to_copies(ForEach&& for_each_array) {
    if (!transport_) return;
    const int processes = transport_->processes();
    std::vector<std::vector<char>> send(processes);
    for (int r = 0; r < processes; ++r)
      for_each_array([&](auto& array, const HaloRows& rows) {
        if (!rows.send[r].empty()) ParticleRows<Backend>::pack(array, rows.send[r], send[r]);
      });
    const auto received = transport_->exchange(send);
    for (int r = 0; r < processes; ++r) {
      std::size_t offset = 0;
      for_each_array([&](auto& array, const HaloRows& rows) {
        if (!rows.receive[r].empty()) ParticleRows<Backend>::unpack(array, rows.receive[r], received[r], offset);
      });
      if (offset != received[r].size())
        throw std::logic_error("process " + std::to_string(r) + " sent more than the copies it refreshes");
    }
  }

  // At the half step and at the end of a step (the owners have reached the same point of the same
  // step), every copy of a moving particle takes its owner's values of what changes in a step and
  // is read of it: what the passes read of a neighbour (its state; its pressure, gradients, free
  // surface and discharge are also sent as they are computed), and what a soil copy's own
  // pore-water state is computed from (PoreWaterState: the pore water, porosity, surface state,
  // free surface and last discharge). A copy's other arrays are constant between rebuilds (phase,
  // id, owner, material, listed position: share_particles sends them whole) or the results of
  // passes whose values on a copy nothing reads before the next refresh (its rates and step-start
  // values, which integrate it).
  void refresh_halo() {
    send_to_copies([&](auto&& send) {
      send(position_, moving_halo_), send(velocity_, moving_halo_), send(density_, moving_halo_);
      send(water_density_, moving_halo_);
      if (!has_soil_) return;
      send(porosity_, soil_halo_), send(saturation_, soil_halo_), send(effective_stress_, soil_halo_);
      send(surface_state_, soil_halo_), send(free_surface_, soil_halo_), send(seepage_, soil_halo_);
      send(skeleton_acceleration_, soil_halo_);
    });
  }

  // The dummies' values, computed by their owners (boundary_values), for the passes that read them.
  void send_dummy_values() {
    send_to_copies([&](auto&& send) {
      send(water_density_, dummy_halo_), send(pressure_, dummy_halo_), send(velocity_, dummy_halo_);
      if (!has_soil_) return;
      send(dummy_pore_pressure_, dummy_block_halo_), send(dummy_stress_, dummy_block_halo_);
      send(dummy_velocity_, dummy_block_halo_);
    });
  }

  // The soil's renormalised gradients (Eq. 25), seepage discharge and conductivity (Eq. 27b), for
  // the interactions.
  void send_pore_water_gradients() {
    send_to_copies([&](auto&& send) {
      send(water_density_gradient_, soil_halo_), send(seepage_, soil_halo_), send(conductivity_, soil_halo_);
    });
  }

  void save_step_start() {
    thrust::copy(Backend::policy(), position_.begin(), position_.end(), start_position_.begin());
    thrust::copy(Backend::policy(), velocity_.begin(), velocity_.end(), start_velocity_.begin());
    thrust::copy(Backend::policy(), density_.begin(), density_.end(), start_density_.begin());
    thrust::copy(Backend::policy(), water_density_.begin(), water_density_.end(), start_water_density_.begin());
    if (!has_soil_) return;
    thrust::copy(Backend::policy(), effective_stress_.begin(), effective_stress_.end(), start_stress_.begin());
    thrust::copy(Backend::policy(), plastic_strain_.begin(), plastic_strain_.end(), start_plastic_strain_.begin());
    thrust::copy(Backend::policy(), porosity_.begin(), porosity_.end(), start_porosity_.begin());
  }

  EngineConfig config_;
  HydraulicForcing forcing_;
  SphConstants<Real, Dim> sph_{};
  WaterConstants<Real> water_{};
  CellSort<Real, Dim, Backend> cells_;
  NeighbourList<Real, Dim, Backend> neighbours_;
  GridView<Real, Dim> grid_{};
  double time_ = 0;
  double dt_ = 0;
  std::uint64_t steps_ = 0;
  std::size_t active_ = 0;
  std::size_t moving_ = 0;

  Vector<V> position_, velocity_, ghost_, acceleration_, water_density_gradient_, start_position_, start_velocity_,
      listed_position_;
  Vector<Real> density_, water_density_, pressure_, density_rate_, water_density_rate_, step_limit_, start_density_,
      start_water_density_;
  Vector<Phase> phase_, scratch_phase_;
  Vector<std::uint8_t> dummy_flags_;
  bool has_soil_ = false;
  Vector<SoilMaterial> soil_materials_;
  Vector<std::uint8_t> soil_material_, free_surface_, surface_state_, wall_;
  Vector<Real> porosity_, saturation_, conductivity_, dummy_pore_pressure_, wall_pore_pressure_;
  Vector<V> seepage_, skeleton_acceleration_, dummy_velocity_;
  Vector<Voigt<Real>> effective_stress_, start_stress_, dummy_stress_;
  Vector<Mat<Real, Dim>> velocity_gradient_;
  Vector<Real> porosity_rate_, plastic_strain_, start_plastic_strain_, start_porosity_;
  // α of the local damping, 0 outside the geostatic stage; not in the checkpoint (state()): the
  // stage orchestrator sets it again after a restore().
  double local_damping_ = 0;
  Vector<Real> unbalanced_acceleration_;  // per particle: |a| of the last evaluation before damping (soil, and water while relaxing)
  Vector<PoreWaterInflow<Real>> pore_water_inflow_;  // per soil particle, of the last evaluation
  Vector<PoreWaterInflow<Real>> pore_water_blocks_;  // their block sums (account_pore_water)
  Vector<double> pore_water_totals_ = std::vector<double>(3, 0.0);  // rain, walls, surface since the clock's start
  std::vector<double> initial_position_;  // host, by id: N × 3
  Vector<std::uint32_t> id_, scratch_index_;
  Transport* transport_ = nullptr;  // a run split over processes (partition.h); null for one process
  Slabs slabs_;
  Vector<std::uint32_t> owner_;     // with a transport: per particle, the process that owns it
  // With a transport: the copies' rows (map_halo), of all moving particles, the water's, the soil's, the dummies'.
  HaloRows moving_halo_, water_halo_, soil_halo_, dummy_halo_, dummy_block_halo_;
  LoadBalance balance_;             // with a transport: measured at every rebuild (measure_balance)
  bool cut_again_ = false;          // the slabs were cut again for the coming rebuild (cut_where_balanced)
};

// The engine on one backend, in the precision and dimension the configuration asks for.
// With a partition: a process's share of a split run (partition.h).
template <typename Backend>
std::unique_ptr<Engine> make_simulation(const EngineConfig& config, const HostParticles& particles,
                                        const PartitionSetup* partition = nullptr) {
  const bool single = config.precision == Precision::single_precision;
  if (config.dimensions == 2)
    return single ? std::unique_ptr<Engine>(std::make_unique<Simulation<float, 2, Backend>>(config, particles, partition))
                  : std::make_unique<Simulation<double, 2, Backend>>(config, particles, partition);
  if (config.dimensions == 3)
    return single ? std::unique_ptr<Engine>(std::make_unique<Simulation<float, 3, Backend>>(config, particles, partition))
                  : std::make_unique<Simulation<double, 3, Backend>>(config, particles, partition);
  throw std::invalid_argument("dimensions must be 2 or 3");
}

}  // namespace cascade
