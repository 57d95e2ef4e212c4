/// \file
/// Spatial inertia (slides 64-77).
#pragma once

#include <string>

#include "soa/detail/plane.hpp"
#include "soa/error.hpp"
#include "soa/phi.hpp"
#include "soa/spatial_vector.hpp"
#include "soa/tilde.hpp"

namespace soa {

/// The spatial inertia of a rigid body about a point x of it (slide 68):
/// \f[ M(x) = \begin{pmatrix} J(x) & m\tilde p(x) \\ -m\tilde p(x) & m I \end{pmatrix},
/// \qquad p(x) = l(x, C), \f]
/// stored as \f$(m,\ m p,\ J(x))\f$: ten numbers, never the 6x6.
template <class S>
class SpatialInertiaT {
 public:
  /// The zero inertia (no body), the start of a sum of inertias.
  SpatialInertiaT() : m_(0), h_(Vec3<S>::Zero()), J_(Mat3<S>::Zero()) {}

  /// From the mass, the first moment \f$h = m\, p(x)\f$ and \f$J(x)\f$ about x, as stored.
  SpatialInertiaT(S m, const Vec3<S>& h, const Mat3<S>& J) : m_(m), h_(h), J_(J) {}

  /// From the mass \f$m > 0\f$, the centre of mass \f$p(x) = l(x, C)\f$ and the inertia
  /// \f$J(C)\f$ about the centre of mass, by the parallel axis theorem (slide 66):
  /// \f$J(x) = J(C) - m\,\tilde p(x)\,\tilde p(x)\f$.
  /// Refuses (soa::Error) a mass that is not positive, anything not finite, a \f$J(C)\f$
  /// that is not symmetric.
  static SpatialInertiaT from_cm(S m, const Vec3<S>& p, const Mat3<S>& J_C) {
    require_finite_scalar(m, "SpatialInertia: mass");
    require_finite(p, "SpatialInertia: center of mass");
    require_finite(J_C, "SpatialInertia: inertia");
    if (!(m > S(0)))
      throw Error("SpatialInertia: mass must be positive (got " + std::to_string(double(m)) + ")");
    if ((J_C - J_C.transpose()).cwiseAbs().maxCoeff() > S(64) * eps<S>() * J_C.norm())
      throw Error("SpatialInertia: inertia not symmetric");
    const Mat3<S> P = tilde(p);
    return SpatialInertiaT(m, m * p, J_C - m * P * P);
  }

  S mass() const { return m_; }            ///< \f$m\f$
  const Vec3<S>& h() const { return h_; }  ///< \f$m\, p(x)\f$
  Vec3<S> p() const { return h_ / m_; }    ///< \f$p(x) = l(x, C)\f$
  const Mat3<S>& J() const { return J_; }  ///< \f$J(x)\f$
  /// \f$J(C) = J(x) + m\,\tilde p\,\tilde p\f$ (slide 66, read backwards).
  Mat3<S> J_cm() const {
    const Mat3<S> H = tilde(h_);
    return J_ + H * H / m_;
  }

  /// The 6x6 matrix, for teaching and tests.
  Mat6<S> matrix() const {
    Mat6<S> M;
    const Mat3<S> H = tilde(h_);
    M << J_, H, -H, m_ * Mat3<S>::Identity();
    return M;
  }

  /// \f$h(x) = M(x)\, V(x) = [J\omega + m p \times v;\ m v - m p \times \omega]\f$
  /// (slide 76).
  MomentumT<S> operator*(const VelocityT<S>& V) const {
    const Vec3<S> w = V.angular(), v = V.linear();
    return MomentumT<S>(J_ * w + h_.cross(v), m_ * v - h_.cross(w));
  }
  /// \f$M(x)\,\alpha(x)\f$, a force (the inertial term of \f$f = M\alpha + b\f$).
  ForceT<S> operator*(const AccelerationT<S>& a) const {
    const Vec3<S> w = a.angular(), v = a.linear();
    return ForceT<S>(J_ * w + h_.cross(v), m_ * v - h_.cross(w));
  }

  /// Kinetic energy \f$\tfrac12 V^*(x)\, M(x)\, V(x)\f$, the same at every point (slide 72).
  S kinetic_energy(const VelocityT<S>& V) const { return dot(*this * V, V) / S(2); }

  /// Sum of two inertias about the same point (slide 74).
  SpatialInertiaT operator+(const SpatialInertiaT& b) const {
    return SpatialInertiaT(m_ + b.m_, h_ + b.h_, J_ + b.J_);
  }

