#pragma once
// A CSV file written row by row without allocating: numbers are formatted with std::to_chars
// (shortest round-trip form) into a preallocated row buffer, and a `FileWriter` (in place: the
// recorder's staging folder makes the recording atomic) checks every write.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/file_writer.hpp"

namespace mjarm::sim_detail {

class CsvStream {
 public:
  /// Opens @p path for writing and writes the header row.
  /// @param text_bytes room for text fields in one row (beyond 32 bytes per column)
  /// @throws Error when the file cannot be opened or written.
  CsvStream(const std::filesystem::path& path, const std::vector<std::string>& columns,
            int flush_rows, std::size_t text_bytes = 0);
  ~CsvStream();
  CsvStream(const CsvStream&) = delete;
  CsvStream& operator=(const CsvStream&) = delete;

  void add(double value) noexcept;
  /// A text field, quoted when it holds a comma, a quote or a line break; cut to fit the row.
  void add_text(std::string_view text) noexcept;
  /// Writes the row; flushes every `flush_rows` rows. Once a write failed, rows are counted
  /// but no longer written (see `error()`).
  void end_row() noexcept;
  /// Pushes buffered rows to the operating system.
  void flush() noexcept;
  /// Flushes, syncs to disk and closes. False (with `error()` set) when any write failed.
  bool close() noexcept;

  std::int64_t rows() const noexcept { return rows_; }
  int columns() const noexcept { return columns_; }
  /// errno of the first failed write, 0 when none.
  int error() const noexcept { return file_.error(); }
  /// "cannot write '<path>': <reason>" for the first failure; empty when none.
  std::string failure() const { return file_.failure(); }
  const std::filesystem::path& path() const noexcept { return file_.path(); }

 private:
  void separator() noexcept;

  FileWriter file_;
  std::vector<char> row_;
  std::size_t used_ = 0;
  int fields_ = 0;
  int columns_ = 0;
  int flush_rows_ = 1;
  std::int64_t rows_ = 0;
};

}  // namespace mjarm::sim_detail
