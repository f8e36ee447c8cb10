#include "server/parallel/distributed_engine.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "server/core/engine_state_rows.h"
#include "server/core/neighbour_list.h"
#include "server/parallel/byte_message.h"

namespace cascade {
namespace {

// A process's rows of a state: their count, then every array (in the state's order of names)
// as its components per particle and its values.
std::vector<char> pack_state_rows(const EngineState& rows) {
  ByteWriter out;
  out.put(std::uint64_t(rows.particles));
  auto pack = [&](const auto& arrays) {
    for (const auto& [name, values] : arrays) {
      out.put(std::uint32_t(row_width(values, rows.particles, name)));
      out.put(values.data(), values.size());
    }
  };
  pack(rows.reals);
  pack(rows.integers);
  return std::move(out.bytes);
}

// A process's rows (pack_state_rows), whose arrays have the names of `like`'s.
EngineState unpack_state_rows(const std::vector<char>& in, const EngineState& like) {
  EngineState rows;
  ByteReader reader(in);
  const auto count = reader.take<std::uint64_t>();
  rows.particles = std::size_t(count);
  auto unpack = [&](const auto& names, auto& arrays) {
    for (const auto& named : names) {
      const auto c = reader.take<std::uint32_t>();
      auto& values = arrays[named.first];
      values.resize(std::size_t(count) * c);
      reader.take(values.data(), values.size());
    }
  };
  unpack(like.reals, rows.reals);
  unpack(like.integers, rows.integers);
  if (!reader.done()) throw std::logic_error("a process's rows of the state are longer than its arrays");
  return rows;
}

// Puts `rows` into `whole` (sized for all particles) at their ids.
void place_state_rows(const EngineState& rows, EngineState& whole, std::vector<char>& seen) {
  if (rows.particles == 0) return;
  const std::vector<std::uint32_t>& ids = rows.integers.at("id");
  for (std::uint32_t id : ids) {
    if (id >= whole.particles || seen[id]) throw std::logic_error("particle " + std::to_string(id) + " is owned twice or unknown");
    seen[id] = 1;
  }
  auto place = [&](const auto& arrays_in, auto& arrays_out) {
    for (const auto& [name, values] : arrays_in) {
      const std::size_t c = row_width(values, rows.particles, name);
      auto& out = arrays_out[name];
      if (out.empty()) out.assign(whole.particles * c, 0);
      if (out.size() != whole.particles * c) throw std::logic_error("the processes' states differ in array " + name);
      for (std::size_t k = 0; k < rows.particles; ++k)
        std::copy(values.begin() + k * c, values.begin() + (k + 1) * c, out.begin() + std::size_t(ids[k]) * c);
    }
  };
  place(rows.reals, whole.reals);
  place(rows.integers, whole.integers);
}

}  // namespace

double halo_width(const EngineConfig& config) {
  const double list_radius = 2.0 * kListRadius * config.h;
  const double skin = 2.0 * (kListRadius - 1.0) * config.h;
  return list_radius + skin;
}

Slabs slabs_for(const EngineConfig& config, const HostParticles& whole, int processes) {
  if (processes < 1) throw std::invalid_argument("a run needs at least one process");
  const int dim = whole.dimensions;
  Slabs slabs;
  slabs.axis = -1;
  double longest = -1;
  for (int a = 0; a < dim; ++a) {  // the longest extent of the moving particles
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (std::size_t i = 0; i < whole.size(); ++i)
      if (whole.phase[i] != Phase::boundary)
        low = std::min(low, whole.position[i * dim + a]), high = std::max(high, whole.position[i * dim + a]);
    if (!config.periodic[a] && high - low > longest) longest = high - low, slabs.axis = a;
  }
  if (slabs.axis < 0)
    throw std::invalid_argument("a run split over processes needs an axis that is not periodic to cut along");
  std::vector<double> x;
  for (std::size_t i = 0; i < whole.size(); ++i)
    if (whole.phase[i] != Phase::boundary) x.push_back(whole.position[i * dim + slabs.axis]);
  std::sort(x.begin(), x.end());
  if (x.size() < std::size_t(processes))
    throw std::invalid_argument("a run of " + std::to_string(x.size()) + " moving particles cannot be split over " +
                                std::to_string(processes) + " processes");
  slabs.cut.assign(processes + 1, 0.0);
  slabs.cut.front() = -std::numeric_limits<double>::infinity();
  slabs.cut.back() = std::numeric_limits<double>::infinity();
  for (int r = 1; r < processes; ++r) {
    const std::size_t k = x.size() * std::size_t(r) / std::size_t(processes);
    slabs.cut[r] = 0.5 * (x[k - 1] + x[k]);  // between two particles
  }
  slabs.halo = halo_width(config);
  return slabs;
}

DistributedEngine::DistributedEngine(const EngineConfig& config, const HostParticles& whole, Transport& transport)
    : config_(config),
      transport_(transport),
      slabs_(slabs_for(config, whole, transport.processes())),
      particles_(whole.size()),
      share_(start_share(whole, nullptr)) {}

// This process's share to start from: the moving particles it owns and the dummies it holds
// (Slabs::holds_dummy; the engine sends the copies itself, Simulation::share_particles), with
// their rows of `checkpoint` (whole run, by id) where the share starts from one.
std::unique_ptr<Engine> DistributedEngine::start_share(const HostParticles& whole, const EngineState* checkpoint) {
  const int dim = whole.dimensions;
  const int me = transport_.process();
  PartitionSetup setup;
  setup.transport = &transport_;
  setup.slabs = slabs_;
  setup.soil = whole.count(Phase::soil) > 0;
  HostParticles share;
  share.dimensions = dim;
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < whole.size(); ++i) {
    const double x = whole.position[i * dim + slabs_.axis];
    const bool dummy = whole.phase[i] == Phase::boundary;
    const double ghost_x = dummy ? whole.ghost[i * dim + slabs_.axis] : x;
    const int owner = slabs_.owner_of(ghost_x);
    const bool held = dummy ? slabs_.holds_dummy(me, x, ghost_x) : owner == me;
    if (!held) continue;
    for (int a = 0; a < dim; ++a) {
      share.position.push_back(whole.position[i * dim + a]);
      share.velocity.push_back(whole.velocity[i * dim + a]);
      share.ghost.push_back(whole.ghost[i * dim + a]);
    }
    share.water_density.push_back(whole.water_density[i]);
    share.porosity.push_back(i < whole.porosity.size() ? whole.porosity[i] : 0.0);
    if (i < whole.soil_material.size()) share.soil_material.push_back(whole.soil_material[i]);
    if (whole.effective_stress.size() == 6 * whole.size())
      share.effective_stress.insert(share.effective_stress.end(), whole.effective_stress.begin() + 6 * i,
                                    whole.effective_stress.begin() + 6 * (i + 1));
    share.phase.push_back(whole.phase[i]);
    if (i < whole.body.size()) share.body.push_back(whole.body[i]);
    setup.global_id.push_back(std::uint32_t(i));
    setup.owner.push_back(std::uint32_t(owner));
    rows.push_back(i);
  }
  if (setup.soil) {
    const int axis3[3] = {0, dim == 2 ? -1 : 1, dim == 2 ? 1 : 2};
    setup.initial_position.assign(3 * whole.size(), 0.0);
    for (std::size_t i = 0; i < whole.size(); ++i)
      for (int c = 0; c < 3; ++c)
        setup.initial_position[3 * i + c] = axis3[c] < 0 ? 0.0 : whole.position[i * dim + axis3[c]];
  }
  EngineState start;
  if (checkpoint) {
    start = state_rows(*checkpoint, rows);
    // The account is the whole run's: process 0 carries it on, the others from zero.
    if (me != 0) start.pore_water = {};
    setup.initial_position = checkpoint->displacement_reference;
    setup.start = &start;
  }
  return make_share_engine(config_, share, setup);
}

