#include "server/service/checkpoint_store.h"

#include <algorithm>
#include <cstdio>

#include "server/io/checkpoint_file.h"
#include "server/service/request_validation.h"

namespace cascade::service {

namespace {
const std::string kCollection = "/checkpoints/";
}

std::filesystem::path checkpoint_directory(const std::filesystem::path& simulation_directory) {
  return simulation_directory / "checkpoints";
}

std::filesystem::path next_checkpoint_path(const std::filesystem::path& simulation_directory) {
  const auto directory = checkpoint_directory(simulation_directory);
  for (unsigned n = 1;; ++n) {
    char id[24];
    std::snprintf(id, sizeof id, "ckpt-%04u.h5", n);
    if (!std::filesystem::exists(directory / id)) return directory / id;
  }
}

std::string checkpoint_name(const std::string& simulation_name, const std::filesystem::path& path) {
  return simulation_name + kCollection + path.stem().string();
}

grpc::Status parse_checkpoint_name(const std::string& field, const std::string& name, std::string& simulation_id,
                                   std::string& checkpoint_id) {
  const auto split = name.find(kCollection);
  if (split == std::string::npos)
    return invalid(field, "'" + name + "' is not simulations/{id}/checkpoints/{checkpoint_id}");
  if (auto status = check_simulation_name(field, name.substr(0, split), simulation_id); !status.ok()) return status;
  checkpoint_id = name.substr(split + kCollection.size());
  return check_simulation_id(field, checkpoint_id);
}

v1::Checkpoint describe_checkpoint(const std::string& simulation_name, const std::filesystem::path& path) {
  const CheckpointSummary summary = read_checkpoint_summary(path);
  v1::Checkpoint c;
  c.set_name(checkpoint_name(simulation_name, path));
  c.set_case_name(summary.case_name);
  c.set_time(summary.time);
  c.set_step(summary.step);
  c.set_wall_time(summary.wall_time);
  c.set_particle_count(summary.particles);
  c.set_path(path.string());
  return c;
}

std::vector<v1::Checkpoint> list_checkpoints(const std::string& simulation_name,
                                             const std::filesystem::path& simulation_directory) {
  std::vector<std::filesystem::path> files;
  std::error_code missing;
  for (const auto& entry : std::filesystem::directory_iterator(checkpoint_directory(simulation_directory), missing))
    if (entry.path().extension() == ".h5") files.push_back(entry.path());
  std::sort(files.begin(), files.end());  // ckpt-NNNN: the order taken
  std::vector<v1::Checkpoint> checkpoints;
  for (const auto& file : files) {
    try {
      checkpoints.push_back(describe_checkpoint(simulation_name, file));
    } catch (const std::exception& e) {  // one unreadable file hid every checkpoint (issue 14)
      v1::Checkpoint c;
      c.set_name(checkpoint_name(simulation_name, file));
      c.set_path(file.string());
      c.set_error(e.what());
      checkpoints.push_back(std::move(c));
    }
  }
  return checkpoints;
}

}  // namespace cascade::service
