#include "csv_stream.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>

#include "mjarm/error.hpp"

namespace mjarm::sim_detail {
namespace {
constexpr std::size_t kIoBuffer = 1 << 16;
constexpr std::size_t kNumberBytes = 32;  // "-2.2250738585072014e-308" and a separator fit
}  // namespace

CsvStream::CsvStream(const std::filesystem::path& path, const std::vector<std::string>& columns,
                     int flush_rows, std::size_t text_bytes)
    : file_(path, FileWriter::Mode::in_place, {}, kIoBuffer),
      columns_(static_cast<int>(columns.size())),
      flush_rows_(std::max(flush_rows, 1)) {
  std::size_t header = 2;
  for (const std::string& c : columns) header += c.size() + 1;
  row_.resize(std::max(header, columns.size() * kNumberBytes + text_bytes + 2));
  for (const std::string& c : columns) add_text(c);
  end_row();
  rows_ = 0;  // the header is not a row
  flush();
  if (file_.error() != 0) throw Error("recorder: " + file_.failure());
}

CsvStream::~CsvStream() = default;

void CsvStream::separator() noexcept {
  if (fields_++ > 0 && used_ + 1 < row_.size()) row_[used_++] = ',';
}

void CsvStream::add(double value) noexcept {
  separator();
  const auto [end, ec] = std::to_chars(row_.data() + used_, row_.data() + row_.size() - 1, value);
  if (ec == std::errc()) used_ = static_cast<std::size_t>(end - row_.data());
}

void CsvStream::add_text(std::string_view text) noexcept {
  separator();
  const std::size_t limit = row_.size() - 1;  // keep room for the newline
  if (text.find_first_of(",\"\n\r") == std::string_view::npos) {
    const std::size_t n = std::min(text.size(), limit - std::min(used_, limit));
    std::memcpy(row_.data() + used_, text.data(), n);
    used_ += n;
    return;
  }
  if (used_ + 2 > limit) return;
  row_[used_++] = '"';
  for (char c : text) {
    const std::size_t need = c == '"' ? 2 : 1;  // "" escapes a quote
    if (used_ + need + 1 > limit) break;
    if (c == '"') row_[used_++] = '"';
    row_[used_++] = c;
  }
  row_[used_++] = '"';
}

void CsvStream::end_row() noexcept {
  row_[used_++] = '\n';
  file_.write(row_.data(), used_);  // a failure is kept by file_ and reported at close
  used_ = 0;
  fields_ = 0;
  if (++rows_ % flush_rows_ == 0) flush();
}

void CsvStream::flush() noexcept { file_.flush(); }

bool CsvStream::close() noexcept { return file_.close(); }

}  // namespace mjarm::sim_detail
