#include "replay_task.hpp"

#include <limits>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/plot/csv_rows.hpp"
#include "replay_frames.hpp"

namespace mjarm::web_detail {

std::map<std::string, std::vector<double>> sample_task(const std::filesystem::path& task_csv,
                                                       const std::vector<std::string>& columns,
                                                       const std::vector<double>& times) {
  plot::CsvRowReader task(task_csv, "recorded table");
  const std::size_t t_column = task.require("t");
  std::vector<std::size_t> found;
  std::vector<std::string> names;
  for (const std::string& name : columns) {
    if (task.find(name) < 0) continue;
    found.push_back(static_cast<std::size_t>(task.find(name)));
    names.push_back(name);
  }
  std::map<std::string, std::vector<double>> out;
  for (const std::string& name : names) out[name].reserve(times.size());

  // the row before the current one, held as text until a frame time says it is the last at or
  // before it
  std::vector<std::string> held(found.size());
  std::size_t held_line = 0;
  auto give = [&] {
    for (std::size_t i = 0; i < found.size(); ++i) {
      const std::string& text = held[i];
      double value = std::numeric_limits<double>::quiet_NaN();
      if (!text.empty()) {
        const auto number = number_from_text(text);
        if (!number) {
          throw Error("'" + task_csv.string() + "' column '" + names[i] + "' line " +
                      std::to_string(held_line) + ": '" + text + "' is not a number");
        }
        value = *number;
      }
      out[names[i]].push_back(value);
    }
  };
  auto hold = [&] {
    held_line = task.line();
    for (std::size_t i = 0; i < found.size(); ++i) held[i].assign(task.cell(found[i]));
  };
  std::size_t f = 0;
  double previous = -std::numeric_limits<double>::infinity();
  while (task.next()) {
    const double t = recorded_time(task, t_column, previous);
    if (task.rows() == 1) hold();  // times before the first row show it
    for (; f < times.size() && times[f] + 1e-12 < t; ++f) give();
    hold();
    previous = t;
  }
  if (task.rows() == 0)
    throw Error("'" + task_csv.string() +
                "' has no rows (the run never ticked): nothing to replay");
  for (; f < times.size(); ++f) give();
  return out;
}

}  // namespace mjarm::web_detail
