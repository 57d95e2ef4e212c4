/// \file
/// The Lie group SE(3) of poses and its Lie algebra se(3): the adjoint Ad, the bracket ad,
/// the exponential and logarithm and the derivative of the exponential (slide 63; the
/// book's appendix on Lie groups; lesson 1, section "SE(3) Lie group connections").
///
/// Conventions of the course, not of the robotics literature:
/// - a twist \f$\xi = [\omega; v]\f$ is stored as a motion vector, angular part first;
/// - \f${}^x T_y = (R, l)\f$ with \f$R = {}^x R_y\f$ mapping y-coordinates to x-coordinates
///   (the passive convention of soa/rotation/convention.hpp) and \f$l = {}^x l(x, y)\f$;
/// - \f$\hat\xi = \begin{pmatrix} \tilde\omega & v \\ 0 & 0 \end{pmatrix}\f$ is the 4x4 of
///   \f$\xi\f$, and \f$\exp(\hat\xi)\f$ is a pose (slide 23).
#pragma once

#include <cmath>

#include "soa/phi.hpp"
#include "soa/pose.hpp"
#include "soa/rotation/axis_angle.hpp"
#include "soa/spatial_cross.hpp"
#include "soa/spatial_vector.hpp"
#include "soa/tilde.hpp"

