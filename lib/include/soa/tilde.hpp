/// \file
/// The 3x3 cross-product matrix (lesson 1, slide 8).
#pragma once

#include "soa/types.hpp"

namespace soa {

/// \f$\tilde{x}\f$, the skew-symmetric matrix with \f$\tilde{x}\, y = x \times y\f$
/// (slide 8):
/// \f[ \tilde{x} = \begin{pmatrix} 0 & -x_3 & x_2 \\ x_3 & 0 & -x_1 \\ -x_2 & x_1 & 0
/// \end{pmatrix} \f]
template <class S>
Mat3<S> tilde(const Vec3<S>& x) {
  Mat3<S> m;
  m << S(0), -x.z(), x.y(), x.z(), S(0), -x.x(), -x.y(), x.x(), S(0);
  return m;
}

/// tilde() of an Eigen expression (`tilde(X.angular())`): forwards to tilde(const Vec3<S>&).
template <class D>
Mat3<typename D::Scalar> tilde(const Eigen::MatrixBase<D>& x) {
  return tilde(Vec3<typename D::Scalar>(x));
}

/// The inverse of tilde(): the 3-vector of the skew-symmetric part of \p m,
/// \f$ \mathrm{vee}(m) = \tfrac12 (m - m^*)^\vee \f$.
template <class S>
Vec3<S> vee(const Mat3<S>& m) {
  return Vec3<S>(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1)) / S(2);
}

/// vee() of an Eigen expression (`vee(R - R.transpose())`): forwards to vee(const Mat3<S>&).
template <class D>
Vec3<typename D::Scalar> vee(const Eigen::MatrixBase<D>& m) {
  return vee(Mat3<typename D::Scalar>(m));
}

}  // namespace soa
