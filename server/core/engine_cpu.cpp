// CPU backend: the engine instantiated with the OpenMP device system, both precisions, 2D and 3D.
#include "server/core/simulation.h"

namespace cascade {

#if defined(CASCADE_HAVE_CUDA)
std::unique_ptr<Engine> make_cuda_engine(const EngineConfig& config, const HostParticles& particles);
#endif

namespace {
template <typename Real>
std::unique_ptr<Engine> make_cpu_engine(const EngineConfig& config, const HostParticles& particles) {
  if (config.dimensions == 2) return std::make_unique<Simulation<Real, 2, OmpBackend>>(config, particles);
  if (config.dimensions == 3) return std::make_unique<Simulation<Real, 3, OmpBackend>>(config, particles);
  throw std::invalid_argument("dimensions must be 2 or 3");
}
}  // namespace

std::unique_ptr<Engine> make_engine(const EngineConfig& config, const HostParticles& particles) {
  if (config.device == Device::cuda) {
#if defined(CASCADE_HAVE_CUDA)
    return make_cuda_engine(config, particles);
#else
    throw std::invalid_argument("this build has no CUDA backend (configure with the cuda preset)");
#endif
  }
  if (config.precision == Precision::single_precision) return make_cpu_engine<float>(config, particles);
  return make_cpu_engine<double>(config, particles);
}

}  // namespace cascade
