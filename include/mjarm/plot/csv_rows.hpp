#pragma once
/// @file
/// `CsvRowReader`: a CSV file with a header row read one row at a time, in bounded memory — a
/// recording's state.csv or task.csv of any length (10⁷ rows are gigabytes), where `CsvTable`
/// holds the whole file.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace mjarm {
class UserFileReader;
}

namespace mjarm::plot {

/// Reads a CSV file row by row. Cells may be quoted as `CsvTable` reads them (commas, doubled
/// quotes and line ends inside quotes). Memory: a read buffer of 1 MiB and one row (a row longer
/// than 64 MiB is refused: no table of numbers has one, a binary file may).
class CsvRowReader {
 public:
  /// Opens @p path (through the checked `UserFileReader`) and reads its header row.
  /// @param what  how errors name the file, e.g. "recorded table".
  /// @throws Error naming the file when it cannot be read, is empty, has an empty header, or
  ///         holds a NUL byte (a binary file).
  CsvRowReader(const std::filesystem::path& path, std::string_view what);
  ~CsvRowReader();
  CsvRowReader(const CsvRowReader&) = delete;
  CsvRowReader& operator=(const CsvRowReader&) = delete;

  const std::filesystem::path& path() const noexcept { return path_; }
  /// The column names, in file order.
  const std::vector<std::string>& header() const noexcept { return header_; }
  /// Index of column @p name, or −1 when there is none.
  int find(std::string_view name) const noexcept;
  /// Index of column @p name.
  /// @throws Error naming the file and the column when it is missing (the columns are listed).
  std::size_t require(std::string_view name) const;

  /// Moves to the next data row (blank lines are skipped); false at the end of the file.
  /// @throws Error naming the file and the line for a row with another number of cells than
  ///         the header, a last row without its line end (a file cut in the middle of a row), a
  ///         NUL byte or a row over 64 MiB (a binary file), or a failed read.
  bool next();
  /// Data rows read so far (the current one included).
  std::size_t rows() const noexcept { return rows_; }
  /// 1-based line of the current row in the file.
  std::size_t line() const noexcept { return line_; }
  /// The current row's cell in @p column (valid until the next call to `next`).
  std::string_view cell(std::size_t column) const { return cells_[column]; }
  /// The current row's cell in @p column as a number ("nan" and "inf" are read; an empty cell is
  /// NaN).
  /// @throws Error naming the file, the column and the line when it is not a number.
  double number(std::size_t column) const;

 private:
  bool next_record(std::string_view& record);
  void split(std::string_view record);
  [[noreturn]] void fail(const std::string& what) const;

  std::filesystem::path path_;
  std::unique_ptr<UserFileReader> file_;
  std::vector<char> buffer_;
  std::size_t begin_ = 0, end_ = 0;  // unread bytes: buffer_[begin_, end_)
  bool eof_ = false;
  std::vector<std::string> header_;
  std::vector<std::string_view> cells_;
  std::vector<std::string> unquoted_;  // quoted cells, unescaped
  std::size_t rows_ = 0, line_ = 0, next_line_ = 1;
};

}  // namespace mjarm::plot
