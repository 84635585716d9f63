#pragma once
/// @file
/// task.csv sampled at a replay's frame times, read row by row in bounded memory: the tool and
/// target poses and the figures the page shows over the scene and in its plots.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace mjarm::web_detail {

/// Task.csv's @p columns at each of @p times (ascending): the last row at or before each time
/// (the first row for a time before it). Columns the file does not have are left out.
/// @throws Error as `plot::CsvRowReader` (a truncated or binary file, a row of other cells),
///         naming the line for a t that is not finite or goes back, or a cell that is not a
///         number; or when the file has no rows.
std::map<std::string, std::vector<double>> sample_task(const std::filesystem::path& task_csv,
                                                       const std::vector<std::string>& columns,
                                                       const std::vector<double>& times);

}  // namespace mjarm::web_detail