void DistributedEngine::refuse(const char* what) {
  throw std::invalid_argument(std::string(what) + " of a run split over processes is not supported yet (issue 17)");
}

std::size_t DistributedEngine::lost_particles() const {
  return std::size_t(transport_.sum(double(share_->lost_particles())));
}

std::size_t DistributedEngine::device_bytes() const {
  return std::size_t(transport_.sum(double(share_->device_bytes())));
}

PoreWaterAccount DistributedEngine::pore_water_account() const {
  const PoreWaterAccount own = share_->pore_water_account();
  return {transport_.sum(own.rain), transport_.sum(own.walls), transport_.sum(own.surface)};
}

std::vector<std::size_t> DistributedEngine::share_sizes() const {
  ByteWriter own;
  own.put(std::uint64_t(share_size()));
  const auto received = transport_.exchange(std::vector<std::vector<char>>(transport_.processes(), own.bytes));
  std::vector<std::size_t> sizes;
  for (const auto& in : received) sizes.push_back(std::size_t(ByteReader(in).take<std::uint64_t>()));
  return sizes;
}

FieldFrame DistributedEngine::frame() const { return gather_frame(FrameTo::every_process); }

FieldFrame DistributedEngine::frame_at_process_0() const { return gather_frame(FrameTo::process_0); }

