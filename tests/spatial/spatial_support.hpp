/// \file
/// Shared by the lesson 1-2 property tests: the three precisions of the typed tests, and
/// tolerances written in units of the machine epsilon of the precision under test.
#pragma once

#include <string>
#include <type_traits>

#include "property.hpp"

namespace soa::test {

/// The precisions of the typed (core) tests.
using Scalars = ::testing::Types<float, double, long double>;

/// The name of a precision, for test names and worst-residual reports.
template <class S>
std::string scalar_name() {
  if (std::is_same_v<S, float>) return "float";
  if (std::is_same_v<S, double>) return "double";
  return "long_double";
}

/// Test-name generator for TYPED_TEST_SUITE: `spatial_Phi/double.Product`.
struct ScalarNames {
  template <class S>
  static std::string GetName(int) {
    return scalar_name<S>();
  }
};

/// \p k machine epsilons of precision S, as a double (Worst keeps residuals in double).
template <class S>
double tol(double k) {
  return k * double(eps<S>());
}

/// A spatial vector given by its six coefficients (angular first).
template <class Kind, class S>
SpatialVector<S, Kind> spatial(const Vec6<S>& v) {
  return SpatialVector<S, Kind>(v);
}

/// The spatial vector \p V with both 3-vector parts rotated by \p R (a change of the
/// coordinates in which a coordinate-free spatial vector is written).
template <class S, class K>
SpatialVector<S, K> rotated(const Mat3<S>& R, const SpatialVector<S, K>& V) {
  return SpatialVector<S, K>(R * Vec3<S>(V.angular()), R * Vec3<S>(V.linear()));
}

}  // namespace soa::test
