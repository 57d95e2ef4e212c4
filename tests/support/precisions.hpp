/// \file
/// The precisions of the typed tests, and their names in test names and reports.
/// Two lists: `Precisions` (float, double, long double) for the tests whose subject is
/// precision (a recursion's error against its operator form, the batch sines and cosines,
/// \f$\exp\f$ and \f$\log\f$ of SE(3) at small angles and near \f$\pi\f$), and `Scalars` (double,
/// the precision the course computes in) for the identities of spatial algebra, whose
/// tolerance scales with \f$\varepsilon\f$ and which say nothing more in another precision.
#pragma once

#include <string>
#include <type_traits>

#include <gtest/gtest.h>

namespace soa::test {

/// The three precisions, for the tests whose subject is precision.
using Precisions = ::testing::Types<float, double, long double>;

/// The precision of the identity tests.
using Scalars = ::testing::Types<double>;

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

}  // namespace soa::test
