/// \file
/// Shared by the lesson 1-2 property tests: tolerances written in units of the machine epsilon
/// of the precision under test (the precisions: precisions.hpp).
#pragma once

#include "precisions.hpp"
#include "property.hpp"

namespace soa::test {

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
