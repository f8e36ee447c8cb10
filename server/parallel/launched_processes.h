// The processes of an mpirun launch, from Open MPI's or MPICH's environment (1 without one): what
// `cascade run` and `cascade-server` split their work over (issue 17).
#pragma once

#include <algorithm>
#include <cstdlib>

namespace cascade {

inline int launched_processes() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* value = std::getenv(name)) return std::max(1, std::atoi(value));
  return 1;
}

}  // namespace cascade
