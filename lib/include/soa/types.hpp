/// \file
/// Fixed-size vector and matrix aliases shared by the whole library.
///
/// Every type and algorithm in `soa` is a template on the scalar `S` (`float`, `double` or
/// `long double`). Each template `XxxT<S>` has a `double` alias `Xxx`, which is what lessons
/// use; the other precisions serve the work-precision reports and `long double` references.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross()
#include <limits>

namespace soa {

template <class S>
using Vec3 = Eigen::Matrix<S, 3, 1>;
template <class S>
using Mat3 = Eigen::Matrix<S, 3, 3>;
template <class S>
using Vec6 = Eigen::Matrix<S, 6, 1>;
template <class S>
using Mat6 = Eigen::Matrix<S, 6, 6>;
template <class S>
using Mat4 = Eigen::Matrix<S, 4, 4>;
/// Stacked quantities of a chain (\f$\theta\f$, \f$\beta\f$, \f$T\f$) and dense operators.
template <class S>
using VecX = Eigen::Matrix<S, Eigen::Dynamic, 1>;
template <class S>
using MatX = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;

/// Machine epsilon of the scalar, the unit in which test tolerances are written.
template <class S>
constexpr S eps() {
  return std::numeric_limits<S>::epsilon();
}

}  // namespace soa
