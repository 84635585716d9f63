#pragma once
/// @file
/// `CsvTable`: a CSV file with a header row, read whole, its columns looked up by name — the
/// layers of a recording (see sim/recorder.hpp) as `mjarm plot` reads them.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace mjarm::plot {

/// A CSV file held in memory: a header of column names and rows of text cells. Cells may be
/// quoted ("a, b" and doubled quotes ""), as the recorder writes event messages.
class CsvTable {
 public:
  /// Reads @p path.
  /// @throws Error naming the file when it cannot be read, has no header row, or a row has a
  ///         different number of cells than the header (the row number is named).
  static CsvTable read(const std::filesystem::path& path);

  /// Reads the header row of @p path only (`rows()` is 0): a table whose rows are streamed
  /// (`CsvRowReader`).
  /// @throws Error as `CsvRowReader`.
  static CsvTable read_header(const std::filesystem::path& path);

  /// Parses CSV text; @p path only names the source in messages.
  /// @throws Error as `read`.
  static CsvTable parse(std::string_view text, const std::filesystem::path& path);

  /// Where the table came from.
  const std::filesystem::path& path() const noexcept { return path_; }
  /// The column names, in file order.
  const std::vector<std::string>& header() const noexcept { return header_; }
  /// Number of data rows (the header is not a row).
  std::size_t rows() const noexcept { return rows_.size(); }
  /// Index of column @p name, or −1 when there is none.
  int find(std::string_view name) const noexcept;
  /// True when column @p name exists.
  bool has(std::string_view name) const noexcept { return find(name) >= 0; }
  /// The names that start with @p prefix (e.g. "force."), in file order.
  std::vector<std::string> columns_with_prefix(std::string_view prefix) const;

  /// Column @p name as numbers ("nan" and "inf" are accepted; an empty cell is NaN).
  /// @throws Error naming the file and the column when it is missing (the columns that exist
  ///         are listed) or when a cell is not a number (its row is named).
  std::vector<double> numbers(std::string_view name) const;
  /// Column @p name as text.
  /// @throws Error naming the file and the column when it is missing.
  std::vector<std::string> text(std::string_view name) const;

 private:
  int require(std::string_view name) const;

  std::filesystem::path path_;
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

}  // namespace mjarm::plot
