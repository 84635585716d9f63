#include "mjarm/plot/csv_rows.hpp"

#include <cmath>
#include <cstring>

#include "mjarm/error.hpp"
#include "mjarm/model/user_file.hpp"
#include "mjarm/number_text.hpp"
#include "quoted_path.hpp"

namespace mjarm::plot {
namespace {

constexpr std::size_t kChunk = std::size_t{1} << 20;
constexpr std::size_t kLongestRecord = std::size_t{64} << 20;

}  // namespace

CsvRowReader::CsvRowReader(const std::filesystem::path& path, std::string_view what)
    : path_(path), file_(std::make_unique<UserFileReader>(path, what)), buffer_(kChunk) {
  std::string_view record;
  if (!next_record(record)) fail("is empty: expected a header row of column names");
  split(record);
  header_.assign(cells_.begin(), cells_.end());
  if (header_.size() == 1 && header_[0].empty()) fail("has an empty header row: expected names");
}

CsvRowReader::~CsvRowReader() = default;

void CsvRowReader::fail(const std::string& what) const { throw Error(quoted(path_) + " " + what); }

int CsvRowReader::find(std::string_view name) const noexcept {
  for (std::size_t i = 0; i < header_.size(); ++i)
    if (header_[i] == name) return static_cast<int>(i);
  return -1;
}

std::size_t CsvRowReader::require(std::string_view name) const {
  const int column = find(name);
  if (column >= 0) return static_cast<std::size_t>(column);
  std::string names;
  for (std::size_t i = 0; i < header_.size() && i < 12; ++i) names += (i ? ", " : "") + header_[i];
  if (header_.size() > 12) names += ", … (" + std::to_string(header_.size()) + " in all)";
  fail("has no column '" + std::string(name) + "' (columns: " + names + ")");
}

// The next record (its line end excluded) in the buffer; false at the end of the file. A record
// ends at a line end outside quotes.
bool CsvRowReader::next_record(std::string_view& record) {
  line_ = next_line_;
  std::size_t scan = begin_;
  bool in_quotes = false;
  while (true) {
    for (; scan < end_; ++scan) {
      const char c = buffer_[scan];
      if (c == '"') {
        in_quotes = !in_quotes;
      } else if (c == '\n') {
        ++next_line_;
        if (!in_quotes) {
          record = std::string_view(buffer_.data() + begin_, scan - begin_);
          begin_ = scan + 1;
          return true;
        }
      } else if (c == '\0') {
        fail("line " + std::to_string(next_line_) +
             " holds a NUL byte: a binary file, not a CSV table");
      }
    }
    if (eof_) {
      if (begin_ == end_) return false;
      fail("ends in the middle of line " + std::to_string(line_) +
           " (its last row has no line end: a truncated file)");
    }
    // keep the record begun, read more after it
    if (begin_ > 0) {
      std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
      scan -= begin_;
      end_ -= begin_;
      begin_ = 0;
    }
    if (buffer_.size() - end_ < kChunk / 2) {
      if (buffer_.size() >= kLongestRecord)
        fail("line " + std::to_string(line_) + " is over " + std::to_string(kLongestRecord >> 20) +
             " MiB long: not a CSV table");
      buffer_.resize(buffer_.size() * 2);
    }
    const std::size_t n = file_->read(buffer_.data() + end_, buffer_.size() - end_);
    if (n == 0) eof_ = true;
    end_ += n;
  }
}

void CsvRowReader::split(std::string_view record) {
  if (!record.empty() && record.back() == '\r') record.remove_suffix(1);
  cells_.clear();
  if (record.find('"') == std::string_view::npos) {
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = record.find(',', start);
      cells_.push_back(record.substr(start, comma - start));
      if (comma == std::string_view::npos) return;
      start = comma + 1;
    }
  }
  // quoted cells, unescaped as CsvTable reads them (rare in a recording: kept simple)
  std::vector<std::string> parts(1);
  bool in_quotes = false;
  for (std::size_t i = 0; i < record.size(); ++i) {
    const char c = record[i];
    if (in_quotes) {
      if (c == '"' && i + 1 < record.size() && record[i + 1] == '"') {
        parts.back() += '"';
        ++i;
      } else if (c == '"') {
        in_quotes = false;
      } else {
        parts.back() += c;
      }
    } else if (c == '"') {
      in_quotes = true;
    } else if (c == ',') {
      parts.emplace_back();
    } else if (c != '\r') {
      parts.back() += c;
    }
  }
  unquoted_ = std::move(parts);
  for (const std::string& text : unquoted_) cells_.push_back(text);
}

bool CsvRowReader::next() {
  std::string_view record;
  while (true) {
    if (!next_record(record)) return false;
    if (!(record.empty() || record == "\r")) break;  // a blank line
  }
  split(record);
  if (cells_.size() != header_.size()) {
    fail("line " + std::to_string(line_) + " has " + std::to_string(cells_.size()) +
         " cells, the header has " + std::to_string(header_.size()) +
         " (a truncated or damaged file, or a table of other columns?)");
  }
  ++rows_;
  return true;
}

double CsvRowReader::number(std::size_t column) const {
  const std::string_view text = cells_[column];
  if (text.empty()) return std::nan("");
  const auto value = number_from_text(text);  // also reads "nan", "inf", "-inf"
  if (!value) {
    fail("column '" + header_[column] + "' line " + std::to_string(line_) + ": '" +
         std::string(text) + "' is not a number");
  }
  return *value;
}

}  // namespace mjarm::plot
