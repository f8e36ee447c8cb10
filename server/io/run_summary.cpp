#include "server/io/run_summary.h"

#include <cmath>
#include <cstdio>

#include "server/io/text_output.h"

namespace cascade {
namespace {

// Length of the valid UTF-8 sequence starting at text[i], or 0 if there is none.
std::size_t utf8_length(const std::string& text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = 0;
  if (lead >= 0xc2 && lead <= 0xdf)
    length = 2;
  else if (lead >= 0xe0 && lead <= 0xef)
    length = 3;
  else if (lead >= 0xf0 && lead <= 0xf4)
    length = 4;
  else
    return 0;
  if (i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k)
    if ((byte(i + k) & 0xc0) != 0x80) return 0;
  // Overlong forms, surrogates and code points above U+10FFFF.
  if (lead == 0xe0 && byte(i + 1) < 0xa0) return 0;
  if (lead == 0xed && byte(i + 1) > 0x9f) return 0;
  if (lead == 0xf0 && byte(i + 1) < 0x90) return 0;
  if (lead == 0xf4 && byte(i + 1) > 0x8f) return 0;
  return length;
}

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x80) {
      const std::size_t length = utf8_length(text, i);
      if (length == 0) {
        out += "\\ufffd";
        ++i;
      } else {
        out.append(text, i, length);
        i += length;
      }
      continue;
    }
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (c < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
          out += escaped;
        } else {
          out += static_cast<char>(c);
        }
    }
    ++i;
  }
  return out + "\"";
}

std::string json_number(double value) {
  return std::isfinite(value) ? format_double(value) : "null";
}

}  // namespace

std::string run_summary_json(const RunSummary& s) {
  const bool failed = s.status == RunSummary::Status::failed;
  std::string j = "{\n";
  j += "  \"format\": \"cascade-run-1\",\n";
  j += "  \"case\": " + json_string(s.case_name) + ",\n";
  j += "  \"status\": " + std::string(failed ? "\"failed\"" : "\"completed\"") + ",\n";
  if (failed) j += "  \"error\": " + json_string(s.error) + ",\n";
  j += "  \"precision\": " + json_string(s.precision) + ",\n";
  j += "  \"sim_time\": " + json_number(s.sim_time) + ",\n";
  j += "  \"steps\": " + std::to_string(s.steps) + ",\n";
  j += "  \"wall_seconds\": " + json_number(s.wall_seconds) + ",\n";
  j += "  \"particles\": {\"total\": " + std::to_string(s.particles.total) +
       ", \"water\": " + std::to_string(s.particles.water) +
       ", \"soil\": " + std::to_string(s.particles.soil) +
       ", \"boundary\": " + std::to_string(s.particles.boundary) + "},\n";
  j += "  \"particle_steps_per_second\": " + json_number(s.particle_steps_per_second) + ",\n";
  j += "  \"bytes_per_particle\": " + json_number(s.bytes_per_particle) + ",\n";
  j += "  \"lost_particles\": " + std::to_string(s.lost_particles) + ",\n";
  j += "  \"outputs\": {\"frames\": " + std::to_string(s.frames_written) +
       ", \"seconds\": " + json_number(s.output_seconds) + "},\n";
  if (s.processes > 1) {
    j += "  \"processes\": " + std::to_string(s.processes) + ",\n";
    j += "  \"process_particles\": [";
    for (std::size_t k = 0; k < s.process_particles.size(); ++k)
      j += (k ? ", " : "") + std::to_string(s.process_particles[k]);
    j += "],\n";
    j += "  \"exchange\": {\"seconds\": " + json_number(s.exchange_seconds) +
         ", \"bytes\": " + std::to_string(s.exchange_bytes) + "},\n";
    j += "  \"balance\": {\"work\": \"neighbour-list entries of the particles a process owns\", \"imbalance\": " +
         json_number(s.balance.last) + ", \"mean_imbalance\": " + json_number(s.balance.mean) +
         ", \"largest_imbalance\": " + json_number(s.balance.largest) + ", \"repartition_above\": " +
         json_number(kRepartitionImbalance) + ", \"rebuilds\": " + std::to_string(s.balance.rebuilds) +
         ", \"repartitions\": " + std::to_string(s.balance.repartitions) + ", \"by_rebuild\": \"balance.csv\"},\n";
  }
  if (s.pore_water.present)
    j += "  \"pore_water\": {\"rain\": " + json_number(s.pore_water.rain) + ", \"walls\": " +
         json_number(s.pore_water.walls) + ", \"surface\": " + json_number(s.pore_water.surface) + "},\n";
  if (s.terrain.present) {
    j += "  \"terrain\": {\"origin\": [" + json_number(s.terrain.origin[0]) + ", " + json_number(s.terrain.origin[1]) +
         "], \"frame\": \"x = X - origin[0], y = Y - origin[1] (2D: x = the distance along the section), z = "
         "elevation\", \"surface\": " + json_string(s.terrain.surface) + ", \"base\": " + json_string(s.terrain.base);
    if (!s.terrain.section.empty()) {
      j += ", \"section\": [";
      for (std::size_t k = 0; k < s.terrain.section.size(); ++k)
        j += (k ? ", [" : "[") + json_number(s.terrain.section[k][0]) + ", " + json_number(s.terrain.section[k][1]) + "]";
      j += "]";
    }
    j += ", \"crs\": " + json_string(s.terrain.crs) + "},\n";
  }
  j += "  \"events\": [";
  for (std::size_t i = 0; i < s.events.size(); ++i) {
    const RunEvent& e = s.events[i];
    j += (i == 0 ? "\n" : ",\n");
    j += "    {\"time\": " + json_number(e.time) + ", \"step\": " + std::to_string(e.step) +
         ", \"kind\": " + json_string(e.kind) + ", \"detail\": " + json_string(e.detail) + "}";
  }
  j += s.events.empty() ? "]\n" : "\n  ]\n";
  j += "}\n";
  return j;
}

void write_run_json(const std::filesystem::path& path, const RunSummary& summary) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  write_file_atomically(path, run_summary_json(summary));
}

void write_balance_csv(const std::filesystem::path& path, const LoadBalance& balance) {
  std::string csv = "step,time,imbalance,repartitioned\n";
  for (const auto& r : balance.rebuilds)
    csv += std::to_string(r.step) + "," + format_double(r.time) + "," + format_double(r.imbalance) + "," +
           (r.repartitioned ? "1" : "0") + "\n";
  write_file_atomically(path, csv);
}

}  // namespace cascade
