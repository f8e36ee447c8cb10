// Transport (server/core/partition.h) over an MPI communicator: one process per rank.
#pragma once

#include <mpi.h>

#include "server/core/partition.h"

namespace cascade {

// MPI_Init on construction and MPI_Finalize on destruction, for a program launched by mpirun.
// `threads`: MPI called from several threads at once (the split server's sessions), which the MPI
// library must provide (MPI_THREAD_MULTIPLE) or the constructor throws.
class MpiSession {
 public:
  MpiSession(int* argc, char*** argv, bool threads = false);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

class MpiTransport final : public Transport {
 public:
  // Over `communicator` (MPI_COMM_WORLD, or a part of it); MPI must be initialised.
  explicit MpiTransport(MPI_Comm communicator = MPI_COMM_WORLD);
  int processes() const override { return processes_; }
  int process() const override { return process_; }
  double minimum(double value) override { return reduce(value, MPI_MIN); }
  double maximum(double value) override { return reduce(value, MPI_MAX); }
  double sum(double value) override { return reduce(value, MPI_SUM); }
  std::vector<std::vector<char>> exchange(const std::vector<std::vector<char>>& send) override;
  // With MPI-IO (MPI_File_write_at), which handles a file system shared between nodes (NFS's
  // locking included) as plain writes from each node would not.
  void write_pieces(const std::string& path, const std::vector<FilePiece>& pieces) override;

 private:
  double reduce(double value, MPI_Op op);
  MPI_Comm communicator_;
  int processes_ = 1;
  int process_ = 0;
};

}  // namespace cascade
