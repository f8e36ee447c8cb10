// Where a simulation's checkpoints live and how they are named: DIR/simulations/{id}/checkpoints/
// {checkpoint_id}.h5, resource `simulations/{id}/checkpoints/{checkpoint_id}`, ids ckpt-0001,
// ckpt-0002, ... in the order taken. The files outlive the server process: a new one with the
// same --data-dir lists and restores them.
#pragma once

#include <grpcpp/support/status.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cascade/v1/checkpoint.pb.h"

namespace cascade::service {

std::filesystem::path checkpoint_directory(const std::filesystem::path& simulation_directory);
// The path of the next checkpoint of a simulation (the first free ckpt-NNNN).
std::filesystem::path next_checkpoint_path(const std::filesystem::path& simulation_directory);
// simulations/{id}/checkpoints/{checkpoint_id} of a checkpoint file.
std::string checkpoint_name(const std::string& simulation_name, const std::filesystem::path& path);

// `name` is simulations/{id}/checkpoints/{checkpoint_id} with valid ids; INVALID_ARGUMENT naming
// `field` otherwise.
grpc::Status parse_checkpoint_name(const std::string& field, const std::string& name, std::string& simulation_id,
                                   std::string& checkpoint_id);

// The message of one checkpoint file (its attributes only). Throws std::runtime_error.
v1::Checkpoint describe_checkpoint(const std::string& simulation_name, const std::filesystem::path& path);
// Every checkpoint of the simulation, oldest first; none when it has no checkpoint directory.
std::vector<v1::Checkpoint> list_checkpoints(const std::string& simulation_name,
                                             const std::filesystem::path& simulation_directory);

}  // namespace cascade::service
