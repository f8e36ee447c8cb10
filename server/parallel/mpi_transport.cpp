#include "server/parallel/mpi_transport.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace cascade {

MpiSession::MpiSession(int* argc, char*** argv, bool threads) {
  int ready = 0;
  MPI_Initialized(&ready);
  if (!ready) {
    int provided = MPI_THREAD_SINGLE;
    MPI_Init_thread(argc, argv, threads ? MPI_THREAD_MULTIPLE : MPI_THREAD_FUNNELED, &provided);
    if (threads && provided < MPI_THREAD_MULTIPLE) {
      MPI_Finalize();
      throw std::runtime_error("the MPI library does not let several threads call it at once (MPI_THREAD_MULTIPLE)");
    }
  }
  // A failure is reported by the process that meets it, as an exception like any other; the
  // default handler would abort every process without a message.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
}

MpiSession::~MpiSession() {
  int done = 0;
  MPI_Finalized(&done);
  if (!done) MPI_Finalize();
}

MpiTransport::MpiTransport(MPI_Comm communicator) : communicator_(communicator) {
  MPI_Comm_size(communicator_, &processes_);
  MPI_Comm_rank(communicator_, &process_);
}

double MpiTransport::reduce(double value, MPI_Op op) {
  double result = 0;
  if (MPI_Allreduce(&value, &result, 1, MPI_DOUBLE, op, communicator_) != MPI_SUCCESS)
    throw std::runtime_error("MPI_Allreduce failed");
  return result;
}

// The sizes first (one all-to-all), then the bytes (MPI_Alltoallv; a message between two
// processes is limited to 2 GiB by MPI's int counts).
std::vector<std::vector<char>> MpiTransport::exchange(const std::vector<std::vector<char>>& send) {
  if (int(send.size()) != processes_) throw std::invalid_argument("exchange needs one message per process");
  std::vector<int> send_count(processes_), receive_count(processes_), send_at(processes_), receive_at(processes_);
  for (int r = 0; r < processes_; ++r) {
    if (send[r].size() > std::size_t(std::numeric_limits<int>::max()))
      throw std::runtime_error("a message to process " + std::to_string(r) + " exceeds 2 GiB");
    send_count[r] = int(send[r].size());
  }
  if (MPI_Alltoall(send_count.data(), 1, MPI_INT, receive_count.data(), 1, MPI_INT, communicator_) != MPI_SUCCESS)
    throw std::runtime_error("MPI_Alltoall failed");
  std::vector<char> out, in;
  int total_out = 0, total_in = 0;
  for (int r = 0; r < processes_; ++r) {
    send_at[r] = total_out, total_out += send_count[r];
    receive_at[r] = total_in, total_in += receive_count[r];
  }
  out.resize(std::size_t(total_out));
  for (int r = 0; r < processes_; ++r) std::copy(send[r].begin(), send[r].end(), out.begin() + send_at[r]);
  in.resize(std::size_t(total_in));
  if (MPI_Alltoallv(out.data(), send_count.data(), send_at.data(), MPI_BYTE, in.data(), receive_count.data(),
                    receive_at.data(), MPI_BYTE, communicator_) != MPI_SUCCESS)
    throw std::runtime_error("MPI_Alltoallv failed");
  std::vector<std::vector<char>> received(processes_);
  for (int r = 0; r < processes_; ++r)
    received[r].assign(in.begin() + receive_at[r], in.begin() + receive_at[r] + receive_count[r]);
  return received;
}

void MpiTransport::write_pieces(const std::string& path, const std::vector<FilePiece>& pieces) {
  MPI_File file;
  if (MPI_File_open(communicator_, path.c_str(), MPI_MODE_WRONLY, MPI_INFO_NULL, &file) != MPI_SUCCESS)
    throw std::runtime_error("MPI-IO: cannot open " + path + " to write");
  std::string failure;
  for (const FilePiece& piece : pieces) {
    const char* bytes = static_cast<const char*>(piece.bytes);
    for (std::size_t done = 0; done < piece.size && failure.empty();) {
      const int count = int(std::min<std::size_t>(piece.size - done, std::size_t(1) << 30));  // MPI's int counts
      MPI_Status status;
      if (MPI_File_write_at(file, MPI_Offset(piece.offset + done), bytes + done, count, MPI_BYTE, &status) != MPI_SUCCESS)
        failure = "MPI-IO: cannot write " + std::to_string(count) + " bytes at " + std::to_string(piece.offset + done) +
                  " in " + path;
      done += std::size_t(count);
    }
  }
  if (MPI_File_close(&file) != MPI_SUCCESS && failure.empty()) failure = "MPI-IO: cannot close " + path;
  if (!failure.empty()) throw std::runtime_error(failure);
}

}  // namespace cascade
