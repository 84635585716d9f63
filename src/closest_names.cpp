#include "mjarm/closest_names.hpp"

#include <algorithm>

namespace mjarm {
namespace {

/// Edit distance counting a swap of neighbours as one edit (optimal string alignment), so
/// that typos like "tpi" for "tip" rank first.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  const std::size_t w = b.size() + 1;
  std::vector<std::size_t> d((a.size() + 1) * w);
  for (std::size_t i = 0; i <= a.size(); ++i) d[i * w] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      std::size_t best =
          std::min({d[(i - 1) * w + j] + 1, d[i * w + j - 1] + 1, d[(i - 1) * w + j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        best = std::min(best, d[(i - 2) * w + j - 2] + 1);
      d[i * w + j] = best;
    }
  }
  return d[a.size() * w + b.size()];
}

}  // namespace

std::vector<std::string> closest_names(std::string_view name,
                                       const std::vector<std::string>& candidates,
                                       std::size_t count) {
  std::vector<std::pair<std::size_t, std::string>> scored;
  for (const auto& candidate : candidates) {
    if (candidate.empty()) continue;
    // a candidate that contains the name (or vice versa) is a near miss whatever its length
    const bool contains = candidate.find(name) != std::string::npos ||
                          std::string_view(name).find(candidate) != std::string_view::npos;
    const std::size_t score = contains ? 0 : edit_distance(name, candidate);
    scored.emplace_back(score, candidate);
  }
  std::stable_sort(scored.begin(), scored.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> result;
  for (std::size_t i = 0; i < scored.size() && i < count; ++i) result.push_back(scored[i].second);
  return result;
}

std::string unknown_name_message(std::string_view kind, std::string_view word,
                                 const std::vector<std::string>& known, std::string_view where) {
  std::string message = "unknown " + std::string(kind) + " '" + std::string(word) + "'";
  if (!where.empty()) message += " in " + std::string(where);
  const auto close = closest_names(word, known, 1);
  if (!close.empty()) message += "; closest: " + close.front();
  message += "; " + std::string(kind) + "s: ";
  for (std::size_t i = 0; i < known.size(); ++i) message += (i ? ", " : "") + known[i];
  return message;
}

}  // namespace mjarm
