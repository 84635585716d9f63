#pragma once
/// @file
/// Specs of an environment's arrays (dm_env's `specs.BoundedArray`): a name, a shape, a dtype
/// and element-wise bounds; and `ObservationSpec`, the named arrays of an observation laid out
/// one after the other in one contiguous buffer.

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/fields.hpp"

namespace mjarm {

/// Element type of an array. Every array of mjarm's environments holds doubles.
enum class DType { float64 };

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const DType*) {
  using E = DType;
  return std::array{EnumName{E::float64, "float64"}};
}

/// A named array with its shape, dtype and bounds. Unbounded elements have −∞ / +∞ bounds.
struct ArraySpec {
  std::string name;
  std::vector<int> shape;  ///< dimensions; {} for a scalar
  DType dtype = DType::float64;
  Eigen::VectorXd minimum;  ///< lower bound of each element (size() entries, row-major)
  Eigen::VectorXd maximum;  ///< upper bound of each element

  /// A one-dimensional array of @p size elements, unbounded.
  static ArraySpec vector(std::string name, int size);
  /// A one-dimensional array with bounds @p minimum, @p maximum (same size).
  static ArraySpec bounded(std::string name, const Eigen::VectorXd& minimum,
                           const Eigen::VectorXd& maximum);

  /// Number of elements (the product of the shape; 1 for a scalar).
  int size() const noexcept;
  /// True when every element has finite bounds on both sides.
  bool bounded() const noexcept;
  /// "name: float64[7] in [-2.9, 2.9] …" — one line for listings.
  std::string describe() const;
  /// @throws Error when the name is empty, a dimension is not positive, the bounds do not have
  ///         size() entries, hold NaN, or a minimum exceeds its maximum.
  void check() const;
};

/// The arrays of an observation, in order, stored back to back in one buffer of `size()`
/// doubles: array i occupies [offset(i), offset(i) + arrays()[i].size()).
class ObservationSpec {
 public:
  ObservationSpec() = default;
  /// @throws Error for an invalid array (`ArraySpec::check`) or a name used twice.
  explicit ObservationSpec(std::vector<ArraySpec> arrays);

  const std::vector<ArraySpec>& arrays() const noexcept { return arrays_; }
  /// Number of arrays.
  int count() const noexcept { return static_cast<int>(arrays_.size()); }
  /// Total number of doubles.
  int size() const noexcept { return size_; }
  /// First element of array @p i in the buffer.
  int offset(int i) const { return offsets_.at(static_cast<std::size_t>(i)); }
  /// Index of the array called @p name.
  /// @throws Error naming @p name and listing the arrays there are.
  int index(std::string_view name) const;
  /// Index of @p name, or −1.
  int find(std::string_view name) const noexcept;
  /// The array called @p name. @throws Error as `index`.
  const ArraySpec& at(std::string_view name) const { return arrays_[index(name)]; }
  /// The names, in order.
  std::vector<std::string> names() const;

 private:
  std::vector<ArraySpec> arrays_;
  std::vector<int> offsets_;
  int size_ = 0;
};

}  // namespace mjarm