FieldFrame DistributedEngine::frame_block() const { return gather_frame(FrameTo::id_blocks); }

FieldFrame DistributedEngine::local_frame() const { return share_->frame(); }

// Each part goes with a first byte that says whether it was taken; a process whose part threw
// sends the reason instead, and process 0 throws it, naming the process: the others do not wait
// for a failure that only one of them met, and the reason is not lost.
std::vector<std::vector<char>> DistributedEngine::parts_at_process_0(const SamplePart& part,
                                                                    const std::vector<char>& /*request*/) const {
  std::vector<std::vector<char>> send(static_cast<std::size_t>(transport_.processes()));
  char taken = 1;
  try {
    const FieldFrame local = share_->frame();
    send[0] = part(local, owned_rows(local, transport_.process()));
  } catch (const std::exception& e) {
    const std::string reason = e.what();
    taken = 0, send[0].assign(reason.begin(), reason.end());
  }
  send[0].insert(send[0].begin(), taken);
  auto received = transport_.exchange(send);
  if (transport_.process() != 0) return {};
  for (std::size_t r = 0; r < received.size(); ++r) {
    std::vector<char>& in = received[r];
    if (in.empty()) throw std::logic_error("process " + std::to_string(r) + " sent no part of the sample");
    if (!in.front())
      throw std::runtime_error("process " + std::to_string(r) + " could not take its part of the sample: " +
                               std::string(in.begin() + 1, in.end()));
    in.erase(in.begin());
  }
  return received;
}

// Each process sends the particles it owns (its share's frame, field "process") to every other,
// to process 0 alone, or to the process whose block of ids holds each (FrameTo::id_blocks), and
// each that receives puts them together by id: the whole run's frame, as one process would give
// it, or its block of it.
FieldFrame DistributedEngine::gather_frame(FrameTo to) const {
  const FieldFrame own = share_->frame();
  if (!own.find("process")) throw std::logic_error("a share's frame has no process field");
  const int me = transport_.process(), processes = transport_.processes();
  const std::size_t n = particles_;
  const auto first = [&](int r) { return id_block_start(n, processes, r); };
  const auto destination = [&](std::uint32_t id) {
    if (to != FrameTo::id_blocks) return 0;
    int r = int(std::uint64_t(id) * std::uint64_t(processes) / std::max<std::size_t>(n, 1));
    while (r + 1 < processes && id >= first(r + 1)) ++r;  // the integer divisions' round-off
    while (r > 0 && id < first(r)) --r;
    return r;
  };
  const int messages = to == FrameTo::id_blocks ? processes : 1;
  std::vector<std::uint64_t> count(static_cast<std::size_t>(messages), 0);
  std::vector<std::uint32_t> rows;
  const std::vector<char> owned = owned_rows(own, me);
  for (std::uint32_t k = 0; k < own.size(); ++k)
    if (owned[k]) rows.push_back(k), ++count[std::size_t(destination(own.id[k]))];

  std::vector<ByteWriter> message(static_cast<std::size_t>(messages));
  for (int m = 0; m < messages; ++m) message[std::size_t(m)].put(count[std::size_t(m)]);
  const bool surface = !own.free_surface.empty();
  for (std::uint32_t k : rows) {
    ByteWriter& out = message[std::size_t(destination(own.id[k]))];
    out.put(own.id[k]);
    out.put(&own.position[3 * std::size_t(k)], 3);
    out.put(own.phase[k]);
    if (surface) out.put(own.free_surface[k]);
    for (const auto& field : own.fields)
      out.put(&field.values[std::size_t(k) * field.components], std::size_t(field.components));
  }
  std::vector<std::vector<char>> send(static_cast<std::size_t>(processes));
  for (int r = 0; r < processes; ++r) {
    if (to == FrameTo::id_blocks) send[std::size_t(r)] = std::move(message[std::size_t(r)].bytes);
    else if (to == FrameTo::every_process || r == 0) send[std::size_t(r)] = message[0].bytes;
  }
  const auto received = transport_.exchange(send);
  FieldFrame whole;
  whole.time = own.time;
  whole.step = own.step;
  whole.dimensions = own.dimensions;
  if (to == FrameTo::process_0 && me != 0) return whole;
  const std::size_t lo = to == FrameTo::id_blocks ? first(me) : 0;
  const std::size_t rows_here = (to == FrameTo::id_blocks ? first(me + 1) : n) - lo;
  whole.position.assign(3 * rows_here, 0.0);
  whole.phase.assign(rows_here, 0);
  whole.id.assign(rows_here, 0);
  if (surface) whole.free_surface.assign(rows_here, 0);
  for (const auto& field : own.fields)
    whole.fields.push_back({field.name, field.units, field.components,
                            std::vector<double>(rows_here * std::size_t(field.components), 0.0)});
  std::vector<char> seen(rows_here, 0);
  std::size_t placed = 0;
  for (const auto& in : received) {
    ByteReader reader(in);
    const auto rows_in = reader.take<std::uint64_t>();
    for (std::uint64_t m = 0; m < rows_in; ++m) {
      const auto id = reader.take<std::uint32_t>();
      if (id < lo || id - lo >= rows_here || seen[id - lo])
        throw std::logic_error("particle " + std::to_string(id) + " is owned twice or unknown");
      const std::size_t row = id - lo;
      seen[row] = 1, ++placed;
      whole.id[row] = id;
      reader.take(&whole.position[3 * row], 3);
      reader.take(&whole.phase[row], 1);
      if (surface) reader.take(&whole.free_surface[row], 1);
      for (auto& field : whole.fields)
        reader.take(&field.values[row * field.components], std::size_t(field.components));
    }
  }
  if (placed != rows_here)
    throw std::logic_error("the processes own " + std::to_string(placed) + " of the " + std::to_string(rows_here) +
                           " particles of " + (to == FrameTo::id_blocks ? "this process's block" : "the run"));
  return whole;
}

