/// \file
/// Unit quaternions, vector part first (slides 18-20).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "soa/error.hpp"
#include "soa/rotation/axis_angle.hpp"

namespace soa {

/// The unit quaternion \f$[q; q_0] = [\sin(\theta/2)\, n;\ \cos(\theta/2)]\f$ of
/// \f${}^A R_B = \exp(\theta\tilde n)\f$ (slide 19): vector part first, as in the course.
///
/// Input that is not of unit norm is normalized when the quaternion is made, and a zero or
/// non-finite input is refused with soa::Error (documented: any non-zero finite 4-vector
/// names a rotation; use from_coeffs_checked() where a non-unit input is a mistake).
template <class S>
class UnitQuaternionT {
 public:
  /// The identity rotation \f$[0; 1]\f$.
  UnitQuaternionT() : q_(Vec3<S>::Zero()), q0_(S(1)) {}

  /// From the vector part \p q and the scalar part \p q0, normalized.
  UnitQuaternionT(const Vec3<S>& q, S q0) : q_(q), q0_(q0) {
    require_finite(q, "UnitQuaternion: vector part");
    require_finite_scalar(q0, "UnitQuaternion: scalar part");
    using std::abs;  // std's for the standard precisions, by lookup for other scalars
    using std::sqrt;
    S n2 = q.squaredNorm() + q0 * q0;
    if (!(n2 >= std::numeric_limits<S>::min() / eps<S>() && n2 <= std::numeric_limits<S>::max())) {
      // The sum of squares under- or overflows: scale by the largest coefficient first.
      const S s = std::max(q.cwiseAbs().maxCoeff(), abs(q0));
      if (!(s > S(0))) throw Error("UnitQuaternion: zero quaternion names no rotation");
      q_ /= s;
      q0_ /= s;
      n2 = q_.squaredNorm() + q0_ * q0_;
    }
    const S norm = sqrt(n2);
    q_ /= norm;
    q0_ /= norm;
  }

  /// From \f$[q; q_0]\f$ that must already be of unit norm within \p tol (else soa::Error
  /// naming the norm found); then normalized to rounding.
  static UnitQuaternionT from_coeffs_checked(const Vec3<S>& q, S q0, S tol) {
    const S norm = std::sqrt(q.squaredNorm() + q0 * q0);
    if (!(std::abs(norm - S(1)) <= tol))
      throw Error("UnitQuaternion: not of unit norm (norm " + std::to_string(double(norm)) + ")");
    return UnitQuaternionT(q, q0);
  }

  /// \f$[\sin(\theta/2)\, n; \cos(\theta/2)]\f$ for the rotation vector \f$w = \theta n\f$
  /// (the quaternion exponential; full precision at \f$\theta \to 0\f$ through sinc()).
  static UnitQuaternionT exp(const Vec3<S>& w) {
    const S half = w.norm() / S(2);
    return UnitQuaternionT(w * (sinc(half) / S(2)), std::cos(half));
  }

  /// The rotation vector \f$\theta n\f$ with \f$\theta \in [0, \pi]\f$ (the sign of the
  /// quaternion is chosen with \f$q_0 \ge 0\f$; \f$\theta \to 0\f$ handled by sinc()).
  Vec3<S> log() const {
    // |q| = sin(θ/2), so θ n = 2 (θ/2) q / |q| = 2 q / sinc(θ/2).
    using std::atan2;
    const S sign = q0_ < S(0) ? S(-1) : S(1);
    const S half = atan2(q_.norm(), sign * q0_);
    return sign * S(2) * q_ / sinc(half);
  }

  const Vec3<S>& q() const { return q_; }  ///< vector part \f$\sin(\theta/2)\, n\f$
  S q0() const { return q0_; }             ///< scalar part \f$\cos(\theta/2)\f$
  /// The four coefficients \f$[q; q_0]\f$.
  Eigen::Matrix<S, 4, 1> coeffs() const {
    Eigen::Matrix<S, 4, 1> c;
    c.template head<3>() = q_;
    c[3] = q0_;
    return c;
  }

