// The engine seen from outside: set-up constants, the abstract Engine, and its factory.
// Callers (the runner, later the server) never see the backend, the precision or Thrust.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include <vector>

#include "server/core/engine_state.h"
#include "server/core/field_frame.h"
#include "server/core/host_particles.h"
#include "server/core/hydraulic_forcing.h"
#include "server/core/partition.h"
#include "server/core/soil_material.h"

namespace cascade {

enum class Precision { single_precision, double_precision };
// The build's default (CASCADE_REAL): what the runner and the server use unless told otherwise.
#if defined(CASCADE_DEFAULT_FLOAT)
inline constexpr Precision kBuildPrecision = Precision::single_precision;
#else
inline constexpr Precision kBuildPrecision = Precision::double_precision;
#endif

// A boundary body whose dummies carry a prescribed pore pressure on their soil side (a drained
// wall, Eqs. 36, 37); the other boundary bodies are impermeable (Eqs. 32b, 35b).
struct DrainedWall {
  std::uint32_t body = 0;    // index of the Body (HostParticles::body)
  double pore_pressure = 0;  // p_w,pres (Pa)
};
enum class Device { cpu, cuda };

struct EngineConfig {
  int dimensions = 2;
  double dp = 0;                        // initial particle spacing (m)
  double h = 0;                         // smoothing length (m)
  std::array<double, 3> gravity{};      // first `dimensions` components used
  std::array<double, 3> domain_min{};
  std::array<double, 3> domain_max{};
  std::array<bool, 3> periodic{};
  double water_density = 1000;          // ρ_w0
  double sound_speed = 0;               // c_w0 (Eq. 24a)
  double delta = 0.1;                   // δ (Eq. 23a)
  double viscosity_alpha = 0.01;        // α_μ,w (Eq. 23b)
  std::vector<SoilMaterial> soils;      // HostParticles::soil_material indexes these
  HydraulicForcing forcing;             // the free-surface conditions at the start (Eq. 39)
  std::vector<DrainedWall> drained_walls;  // at most 255
  double cfl = 0.2;                     // C0 (Eq. 40d)
  double max_dt = 0;                    // 0: none
  double min_dt = 1e-12;                // a smaller step fails the run
  Precision precision = Precision::double_precision;
  Device device = Device::cpu;
};

// A run's switch from one stage to the next (ScenarioSpec.stages, server/solver/staged_engine.h).
struct StageChange {
  double time = 0;           // simulated time of the switch (s)
  std::uint64_t step = 0;    // the step count there
  int from = -1, to = 0;     // indices into the case's stages (-1: the start of the run)
  std::string from_name, to_name;
  std::string reason;        // what ended the stage, and its figures
};

// The state of a dynamic relaxation (the geostatic stage, docs/physics.md "Geostatic start"), at
// the engine's last step.
struct Equilibrium {
  double force_ratio = 0;  // largest unbalanced force on a soil particle over the mean gravity force on one
  double max_speed = 0;    // largest soil speed (m/s)
};

// Why a run cannot go on (time step collapsed, non-finite state).
class SimulationFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Engine {
 public:
  virtual ~Engine() = default;
  virtual void step() = 0;                       // one Symplectic Position Verlet step
  virtual double time() const = 0;               // simulated time (s)
  virtual std::uint64_t step_count() const = 0;
  virtual double last_dt() const = 0;
  virtual std::size_t particle_count() const = 0;
  virtual std::size_t lost_particles() const = 0;  // left the domain along a non-periodic axis
  virtual std::size_t device_bytes() const = 0;    // memory held in particle and grid arrays
  virtual FieldFrame frame() const = 0;            // all fields on the host, ordered by id
  // The whole frame where one process draws it (VTK files, snapshots): split over processes
  // (DistributedEngine), gathered to process 0 alone (the others get one with the time and step
  // and no particles), so that a frame costs each particle one message, not one to every process.
  virtual FieldFrame frame_at_process_0() const { return frame(); }
  // This process's particles, with no message sent: the whole run's frame in one process; split
  // over processes, the particles it holds (those it owns and its copies of its neighbours'), whose
  // field "process" names each one's owner (owned_rows, field_frame.h). Probes and events are
  // sampled on it and their parts combined (ProbeSampler::combine, CascadeEventDetector::observe).
  virtual FieldFrame local_frame() const { return frame(); }
  // Each process's part of a sample of the outputs (probes, events, energy: server/io/sample_parts.h),
  // taken by `part` on its local frame and the rows it owns, brought to process 0, which gets one
  // per process (the others none): no frame is gathered. A part that throws reaches process 0 as
  // an exception: its own, or a std::runtime_error naming the process and its reason. `request`:
  // what the part is to hold, for the processes that take theirs with a function of their own (a
  // split server's other processes, split_server.cpp, which receive it with the call); `part`
  // knows it already.
  using SamplePart = std::function<std::vector<char>(const FieldFrame& local, const std::vector<char>& owned)>;
  virtual std::vector<std::vector<char>> parts_at_process_0(const SamplePart& part,
                                                            const std::vector<char>& /*request*/) const {
    const FieldFrame whole = frame();
    return {part(whole, owned_rows(whole, 0))};
  }
  // This process's block of the whole run's frame, for a frame that every process writes its own
  // rows of (Hdf5FieldWriter::reserve): the particles of ids id_block_start(N, P, r) up to
  // id_block_start(N, P, r + 1) on process r of P, in id order; the whole frame in one process.
  virtual FieldFrame frame_block() const { return frame(); }
  virtual const char* device_name() const = 0;
  // The free-surface hydraulic conditions (Eq. 39); a change applies from the next step on.
  virtual void set_forcing(const HydraulicForcing& forcing) = 0;
  virtual HydraulicForcing forcing() const = 0;
  // The end of an initialisation stage (ScenarioSpec.initialisation): the simulated time is set
  // back to 0 and the displacement field is measured from the positions reached. The state, the
  // step count and the forcing are kept.
  virtual void restart_clock() = 0;
  // What the next steps depend on, taken between steps; restore() of it into an engine of the same
  // case, precision and dimension gives the same bits from there on (engine_state.h). restore()
  // throws std::invalid_argument when the state belongs to another kind of engine or particle set.
  virtual EngineState state() const = 0;
  virtual void restore(const EngineState& state) = 0;
  // An independent engine with this one's state on the same device: its next steps give the
  // same bits as this one's would (with the same number of threads). A fork (ForkSimulation)
  // without state() and restore()'s host round trip; derived data that the state determines (the
  // neighbour lists) may be left for the clone to rebuild at its first step.
  virtual std::unique_ptr<Engine> clone() const = 0;
  // After restore() of a state whose pore pressures another solver advanced (the implicit stage):
  // forms the seepage discharge (Eq. 27b) of those pressures, which frames report and the next
  // step's surface switch (Eq. 39) reads as the last evaluation's, in place of the stale one.
  virtual void refresh_seepage() {}
  // The pore water that entered the soil through each kind of boundary since the run began
  // (engine_state.h); zero for a run without soil.
  virtual PoreWaterAccount pore_water_account() const { return {}; }

