// CUDA backend: the one translation unit nvcc compiles, so every kernel launch comes from here.
#include "server/core/simulation.h"

namespace cascade {

std::unique_ptr<Engine> make_cuda_engine(const EngineConfig& config, const HostParticles& particles,
                                         const PartitionSetup* partition) {
  return make_simulation<CudaBackend>(config, particles, partition);
}

}  // namespace cascade
