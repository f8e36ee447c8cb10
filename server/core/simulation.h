// Simulation<Real, Dim, Backend>: particle arrays on one backend and the step that calls the
// physical terms in order. Included only by the backend files (engine_cpu.cpp, engine_cuda.cu).
#pragma once

#include <thrust/copy.h>
#include <thrust/for_each.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/reduce.h>
#include <thrust/transform_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "server/core/backend.h"
#include "server/core/engine.h"
#include "server/core/cell_sort.h"
#include "server/core/neighbour_list.h"
#include "server/core/particle_view.h"
#include "server/physics/renormalised_gradient.h"
#include "server/physics/solid_boundary.h"
#include "server/physics/symplectic_verlet.h"
#include "server/physics/time_step.h"
#include "server/physics/water_interaction.h"

namespace cascade {

template <typename Real, int Dim, typename Backend>
class Simulation final : public Engine {
  template <typename T>
  using Vector = typename Backend::template Vector<T>;
  using V = Vec<Real, Dim>;

 public:
  Simulation(const EngineConfig& config, const HostParticles& host)
      : config_(config),
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
      id[i] = std::uint32_t(i);
    }
    position_ = position;
    velocity_ = velocity;
    ghost_ = ghost;
    water_density_ = water_density;
    density_ = std::vector<Real>(n, Real(config.water_density));  // one initial numerical density (Section 3.2)
    phase_ = host.phase;
    id_ = id;
    for (auto* v : {&pressure_, &density_rate_, &water_density_rate_, &step_limit_, &start_density_, &start_water_density_})
      v->resize(n);
    for (auto* v : {&acceleration_, &water_density_gradient_, &start_position_, &start_velocity_, &listed_position_})
      v->resize(n);
    scratch_vec_.resize(n);
    ghost_wet_.resize(n);
    scratch_real_.resize(n);
    scratch_phase_.resize(n);
    scratch_index_.resize(n);

