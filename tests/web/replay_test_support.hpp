#pragma once
// The replay tests' recordings (a swing of a hinge recorded by the real Simulation and Recorder)
// and a replay file read back: its JSON block, and the base64 arrays in it.

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "mjarm/model/chain.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/sim/simulation.hpp"
#include "sim/sim_test_support.hpp"

namespace mjarm::test {

/// Records @p duration seconds of @p robot (a site "tip", a hinge "swing" actuated) into @p dir:
/// a PD on the joints swings the hinge towards 1.2 rad, one phase "swing".
inline void record_swing(const Robot& robot, const std::filesystem::path& dir, double duration) {
  const Chain chain(robot, "tip");
  SimulationOptions options;
  options.control_period = 0.004;
  Simulation sim(robot, options);
  PdTorque pd(chain, 5.0, 0.1, false);
  sim.add_controller(pd);
  Recorder recorder(sim, dir);
  Reference reference;
  reference.joint.q = Eigen::VectorXd::Constant(chain.size(), 1.2);
  ConstantReferenceSource source(reference);
  recorder.event(0.0, "phase", "swing");
  const RunResult run = sim.run(source, duration, &recorder);
  recorder.finalize(run);
}

inline std::string slurp_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::vector<unsigned char> unbase64(const std::string& text) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    return c == '+' ? 62 : c == '/' ? 63 : -1;
  };
  std::vector<unsigned char> bytes;
  unsigned bits = 0;
  int count = 0;
  for (char c : text) {
    const int v = value(c);
    if (v < 0) break;  // padding
    bits = (bits << 6) | static_cast<unsigned>(v);
    count += 6;
    if (count >= 8) {
      count -= 8;
      bytes.push_back(static_cast<unsigned char>((bits >> count) & 0xFF));
    }
  }
  return bytes;
}

inline std::vector<float> unbase64_floats(const std::string& text) {
  const std::vector<unsigned char> bytes = unbase64(text);
  std::vector<float> values(bytes.size() / 4);
  std::memcpy(values.data(), bytes.data(), values.size() * 4);
  return values;
}

// the JSON block of a replay file
inline nlohmann::json data_block(const std::filesystem::path& html) {
  const std::string text = slurp_file(html);
  const std::string open = R"(<script type="application/json" id="mjarm-replay-data">)";
  const std::size_t begin = text.find(open);
  EXPECT_NE(begin, std::string::npos);
  const std::size_t end = text.find("</script>", begin);
  return nlohmann::json::parse(text.substr(begin + open.size(), end - begin - open.size()));
}

}  // namespace mjarm::test
