#include "server/service/field_query.h"

#include <algorithm>

#include "server/service/request_validation.h"

namespace cascade::service {

namespace {

int phase_code(const std::string& phase) {
  if (phase == "water") return 0;
  if (phase == "soil") return 1;
  if (phase == "boundary") return 2;
  return -1;  // all
}

}  // namespace

grpc::Status FieldQuery::select(const v1::QueryFieldsRequest& request, std::shared_ptr<const FieldFrame> frame,
                                FieldQuery& query) {
  query = FieldQuery();
  for (int k = 0; k < request.fields_size(); ++k) {
    const auto* field = frame->find(request.fields(k));
    if (!field) {
      std::string known;
      for (const auto& f : frame->fields) known += (known.empty() ? "" : ", ") + f.name;
      return invalid("fields[" + std::to_string(k) + "]",
                     "no field '" + request.fields(k).substr(0, 80) + "' in this simulation (" + known + ")");
    }
    query.fields_.push_back(field);
  }
  const int phase = phase_code(request.phase());
  const std::size_t stride = std::max<std::uint32_t>(1, request.stride());
  std::size_t matched = 0;
  for (std::size_t i = 0; i < frame->size(); ++i) {
    if (phase >= 0 && frame->phase[i] != phase) continue;
    if (request.has_box()) {
      bool inside = true;
      for (int a = 0; a < 3; ++a) {
        const double x = frame->position[3 * i + a];
        inside &= x >= request.box().min(a) && x <= request.box().max(a);
      }
      if (!inside) continue;
    }
    if (matched++ % stride == 0) query.selected_.push_back(i);
  }
  std::size_t bytes = sizeof(std::uint32_t) * 2 + 3 * sizeof(double);  // id, phase, position
  for (const auto* f : query.fields_) bytes += sizeof(double) * std::size_t(f->components);
  query.per_chunk_ = std::max<std::size_t>(1, kChunkBytes / bytes);
  query.frame_ = std::move(frame);
  return grpc::Status::OK;
}

v1::FieldChunk FieldQuery::next_chunk() {
  const FieldFrame& frame = *frame_;
  const std::size_t end = std::min(selected_.size(), next_ + per_chunk_);
  v1::FieldChunk chunk;
  chunk.set_time(frame.time);
  chunk.set_step(frame.step);
  chunk.set_dimensions(std::uint32_t(frame.dimensions));
  chunk.set_first(next_);
  chunk.set_count(end - next_);
  for (std::size_t k = next_; k < end; ++k) {
    const std::size_t i = selected_[k];
    chunk.add_id(frame.id[i]);
    chunk.add_phase(frame.phase[i]);
    for (int a = 0; a < 3; ++a) chunk.add_position(frame.position[3 * i + a]);
  }
  for (const auto* f : fields_) {
    auto* values = chunk.add_fields();
    values->set_name(f->name);
    values->set_units(f->units);
    values->set_components(std::uint32_t(f->components));
    for (std::size_t k = next_; k < end; ++k)
      for (int c = 0; c < f->components; ++c) values->add_values(f->values[selected_[k] * std::size_t(f->components) + c]);
  }
  next_ = end;
  sent_any_ = true;
  return chunk;
}

}  // namespace cascade::service
