/// \file
/// soa::test::Counted: a double that counts the operations done on it, for the flop counts of
/// the recursions. The library's templates instantiate with it implicitly (its explicit
/// instantiations are for float, double and long double only), and Eigen has no packet type for
/// it: every expression kernel runs coefficient by coefficient, so the counts are the scalar
/// operations of the code as written (a vectorized multiply of the double build counts once per
/// lane). Counted arithmetic is IEEE double arithmetic, one rounding per operation: the results
/// are those of double without vectorization.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <limits>

namespace soa::test {

/// Operations counted since the last reset_counts(): flops() = add + mul + div; the square
/// roots, sines and cosines, other elementary functions and comparisons apart.
struct OpCounts {
  long long add = 0;    ///< + and - (binary, and their compound assignments)
  long long mul = 0;    ///< *
  long long div = 0;    ///< /
  long long sqrt = 0;   ///< sqrt
  long long trig = 0;   ///< sin, cos
  long long other = 0;  ///< tan, atan2, acos, asin, exp, log, pow, hypot
  long long cmp = 0;    ///< <, <=, >, >=, ==, != (min, max and abs count none)
  long long flops() const { return add + mul + div; }
  OpCounts operator-(const OpCounts& o) const {
    return {add - o.add,   mul - o.mul,     div - o.div, sqrt - o.sqrt,
            trig - o.trig, other - o.other, cmp - o.cmp};
  }
};

inline OpCounts g_op_counts;
inline void reset_counts() {
  g_op_counts = OpCounts();
}
inline OpCounts counts() {
  return g_op_counts;
}

class Counted {
 public:
  constexpr Counted() = default;
  constexpr Counted(double v) : v_(v) {}  // NOLINT: implicit, as a literal converts to double
  constexpr explicit operator double() const { return v_; }
  constexpr double value() const { return v_; }

  Counted& operator+=(Counted b) { return ++g_op_counts.add, v_ += b.v_, *this; }
  Counted& operator-=(Counted b) { return ++g_op_counts.add, v_ -= b.v_, *this; }
  Counted& operator*=(Counted b) { return ++g_op_counts.mul, v_ *= b.v_, *this; }
  Counted& operator/=(Counted b) { return ++g_op_counts.div, v_ /= b.v_, *this; }
  friend Counted operator+(Counted a, Counted b) { return a += b; }
  friend Counted operator-(Counted a, Counted b) { return a -= b; }
  friend Counted operator*(Counted a, Counted b) { return a *= b; }
  friend Counted operator/(Counted a, Counted b) { return a /= b; }
  // A sign change is not a flop (the compiler folds it into the next add or flips a bit).
  friend Counted operator-(Counted a) { return Counted(-a.v_); }
  friend Counted operator+(Counted a) { return a; }

  friend bool operator<(Counted a, Counted b) { return ++g_op_counts.cmp, a.v_ < b.v_; }
  friend bool operator<=(Counted a, Counted b) { return ++g_op_counts.cmp, a.v_ <= b.v_; }
  friend bool operator>(Counted a, Counted b) { return ++g_op_counts.cmp, a.v_ > b.v_; }
  friend bool operator>=(Counted a, Counted b) { return ++g_op_counts.cmp, a.v_ >= b.v_; }
  friend bool operator==(Counted a, Counted b) { return ++g_op_counts.cmp, a.v_ == b.v_; }
  friend bool operator!=(Counted a, Counted b) { return ++g_op_counts.cmp, a.v_ != b.v_; }

  // Found by argument-dependent lookup from `using std::sqrt; sqrt(x)` and from Eigen's
  // numext functions.
  friend Counted sqrt(Counted a) { return ++g_op_counts.sqrt, Counted(std::sqrt(a.v_)); }
  friend Counted sin(Counted a) { return ++g_op_counts.trig, Counted(std::sin(a.v_)); }
  friend Counted cos(Counted a) { return ++g_op_counts.trig, Counted(std::cos(a.v_)); }
  friend Counted tan(Counted a) { return ++g_op_counts.other, Counted(std::tan(a.v_)); }
  friend Counted asin(Counted a) { return ++g_op_counts.other, Counted(std::asin(a.v_)); }
  friend Counted acos(Counted a) { return ++g_op_counts.other, Counted(std::acos(a.v_)); }
  friend Counted atan(Counted a) { return ++g_op_counts.other, Counted(std::atan(a.v_)); }
  friend Counted atan2(Counted a, Counted b) {
    return ++g_op_counts.other, Counted(std::atan2(a.v_, b.v_));
  }
  friend Counted exp(Counted a) { return ++g_op_counts.other, Counted(std::exp(a.v_)); }
  friend Counted log(Counted a) { return ++g_op_counts.other, Counted(std::log(a.v_)); }
  friend Counted pow(Counted a, Counted b) {
    return ++g_op_counts.other, Counted(std::pow(a.v_, b.v_));
  }
  friend Counted hypot(Counted a, Counted b) {
    return ++g_op_counts.other, Counted(std::hypot(a.v_, b.v_));
  }
  friend Counted abs(Counted a) { return Counted(std::fabs(a.v_)); }
  friend Counted fabs(Counted a) { return Counted(std::fabs(a.v_)); }
  friend Counted floor(Counted a) { return Counted(std::floor(a.v_)); }
  friend Counted ceil(Counted a) { return Counted(std::ceil(a.v_)); }
  friend bool isfinite(Counted a) { return std::isfinite(a.v_); }
  friend bool isnan(Counted a) { return std::isnan(a.v_); }
  friend bool isinf(Counted a) { return std::isinf(a.v_); }

 private:
  double v_ = 0;
};

}  // namespace soa::test

namespace std {
template <>
class numeric_limits<soa::test::Counted> : public numeric_limits<double> {
  using C = soa::test::Counted;
  using D = std::numeric_limits<double>;

 public:
  static constexpr C min() noexcept { return C(D::min()); }
  static constexpr C max() noexcept { return C(D::max()); }
  static constexpr C lowest() noexcept { return C(D::lowest()); }
  static constexpr C epsilon() noexcept { return C(D::epsilon()); }
  static constexpr C round_error() noexcept { return C(D::round_error()); }
  static constexpr C infinity() noexcept { return C(D::infinity()); }
  static constexpr C quiet_NaN() noexcept { return C(D::quiet_NaN()); }
  static constexpr C signaling_NaN() noexcept { return C(D::signaling_NaN()); }
  static constexpr C denorm_min() noexcept { return C(D::denorm_min()); }
};
}  // namespace std

namespace Eigen {
/// Costs as double's, so that Eigen picks the same product and reduction kernels; no packet
/// type, so that no kernel is vectorized.
template <>
struct NumTraits<soa::test::Counted> : GenericNumTraits<soa::test::Counted> {
  using Real = soa::test::Counted;
  using NonInteger = soa::test::Counted;
  using Nested = soa::test::Counted;
  using Literal = soa::test::Counted;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 1,
    AddCost = 1,
    MulCost = 1
  };
  static inline Real epsilon() { return std::numeric_limits<double>::epsilon(); }
  static inline Real dummy_precision() { return NumTraits<double>::dummy_precision(); }
  static inline Real highest() { return std::numeric_limits<double>::max(); }
  static inline Real lowest() { return std::numeric_limits<double>::lowest(); }
  static inline int digits10() { return std::numeric_limits<double>::digits10; }
};
}  // namespace Eigen