  /// \f${}^A R_B = (q_0^2 - q^* q)\, I + 2 q q^* + 2 q_0 \tilde q\f$.
  Mat3<S> matrix() const {
    return (q0_ * q0_ - q_.squaredNorm()) * Mat3<S>::Identity() + S(2) * q_ * q_.transpose() +
           S(2) * q0_ * tilde(q_);
  }

  /// The quaternion of \p R by Shepperd's method: the largest of \f$q_0^2, q_1^2, q_2^2,
  /// q_3^2\f$ is found from the diagonal first, so no division by a small number (valid at
  /// every angle, \f$\pi\f$ included). The result has \f$q_0 \ge 0\f$.
  static UnitQuaternionT from_matrix(const Mat3<S>& R) {
    require_finite(R, "UnitQuaternion::from_matrix: R");
    const S t = R.trace();
    Vec3<S> q;
    S q0;
    Eigen::Index k;
    const S dmax = R.diagonal().maxCoeff(&k);
    if (t >= dmax) {
      q0 = std::sqrt(S(1) + t) / S(2);
      q = vee(R) / (S(2) * q0);
    } else {
      const Eigen::Index i = k, j = (k + 1) % 3, m = (k + 2) % 3;
      q[i] = std::sqrt(S(1) + R(i, i) - R(j, j) - R(m, m)) / S(2);
      q[j] = (R(j, i) + R(i, j)) / (S(4) * q[i]);
      q[m] = (R(m, i) + R(i, m)) / (S(4) * q[i]);
      q0 = (R(m, j) - R(j, m)) / (S(4) * q[i]);
    }
    if (q0 < S(0)) {
      q = -q;
      q0 = -q0;
    }
    return UnitQuaternionT(q, q0);
  }

  /// The product with \f$R(a \otimes b) = R(a)\, R(b)\f$, so quaternions compose as the
  /// matrices do (slide 15): \f$[a; a_0] \otimes [b; b_0] = [a_0 b + b_0 a + a \times b;
  /// a_0 b_0 - a^* b]\f$ (Hamilton's product, vector part first).
  UnitQuaternionT operator*(const UnitQuaternionT& b) const {
    return UnitQuaternionT(q0_ * b.q_ + b.q0_ * q_ + q_.cross(b.q_), q0_ * b.q0_ - q_.dot(b.q_));
  }
  /// The inverse rotation \f$[-q; q_0]\f$.
  UnitQuaternionT conjugate() const { return UnitQuaternionT(-q_, q0_); }
  /// \f${}^A x = {}^A R_B\, {}^B x\f$ without forming the matrix.
  Vec3<S> rotate(const Vec3<S>& x) const {
    const Vec3<S> t = S(2) * q_.cross(x);
    return x + q0_ * t + q_.cross(t);
  }

  /// The quaternion rate for the angular velocity \f$\omega\f$ of B relative to A expressed
  /// in B: \f$\dot{\mathfrak q} = \tfrac12\, \mathfrak q \otimes [\omega; 0]\f$, as the
  /// 4-vector \f$[\dot q; \dot q_0]\f$.
  Eigen::Matrix<S, 4, 1> rate(const Vec3<S>& omega_B) const {
    const Vec3<S> q_dot = (q0_ * omega_B + q_.cross(omega_B)) / S(2);
    Eigen::Matrix<S, 4, 1> r;
    r.template head<3>() = q_dot;
    r[3] = -q_.dot(omega_B) / S(2);
    return r;
  }

  template <class T>
  UnitQuaternionT<T> cast() const {
    return UnitQuaternionT<T>(q_.template cast<T>(), T(q0_));
  }

 private:
  Vec3<S> q_;
  S q0_;
};
using UnitQuaternion = UnitQuaternionT<double>;

}  // namespace soa
