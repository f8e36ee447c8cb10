// A Transport that counts what passes through it: the bytes this process sends to the others and
// the wall time it spends in the transport's calls, waiting for the other processes included (a
// slower process shows as time the others spend here). For run.json and bench/split_scaling.py.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "server/core/partition.h"

namespace cascade {

class MeasuredTransport final : public Transport {
 public:
  explicit MeasuredTransport(Transport& inner) : inner_(inner) {}

  int processes() const override { return inner_.processes(); }
  int process() const override { return inner_.process(); }
  double minimum(double value) override { return timed([&] { return inner_.minimum(value); }); }
  double maximum(double value) override { return timed([&] { return inner_.maximum(value); }); }
  double sum(double value) override { return timed([&] { return inner_.sum(value); }); }
  std::vector<std::vector<char>> exchange(const std::vector<std::vector<char>>& send) override {
    for (int r = 0; r < int(send.size()); ++r)
      if (r != process()) bytes_sent_ += send[r].size();
    return timed([&] { return inner_.exchange(send); });
  }

  // Not counted: a frame's write is an output's time (run.json's outputs), not the exchange's.
  void write_pieces(const std::string& path, const std::vector<FilePiece>& pieces) override {
    inner_.write_pieces(path, pieces);
  }

  double seconds() const { return seconds_; }               // in the transport's calls so far
  std::uint64_t bytes_sent() const { return bytes_sent_; }  // to the other processes so far

 private:
  template <typename F>
  auto timed(F&& call) -> decltype(call()) {
    const auto start = std::chrono::steady_clock::now();
    auto result = call();
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }

  Transport& inner_;
  double seconds_ = 0;
  std::uint64_t bytes_sent_ = 0;
};

}  // namespace cascade
