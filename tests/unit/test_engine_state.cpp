// Engine::state / Engine::restore: an engine restored from a state taken between steps runs on
// with the same bits as the engine it was taken from (the checkpoints' promise, docs/api.md); and
// Engine::clone, the forks' copy, the same without the round trip through the host.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include "server/io/checkpoint_file.h"
#include "server/scenario/case_loader.h"
#include "server/scenario/engine_setup.h"
#include "server/scenario/particle_builder.h"

namespace cascade {
namespace {

struct Case {
  v1::ScenarioSpec spec;
  EngineConfig config;
  HostParticles particles;
};

Case coarse_case(const std::string& name, const std::string& dp) {
  const auto spec = load_case_file(std::string(CASCADE_SOURCE_DIR) + "/cases/" + name + ".yaml", {{"dp", dp}});
  Case c;
  c.spec = spec;
  c.particles = build_particle_set(spec).particles;
  c.config = engine_config(spec, c.particles, Precision::double_precision);
  return c;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

void expect_same_frames(const FieldFrame& a, const FieldFrame& b) {
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.step, b.step);
  EXPECT_TRUE(same_bits(a.position, b.position)) << "position";
  EXPECT_EQ(a.free_surface, b.free_surface);
  ASSERT_EQ(a.fields.size(), b.fields.size());
  for (std::size_t k = 0; k < a.fields.size(); ++k)
    EXPECT_TRUE(same_bits(a.fields[k].values, b.fields[k].values)) << a.fields[k].name;
}

// Whether some position or field differs: a bit-identity check after steps is then not one of two
// unchanged states (a rigid column keeps its positions; its pore pressure moves).
bool frames_differ(const FieldFrame& a, const FieldFrame& b) {
  bool differ = !same_bits(a.position, b.position);
  for (std::size_t k = 0; k < a.fields.size(); ++k) differ = differ || !same_bits(a.fields[k].values, b.fields[k].values);
  return differ;
}

// Runs `before` steps, takes the state, runs `after` more; a second engine restored from the state
// runs the same `after` steps. The state goes through a checkpoint file and back.
void expect_restore_continues_bit_identically(const Case& c, int before, int after) {
  const auto original = make_engine(c.config, c.particles);
  for (int k = 0; k < before; ++k) original->step();
  Checkpoint written;
  written.simulation = "simulations/test";
  written.spec = c.spec;
  written.journal = "{\"command\":\"create\"}\n";
  written.engine = original->state();
  const auto path = std::filesystem::temp_directory_path() / ("cascade_engine_state_" + c.spec.name() + ".h5");
  write_checkpoint(path, written);
  const Checkpoint read = read_checkpoint(path);
  std::filesystem::remove(path);
  EXPECT_EQ(read.journal, written.journal);
  EXPECT_EQ(read.spec.SerializeAsString(), c.spec.SerializeAsString());
  const EngineState& state = read.engine;
  const FieldFrame at_state = original->frame();
  for (int k = 0; k < after; ++k) original->step();

  const auto restored = make_engine(c.config, c.particles);
  restored->restore(state);
  expect_same_frames(restored->frame(), at_state);
  for (int k = 0; k < after; ++k) restored->step();
  expect_same_frames(restored->frame(), original->frame());
  EXPECT_EQ(restored->last_dt(), original->last_dt());
  // The pore water's account (engine_state.h) goes through the file and on with the same bits.
  const PoreWaterAccount a = restored->pore_water_account(), b = original->pore_water_account();
  EXPECT_EQ(a.rain, b.rain);
  EXPECT_EQ(a.walls, b.walls);
  EXPECT_EQ(a.surface, b.surface);
  EXPECT_TRUE(frames_differ(at_state, original->frame()));
}

TEST(EngineState, SoilUnderWaterContinuesBitIdentically) {
  expect_restore_continues_bit_identically(coarse_case("submerged_layer_2d", "0.02"), 15, 25);
}

// A rained column: the pore water's account is not zero.
TEST(EngineState, RainedColumnContinuesBitIdentically) {
  const Case c = coarse_case("infiltration_1d", "0.02");  // its own dp
  expect_restore_continues_bit_identically(c, 20, 30);
  const auto engine = make_engine(c.config, c.particles);
  for (int k = 0; k < 50; ++k) engine->step();
  EXPECT_GT(engine->pore_water_account().rain, 0.0);
}

// Water falling freely: the particles cross cells and the neighbour lists are rebuilt between the
// state and the end.
TEST(EngineState, DamBreakContinuesBitIdentically) {
  expect_restore_continues_bit_identically(coarse_case("dam_break_2d", "0.02"), 200, 300);
}

// Engine::clone (ForkSimulation): the clone and the original, each stepped on, stay bit-identical,
// and stepping one leaves the other as it was (no array shared between them).
void expect_clone_continues_bit_identically(const Case& c, int before, int after) {
  const auto original = make_engine(c.config, c.particles);
  for (int k = 0; k < before; ++k) original->step();
  const auto clone = original->clone();
  const FieldFrame at_clone = original->frame();
  expect_same_frames(clone->frame(), at_clone);
  for (int k = 0; k < after; ++k) original->step();
  expect_same_frames(clone->frame(), at_clone);  // untouched by the original's steps
  for (int k = 0; k < after; ++k) clone->step();
  expect_same_frames(clone->frame(), original->frame());
  EXPECT_EQ(clone->last_dt(), original->last_dt());
  EXPECT_EQ(clone->pore_water_account().rain, original->pore_water_account().rain);
  EXPECT_TRUE(frames_differ(at_clone, original->frame()));
}

TEST(EngineState, CloneOfSoilUnderWaterContinuesBitIdentically) {
  expect_clone_continues_bit_identically(coarse_case("submerged_layer_2d", "0.02"), 15, 25);
}

TEST(EngineState, CloneOfDamBreakContinuesBitIdentically) {
  expect_clone_continues_bit_identically(coarse_case("dam_break_2d", "0.02"), 200, 300);
}

TEST(EngineState, CloneOfRainedColumnContinuesBitIdentically) {
  expect_clone_continues_bit_identically(coarse_case("infiltration_1d", "0.02"), 20, 30);
}

TEST(EngineState, RestoreRefusesAnotherParticleSet) {
  const auto layer = coarse_case("submerged_layer_2d", "0.02");
  const auto dam = coarse_case("dam_break_2d", "0.02");
  const auto engine = make_engine(layer.config, layer.particles);
  EXPECT_THROW(engine->restore(make_engine(dam.config, dam.particles)->state()), std::invalid_argument);
}

// A checkpoint damaged after it was written is refused, whichever of its bytes changed: the last
// 4 KiB flipped (the data of the last datasets) restored without an error before the checksum.
TEST(EngineState, DamagedCheckpointIsRefused) {
  const auto c = coarse_case("dam_break_2d", "0.02");
  const auto engine = make_engine(c.config, c.particles);
  for (int k = 0; k < 20; ++k) engine->step();
  Checkpoint written;
  written.simulation = "simulations/test";
  written.spec = c.spec;
  written.journal = "{\"command\":\"create\"}\n";
  written.engine = engine->state();
  const auto path = std::filesystem::temp_directory_path() / "cascade_damaged_checkpoint.h5";
  write_checkpoint(path, written);
  EXPECT_NO_THROW(read_checkpoint(path));
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  ASSERT_GT(bytes.size(), 8192u);
  int refused = 0, tried = 0;
  // Damage in the data, one byte at a time at several places of the last 4 KiB, then all of it.
  for (std::size_t offset : {bytes.size() - 4096, bytes.size() - 2048, bytes.size() - 1}) {
    std::string damaged = bytes;
    damaged[offset] = char(~damaged[offset]);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << damaged;
    ++tried;
    try {
      read_checkpoint(path);
    } catch (const std::runtime_error&) {
      ++refused;
    }
  }
  std::string flipped = bytes;
  for (std::size_t k = bytes.size() - 4096; k < bytes.size(); ++k) flipped[k] = char(~flipped[k]);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << flipped;
  ++tried;
  try {
    read_checkpoint(path);
  } catch (const std::runtime_error& e) {
    ++refused;
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
  EXPECT_EQ(tried, 4);
  EXPECT_EQ(refused, tried);
}

}  // namespace
}  // namespace cascade