EngineState DistributedEngine::state() const { return gather_state(true); }

EngineState DistributedEngine::state_at_process_0() const { return gather_state(false); }

// Each process sends the rows of the particles it owns (its share's state) to every other, or to
// process 0 alone, and each that receives puts them together by id.
EngineState DistributedEngine::gather_state(bool everywhere) const {
  const EngineState own = share_->state();
  const PoreWaterAccount account = pore_water_account();
  const std::vector<char> rows = pack_state_rows(own);
  std::vector<std::vector<char>> send(transport_.processes());
  for (int r = 0; r < transport_.processes(); ++r)
    if (everywhere || r == 0) send[r] = rows;
  const auto received = transport_.exchange(send);
  if (!everywhere && transport_.process() != 0) return {};
  EngineState whole = own;
  whole.particles = particles_;
  for (auto& [name, values] : whole.reals) values.clear();
  for (auto& [name, values] : whole.integers) values.clear();
  std::vector<char> seen(particles_, 0);
  for (const auto& in : received) place_state_rows(unpack_state_rows(in, own), whole, seen);
  if (std::count(seen.begin(), seen.end(), 1) != std::ptrdiff_t(particles_))
    throw std::logic_error("the processes own fewer particles than the run's " + std::to_string(particles_));
  whole.pore_water = account;
  return whole;
}

void DistributedEngine::restore(const EngineState& state) {
  if (state.particles != particles_ || state.dimensions != config_.dimensions)
    throw std::invalid_argument("the state is of a " + std::to_string(state.dimensions) + "D run with " +
                                std::to_string(state.particles) + " particles; this one is " +
                                std::to_string(config_.dimensions) + "D with " + std::to_string(particles_));
  const EngineState by_id = state_by_id(state);
  const int dim = config_.dimensions;
  auto reals = [&](const char* name, std::size_t components) -> const std::vector<double>& {
    const auto found = by_id.reals.find(name);
    if (found == by_id.reals.end() || found->second.size() != particles_ * components)
      throw std::invalid_argument(std::string("the state's array '") + name + "' is missing or has the wrong size");
    return found->second;
  };
  const auto phase = by_id.integers.find("phase");
  if (phase == by_id.integers.end() || phase->second.size() != particles_)
    throw std::invalid_argument("the state's array 'phase' is missing or has the wrong size");
  // The whole run as the shares are cut from it: positions, phases and ghosts decide the slabs
  // and what each process holds; the rest of the share's start is the state's rows.
  HostParticles whole;
  whole.dimensions = dim;
  whole.position = reals("position", dim);
  whole.velocity = reals("velocity", dim);
  whole.ghost = reals("ghost", dim);
  whole.water_density = reals("water_density", 1);
  for (std::uint32_t p : phase->second) whole.phase.push_back(Phase(p));
  if (whole.count(Phase::soil) > 0) {
    whole.porosity = reals("porosity", 1);
    whole.effective_stress = reals("effective_stress", 6);
    const auto material = by_id.integers.find("soil_material");
    if (material == by_id.integers.end() || material->second.size() != particles_)
      throw std::invalid_argument("the state's array 'soil_material' is missing or has the wrong size");
    whole.soil_material.assign(material->second.begin(), material->second.end());
  }
  slabs_ = slabs_for(config_, whole, transport_.processes());
  share_ = start_share(whole, &by_id);
}

}  // namespace cascade
