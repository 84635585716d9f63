#pragma once
/// @file
/// The bound on a model's size, checked before MuJoCo compiles it: MuJoCo's compile time grows
/// with the square of the element count (8000 bodies took 2.8 s on a shared 2-core machine,
/// 16000 took 19 s), so a 400 000-geom file would run for many minutes without a word.

#include <cstdint>
#include <map>
#include <string>
#include <string_view>

namespace mjarm {

/// The default bound on a model's elements: 20 000 (a few seconds of compiling at worst; the
/// bundled scenes have a few hundred).
inline constexpr std::uint64_t kDefaultMaxModelElements = 20000;
/// The largest bound `set_max_model_elements` accepts.
inline constexpr std::uint64_t kLargestMaxModelElements = 100'000'000;

/// The bound every model load applies (process-wide; `kDefaultMaxModelElements` until set).
std::uint64_t max_model_elements() noexcept;
/// Sets the bound of every later model load in this process (the CLI's --max-model-elements,
/// Python's `mjarm.set_max_model_elements`).
/// @throws Error when @p count is 0 or beyond `kLargestMaxModelElements`.
void set_max_model_elements(std::uint64_t count);

/// Counts a model's elements by kind before it is compiled, and checks the total against
/// `max_model_elements()`.
class ModelSizeCount {
 public:
  /// Adds @p count elements of kind @p tag (saturating: a count cannot wrap around).
  void add(std::string_view tag, std::uint64_t count = 1);
  /// Every element counted so far.
  std::uint64_t total() const noexcept { return total_; }
  /// @throws Error naming @p what, the total, the most numerous kinds, the bound and how to
  ///         raise it, when the total is beyond `max_model_elements()`.
  void check(const std::string& what) const;

 private:
  std::map<std::string, std::uint64_t, std::less<>> by_tag_;
  std::uint64_t total_ = 0;
};

}  // namespace mjarm
