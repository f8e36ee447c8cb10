// CUDA backend: the one translation unit nvcc compiles, so every kernel launch comes from here.
#include "server/core/simulation.h"

namespace cascade {

namespace {
template <typename Real>
std::unique_ptr<Engine> make_cuda_engine_of(const EngineConfig& config, const HostParticles& particles) {
  if (config.dimensions == 2) return std::make_unique<Simulation<Real, 2, CudaBackend>>(config, particles);
  if (config.dimensions == 3) return std::make_unique<Simulation<Real, 3, CudaBackend>>(config, particles);
  throw std::invalid_argument("dimensions must be 2 or 3");
}
}  // namespace

std::unique_ptr<Engine> make_cuda_engine(const EngineConfig& config, const HostParticles& particles) {
  if (config.precision == Precision::single_precision) return make_cuda_engine_of<float>(config, particles);
  return make_cuda_engine_of<double>(config, particles);
}

}  // namespace cascade
