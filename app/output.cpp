#include "output.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "mjarm/interrupt.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm::cli {

InterruptedError::InterruptedError(const std::string& what, int signal)
    : std::runtime_error(what), signal_(signal > 0 ? signal : SIGINT) {}

void stop_writing_if_interrupted(const std::string& command, const std::string& path) {
  if (!interrupt_requested()) return;
  std::error_code ec;
  const bool kept = std::filesystem::exists(path, ec);
  throw InterruptedError(command + ": interrupted; '" + path + "' was not written" +
                             (kept ? " (the file already there is kept)" : ""),
                         interrupt_signal());
}

void report_interrupt_after_writing(const std::string& command, const std::string& path) {
  if (interrupt_requested())
    throw InterruptedError(command + ": interrupted after '" + path + "' was written",
                           interrupt_signal());
}

namespace {

std::string non_finite(double v) {
  if (std::isnan(v)) return "nan";
  return v > 0 ? "inf" : "-inf";
}

}  // namespace

std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return non_finite(v);
  // avoid printing "-0.0000" for tiny negatives
  const double scale = std::pow(10.0, decimals);
  if (std::abs(v) * scale < 0.5) v = 0.0;
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, v);
  return buffer;
}

std::string general(double v, int digits) {
  if (!std::isfinite(v)) return non_finite(v);
  char buffer[64];
  const double a = std::abs(v);
  if (a != 0.0 && (a < 1e-3 || a >= 1e6)) {
    std::snprintf(buffer, sizeof(buffer), "%.*e", digits - 1, v);
  } else {
    // enough decimals for the requested significant digits, none for large values
    const int magnitude = a == 0.0 ? 0 : static_cast<int>(std::floor(std::log10(a)));
    const int decimals = std::max(0, digits - 1 - magnitude);
    std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, v);
  }
  return buffer;
}

std::string compact(double v) { return number_text(v, 6); }

std::string vector_text(const Eigen::Ref<const Eigen::VectorXd>& v, int decimals) {
  std::string text = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (i > 0) text += ", ";
    text += fixed(v[i], decimals);
  }
  return text + "]";
}

std::string join(const std::vector<std::string>& items, std::string_view separator) {
  if (items.empty()) return "(none)";
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) text += separator;
    text += items[i];
  }
  return text;
}

std::size_t display_width(std::string_view text) {
  // count code points: every byte that is not a UTF-8 continuation byte
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  }));
}

Table::Table(std::vector<Column> columns) : columns_(std::move(columns)) {}

void Table::add_row(std::vector<std::string> cells) {
  cells.resize(columns_.size());
  rows_.push_back(std::move(cells));
}

void Table::print(std::ostream& os, int indent) const {
  std::vector<std::size_t> widths(columns_.size());
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    widths[c] = display_width(columns_[c].header);
    for (const auto& row : rows_) widths[c] = std::max(widths[c], display_width(row[c]));
  }
  const std::string margin(static_cast<std::size_t>(indent), ' ');
  auto print_line = [&](auto cell_of) {
    std::string line = margin;
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      const std::string& text = cell_of(c);
      const std::string pad(widths[c] - display_width(text), ' ');
      if (c > 0) line += "  ";
      line += columns_[c].align == Align::right ? pad + text : text + pad;
    }
    // no trailing blanks
    line.erase(line.find_last_not_of(' ') + 1);
    os << line << '\n';
  };
  print_line([&](std::size_t c) -> const std::string& { return columns_[c].header; });
  std::size_t total = 0;
  for (std::size_t c = 0; c < widths.size(); ++c) total += widths[c] + (c > 0 ? 2 : 0);
  std::string rule;
  for (std::size_t i = 0; i < total; ++i) rule += "─";
  os << margin << rule << '\n';
  for (const auto& row : rows_)
    print_line([&](std::size_t c) -> const std::string& { return row[c]; });
}

void print_fields(std::ostream& os, const std::vector<std::pair<std::string, std::string>>& fields,
                  int indent) {
  std::size_t width = 0;
  for (const auto& [key, value] : fields) width = std::max(width, display_width(key));
  const std::string margin(static_cast<std::size_t>(indent), ' ');
  for (const auto& [key, value] : fields) {
    os << margin << key << std::string(width - display_width(key) + 2, ' ') << value << '\n';
  }
}

void print_heading(std::ostream& os, std::string_view title) { os << "\n== " << title << " ==\n"; }

Json vector_json(const Eigen::Ref<const Eigen::VectorXd>& v) {
  Json array = Json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) array.push_back(v[i]);
  return array;
}

Json matrix_json(const Eigen::Ref<const Eigen::MatrixXd>& m) {
  Json rows = Json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    Json row = Json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
    rows.push_back(std::move(row));
  }
  return rows;
}

void print_json(const Json& document) { std::cout << document.dump(2) << '\n'; }

bool stderr_is_terminal() noexcept { return ::isatty(STDERR_FILENO) == 1; }

Progress::Progress(std::string label, std::int64_t total, bool enabled)
    : label_(std::move(label)), total_(std::max<std::int64_t>(total, 1)), enabled_(enabled) {}

Progress::~Progress() { finish(); }

void Progress::update(std::int64_t done) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && done < total_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  drawn_ = true;
  const double fraction =
      std::clamp(static_cast<double>(done) / static_cast<double>(total_), 0.0, 1.0);
  constexpr int kBar = 30;
  const int filled = static_cast<int>(fraction * kBar);
  std::string bar;
  for (int i = 0; i < kBar; ++i) bar += i < filled ? "█" : "░";
  std::fprintf(stderr, "\r%s %s %5.1f%% (%lld/%lld)", label_.c_str(), bar.c_str(), 100.0 * fraction,
               static_cast<long long>(done), static_cast<long long>(total_));
  std::fflush(stderr);
}

void Progress::update(std::int64_t done, std::int64_t total) {
  total_ = std::max<std::int64_t>(total, 1);
  update(done);
}

void Progress::finish() {
  if (!enabled_ || !drawn_) return;
  // erase the line so that the result prints on a clean terminal
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace mjarm::cli