  // Stages (server/solver/staged_engine.h): the index of the one running (into the case's stages;
  // 0 for a run of one stage), the switches since the last call, and the operator's hand-over to
  // the next stage at the next step boundary (std::invalid_argument when there is none).
  virtual int stage() const { return 0; }
  virtual std::vector<StageChange> take_stage_changes() { return {}; }
  virtual void advance_stage(const std::string& caller) {
    throw std::invalid_argument("the run has no further stage (requested by " + caller + ")");
  }

  // Dynamic relaxation of the geostatic stage: with a coefficient in (0, 1) the soil's
  // acceleration takes Cundall's local non-viscous damping with it and the pore water is held
  // (pressure, saturation and seepage of the state at the call); 0 switches both off again.
  virtual void set_relaxation(double local_damping) = 0;
  virtual Equilibrium equilibrium() const = 0;
  virtual void zero_velocities() = 0;  // every moving particle at rest; positions and stresses kept

  // A run split over processes: how evenly they share the work (partition.h); one process's
  // engine has nothing to balance.
  virtual LoadBalance load_balance() const { return {}; }
};

std::unique_ptr<Engine> make_engine(const EngineConfig& config, const HostParticles& particles);

// One process's share of a run split over processes (partition.h; server/parallel/ sets it up).
struct PartitionSetup;
std::unique_ptr<Engine> make_share_engine(const EngineConfig& config, const HostParticles& share,
                                          const PartitionSetup& partition);

}  // namespace cascade
