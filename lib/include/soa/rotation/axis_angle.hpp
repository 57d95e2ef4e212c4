/// \file
/// Axis-angle, and the exponential and logarithm maps of rotations (slide 19).
#pragma once

#include <cmath>

#include "soa/error.hpp"
#include "soa/rotation/convention.hpp"

namespace soa {

/// \f$\exp(\tilde w)\f$ for the rotation vector \f$w = \theta n\f$ (slide 19):
/// \f[ \exp(\tilde w) = I + \frac{\sin\theta}{\theta}\tilde w
///     + \frac{2\sin^2(\theta/2)}{\theta^2}\tilde w \tilde w . \f]
/// Written with \f$1-\cos\theta = 2\sin^2(\theta/2)\f$ and sinc(), so it keeps full precision
/// down to \f$\theta = 0\f$.
template <class S>
Mat3<S> exp_so3(const Vec3<S>& w) {
  const S theta = w.norm();
  const Mat3<S> W = tilde(w);
  const S half_sinc = sinc(theta / S(2));
  return Mat3<S>::Identity() + sinc(theta) * W + (half_sinc * half_sinc / S(2)) * W * W;
}

/// exp_so3() of an Eigen expression (`exp_so3(theta * a)`): forwards to exp_so3(const Vec3<S>&).
template <class D>
Mat3<typename D::Scalar> exp_so3(const Eigen::MatrixBase<D>& w) {
  return exp_so3(Vec3<typename D::Scalar>(w));
}

/// \f$\exp(\theta\tilde n)\f$ for a unit axis \f$n\f$ (slide 19):
/// \f$\cos\theta\, I + (1-\cos\theta)\, n n^* + \sin\theta\, \tilde n\f$ — the
/// hinge rotation of the chain recursions, cheaper than exp_so3() when the axis is known to
/// be of unit length.
template <class S>
Mat3<S> exp_unit_axis(const Vec3<S>& n, S theta) {
  using std::cos;
  using std::sin;
  const S c = cos(theta), s = sin(theta), t = S(1) - c;
  const S xy = t * n.x() * n.y(), xz = t * n.x() * n.z(), yz = t * n.y() * n.z();
  const S sx = s * n.x(), sy = s * n.y(), sz = s * n.z();
  Mat3<S> R;
  R(0, 0) = c + t * n.x() * n.x();
  R(1, 1) = c + t * n.y() * n.y();
  R(2, 2) = c + t * n.z() * n.z();
  R(0, 1) = xy - sz;
  R(1, 0) = xy + sz;
  R(0, 2) = xz + sy;
  R(2, 0) = xz - sy;
  R(1, 2) = yz - sx;
  R(2, 1) = yz + sx;
  return R;
}

/// exp_unit_axis() of an Eigen expression: forwards to exp_unit_axis(const Vec3<S>&, S).
template <class D>
Mat3<typename D::Scalar> exp_unit_axis(const Eigen::MatrixBase<D>& n, typename D::Scalar theta) {
  return exp_unit_axis(Vec3<typename D::Scalar>(n), theta);
}

/// The logarithm: the rotation vector \f$w = \theta n\f$, \f$\theta \in [0, \pi]\f$, with
/// \f$\exp(\tilde w) = R\f$.
///
/// \f$\theta = \mathrm{atan2}(\sin\theta, \cos\theta)\f$ with \f$\sin\theta\, n =
/// \mathrm{vee}(R)\f$ and \f$\cos\theta = (\mathrm{tr} R - 1)/2\f$. Documented fallbacks:
/// - \f$\theta \to 0\f$: \f$w = \mathrm{vee}(R)\,\theta/\sin\theta\f$ with the ratio taken as
///   1/sinc(), finite at \f$\theta = 0\f$ (gives \f$w = 0\f$ for \f$R = I\f$).
/// - \f$\theta > \pi/2\f$ (up to \f$\pi\f$, where vee(R) vanishes): the axis is read from the
///   symmetric part \f$(R + R^*)/2 - \cos\theta\, I = (1-\cos\theta)\, n n^*\f$, its sign from
///   vee(R); at exactly \f$\pi\f$ either sign is the same rotation.
template <class S>
Vec3<S> log_so3(const Mat3<S>& R) {
  using std::atan2;
  require_finite(R, "log_so3: R");
  const Vec3<S> s = vee(R);
  const S c = (R.trace() - S(1)) / S(2);
  const S theta = atan2(s.norm(), c);
  if (c >= S(0)) return s / sinc(theta);
  const Mat3<S> B = (R + R.transpose()) / S(2) - c * Mat3<S>::Identity();
  Eigen::Index k;
  B.diagonal().maxCoeff(&k);
  Vec3<S> n = B.col(k).normalized();
  if (n.dot(s) < S(0)) n = -n;
  return theta * n;
}

/// log_so3() of an Eigen expression (`log_so3(R1 * R2)`): forwards to log_so3(const Mat3<S>&).
template <class D>
Vec3<typename D::Scalar> log_so3(const Eigen::MatrixBase<D>& R) {
  return log_so3(Mat3<typename D::Scalar>(R));
}

/// Axis-angle \f$(n, \theta)\f$: turning through \f$\theta\f$ about the unit axis \f$n\f$.
template <class S>
struct AxisAngleT {
  Vec3<S> n = Vec3<S>::UnitZ();  ///< unit axis
  S theta = S(0);                ///< angle, radians

  /// From an axis of any non-zero length (normalized here) and an angle.
  static AxisAngleT from(const Vec3<S>& axis, S angle) {
    require_finite(axis, "AxisAngle: axis");
    require_finite_scalar(angle, "AxisAngle: angle");
    const S len = axis.norm();
    if (!(len > S(0))) throw Error("AxisAngle: zero axis");
    return {axis / len, angle};
  }
  /// From the rotation vector \f$w = \theta n\f$ (the axis is +z when \f$w = 0\f$).
  static AxisAngleT from_rotation_vector(const Vec3<S>& w) {
    const S t = w.norm();
    return t > S(0) ? AxisAngleT{w / t, t} : AxisAngleT{};
  }
  /// The rotation vector \f$\theta n\f$.
  Vec3<S> rotation_vector() const { return theta * n; }
  /// \f${}^A R_B = \exp(\theta \tilde n)\f$.
  Mat3<S> matrix() const { return exp_so3<S>(rotation_vector()); }
  /// The axis-angle of \p R with \f$\theta \in [0, \pi]\f$ (see log_so3()).
  static AxisAngleT from_matrix(const Mat3<S>& R) { return from_rotation_vector(log_so3(R)); }
};
using AxisAngle = AxisAngleT<double>;

}  // namespace soa
