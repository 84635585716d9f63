#pragma once
// Polynomial arithmetic for the jerk-limited profile solvers (private to the trajectory room).
//
// A profile structure with one free parameter x has phase durations that are polynomials in x,
// or of the form A(x) + r·B(x) where r = ±√Q(x) (a level fixed by the velocity equation). `Ext`
// carries such a value; products reduce r² to Q. Integrating the phases symbolically gives the
// position residual R = R_a + r·R_b, whose roots are those of R_a² − Q·R_b² (a polynomial).

#include "mjarm/trajectory/jerk_limited_profile.hpp"
#include "mjarm/trajectory/jerk_limited_roots.hpp"

namespace mjarm::jerk_detail {

/// c₀ + c₁x.
inline Polynomial linear(double c0, double c1 = 0.0) noexcept {
  Polynomial p;
  p.c[0] = c0;
  p.c[1] = c1;
  p.degree = c1 != 0.0 ? 1 : 0;
  return p;
}

inline Polynomial operator+(const Polynomial& a, const Polynomial& b) noexcept {
  Polynomial s;
  s.degree = a.degree > b.degree ? a.degree : b.degree;
  for (int i = 0; i <= s.degree; ++i) s.c[i] = a.c[i] + b.c[i];
  return s;
}

inline Polynomial operator-(const Polynomial& a, const Polynomial& b) noexcept {
  Polynomial s;
  s.degree = a.degree > b.degree ? a.degree : b.degree;
  for (int i = 0; i <= s.degree; ++i) s.c[i] = a.c[i] - b.c[i];
  return s;
}

inline Polynomial operator*(double k, const Polynomial& a) noexcept {
  Polynomial s = a;
  for (int i = 0; i <= s.degree; ++i) s.c[i] *= k;
  return s;
}

/// The product; terms above the capacity are dropped (the solvers stay within degree 8).
inline Polynomial operator*(const Polynomial& a, const Polynomial& b) noexcept {
  Polynomial s;
  s.degree = a.degree + b.degree;
  if (s.degree > Polynomial::kMaxDegree) s.degree = Polynomial::kMaxDegree;
  for (int i = 0; i <= a.degree; ++i) {
    if (a.c[i] == 0.0) continue;
    for (int k = 0; k <= b.degree && i + k <= Polynomial::kMaxDegree; ++k)
      s.c[i + k] += a.c[i] * b.c[k];
  }
  return s;
}

/// A value a(x) + r·b(x) with r² = Q(x).
struct Ext {
  Polynomial a;  ///< rational part
  Polynomial b;  ///< coefficient of r
};

inline Ext ext(const Polynomial& a, const Polynomial& b = Polynomial{}) noexcept { return {a, b}; }
inline Ext operator+(const Ext& x, const Ext& y) noexcept { return {x.a + y.a, x.b + y.b}; }
inline Ext operator-(const Ext& x, const Ext& y) noexcept { return {x.a - y.a, x.b - y.b}; }
inline Ext operator*(double k, const Ext& x) noexcept { return {k * x.a, k * x.b}; }

/// The value of @p e at x with r = @p r.
inline double evaluate(const Ext& e, double x, double r) noexcept { return e.a(x) + r * e.b(x); }

/// Symbolic integration of phases of constant jerk with durations of type Ext.
class SymbolicPhases {
 public:
  /// Starts at (0, v, a) with r² = @p q.
  SymbolicPhases(const Polynomial& q, double v, double a) noexcept : q_(q) {
    v_ = ext(linear(v));
    a_ = ext(linear(a));
  }
  /// A phase of jerk @p j lasting @p t.
  void phase(double j, const Ext& t) noexcept {
    const Ext t2 = mul(t, t);
    const Ext t3 = mul(t2, t);
    p_ = p_ + mul(v_, t) + 0.5 * mul(a_, t2) + (j / 6.0) * t3;
    v_ = v_ + mul(a_, t) + (0.5 * j) * t2;
    a_ = a_ + j * t;
  }
  /// Position reached (relative to the start).
  const Ext& position() const noexcept { return p_; }
  /// The polynomial whose roots make position() equal @p distance for r = +√Q or r = −√Q.
  Polynomial residual(double distance) const noexcept {
    const Polynomial ra = p_.a - linear(distance);
    bool has_r = false;
    for (int i = 0; i <= p_.b.degree; ++i) has_r = has_r || p_.b.c[i] != 0.0;
    if (!has_r) return ra;
    return ra * ra - q_ * (p_.b * p_.b);
  }

 private:
  Ext mul(const Ext& x, const Ext& y) const noexcept {
    return {x.a * y.a + q_ * (x.b * y.b), x.a * y.b + x.b * y.a};
  }
  Polynomial q_;
  Ext p_{};
  Ext v_{};
  Ext a_{};
};

}  // namespace mjarm::jerk_detail
