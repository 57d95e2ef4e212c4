/// \file
/// Simulating one free rigid body: state, right-hand side and a Lie-group RK4 (lesson 2).
#pragma once

#include "soa/rigid_body.hpp"
#include "soa/rotation/quaternion.hpp"

namespace soa {

/// The state of a free rigid body with body frame at the point x:
/// attitude \f${}^I R_B\f$ as a unit quaternion, position \f${}^I l(I, x)\f$, and the
/// spatial velocity \f$V(x) = [\omega; v(x)]\f$ in body coordinates.
template <class S>
struct FreeBodyStateT {
  UnitQuaternionT<S> q;         ///< \f${}^I R_B\f$
  Vec3<S> r = Vec3<S>::Zero();  ///< \f${}^I l(I, x)\f$
  VelocityT<S> V;               ///< \f${}^B V(x)\f$
};
using FreeBodyState = FreeBodyStateT<double>;

/// The time derivative of FreeBodyStateT: the body-frame angular velocity that drives the
/// attitude (\f${}^I\dot R_B = {}^I R_B\,\tilde\omega\f$), \f$\dot r\f$, and the rates of the
/// body-frame coordinates of \f$V\f$.
template <class S>
struct FreeBodyRateT {
  Vec3<S> omega;  ///< \f$\omega\f$ in body coordinates
  Vec3<S> r_dot;  ///< \f${}^I R_B\, v(x)\f$
  Vec6<S> V_dot;  ///< \f$\frac{d}{dt}\,{}^B V(x)\f$ (component rates)
};

/// The right-hand side of the free body (lesson 2). The spatial acceleration \f$\alpha(x)\f$
/// is the inertial derivative of \f$V(x)\f$; in body coordinates it relates to the
/// component rates by \f$\alpha = [\dot\omega;\ \dot v + \omega \times v]\f$, so
/// \f[ \alpha = M^{-1}(f - b), \qquad \dot\omega = \alpha_\omega, \qquad
///     \dot v = \alpha_v - \omega \times v . \f]
/// \p f is the applied spatial force at x in body coordinates.
template <class S>
FreeBodyRateT<S> free_body_rate(const SpatialInertiaT<S>& M, const FreeBodyStateT<S>& x,
                                const ForceT<S>& f) {
  const AccelerationT<S> alpha = rigid_body_acceleration(M, x.V, f);
  const Vec3<S> w = x.V.angular(), v = x.V.linear();
  FreeBodyRateT<S> d;
  d.omega = w;
  d.r_dot = x.q.rotate(v);
  d.V_dot.template head<3>() = alpha.angular();
  d.V_dot.template tail<3>() = Vec3<S>(alpha.linear()) - w.cross(v);
  return d;
}

/// The inverse of the differential of the exponential map, as used by Runge-Kutta-Munthe-Kaas
/// with \f$R = R_n \exp(\tilde\delta)\f$: the local coordinates move as
/// \f$\dot\delta = \mathrm{dexp}^{-1}_{-\delta}\,\omega =
/// \omega + \tfrac12\,\delta\times\omega + c(\theta)\,\delta\times(\delta\times\omega)\f$,
/// \f$c(\theta) = (1 - \tfrac{\theta}{2}\cot\tfrac{\theta}{2})/\theta^2\f$
/// (\f$\to 1/12\f$ as \f$\theta \to 0\f$).
template <class S>
Vec3<S> dexp_inv_right(const Vec3<S>& delta, const Vec3<S>& omega) {
  const S t = delta.norm();
  const S c = t < S(1e-2) ? S(1) / S(12) + t * t / S(720) + t * t * t * t / S(30240)
                          : (S(1) - (t / S(2)) / std::tan(t / S(2))) / (t * t);
  return omega + delta.cross(omega) / S(2) + c * delta.cross(delta.cross(omega));
}

/// dexp_inv_right() of Eigen expressions: forwards to dexp_inv_right(const Vec3<S>&, ...).
template <class D1, class D2>
Vec3<typename D1::Scalar> dexp_inv_right(const Eigen::MatrixBase<D1>& delta,
                                         const Eigen::MatrixBase<D2>& omega) {
  using S = typename D1::Scalar;
  return dexp_inv_right(Vec3<S>(delta), Vec3<S>(omega));
}

/// One step of RK4 on the free body, Runge-Kutta-Munthe-Kaas form: the attitude is moved by
/// the exponential of the RK4 combination of local rotation-vector rates, so it stays a
/// unit quaternion by construction (products of unit quaternions; the final normalization
/// only removes rounding). Fourth order in every state component.
/// \p force(t, state) gives the applied force at x in body coordinates.
template <class S, class ForceFn>
FreeBodyStateT<S> rk4_step(const SpatialInertiaT<S>& M, const FreeBodyStateT<S>& x0, S t, S h,
                           ForceFn force) {
  const auto stage = [&](const Vec3<S>& delta, const Vec3<S>& r, const Vec6<S>& V, S ts,
                         Vec3<S>& delta_dot, FreeBodyRateT<S>& d) {
    FreeBodyStateT<S> x{x0.q * UnitQuaternionT<S>::exp(delta), r, VelocityT<S>(V)};
    d = free_body_rate(M, x, force(ts, x));
    delta_dot = dexp_inv_right(delta, d.omega);
  };
  const Vec6<S>& V0 = x0.V.vector();
  FreeBodyRateT<S> d1, d2, d3, d4;
  Vec3<S> e1, e2, e3, e4;
  stage(Vec3<S>::Zero(), x0.r, V0, t, e1, d1);
  stage(h / 2 * e1, x0.r + h / 2 * d1.r_dot, V0 + h / 2 * d1.V_dot, t + h / 2, e2, d2);
  stage(h / 2 * e2, x0.r + h / 2 * d2.r_dot, V0 + h / 2 * d2.V_dot, t + h / 2, e3, d3);
  stage(h * e3, x0.r + h * d3.r_dot, V0 + h * d3.V_dot, t + h, e4, d4);
  FreeBodyStateT<S> x1;
  x1.q = x0.q * UnitQuaternionT<S>::exp(h / 6 * (e1 + 2 * e2 + 2 * e3 + e4));
  x1.r = x0.r + h / 6 * (d1.r_dot + 2 * d2.r_dot + 2 * d3.r_dot + d4.r_dot);
  x1.V = VelocityT<S>(Vec6<S>(V0 + h / 6 * (d1.V_dot + 2 * d2.V_dot + 2 * d3.V_dot + d4.V_dot)));
  return x1;
}

/// Torque-free RK4 step.
template <class S>
FreeBodyStateT<S> rk4_step(const SpatialInertiaT<S>& M, const FreeBodyStateT<S>& x0, S h) {
  return rk4_step(M, x0, S(0), h, [](S, const FreeBodyStateT<S>&) { return ForceT<S>::Zero(); });
}

/// Kinetic energy of the free body, \f$\tfrac12 V^* M V\f$ (slide 72).
template <class S>
S kinetic_energy(const SpatialInertiaT<S>& M, const FreeBodyStateT<S>& x) {
  return M.kinetic_energy(x.V);
}

/// The spatial momentum about the inertial origin O in inertial coordinates,
/// \f$h(O) = \phi(O, x)\, h(x)\f$ with \f$\phi(O,x)\f$ from \f$({}^I R_B, {}^I l(I,x))\f$
/// (slide 77): conserved when no force acts.
template <class S>
MomentumT<S> inertial_momentum(const SpatialInertiaT<S>& M, const FreeBodyStateT<S>& x) {
  return PhiT<S>(x.q.matrix(), x.r).apply(M * x.V);
}

}  // namespace soa
