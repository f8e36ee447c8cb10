// The machine's sustainable memory bandwidth, STREAM's triad (J. D. McCalpin, "Memory bandwidth
// and machine balance in current high performance computers", IEEE TCCA Newsletter, 1995):
// a[i] = b[i] + s c[i] over arrays far larger than the caches, counted as 24 bytes per element
// (two reads, one write; the write-allocate read is not counted, as in STREAM). The best of 10
// repetitions, on the OpenMP threads the environment gives (OMP_NUM_THREADS), each thread first
// touching the part it works on. Printed so that figures from different machines can be compared
// (docs/performance.md).
//
// usage: stream_triad [elements per array, default 2^25 = 256 MiB each]
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>

int main(int argc, char** argv) {
  const long n = argc > 1 ? std::atol(argv[1]) : (1L << 25);
  if (n < 1000) {
    std::fprintf(stderr, "stream_triad: at least 1000 elements per array\n");
    return 2;
  }
  std::unique_ptr<double[]> a(new double[n]), b(new double[n]), c(new double[n]);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    a[i] = 0.0;
    b[i] = 1.0;
    c[i] = 2.0;
  }
  const double s = 3.0;
  double best = 1e30;
  for (int repeat = 0; repeat < 10; ++repeat) {
    const auto start = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best = std::min(best, seconds);
  }
  // The result is read, so that the loop cannot be dropped.
  if (a[n / 2] != 7.0) {
    std::fprintf(stderr, "stream_triad: wrong result %g\n", a[n / 2]);
    return 1;
  }
  std::printf("triad: %.1f GB/s (%ld elements per array, %d threads, best of 10: %.4f s)\n",
              24.0 * double(n) / best / 1e9, n, omp_get_max_threads(), best);
  return 0;
}
