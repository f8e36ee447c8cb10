// Snapshot render time on the machine's EGL (llvmpipe without a GPU): a 3D soil block under
// water seen by the orbit camera, and a 2D section seen from the side, 10^5 and 10^6 particles at
// 1280×720, coloured by pressure with the colour bar. A timed iteration is what a service does
// per snapshot: choose and colour particles, draw, read back, overlay, encode the PNG.
// Counters: drawn particles (after level of detail), sprite pixels, PNG bytes.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>

#include "render/png_encoder.h"
#include "render/snapshot_renderer.h"

namespace {

using namespace cascade;
using namespace cascade::render;

// A cube (3D) or square (2D) lattice of about n particles with spacing dp: soil below mid-height,
// water above, pressure rising with depth.
FieldFrame lattice(std::size_t n, int dimensions, double dp) {
  const int side = int(std::lround(std::pow(double(n), 1.0 / dimensions)));
  const int ny = dimensions == 3 ? side : 1;
  FieldFrame f;
  f.dimensions = dimensions;
  f.time = 12.5;
  FieldFrame::RealField pressure{"pressure", "Pa", 1, {}};
  std::uint32_t id = 0;
  for (int k = 0; k < side; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < side; ++i) {
        f.position.insert(f.position.end(), {i * dp, j * dp, k * dp});
        f.phase.push_back(k < side / 2 ? 1 : 0);
        f.id.push_back(id++);
        pressure.values.push_back(1000 * 9.81 * (side - k) * dp);
      }
  f.fields.push_back(std::move(pressure));
  return f;
}

SnapshotRenderer& renderer() {
  static SnapshotRenderer r;
  return r;
}

void render_snapshot(benchmark::State& state, int dimensions) {
  const double dp = 0.01;
  const FieldFrame frame = lattice(std::size_t(state.range(0)), dimensions, dp);
  SnapshotSettings s;
  s.field = "pressure";
  s.particle_diameter = dp;
  s.camera.kind = dimensions == 3 ? CameraKind::orbit : CameraKind::side;
  Snapshot shot;
  std::size_t png_bytes = 0;
  for (auto _ : state) {
    shot = renderer().render(frame, s);
    png_bytes = encode_png(shot.image).size();
  }
  state.counters["particles"] = double(frame.size());
  state.counters["drawn"] = double(shot.drawn_particles);
  state.counters["sprite_pixels"] = shot.sprite_pixels;
  state.counters["png_bytes"] = double(png_bytes);
}

void Render3dOrbit(benchmark::State& state) { render_snapshot(state, 3); }
void Render2dSide(benchmark::State& state) { render_snapshot(state, 2); }

}  // namespace

BENCHMARK(Render3dOrbit)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(Render2dSide)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_MAIN();
