/// \file
/// The attitude convention of the whole library (slides 15-20).
///
/// The course uses the aerospace (passive) convention of slides 16-17, stated here once:
/// - \f${}^A R_B\f$ is the attitude of frame B relative to frame A. It maps B-coordinates to
///   A-coordinates, \f${}^A x = {}^A R_B\, {}^B x\f$; its columns are B's axes seen in A.
/// - Rotations accumulate with matching inner indices (slide 15):
///   \f${}^A R_C = {}^A R_B\, {}^B R_C\f$.
/// - Frame B reached from A by turning through \f$\theta\f$ about the unit axis \f$n\f$ has
///   \f${}^A R_B = \exp(\theta \tilde n) = \cos\theta\, I + (1-\cos\theta)\, n n^* +
///   \sin\theta\, \tilde n\f$ (slide 19).
/// - The unit quaternion of that rotation stores the vector part first (slide 19):
///   \f$ q = [\sin(\theta/2)\, n;\ \cos(\theta/2)]\f$.
///
/// Every representation in `soa/rotation/` converts to and from this matrix, so converting
/// at a boundary means going through `matrix()` and `from_matrix()` (see convert()).
#pragma once

#include <cmath>

#include "soa/tilde.hpp"
#include "soa/types.hpp"

namespace soa {

/// True when \p R is orthonormal with determinant +1 to within \p tol.
template <class S>
bool is_rotation(const Mat3<S>& R, S tol) {
  return (R.transpose() * R - Mat3<S>::Identity()).cwiseAbs().maxCoeff() <= tol &&
         std::abs(R.determinant() - S(1)) <= tol;
}

/// is_rotation() of an Eigen expression: forwards to is_rotation(const Mat3<S>&, S).
template <class D>
bool is_rotation(const Eigen::MatrixBase<D>& R, typename D::Scalar tol) {
  return is_rotation(Mat3<typename D::Scalar>(R), tol);
}

/// \f$\sin(x)/x\f$, exact to rounding for every x including 0.
template <class S>
S sinc(S x) {
  using std::abs;
  using std::sin;
  using std::sqrt;
  return abs(x) < sqrt(sqrt(eps<S>())) ? S(1) - x * x / S(6) : sin(x) / x;
}

/// Conversion between any two attitude representations through the rotation matrix, the hub
/// of the convention: `convert<EulerZYXT<double>>(q)`.
template <class To, class From>
To convert(const From& from) {
  return To::from_matrix(from.matrix());
}

}  // namespace soa
