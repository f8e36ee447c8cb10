// A QueryFields request applied to a frame: the selected particles (phase, box, stride) and
// fields, handed out as FieldChunks of whole particles under kChunkBytes each.
#pragma once

#include <grpcpp/support/status.h>

#include <memory>
#include <vector>

#include "cascade/v1/simulation.pb.h"
#include "server/core/field_frame.h"

namespace cascade::service {

class FieldQuery {
 public:
  // Well under gRPC's default 4 MiB message limit, whatever the fields.
  static constexpr std::size_t kChunkBytes = 1 << 20;

  // INVALID_ARGUMENT naming `fields[k]` when the frame has no such field. The request's other
  // fields are checked already (check_query).
  static grpc::Status select(const v1::QueryFieldsRequest& request, std::shared_ptr<const FieldFrame> frame,
                             FieldQuery& query);

  // True until every selected particle has been handed out; a query that selects nothing still
  // gives one (empty) chunk, so that the client learns the time and step.
  bool has_next() const { return !sent_any_ || next_ < selected_.size(); }
  v1::FieldChunk next_chunk();

 private:
  std::shared_ptr<const FieldFrame> frame_;
  std::vector<const FieldFrame::RealField*> fields_;
  std::vector<std::size_t> selected_;  // particle indices in the frame
  std::size_t per_chunk_ = 1;
  std::size_t next_ = 0;
  bool sent_any_ = false;
};

}  // namespace cascade::service
