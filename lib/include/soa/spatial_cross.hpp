/// \file
/// The spatial cross products \f$\tilde X\f$ and \f$\bar X\f$ (slides 53-57).
#pragma once

#include "soa/spatial_vector.hpp"
#include "soa/tilde.hpp"

namespace soa {

/// \f$\tilde X\f$ for \f$X = [x; y]\f$, the spatial cross product that acts on motion
/// vectors (slide 53):
/// \f[ \tilde X = \begin{pmatrix} \tilde x & 0 \\ \tilde y & \tilde x \end{pmatrix}. \f]
/// The 6x6 is for teaching and tests; cross() applies it without forming it.
template <class S, class K>
Mat6<S> tilde(const SpatialVector<S, K>& X) {
  static_assert(K::is_motion, "the spatial cross product is taken of a motion vector");
  Mat6<S> m = Mat6<S>::Zero();
  const Mat3<S> x = tilde<S>(X.angular()), y = tilde<S>(X.linear());
  m.template topLeftCorner<3, 3>() = x;
  m.template bottomRightCorner<3, 3>() = x;
  m.template bottomLeftCorner<3, 3>() = y;
  return m;
}

/// \f$\bar X = -\tilde X^*\f$ for \f$X = [x; y]\f$, the spatial cross product that acts on
/// force vectors (slide 55):
/// \f[ \bar X = \begin{pmatrix} \tilde x & \tilde y \\ 0 & \tilde x \end{pmatrix}. \f]
template <class S, class K>
Mat6<S> bar(const SpatialVector<S, K>& X) {
  return -tilde(X).transpose();
}

/// \f$\tilde X\, Y = [x \times y_\omega;\ y \times y_\omega + x \times y_v]\f$. The result is
/// a rate of change of motion, so its kind is an acceleration.
template <class S, class KX, class KY>
AccelerationT<S> cross(const SpatialVector<S, KX>& X, const SpatialVector<S, KY>& Y) {
  static_assert(KX::is_motion && KY::is_motion, "cross(X, Y) takes two motion vectors");
  const Vec3<S> x = X.angular(), y = X.linear();
  return AccelerationT<S>(x.cross(Vec3<S>(Y.angular())),
                          y.cross(Vec3<S>(Y.angular())) + x.cross(Vec3<S>(Y.linear())));
}

/// \f$\bar X\, f = [x \times f_N + y \times f_F;\ x \times f_F]\f$. The result is a rate of
/// change of momentum, so its kind is a force.
template <class S, class KX, class KF>
ForceT<S> cross_bar(const SpatialVector<S, KX>& X, const SpatialVector<S, KF>& f) {
  static_assert(KX::is_motion && !KF::is_motion,
                "cross_bar(X, f) takes a motion vector and a force (or momentum)");
  const Vec3<S> x = X.angular(), y = X.linear(), N = f.angular(), F = f.linear();
  return ForceT<S>(x.cross(N) + y.cross(F), x.cross(F));
}

}  // namespace soa
