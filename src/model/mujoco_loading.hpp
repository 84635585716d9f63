#pragma once
// How the model room lets MuJoCo parse and compile (robot.cpp, mjcf_spec.cpp): one XML parser at
// a time, and MuJoCo's warnings collected per thread for the robot's load report.

#include <mutex>
#include <string>
#include <vector>

namespace mjarm::model_detail {

/// MuJoCo's XML parser keeps the last parsed model in a global (for mj_saveLastXML): parses from
/// several threads (parallel trial batches) take turns on this mutex.
std::mutex& xml_loader_mutex();

/// Collects MuJoCo's warnings (mju_warning) on this thread into a sink while it lives; they are
/// printed to stderr as well.
class LoadWarnings {
 public:
  explicit LoadWarnings(std::vector<std::string>& sink);
  ~LoadWarnings();
  LoadWarnings(const LoadWarnings&) = delete;
  LoadWarnings& operator=(const LoadWarnings&) = delete;

 private:
  std::vector<std::string>* previous_;
};

/// The message MuJoCo left in a load's error buffer although the load succeeded (a warning of
/// the parser or the compiler), as @p mapped (its lines mapped back to the user's files). MuJoCo
/// 4 also sends it to the log handler, so it is usually in @p warnings already: it is kept once,
/// in its mapped form; one that is new is printed and added.
void add_load_message(std::vector<std::string>& warnings, const char* raw, std::string mapped);

}  // namespace mjarm::model_detail
