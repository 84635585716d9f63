#include "mjarm/plot/csv_table.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "mjarm/error.hpp"
#include "mjarm/model/user_file.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/plot/csv_rows.hpp"
#include "quoted_path.hpp"

namespace mjarm::plot {
namespace {

// Splits one record starting at text[pos]; a quoted cell may hold commas, doubled quotes and
// newlines. Leaves pos after the record's line end.
std::vector<std::string> split_record(std::string_view text, std::size_t& pos) {
  std::vector<std::string> cells(1);
  bool in_quotes = false;
  while (pos < text.size()) {
    const char c = text[pos++];
    if (in_quotes) {
      if (c == '"' && pos < text.size() && text[pos] == '"') {
        cells.back() += '"';
        ++pos;
      } else if (c == '"') {
        in_quotes = false;
      } else {
        cells.back() += c;
      }
    } else if (c == '"') {
      in_quotes = true;
    } else if (c == ',') {
      cells.emplace_back();
    } else if (c == '\n') {
      break;
    } else if (c != '\r') {
      cells.back() += c;
    }
  }
  return cells;
}

bool parse_number(const std::string& cell, double& value) {
  if (cell.empty()) {
    value = std::nan("");
    return true;
  }
  const auto number = number_from_text(cell);  // also reads "nan", "inf", "-inf"
  if (number) value = *number;
  return number.has_value();
}

}  // namespace

CsvTable CsvTable::read(const std::filesystem::path& path) {
  return parse(read_user_file(path, "recorded table", kMaxDataFileBytes), path);
}

CsvTable CsvTable::read_header(const std::filesystem::path& path) {
  const CsvRowReader reader(path, "recorded table");
  CsvTable table;
  table.path_ = path;
  table.header_ = reader.header();
  return table;
}

CsvTable CsvTable::parse(std::string_view text, const std::filesystem::path& path) {
  CsvTable table;
  table.path_ = path;
  std::size_t pos = 0;
  if (text.empty()) throw Error(quoted(path) + " is empty: expected a header row of column names");
  table.header_ = split_record(text, pos);
  if (table.header_.size() == 1 && table.header_[0].empty())
    throw Error(quoted(path) + " has an empty header row: expected column names");
  while (pos < text.size()) {
    const std::size_t line = table.rows_.size() + 2;  // 1-based, after the header
    std::vector<std::string> cells = split_record(text, pos);
    if (cells.size() == 1 && cells[0].empty()) continue;  // blank line
    if (cells.size() != table.header_.size()) {
      throw Error(quoted(path) + " line " + std::to_string(line) + " has " +
                  std::to_string(cells.size()) + " cells, the header has " +
                  std::to_string(table.header_.size()) + " (a truncated or damaged file?)");
    }
    table.rows_.push_back(std::move(cells));
  }
  return table;
}

int CsvTable::find(std::string_view name) const noexcept {
  for (std::size_t i = 0; i < header_.size(); ++i)
    if (header_[i] == name) return static_cast<int>(i);
  return -1;
}

std::vector<std::string> CsvTable::columns_with_prefix(std::string_view prefix) const {
  std::vector<std::string> names;
  for (const std::string& h : header_)
    if (h.size() > prefix.size() && h.compare(0, prefix.size(), prefix) == 0) names.push_back(h);
  return names;
}

int CsvTable::require(std::string_view name) const {
  const int column = find(name);
  if (column >= 0) return column;
  std::string names;
  for (std::size_t i = 0; i < header_.size() && i < 12; ++i) names += (i ? ", " : "") + header_[i];
  if (header_.size() > 12) names += ", … (" + std::to_string(header_.size()) + " in all)";
  throw Error(quoted(path_) + " has no column '" + std::string(name) + "' (columns: " + names +
              ")");
}

std::vector<double> CsvTable::numbers(std::string_view name) const {
  const auto column = static_cast<std::size_t>(require(name));
  std::vector<double> values(rows_.size());
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    if (!parse_number(rows_[r][column], values[r])) {
      throw Error(quoted(path_) + " column '" + std::string(name) + "' line " +
                  std::to_string(r + 2) + ": '" + rows_[r][column] + "' is not a number");
    }
  }
  return values;
}

std::vector<std::string> CsvTable::text(std::string_view name) const {
  const auto column = static_cast<std::size_t>(require(name));
  std::vector<std::string> values;
  values.reserve(rows_.size());
  for (const auto& row : rows_) values.push_back(row[column]);
  return values;
}

}  // namespace mjarm::plot
