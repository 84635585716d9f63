#pragma once
// Small controllers and helpers for the sim tests (the real controllers live in control/).

#include <mujoco/mujoco.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "mjarm/control/controller.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm::test {

/// τ = Kp·(q_ref − q) − Kd·q̇ (+ qfrc_bias when `gravity`), q_ref = reference.joint.q.
class PdTorque final : public Controller {
 public:
  PdTorque(const Chain& chain, double kp, double kd, bool gravity = true)
      : chain_(chain), kp_(kp), kd_(kd), gravity_(gravity) {}
  std::string_view name() const noexcept override { return "test-pd"; }
  CommandKind command_kind() const noexcept override { return CommandKind::torque; }
  const Chain& chain() const noexcept override { return chain_; }
  void compute(const mjData& d, const Reference& reference, JointCommand& command) noexcept override {
    double norm = 0.0;
    for (int i = 0; i < chain_.size(); ++i) {
      const double q = d.qpos[chain_.qpos_address(i)];
      const double v = d.qvel[chain_.dof_address(i)];
      const double e = reference.joint.q.size() == chain_.size() ? reference.joint.q[i] - q : 0.0;
      command.value[i] = kp_ * e - kd_ * v + (gravity_ ? d.qfrc_bias[chain_.dof_address(i)] : 0.0);
      norm += e * e;
    }
    values_[0] = std::sqrt(norm);
  }
  std::span<const std::string> internal_names() const noexcept override { return names_; }
  std::span<const double> internal_values() const noexcept override { return values_; }

 private:
  Chain chain_;
  double kp_, kd_;
  bool gravity_;
  std::array<std::string, 1> names_{"error_norm"};
  std::array<double, 1> values_{0.0};
};

/// Writes reference.joint.q as position targets.
class PositionTarget final : public Controller {
 public:
  explicit PositionTarget(const Chain& chain) : chain_(chain) {}
  std::string_view name() const noexcept override { return "test-target"; }
  CommandKind command_kind() const noexcept override { return CommandKind::position; }
  const Chain& chain() const noexcept override { return chain_; }
  void compute(const mjData&, const Reference& reference, JointCommand& command) noexcept override {
    if (reference.joint.q.size() == chain_.size()) command.value = reference.joint.q;
  }

 private:
  Chain chain_;
};

/// A fixed command, except NaN on entry `bad` from time `bad_time` on.
class FixedTorque final : public Controller {
 public:
  FixedTorque(const Chain& chain, Eigen::VectorXd torque,
              double bad_time = std::numeric_limits<double>::infinity(), int bad = 0,
              CommandKind kind = CommandKind::torque)
      : chain_(chain), torque_(std::move(torque)), bad_time_(bad_time), bad_(bad), kind_(kind) {}
  std::string_view name() const noexcept override { return "fixed"; }
  CommandKind command_kind() const noexcept override { return kind_; }
  const Chain& chain() const noexcept override { return chain_; }
  void compute(const mjData& d, const Reference&, JointCommand& command) noexcept override {
    command.value = torque_;
    if (d.time >= bad_time_) command.value[bad_] = std::numeric_limits<double>::quiet_NaN();
  }

 private:
  Chain chain_;
  Eigen::VectorXd torque_;
  double bad_time_;
  int bad_;
  CommandKind kind_;
};

/// Records what it is shown (time, qpos, qvel, qfrc_bias) into preallocated storage, and writes
/// a smooth torque that depends on the state (so that a wrong state would change the run).
class Spy final : public Controller {
 public:
  Spy(const Chain& chain, int capacity) : chain_(chain) {
    const std::size_t n = static_cast<std::size_t>(capacity);
    time.reserve(n);
    qpos.reserve(n * chain.robot().nq());
    qvel.reserve(n * chain.robot().nv());
    bias.reserve(n * chain.robot().nv());
  }
  std::string_view name() const noexcept override { return "spy"; }
  CommandKind command_kind() const noexcept override { return CommandKind::torque; }
  const Chain& chain() const noexcept override { return chain_; }
  void compute(const mjData& d, const Reference&, JointCommand& command) noexcept override {
    const int nq = chain_.robot().nq(), nv = chain_.robot().nv();
    if (time.size() < time.capacity()) {
      time.push_back(d.time);
      qpos.insert(qpos.end(), d.qpos, d.qpos + nq);
      qvel.insert(qvel.end(), d.qvel, d.qvel + nv);
      bias.insert(bias.end(), d.qfrc_bias, d.qfrc_bias + nv);
    }
    for (int i = 0; i < chain_.size(); ++i) command.value[i] = torque(d, i);
  }
  /// The law, shared with the reference loops of the tests.
  double torque(const mjData& d, int i) const noexcept {
    const int dof = chain_.dof_address(i);
    return 0.9 * d.qfrc_bias[dof] - 3.0 * d.qvel[dof] + 2.0 * std::sin(5.0 * d.time + i);
  }
  std::vector<double> time, qpos, qvel, bias;

 private:
  Chain chain_;
};

/// A CSV file: header and rows of text fields (quotes handled).
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  bool ends_with_newline = false;

  int column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return static_cast<int>(i);
    }
    return -1;
  }
  double value(std::size_t row, const std::string& name) const {
    return std::stod(rows.at(row).at(column(name)));
  }
};

inline std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

inline Csv read_csv(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  Csv csv;
  csv.ends_with_newline = !text.empty() && text.back() == '\n';
  std::istringstream lines(text);
  std::string line;
  bool first = true;
  while (std::getline(lines, line)) {
    if (first) {
      csv.header = split_csv_line(line);
      first = false;
    } else {
      csv.rows.push_back(split_csv_line(line));
    }
  }
  return csv;
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

/// A fresh empty directory under the system's temp dir, removed on destruction.
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("mjarm_sim_" + tag + "_" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// Entries of @p dir whose name starts with ".partial-".
inline int partial_folders(const std::filesystem::path& dir) {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    n += entry.path().filename().string().rfind(".partial-", 0) == 0 ? 1 : 0;
  }
  return n;
}

}  // namespace mjarm::test
