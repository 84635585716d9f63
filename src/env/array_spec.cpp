#include "mjarm/env/array_spec.hpp"

#include <cmath>
#include <cstdio>

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"

namespace mjarm {
namespace {

std::string bound_text(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

std::string list(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "(none)" : out;
}

}  // namespace

ArraySpec ArraySpec::vector(std::string name, int size) {
  const double inf = INFINITY;
  return ArraySpec{std::move(name),
                   {size},
                   DType::float64,
                   Eigen::VectorXd::Constant(size, -inf),
                   Eigen::VectorXd::Constant(size, inf)};
}

ArraySpec ArraySpec::bounded(std::string name, const Eigen::VectorXd& minimum,
                             const Eigen::VectorXd& maximum) {
  return ArraySpec{
      std::move(name), {static_cast<int>(minimum.size())}, DType::float64, minimum, maximum};
}

int ArraySpec::size() const noexcept {
  int n = 1;
  for (int d : shape) n *= d;
  return n;
}

bool ArraySpec::bounded() const noexcept { return minimum.allFinite() && maximum.allFinite(); }

std::string ArraySpec::describe() const {
  std::string shape_text;
  for (int d : shape) shape_text += (shape_text.empty() ? "" : ",") + std::to_string(d);
  std::string text = name + ": " + to_string(dtype) + "[" + shape_text + "]";
  if (minimum.size() == 0) return text;
  // one range when every element shares it, else the ranges element by element
  const bool uniform =
      (minimum.array() == minimum[0]).all() && (maximum.array() == maximum[0]).all();
  if (uniform) return text + " in [" + bound_text(minimum[0]) + ", " + bound_text(maximum[0]) + "]";
  text += " in";
  for (Eigen::Index i = 0; i < minimum.size(); ++i)
    text += std::string(i == 0 ? " " : ", ") + "[" + bound_text(minimum[i]) + ", " +
            bound_text(maximum[i]) + "]";
  return text;
}

void ArraySpec::check() const {
  if (name.empty()) throw Error("array spec: the name is empty");
  for (int d : shape) {
    if (d <= 0)
      throw Error("array spec '" + name + "': dimension " + std::to_string(d) + " is not positive");
  }
  const int n = size();
  if (minimum.size() != n || maximum.size() != n)
    throw Error("array spec '" + name + "': bounds need " + std::to_string(n) + " entries, got " +
                std::to_string(minimum.size()) + " and " + std::to_string(maximum.size()));
  for (int i = 0; i < n; ++i) {
    if (std::isnan(minimum[i]) || std::isnan(maximum[i]) || minimum[i] > maximum[i])
      throw Error("array spec '" + name + "': element " + std::to_string(i) + " has bounds [" +
                  bound_text(minimum[i]) + ", " + bound_text(maximum[i]) +
                  "] (expected minimum ≤ maximum, no NaN)");
  }
}

ObservationSpec::ObservationSpec(std::vector<ArraySpec> arrays) : arrays_(std::move(arrays)) {
  for (std::size_t i = 0; i < arrays_.size(); ++i) {
    arrays_[i].check();
    for (std::size_t j = 0; j < i; ++j) {
      if (arrays_[j].name == arrays_[i].name)
        throw Error("observation spec: '" + arrays_[i].name + "' is listed twice");
    }
    offsets_.push_back(size_);
    size_ += arrays_[i].size();
  }
}

int ObservationSpec::find(std::string_view name) const noexcept {
  for (std::size_t i = 0; i < arrays_.size(); ++i) {
    if (arrays_[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

int ObservationSpec::index(std::string_view name) const {
  const int i = find(name);
  if (i >= 0) return i;
  const std::vector<std::string> all = names();
  const std::vector<std::string> close = closest_names(name, all);
  throw Error("observation '" + std::string(name) + "' is not in this observation" +
              (close.empty() ? "" : "; closest: " + list(close)) + "; it holds: " + list(all));
}

std::vector<std::string> ObservationSpec::names() const {
  std::vector<std::string> out;
  out.reserve(arrays_.size());
  for (const auto& a : arrays_) out.push_back(a.name);
  return out;
}

}  // namespace mjarm
