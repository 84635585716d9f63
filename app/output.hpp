#pragma once
/// @file
/// Printing shared by the `mjarm` commands: aligned tables, number formatting, JSON conversion
/// of Eigen objects, a progress line on an interactive terminal, and the error type for bad
/// command lines.

#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mjarm/json_or_null.hpp"

namespace mjarm::cli {

/// JSON documents keep their keys in insertion order, so that output reads top-down.
using Json = nlohmann::ordered_json;

/// A command line that parsed but makes no sense (missing choice, bad value): exit code 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A command stopped by SIGINT or SIGTERM (mjarm/interrupt.hpp) after printing what it had done:
/// `main` exits with 128 + the signal's number (130 for Ctrl-C, 143 for SIGTERM).
class InterruptedError : public std::runtime_error {
 public:
  /// @param signal the signal that stopped the command (`interrupt_signal()`; 0: SIGINT)
  InterruptedError(const std::string& what, int signal);
  int exit_code() const noexcept { return 128 + signal_; }

 private:
  int signal_;
};

/// Under the caller's `InterruptGuard`, between the parts of an output file and before its
/// commit: when SIGINT or SIGTERM has arrived, throws InterruptedError "COMMAND: interrupted;
/// 'PATH' was not written" (saying that a file already at PATH is kept). The unwinding destroys
/// the uncommitted FileWriter, which removes its temporary file: the old file stays as it was.
void stop_writing_if_interrupted(const std::string& command, const std::string& path);

/// At the end of a command that holds an `InterruptGuard` while it writes @p path: a signal that
/// came after the file was moved into place still ends the command with 128 + the signal, the
/// message saying the file was written.
void report_interrupt_after_writing(const std::string& command, const std::string& path);

/// @p v with @p decimals digits after the point; "inf", "-inf" and "nan" spelled out.
std::string fixed(double v, int decimals = 4);

/// @p v with @p digits significant digits, switching to exponent notation when very small or
/// large (for condition numbers, rates).
std::string general(double v, int digits = 4);

/// Shortest natural form of @p v with up to 6 significant digits ("1", "0.002", "2.5e-07").
std::string compact(double v);

/// "[a, b, c]" with fixed(…, @p decimals) entries.
std::string vector_text(const Eigen::Ref<const Eigen::VectorXd>& v, int decimals = 4);

/// Comma-separated list "a, b, c"; "(none)" when empty.
std::string join(const std::vector<std::string>& items, std::string_view separator = ", ");

/// Display width of a UTF-8 string (code points; all our glyphs are one column wide).
std::size_t display_width(std::string_view text);

/// A table with a header row and aligned columns; numeric columns are right-aligned.
class Table {
 public:
  /// Horizontal alignment of a column.
  enum class Align { left, right };
  /// A column: its header (units in brackets, e.g. "lower [rad]") and alignment.
  struct Column {
    std::string header;
    Align align = Align::right;
  };

  explicit Table(std::vector<Column> columns);

  /// Adds one row; it must have one cell per column.
  void add_row(std::vector<std::string> cells);

  /// Number of rows added so far.
  std::size_t rows() const noexcept { return rows_.size(); }

  /// Prints the header, a rule, and the rows, each line indented by @p indent spaces.
  void print(std::ostream& os, int indent = 2) const;

 private:
  std::vector<Column> columns_;
  std::vector<std::vector<std::string>> rows_;
};

/// Prints "key  value" lines with the values aligned, indented by @p indent spaces.
void print_fields(std::ostream& os, const std::vector<std::pair<std::string, std::string>>& fields,
                  int indent = 0);

/// Prints a section heading ("\n== title ==") used by multi-part outputs such as `demo`.
void print_heading(std::ostream& os, std::string_view title);

/// A vector as a JSON array of numbers.
Json vector_json(const Eigen::Ref<const Eigen::VectorXd>& v);

/// A matrix as a JSON array of rows.
Json matrix_json(const Eigen::Ref<const Eigen::MatrixXd>& m);

/// Writes one JSON document (2-space indent) and a newline to stdout.
void print_json(const Json& document);

/// True when standard error is an interactive terminal (progress lines are shown only then).
bool stderr_is_terminal() noexcept;

/// A one-line progress indicator on standard error, redrawn in place at most every 100 ms and
/// erased when done. Silent when disabled (stderr piped or redirected), so logs stay clean.
class Progress {
 public:
  /// @param label what is being counted ("sampling")
  /// @param total the count at completion (> 0)
  /// @param enabled draw at all; defaults to `stderr_is_terminal()`
  Progress(std::string label, std::int64_t total, bool enabled = stderr_is_terminal());
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Reports that @p done of the total are complete.
  void update(std::int64_t done);
  /// Reports that @p done of @p total are complete (a total known only once the work started).
  void update(std::int64_t done, std::int64_t total);
  /// Erases the line (idempotent).
  void finish();

 private:
  std::string label_;
  std::int64_t total_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace mjarm::cli