  template <class T>
  SpatialInertiaT<T> cast() const {
    return SpatialInertiaT<T>(T(m_), h_.template cast<T>(), J_.template cast<T>());
  }

 private:
  S m_;
  Vec3<S> h_;
  Mat3<S> J_;
};
using SpatialInertia = SpatialInertiaT<double>;

namespace detail {

/// soa::transform() with the coordinate axis \p axis of \f$\phi\f$'s rotation known
/// (detail::plane_rotation_axis(), or -1 for the general path).
template <class S>
SpatialInertiaT<S> transform_about(const PhiT<S>& phi_xy, const SpatialInertiaT<S>& M_y, int axis) {
  const S m = M_y.mass();
  const Mat3<S>& R = phi_xy.R();
  const Vec3<S>& l = phi_xy.l();
  Vec3<S> h;
  Mat3<S> J_rot;  // J' = R J(y) R^*, lower triangle i >= j (the rest unused)
  // A rotation about a coordinate axis mixes h and J in its plane only (index names as in
  // soa/detail/plane.hpp): the general products less those with R's exact zeros and ones.
  const bool plane = detail::with_plane_axis(axis, [&](auto axis_c) {
    constexpr int Axis = decltype(axis_c)::value, U = Axis == 2 ? 0 : Axis + 1,
                  W = U == 2 ? 0 : U + 1;
    const Vec3<S>& hy = M_y.h();
    h[Axis] = hy[Axis];
    h[U] = R(U, U) * hy[U] + R(U, W) * hy[W];
    h[W] = R(W, U) * hy[U] + R(W, W) * hy[W];
    J_rot = detail::plane_rotate<Axis>(R, M_y.J(), true);
  });
  if (!plane) {
    h = R * M_y.h();
    const Mat3<S> RJ = R * M_y.J();
    for (int j = 0; j < 3; ++j)
      for (int i = j; i < 3; ++i) J_rot(i, j) = RJ.row(i).dot(R.row(j));
  }
  const Vec3<S> u = h + (m / S(2)) * l;
  const S two_lu = S(2) * l.dot(u);
  Mat3<S> J;
  for (int j = 0; j < 3; ++j)
    for (int i = j; i < 3; ++i) {
      S v = J_rot(i, j) - (u[i] * l[j] + l[i] * u[j]);
      if (i == j) v += two_lu;
      J(i, j) = v;
      J(j, i) = v;
    }
  return SpatialInertiaT<S>(m, h + m * l, J);
}

}  // namespace detail

/// The parallel axis theorem for spatial inertias (slide 70):
/// \f$M(x) = \phi(x,y)\, M(y)\, \phi^*(x,y)\f$, in \f$(m, mp, J)\f$ form. With
/// \f$R = {}^xR_y\f$, \f$l = {}^x l(x,y)\f$, \f$h' = R\,h(y)\f$, \f$J' = R\,J(y)\,R^*\f$:
/// \f[ h(x) = h' + m l, \qquad
///     J(x) = J' - \tilde l\,\tilde h' - \tilde h'\,\tilde l - m\,\tilde l\,\tilde l . \f]
/// By \f$\tilde a\,\tilde b = b\,a^* - (a^* b)\, I\f$ (lesson 1) the last three terms are one
/// symmetric rank-2 update: with \f$u = h' + \tfrac m2 l\f$,
/// \f[ J(x) = J' - (u\,l^* + l\,u^*) + 2\,(l^* u)\, I , \f]
/// and \f$J'\f$ is symmetric: six entries are formed, not nine (about 110 flops in all). When
/// \f$R\f$ turns about a coordinate axis (detail::plane_rotation_axis()) and \p fast_path is
/// on, \f$h'\f$ and \f$J'\f$ mix in its plane only (detail::plane_rotate(), 27 flops for
/// \f$J'\f$ instead of 75): each sum loses its products with an exact 0 or 1 and keeps at
/// most two, so the result is the general one bit for bit, or within an ulp of each term
/// where Eigen's general products fuse multiply-adds (FMA targets).
template <class S>
SpatialInertiaT<S> transform(const PhiT<S>& phi_xy, const SpatialInertiaT<S>& M_y,
                             bool fast_path = true) {
  return detail::transform_about(phi_xy, M_y,
                                 fast_path ? detail::plane_rotation_axis(phi_xy.R()) : -1);
}

}  // namespace soa
