// Backends: where particle arrays live and which Thrust execution policy runs the kernels.
// The engine is a template on the backend; the physics functors are the same for both.
// OmpBackend is compiled by the host compiler; CudaBackend exists only in the one translation
// unit nvcc compiles (engine_cuda.cu), so every CUDA launch comes from that file.
#pragma once

#include <thrust/execution_policy.h>
#include <thrust/system/omp/execution_policy.h>
#include <thrust/system/omp/vector.h>

#if defined(__CUDACC__)
#include <thrust/system/cuda/execution_policy.h>
#include <thrust/system/cuda/vector.h>
#endif

namespace cascade {

struct OmpBackend {
  template <typename T>
  using Vector = thrust::omp::vector<T>;
  static auto policy() { return thrust::omp::par; }
  static constexpr const char* name = "cpu";
};

#if defined(__CUDACC__)
struct CudaBackend {
  template <typename T>
  using Vector = thrust::cuda::vector<T>;
  static auto policy() { return thrust::cuda::par; }
  static constexpr const char* name = "cuda";
};
#endif

// The raw pointer to a backend vector's elements, for the views handed to kernels.
template <typename Vector>
auto raw(Vector& v) {
  return thrust::raw_pointer_cast(v.data());
}

}  // namespace cascade
