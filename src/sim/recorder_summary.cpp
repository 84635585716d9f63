#include "recorder_summary.hpp"

#include <mujoco/mujoco.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>

#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/version.hpp"

namespace mjarm::sim_detail {
namespace {

std::string json_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
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
        if (static_cast<unsigned char>(c) < 0x20) {
          char escape[8];
          std::snprintf(escape, sizeof(escape), "\\u%04x", c);
          out += escape;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string number(double v) {
  if (!std::isfinite(v)) return "null";  // JSON has no NaN/inf
  char text[32];
  const auto [end, ec] = std::to_chars(text, text + sizeof(text), v);
  return ec == std::errc() ? std::string(text, end) : "null";
}

std::string invocation_json(const SummaryInfo::Invocation& in) {
  std::string command_line = "[";
  for (std::size_t k = 0; k < in.command_line.size(); ++k)
    command_line += (k ? ", " : "") + json_string(in.command_line[k]);
  return "{\"command_line\": " + command_line +
         "], \"working_directory\": " + json_string(in.working_directory) +
         ", \"pid\": " + std::to_string(in.pid) + ", \"started\": " + json_string(in.started) +
         ", \"seed\": " + (in.has_seed ? std::to_string(in.seed) : std::string("null")) +
         ", \"mjarm_version\": " + json_string(in.mjarm_version) +
         ", \"mujoco_version\": " + json_string(in.mujoco_version) + "}";
}

}  // namespace

SummaryInfo::Invocation current_invocation(const std::uint64_t* seed) {
  SummaryInfo::Invocation in;
  // the arguments as the program got them, NUL-separated (Linux)
  std::ifstream cmdline("/proc/self/cmdline", std::ios::binary);
  std::string argument;
  while (std::getline(cmdline, argument, '\0')) in.command_line.push_back(argument);
  std::error_code ec;
  in.working_directory = std::filesystem::current_path(ec).string();
  in.pid = static_cast<long>(::getpid());
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char started[32];
  std::strftime(started, sizeof(started), "%Y-%m-%dT%H:%M:%SZ", &utc);
  in.started = started;
  in.has_seed = seed != nullptr;
  in.seed = seed != nullptr ? *seed : 0;
  in.mjarm_version = version();
  in.mujoco_version = mj_versionString();
  return in;
}

std::string summary_json(const SummaryInfo& info) {
  std::string j = "{\n";
  auto field = [&](const char* key, const std::string& value, bool last = false) {
    j += "  " + json_string(key) + ": " + value + (last ? "\n" : ",\n");
  };
  field("invocation", invocation_json(info.invocation));
  field("model", json_string(info.model));
  field("source", json_string(info.source));
  field("mode", json_string(info.mode));
  field("integrator", json_string(info.integrator));
  field("timestep", number(info.timestep));
  field("control_period", number(info.control_period));
  field("steps_per_tick", std::to_string(info.steps_per_tick));
  field("state_decimation", std::to_string(info.state_decimation));
  field("frame", json_string(info.frame));
  field("status", json_string(info.status));
  field("message", json_string(info.message));
  if (!info.write_error.empty()) field("write_error", json_string(info.write_error));
  field("start_time", number(info.start_time));
  field("end_time", number(info.end_time));
  field("duration", number(info.end_time - info.start_time));
  field("counts", "{\"state_rows\": " + std::to_string(info.state_rows) +
                      ", \"task_rows\": " + std::to_string(info.task_rows) +
                      ", \"events\": " + std::to_string(info.event_rows) + "}");
  std::string controllers = "[";
  for (std::size_t c = 0; c < info.controllers.size(); ++c) {
    const auto& ci = info.controllers[c];
    std::string joints = "[";
    for (std::size_t k = 0; k < ci.joints.size(); ++k)
      joints += (k ? ", " : "") + json_string(ci.joints[k]);
    controllers += std::string(c ? ", " : "") + "{\"name\": " + json_string(ci.name) +
                   ", \"command\": " + json_string(ci.command) + ", \"joints\": " + joints + "]}";
  }
  field("controllers", controllers + "]");
  std::string saturation = "{";
  for (std::size_t k = 0; k < info.saturation.size(); ++k) {
    saturation += (k ? ", " : "") + json_string(info.saturation[k].actuator) + ": " +
                  std::to_string(info.saturation[k].ticks);
  }
  field("saturated_ticks", saturation + "}");
  std::string actuators = "[";
  for (std::size_t k = 0; k < info.actuators.size(); ++k) {
    const auto& a = info.actuators[k];
    const std::string range =
        a.force_limited ? "[" + number(a.force_lower) + ", " + number(a.force_upper) + "]" : "null";
    actuators += std::string(k ? ", " : "") + "{\"name\": " + json_string(a.name) +
                 ", \"kind\": " + json_string(a.kind) + ", \"joint\": " + json_string(a.joint) +
                 ", \"gear\": " + number(a.gear) + ", \"force_range\": " + range + "}";
  }
  field("actuators", actuators + "]");
  std::string files = "{";
  for (std::size_t k = 0; k < info.files.size(); ++k) {
    files += (k ? ", " : "") + json_string(info.files[k].layer) +
             ": {\"file\": " + json_string(info.files[k].name) +
             ", \"columns\": " + std::to_string(info.files[k].columns) + "}";
  }
  field("files", files + "}", true);
  return j + "}\n";
}

void write_summary(const std::filesystem::path& path, const SummaryInfo& info) {
  const std::string text = summary_json(info);
  // in place: the staging folder is what makes the recording atomic
  FileWriter file(path, FileWriter::Mode::in_place, {}, text.size() + 1);
  file.write(text);
  if (!file.close()) throw Error(file.failure());
}

}  // namespace mjarm::sim_detail
