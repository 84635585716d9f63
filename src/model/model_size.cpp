#include "mjarm/model/model_size.hpp"

#include <algorithm>
#include <atomic>
#include <limits>
#include <vector>

#include "mjarm/error.hpp"

namespace mjarm {

namespace {

std::atomic<std::uint64_t> model_element_bound{kDefaultMaxModelElements};

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
  return a > std::numeric_limits<std::uint64_t>::max() - b
             ? std::numeric_limits<std::uint64_t>::max()
             : a + b;
}

}  // namespace

std::uint64_t max_model_elements() noexcept { return model_element_bound.load(); }

void set_max_model_elements(std::uint64_t count) {
  if (count == 0 || count > kLargestMaxModelElements)
    throw Error("the bound on a model's elements must be from 1 to " +
                std::to_string(kLargestMaxModelElements) + ", got " + std::to_string(count));
  model_element_bound.store(count);
}

void ModelSizeCount::add(std::string_view tag, std::uint64_t count) {
  auto it = by_tag_.find(tag);
  if (it == by_tag_.end()) it = by_tag_.emplace(std::string(tag), 0).first;
  it->second = saturating_add(it->second, count);
  total_ = saturating_add(total_, count);
}

void ModelSizeCount::check(const std::string& what) const {
  const std::uint64_t bound = max_model_elements();
  if (total_ <= bound) return;
  std::vector<std::pair<std::string, std::uint64_t>> kinds(by_tag_.begin(), by_tag_.end());
  std::stable_sort(kinds.begin(), kinds.end(),  // ties in alphabetical order
            [](const auto& a, const auto& b) { return a.second > b.second; });
  std::string most;
  for (std::size_t i = 0; i < kinds.size() && i < 3; ++i)
    most += (i ? ", " : "") + std::to_string(kinds[i].second) + " " + kinds[i].first;
  throw Error(what + " has " + std::to_string(total_) + " elements (" + most +
              "), more than the " + std::to_string(bound) +
              " a model may have: MuJoCo's compile time grows with the square of the count "
              "(16000 bodies take about 20 s); raise the bound with --max-model-elements N on "
              "the command line, mjarm.set_max_model_elements(N) in Python or "
              "mjarm::set_max_model_elements in C++");
}

}  // namespace mjarm
