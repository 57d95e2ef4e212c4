/// \file
/// Homogeneous transforms (poses), slides 22-28.
#pragma once

#include "soa/error.hpp"
#include "soa/types.hpp"

namespace soa {

/// The pose of frame B relative to frame A as the homogeneous transform (slide 23)
/// \f[ {}^A T_B = \begin{pmatrix} {}^A R_B & {}^A l(A,B) \\ 0 & 1 \end{pmatrix}, \f]
/// stored as the rotation and the offset, never as the 4x4.
template <class S>
class PoseT {
 public:
  /// The identity pose.
  PoseT() : R_(Mat3<S>::Identity()), l_(Vec3<S>::Zero()) {}
  /// \f${}^A T_B\f$ from \f${}^A R_B\f$ and \f${}^A l(A,B)\f$ (B's origin in A coordinates).
  PoseT(const Mat3<S>& R, const Vec3<S>& l) : R_(R), l_(l) {}
  /// The pure rotation \f${}^A T_B = ({}^A R_B, 0)\f$: B's origin at A's
  /// (`Pose(exp_so3(theta * a))`).
  explicit PoseT(const Mat3<S>& R) : R_(R), l_(Vec3<S>::Zero()) {}

  const Mat3<S>& R() const { return R_; }  ///< \f${}^A R_B\f$
  const Vec3<S>& l() const { return l_; }  ///< \f${}^A l(A,B)\f$

  /// Composition \f${}^A T_C = {}^A T_B\, {}^B T_C\f$ (slides 25-27):
  /// \f${}^A R_C = {}^A R_B {}^B R_C\f$, \f${}^A l(A,C) = {}^A l(A,B) + {}^A R_B\,{}^B
  /// l(B,C)\f$.
  PoseT operator*(const PoseT& BC) const { return PoseT(R_ * BC.R_, l_ + R_ * BC.l_); }

  /// Inverse \f${}^A T_B^{-1} = {}^B T_A\f$ (slide 24): \f${}^B R_A = {}^A R_B^*\f$,
  /// \f${}^B l(B,A) = -{}^A R_B^*\, {}^A l(A,B)\f$.
  PoseT inverse() const { return PoseT(R_.transpose(), -(R_.transpose() * l_)); }

  /// A point given in B coordinates, in A coordinates (slide 28):
  /// \f${}^A p = {}^A l(A,B) + {}^A R_B\, {}^B p\f$.
  Vec3<S> apply(const Vec3<S>& p_B) const { return l_ + R_ * p_B; }

  /// The 4x4 matrix, for teaching and tests.
  Mat4<S> matrix() const {
    Mat4<S> T = Mat4<S>::Identity();
    T.template topLeftCorner<3, 3>() = R_;
    T.template topRightCorner<3, 1>() = l_;
    return T;
  }

  template <class T>
  PoseT<T> cast() const {
    return PoseT<T>(R_.template cast<T>(), l_.template cast<T>());
  }

 private:
  Mat3<S> R_;
  Vec3<S> l_;
};
using Pose = PoseT<double>;

}  // namespace soa
