// MPI around Google Test for the programs of tests/parallel: every process runs every test; only
// process 0 prints gtest's report, and a failure on any process fails its exit code, which mpirun
// returns. `world` is set to the transport over all processes while the tests run.
#pragma once

#include <gtest/gtest.h>
#include <omp.h>

#include "server/parallel/mpi_transport.h"

namespace cascade::testing {

inline int mpi_test_main(int argc, char** argv, MpiTransport*& world) {
  MpiSession mpi(&argc, &argv);
  MpiTransport transport;
  world = &transport;
  omp_set_num_threads(1);  // the processes share the cores
  ::testing::InitGoogleTest(&argc, argv);
  if (transport.process() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int failed = RUN_ALL_TESTS();
  world = nullptr;
  return failed;
}

}  // namespace cascade::testing