    sph_.h = Real(config.h);
    sph_.kernel = WendlandC2<Real, Dim>(Real(config.h));
    sph_.eta2 = Real(0.01 * config.h * config.h);
    sph_.mass = Real(config.water_density * std::pow(config.dp, Dim));
    for (int a = 0; a < Dim; ++a) sph_.gravity[a] = Real(config.gravity[a]);
    water_ = WaterConstants<Real>{Real(config.water_density), Real(config.sound_speed), Real(config.delta),
                                  Real(config.viscosity_alpha)};
    // Pressures of the initial state (Eq. 6 and the boundary extrapolation), so that frame 0 has them.
    sort_by_cell();
    launch(SolidBoundaryWater<Real, Dim>{view(), grid_, sph_, water_, raw(ghost_wet_), false}, moving_, active_);
    launch(RenormalisedDensityGradient<Real, Dim>{view(), grid_, neighbours_.view(), sph_, water_}, 0, moving_);
  }

  void step() override {
    if (!lists_hold()) sort_by_cell();
    evaluate_rates(false);
    dt_ = next_time_step();
    save_step_start();
    launch(SymplecticPredictor<Real, Dim>{view(), start_view(), grid_, Real(dt_)}, 0, moving_);
    evaluate_rates(true);
    launch(SymplecticCorrector<Real, Dim>{view(), start_view(), grid_, Real(dt_)}, 0, moving_);
    time_ += dt_;
    ++steps_;
  }

  double time() const override { return time_; }
  std::uint64_t step_count() const override { return steps_; }
  double last_dt() const override { return dt_; }
  std::size_t particle_count() const override { return phase_.size(); }
  std::size_t lost_particles() const override { return phase_.size() - active_; }
  const char* device_name() const override { return Backend::name; }

  std::size_t device_bytes() const override {
    std::size_t bytes = 0;
    auto add = [&](const auto& v) { bytes += v.capacity() * sizeof(typename std::decay_t<decltype(v)>::value_type); };
    add(position_), add(velocity_), add(ghost_), add(acceleration_), add(water_density_gradient_);
    add(start_position_), add(start_velocity_), add(listed_position_), add(scratch_vec_);
    add(density_), add(water_density_), add(pressure_), add(density_rate_), add(water_density_rate_);
    add(step_limit_), add(start_density_), add(start_water_density_), add(scratch_real_);
    add(phase_), add(scratch_phase_), add(ghost_wet_), add(id_), add(scratch_index_);
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
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = id[k];  // ordered by id
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
    f.fields = {std::move(vel), std::move(pres), std::move(dens), std::move(num)};
    return f;
  }

 private:
  // Runs f on particles [begin, end): the moving particles are [0, moving_), the dummy particles
  // [moving_, active_) (cell_sort.h), so each pass runs on its own particles, evenly split.
  template <typename F>
  void launch(const F& f, std::size_t begin, std::size_t end) {
    thrust::for_each(Backend::policy(), thrust::counting_iterator<std::uint32_t>(std::uint32_t(begin)),
                     thrust::counting_iterator<std::uint32_t>(std::uint32_t(end)), f);
  }

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
    cells_.reorder(position_, scratch_vec_);
    cells_.reorder(velocity_, scratch_vec_);
    cells_.reorder(ghost_, scratch_vec_);
    cells_.reorder(density_, scratch_real_);
    cells_.reorder(water_density_, scratch_real_);
    cells_.reorder(phase_, scratch_phase_);
    cells_.reorder(id_, scratch_index_);
    grid_ = cells_.view();
    active_ = cells_.active();
    moving_ = cells_.moving();
    neighbours_.build(grid_, position_, moving_);
    thrust::copy(Backend::policy(), position_.begin(), position_.end(), listed_position_.begin());
  }

  // Whether the cell sort and the neighbour lists of the last build still hold for the coming
  // step: no particle can be farther than half the skin from where it was listed by the half
  // step (neighbour_list.h). Δt <= C0 h / c_w0 (Eq. 40b with μ = 0, 40d), or max_dt without water.
  bool lists_hold() {
    if (!(config_.sound_speed > 0)) return false;
    const double max_dt = std::max(config_.cfl * config_.h / config_.sound_speed, config_.max_dt);
    const Real half_skin = Real((kListRadius - 1.0) * config_.h);
    const Real drift = thrust::transform_reduce(
        Backend::policy(), thrust::counting_iterator<std::uint32_t>(0),
        thrust::counting_iterator<std::uint32_t>(std::uint32_t(moving_)),
        ListDrift<Real, Dim>{grid_, raw(position_), raw(listed_position_), raw(velocity_), Real(0.5 * max_dt)},
        Real(0), MaximumOf<Real>());
    return drift < half_skin;  // false for NaN
  }

  // Right-hand sides at the current state: boundary values first (Eqs. 30-35), then pressure and
  // renormalised density gradients (Eqs. 6, 25), then the water interaction (Eqs. 22-24, 40).
  void evaluate_rates(bool half_step) {
    launch(SolidBoundaryWater<Real, Dim>{view(), grid_, sph_, water_, raw(ghost_wet_), half_step}, moving_, active_);
    launch(RenormalisedDensityGradient<Real, Dim>{view(), grid_, neighbours_.view(), sph_, water_}, 0, moving_);
    launch(WaterInteraction<Real, Dim>{view(), grid_, neighbours_.view(), sph_, water_}, 0, moving_);
  }

  double next_time_step() {
    const Real limit = thrust::reduce(Backend::policy(), step_limit_.begin(), step_limit_.begin() + moving_,
                                      std::numeric_limits<Real>::max(), MinimumOf<Real>());
    if (limit < Real(0))
      throw SimulationFailure("the state holds NaN or infinity at t = " + std::to_string(time_) + " s, step " +
                              std::to_string(steps_) + " (a rate of change is not finite)");
    double dt = config_.cfl * double(limit);
    if (limit == std::numeric_limits<Real>::max()) dt = config_.max_dt > 0 ? config_.max_dt : 0.0;  // no water
    else if (config_.max_dt > 0 && dt > config_.max_dt) dt = config_.max_dt;
    if (dt < config_.min_dt)
      throw SimulationFailure("time step " + std::to_string(dt) + " s fell below min_dt " +
                              std::to_string(config_.min_dt) + " s at t = " + std::to_string(time_) + " s");
    return dt;
  }

  void save_step_start() {
    thrust::copy(Backend::policy(), position_.begin(), position_.end(), start_position_.begin());
    thrust::copy(Backend::policy(), velocity_.begin(), velocity_.end(), start_velocity_.begin());
    thrust::copy(Backend::policy(), density_.begin(), density_.end(), start_density_.begin());
    thrust::copy(Backend::policy(), water_density_.begin(), water_density_.end(), start_water_density_.begin());
  }

  EngineConfig config_;
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
      listed_position_, scratch_vec_;
  Vector<Real> density_, water_density_, pressure_, density_rate_, water_density_rate_, step_limit_, start_density_,
      start_water_density_, scratch_real_;
  Vector<Phase> phase_, scratch_phase_;
  Vector<std::uint8_t> ghost_wet_;
  Vector<std::uint32_t> id_, scratch_index_;
};

// The engine on one backend, in the precision and dimension the configuration asks for.
template <typename Backend>
std::unique_ptr<Engine> make_simulation(const EngineConfig& config, const HostParticles& particles) {
  const bool single = config.precision == Precision::single_precision;
  if (config.dimensions == 2)
    return single ? std::unique_ptr<Engine>(std::make_unique<Simulation<float, 2, Backend>>(config, particles))
                  : std::make_unique<Simulation<double, 2, Backend>>(config, particles);
  if (config.dimensions == 3)
    return single ? std::unique_ptr<Engine>(std::make_unique<Simulation<float, 3, Backend>>(config, particles))
                  : std::make_unique<Simulation<double, 3, Backend>>(config, particles);
  throw std::invalid_argument("dimensions must be 2 or 3");
}

}  // namespace cascade
