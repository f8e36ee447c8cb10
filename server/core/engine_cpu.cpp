// CPU backend: the engine instantiated with the OpenMP device system, both precisions, 2D and 3D.
#include "server/core/simulation.h"

namespace cascade {

#if defined(CASCADE_HAVE_CUDA)
std::unique_ptr<Engine> make_cuda_engine(const EngineConfig& config, const HostParticles& particles,
                                         const PartitionSetup* partition);
#endif

namespace {
std::unique_ptr<Engine> make_on_device(const EngineConfig& config, const HostParticles& particles,
                                       const PartitionSetup* partition) {
  if (config.device == Device::cuda) {
#if defined(CASCADE_HAVE_CUDA)
    return make_cuda_engine(config, particles, partition);
#else
    throw std::invalid_argument("this build has no CUDA backend (configure with the cuda preset)");
#endif
  }
  return make_simulation<OmpBackend>(config, particles, partition);
}
}  // namespace

std::unique_ptr<Engine> make_engine(const EngineConfig& config, const HostParticles& particles) {
  return make_on_device(config, particles, nullptr);
}

std::unique_ptr<Engine> make_share_engine(const EngineConfig& config, const HostParticles& share,
                                          const PartitionSetup& partition) {
  return make_on_device(config, share, &partition);
}

}  // namespace cascade