namespace soa {

/// The coefficients of the exponential's series, lesson 1, "The Lie group connection: SE(3)":
/// \f[ g_n(\theta) = \sum_{k \ge 0} \frac{(-1)^k\, \theta^{2k}}{(2k+n)!}, \qquad
///     g_0 = \cos\theta,\ g_1 = \frac{\sin\theta}{\theta},\ g_2 = \frac{1-\cos\theta}{\theta^2},
///     \ g_3 = \frac{\theta - \sin\theta}{\theta^3},\ \ldots,\quad
///     g_{n+2} = \frac{1/n! - g_n}{\theta^2} . \f]
/// For \f$\theta < 2\f$ the series is summed (no cancellation: its terms fall fast and do not
/// cancel by more than a factor of a few); above, the recurrence from \f$\cos\theta\f$ and
/// \f$\sin\theta/\theta\f$ is used, whose subtractions lose at most a factor of about 5 there.
/// The closed forms \f$(1-\cos\theta)/\theta^2\f$, \f$(\theta-\sin\theta)/\theta^3\f$ lose all
/// digits as \f$\theta \to 0\f$ (slide 63, small-angle behaviour as in exp_so3()).
template <class S>
S g_series(int n, S theta) {
  using std::abs;
  const S t2 = theta * theta;
  if (abs(theta) < S(2)) {
    S inv_fact = S(1);  // 1/n!
    for (int i = 2; i <= n; ++i) inv_fact /= S(i);
    S term = inv_fact, sum = inv_fact;
    for (int k = 1; abs(term) > eps<S>() * abs(sum) / S(8); ++k) {
      term *= -t2 / (S(2 * k + n - 1) * S(2 * k + n));
      sum += term;
    }
    return sum;
  }
  S g_even = std::cos(theta), g_odd = std::sin(theta) / theta, inv_fact_even = S(1),
    inv_fact_odd = S(1);  // g_0, g_1, 1/0!, 1/1!
  for (int m = 0; m + 2 <= n; m += 2) {
    g_even = (inv_fact_even - g_even) / t2;  // g_{m+2}
    g_odd = (inv_fact_odd - g_odd) / t2;     // g_{m+3}
    inv_fact_even /= S((m + 1) * (m + 2));
    inv_fact_odd /= S((m + 2) * (m + 3));
  }
  return n % 2 == 0 ? g_even : g_odd;
}

/// \f$\hat\xi = \begin{pmatrix} \tilde\omega & v \\ 0 & 0 \end{pmatrix}\f$, the 4x4 of the
/// twist \f$\xi = [\omega; v]\f$ (slide 63), for teaching and tests.
template <class S, class K>
Mat4<S> hat(const SpatialVector<S, K>& xi) {
  static_assert(K::is_motion, "a twist is a motion vector");
  Mat4<S> m = Mat4<S>::Zero();
  m.template topLeftCorner<3, 3>() = tilde<S>(xi.angular());
  m.template topRightCorner<3, 1>() = xi.linear();
  return m;
}

/// The inverse of hat(): the twist \f$[\omega; v]\f$ of the 4x4 \p m (its skew part and last
/// column; the bottom row is ignored).
template <class S>
VelocityT<S> vee_se3(const Mat4<S>& m) {
  return VelocityT<S>(vee<S>(m.template topLeftCorner<3, 3>()), m.template topRightCorner<3, 1>());
}

/// vee_se3() of an Eigen expression: forwards to vee_se3(const Mat4<S>&).
template <class D>
VelocityT<typename D::Scalar> vee_se3(const Eigen::MatrixBase<D>& m) {
  return vee_se3(Mat4<typename D::Scalar>(m));
}

/// \f$\mathrm{Ad}({}^x T_y) = \phi^*(y,x) = \begin{pmatrix} R & 0 \\ \tilde l R & R
/// \end{pmatrix}\f$, the adjoint of SE(3) (slide 63; lesson 1, "The Lie group connection: SE(3)"), defined by
/// \f$(T\hat\xi T^{-1})^\vee = \mathrm{Ad}(T)\,\xi\f$. For \f$T = {}^x T_y\f$ it takes a
/// motion vector at y in y-coordinates to the same motion at x in x-coordinates. The 6x6 is
/// for teaching and tests; Ad_apply() applies it without forming it.
template <class S>
Mat6<S> Ad(const PoseT<S>& T) {
  Mat6<S> m = Mat6<S>::Zero();
  m.template topLeftCorner<3, 3>() = T.R();
  m.template bottomRightCorner<3, 3>() = T.R();
  m.template bottomLeftCorner<3, 3>() = tilde<S>(T.l()) * T.R();
  return m;
}

/// \f$\mathrm{Ad}(T)\,\xi = [R\omega;\ R v + l \times R\omega]\f$ (lesson 1, "The Lie group connection: SE(3)"),
/// equal to \f$\phi^*(y,x)\,\xi\f$ for \f$T = {}^x T_y\f$ (slide 63).
template <class S, class K>
SpatialVector<S, K> Ad_apply(const PoseT<S>& T, const SpatialVector<S, K>& xi) {
  static_assert(K::is_motion, "Ad acts on motion vectors");
  const Vec3<S> w = T.R() * xi.angular();
  return SpatialVector<S, K>(w, T.R() * xi.linear() + T.l().cross(w));
}

/// \f$\mathrm{ad}(\xi) = \tilde\xi = \begin{pmatrix} \tilde\omega & 0 \\ \tilde v &
/// \tilde\omega \end{pmatrix}\f$: the Lie bracket of se(3),
/// \f$\mathrm{ad}(X)\,Y = ([\hat X, \hat Y])^\vee\f$, is the spatial cross product of
/// slide 53 (slide 63; lesson 1, "The Lie group connection: SE(3)").
template <class S, class K>
Mat6<S> ad(const SpatialVector<S, K>& xi) {
  return tilde(xi);
}

/// \f$\mathrm{dexp}_{SO(3)}(w) = I + g_2(\theta)\,\tilde w + g_3(\theta)\,\tilde w^2\f$,
/// \f$\theta = |w|\f$: the left Jacobian of SO(3), \f$\dot R R^* =
/// (\mathrm{dexp}_{SO(3)}(w)\,\dot w)^\sim\f$ for \f$R = \exp(\tilde w)\f$, and the matrix
/// that carries \f$v\f$ into the offset of \f$\exp(\hat\xi)\f$ (lesson 1, "The Lie group connection: SE(3)").
template <class S>
Mat3<S> dexp_so3(const Vec3<S>& w) {
  const S theta = w.norm();
  const Mat3<S> W = tilde(w);
  return Mat3<S>::Identity() + g_series(2, theta) * W + g_series(3, theta) * W * W;
}

/// dexp_so3() of an Eigen expression: forwards to dexp_so3(const Vec3<S>&).
template <class D>
Mat3<typename D::Scalar> dexp_so3(const Eigen::MatrixBase<D>& w) {
  return dexp_so3(Vec3<typename D::Scalar>(w));
}

/// \f$\mathrm{dexp}_{SO(3)}^{-1}(w) = I - \tfrac12\tilde w + D(\theta)\,\tilde w^2\f$ with
/// \f$D = \frac{1}{\theta^2}\big(1 - \frac{\theta\sin\theta}{2(1-\cos\theta)}\big) =
/// \frac{g_3 - 2 g_4}{2 g_2}\f$, the second form free of cancellation (lesson 1,
/// "The Lie group connection: SE(3)"); valid for \f$\theta < 2\pi\f$.
template <class S>
Mat3<S> dexp_so3_inv(const Vec3<S>& w) {
  const S theta = w.norm();
  const Mat3<S> W = tilde(w);
  const S D = (g_series(3, theta) - S(2) * g_series(4, theta)) / (S(2) * g_series(2, theta));
  return Mat3<S>::Identity() - W / S(2) + D * W * W;
}

/// dexp_so3_inv() of an Eigen expression: forwards to dexp_so3_inv(const Vec3<S>&).
template <class D>
Mat3<typename D::Scalar> dexp_so3_inv(const Eigen::MatrixBase<D>& w) {
  return dexp_so3_inv(Vec3<typename D::Scalar>(w));
}

/// \f$\exp(\hat\xi) = \begin{pmatrix} \exp(\tilde\omega) & \mathrm{dexp}_{SO(3)}(\omega)\, v
/// \\ 0 & 1 \end{pmatrix}\f$, the exponential of SE(3) (slide 63; lesson 1, "The Lie group connection: SE(3)"),
/// exact to rounding down to \f$\theta = |\omega| = 0\f$ (exp_so3() and g_series()).
template <class S, class K>
PoseT<S> exp_se3(const SpatialVector<S, K>& xi) {
  static_assert(K::is_motion, "a twist is a motion vector");
  const Vec3<S> w = xi.angular();
  return PoseT<S>(exp_so3<S>(w), dexp_so3<S>(w) * Vec3<S>(xi.linear()));
}

/// The logarithm of SE(3): the twist \f$\xi = [\omega; \mathrm{dexp}_{SO(3)}^{-1}(\omega)\, l]\f$
/// with \f$\omega\f$ = log_so3(R), \f$\theta \in [0, \pi]\f$, and \f$\exp(\hat\xi) = T\f$
/// (slide 63; lesson 1, "The Lie group connection: SE(3)"). At \f$\theta \to 0\f$ and \f$\theta \to \pi\f$ it
/// inherits log_so3()'s fallbacks; \f$\mathrm{dexp}^{-1}\f$ is regular on \f$[0, \pi]\f$
/// (\f$D(\pi) = 1/\pi^2\f$).
template <class S>
VelocityT<S> log_se3(const PoseT<S>& T) {
  const Vec3<S> w = log_so3(T.R());
  return VelocityT<S>(w, dexp_so3_inv<S>(w) * T.l());
}

/// \f$\mathrm{dexp}(\xi) = \sum_{k\ge0} \frac{\mathrm{ad}(\xi)^k}{(k+1)!} =
/// \begin{pmatrix} J & 0 \\ Q & J \end{pmatrix}\f$, the left Jacobian of SE(3) (the
/// derivative of the exponential, lesson 1, "The Lie group connection: SE(3)"; the book's appendix on Lie groups):
/// \f[ \frac{d}{dt}\exp(\hat\xi)\;\exp(\hat\xi)^{-1} = \big(\mathrm{dexp}(\xi)\,\dot\xi\big)^\wedge,
///     \qquad J = \mathrm{dexp}_{SO(3)}(\omega), \f]
/// \f[ Q = \tfrac12 \tilde v + g_3 (\tilde\omega\tilde v + \tilde v\tilde\omega +
///     \tilde\omega\tilde v\tilde\omega) + g_4 (\tilde\omega^2\tilde v + \tilde v\tilde\omega^2
///     - 3\tilde\omega\tilde v\tilde\omega) + \tfrac12 (g_4 - 3 g_5)(\tilde\omega\tilde v
///     \tilde\omega^2 + \tilde\omega^2\tilde v\tilde\omega) . \f]
/// \f$\mathrm{dexp}(-\xi)\f$ is the right Jacobian, \f$\exp(\hat\xi)^{-1}\frac{d}{dt}
/// \exp(\hat\xi) = (\mathrm{dexp}(-\xi)\,\dot\xi)^\wedge\f$.
template <class S, class K>
Mat6<S> dexp_se3(const SpatialVector<S, K>& xi) {
  static_assert(K::is_motion, "a twist is a motion vector");
  const Vec3<S> w = xi.angular();
  const S theta = w.norm();
  const Mat3<S> W = tilde(w), U = tilde<S>(xi.linear());
  const Mat3<S> WU = W * U, UW = U * W, WUW = WU * W, WW = W * W;
  const S g3 = g_series(3, theta), g4 = g_series(4, theta), g5 = g_series(5, theta);
  const Mat3<S> Q = U / S(2) + g3 * (WU + UW + WUW) + g4 * (WW * U + U * WW - S(3) * WUW) +
                    (g4 - S(3) * g5) / S(2) * (WUW * W + W * WUW);
  Mat6<S> m = Mat6<S>::Zero();
  const Mat3<S> J = dexp_so3<S>(w);
  m.template topLeftCorner<3, 3>() = J;
  m.template bottomRightCorner<3, 3>() = J;
  m.template bottomLeftCorner<3, 3>() = Q;
  return m;
}

}  // namespace soa
