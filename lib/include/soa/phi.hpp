/// \file
/// The rigid body transformation \f$\phi(x, y)\f$ (slides 39-50, 69-71).
#pragma once

#include "soa/pose.hpp"
#include "soa/spatial_vector.hpp"
#include "soa/tilde.hpp"

namespace soa {

/// \f$\phi(x, y)\f$, the rigid body transformation between points x and y, with the rotation
/// from y's frame to x's shown (slide 43):
/// \f[ {}^x\phi(x,y) = \begin{pmatrix} I & {}^x\tilde l(x,y) \\ 0 & I \end{pmatrix}
///     \begin{pmatrix} {}^xR_y & 0 \\ 0 & {}^xR_y \end{pmatrix}. \f]
/// Stored as the pose \f${}^x T_y\f$ (rotation and offset, never as the 6x6).
///
/// Forces move with \f$\phi\f$, velocities with \f$\phi^*\f$ (slide 50):
/// \f$f(x) = \phi(x,y) f(y)\f$ and \f$V(y) = \phi^*(x,y) V(x)\f$.
template <class S>
class PhiT {
 public:
  /// \f$\phi(x, x) = I\f$.
  PhiT() = default;
  /// \f$\phi(x,y)\f$ from \f${}^xR_y\f$ and \f${}^x l(x,y)\f$.
  PhiT(const Mat3<S>& R, const Vec3<S>& l) : T_(R, l) {}
  /// \f$\phi(x,y)\f$ from the pose \f${}^x T_y\f$.
  explicit PhiT(const PoseT<S>& T) : T_(T) {}
  /// The coordinate-free \f$\phi(x,y) = \begin{pmatrix} I & \tilde l \\ 0 & I
  /// \end{pmatrix}\f$ of the vector \f$l = l(x, y)\f$ (slide 39).
  static PhiT translation(const Vec3<S>& l) { return PhiT(Mat3<S>::Identity(), l); }

  const Mat3<S>& R() const { return T_.R(); }  ///< \f${}^xR_y\f$
  const Vec3<S>& l() const { return T_.l(); }  ///< \f${}^x l(x, y)\f$
  const PoseT<S>& pose() const { return T_; }  ///< \f${}^x T_y\f$

  /// \f$\phi(x,y) f(y)\f$ for a force or momentum at y (slide 49):
  /// \f$N(x) = R N(y) + l \times R F(y)\f$, \f$F(x) = R F(y)\f$.
  template <class K>
  SpatialVector<S, K> apply(const SpatialVector<S, K>& f) const {
    static_assert(!K::is_motion, "phi applies to forces; velocities take phi* (slide 50)");
    const Vec3<S> F = R() * f.linear();
    return SpatialVector<S, K>(R() * f.angular() + l().cross(F), F);
  }

  /// \f$\phi^*(x,y) V(x)\f$ for a velocity or acceleration at x (slide 41):
  /// \f$\omega(y) = R^*\omega(x)\f$, \f$v(y) = R^*(v(x) + \omega(x) \times l)\f$.
  template <class K>
  SpatialVector<S, K> transpose_apply(const SpatialVector<S, K>& V) const {
    static_assert(K::is_motion, "phi* applies to velocities; forces take phi (slide 50)");
    const Vec3<S> w = V.angular();
    const Vec3<S> v = Vec3<S>(V.linear()) + w.cross(l());
    return SpatialVector<S, K>(transpose_times(w), transpose_times(v));
  }

  /// \f$\phi(x,z) = \phi(x,y)\,\phi(y,z)\f$ (slide 45), i.e. \f${}^xT_z = {}^xT_y\,{}^yT_z\f$.
  PhiT operator*(const PhiT& yz) const { return PhiT(T_ * yz.T_); }

  /// \f$\phi^{-1}(x,y) = \phi(y,x)\f$ (slide 44).
  PhiT inverse() const { return PhiT(T_.inverse()); }

  /// The 6x6 matrix, for teaching and tests only.
  Mat6<S> matrix() const {
    Mat6<S> m = Mat6<S>::Zero();
    m.template topLeftCorner<3, 3>() = R();
    m.template bottomRightCorner<3, 3>() = R();
    m.template topRightCorner<3, 3>() = tilde<S>(l()) * R();
    return m;
  }

  template <class T>
  PhiT<T> cast() const {
    return PhiT<T>(T_.template cast<T>());
  }

 private:
  // R^* x as three column dot products (faster than Eigen's transposed product here).
  Vec3<S> transpose_times(const Vec3<S>& x) const {
    return Vec3<S>(R().col(0).dot(x), R().col(1).dot(x), R().col(2).dot(x));
  }

  PoseT<S> T_;
};
using Phi = PhiT<double>;

}  // namespace soa
