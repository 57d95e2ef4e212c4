/// \file
/// Lesson 2 exercises: the equations of motion of one rigid body about an arbitrary body
/// point x, \f$f(x) = M(x)\,\alpha(x) + b(x)\f$, and the simulation of a free body.
///
/// Conventions (the notes' page "Conventions", docs/conventions.md): spatial vectors angular part first, \f$V = [\omega; v]\f$,
/// \f$f = [N; F]\f$; \f$\tilde a\, b = a \times b\f$; \f$p(x) = l(x, C)\f$ is the vector from
/// the body point x to the centre of mass C; \f$M(x)\f$ is stored as \f$(m,\ m p(x),\ J(x))\f$
/// (soa::SpatialInertia: `M.mass()`, `M.p()`, `M.J()`, `M.J_cm()`, `M.matrix()`).
/// Every vector of one exercise is in one frame (the body frame).
///
/// The stubs in exercises.cpp throw soa::exercise::NotDone; replace each body with your code
/// and run `make exercises`. Do not call the library function an exercise reproduces (named
/// in its statement); the other library functions are yours to use.
#pragma once

#include "soa/soa.hpp"

namespace soa::ex02 {

/// **Exercise 2.1: the gyroscopic term.**
/// A body with spatial inertia \f$M(x)\f$ about its point x moves with \f$V(x) = [\omega; v]\f$.
/// Return the gyroscopic term of its equations of motion about x (lesson 2, section 3):
/// \f[ b(x) = \begin{pmatrix} \tilde\omega\, J(x)\, \omega
///     \\ m\, \tilde\omega\tilde\omega\, p(x) \end{pmatrix}. \f]
/// (It does not depend on v.) Reproduces soa::gyroscopic_force.
Force gyroscopic_term(const SpatialInertia& M, const Velocity& V);

/// **Exercise 2.2: the spatial force, through the centre of mass.**
/// A body of mass \p m with inertia \p J_C about its centre of mass C has its frame at the
/// point x, with \p p \f$= p(x) = l(x, C)\f$. At some instant x moves with \p V \f$= V(x) =
/// [\omega; v(x)]\f$ and \p alpha \f$= \alpha(x) = [\dot\omega; \dot v(x)]\f$ (inertial
/// derivative). Return the spatial force \f$f(x)\f$ that produces this motion, computed
/// through C (lesson 2, sections 1-3):
/// 1. \f$\alpha(C) = \phi^*(x, C)\, \alpha(x) + [0;\ \omega \times (\omega \times p)]\f$;
/// 2. Newton and Euler at C: \f$f(C) = [J(C)\dot\omega + \omega \times J(C)\omega;
///    m\, \dot v(C)]\f$;
/// 3. \f$f(x) = \phi(x, C)\, f(C)\f$, with \f$\phi(x, C) = \begin{pmatrix} I & \tilde p
///    \\ 0 & I \end{pmatrix}\f$: \f$N(x) = N(C) + p \times F(C)\f$, \f$F(x) = F(C)\f$.
///
/// The result must equal \f$M(x)\,\alpha(x) + b(x)\f$ (soa::rigid_body_force, which you
/// must not call).
Force spatial_force(double m, const Mat3<double>& J_C, const Vec3<double>& p, const Velocity& V,
                    const Acceleration& alpha);

/// **Exercise 2.3: the rates of a free body.**
/// The state \p x of a free body with frame at x (soa::FreeBodyState: attitude `x.q` =
/// \f${}^I R_B\f$, position `x.r` = \f${}^I l(I, x)\f$, velocity `x.V` = \f$[\omega; v]\f$ in
/// body coordinates) is acted on by the spatial force \p f at x, in body coordinates.
/// Return its rates (soa::FreeBodyRateT<double>):
/// - `omega` \f$= \omega\f$ (what drives the attitude, \f$\dot R = R\,\tilde\omega\f$);
/// - `r_dot` \f$= {}^I R_B\, v\f$;
/// - `V_dot` \f$= [\dot\omega;\ \dot v]\f$, the rates of the body-frame components of V, from
///   \f$\alpha = M^{-1}(f - b)\f$ (solve the 6x6 system, e.g. with `M.matrix().llt()`) and
///   \f$\alpha = [\dot\omega;\ \dot v + \omega \times v]\f$.
///
/// Reproduces soa::free_body_rate (and do not call soa::rigid_body_acceleration either).
FreeBodyRateT<double> body_rates(const SpatialInertia& M, const FreeBodyState& x, const Force& f);

/// **Exercise 2.4: one step of the Lie-group RK4 (Runge-Kutta-Munthe-Kaas), torque-free.**
/// Advance the torque-free body from \p x0 by the step \p h. Over the step the attitude is
/// \f$\mathfrak q_0 \otimes \exp(\delta)\f$ with a rotation vector \f$\delta\f$ that starts at
/// 0 and moves as \f$\dot\delta = \mathrm{dexp}^{-1}_{-\delta}\,\omega\f$; classical RK4 runs
/// on \f$(\delta, r, V)\f$ (lesson 2, section 6). Stage i = 1..4, at the stage values
/// \f$(\delta_i, r_i, V_i)\f$, takes
/// - \f$d_i\f$ = `soa::free_body_rate(M, s_i, Force::Zero())` for the state \f$s_i\f$ with
///   attitude `x0.q * UnitQuaternion::exp(delta_i)`, position \f$r_i\f$, velocity \f$V_i\f$:
///   this gives \f$\dot r_i\f$ = `d_i.r_dot` and \f$\dot V_i\f$ = `d_i.V_dot`;
/// - \f$e_i\f$ = `soa::dexp_inv_right(delta_i, d_i.omega)`, the rate of \f$\delta\f$;
///
/// with the stage values
/// \f[ (\delta_1, r_1, V_1) = (0,\ r_0,\ V_0), \quad
///     (\delta_2, r_2, V_2) = (\tfrac h2 e_1,\ r_0 + \tfrac h2 \dot r_1,\ V_0 + \tfrac h2
///     \dot V_1), \f]
/// \f[ (\delta_3, r_3, V_3) = (\tfrac h2 e_2,\ r_0 + \tfrac h2 \dot r_2,\ V_0 + \tfrac h2
///     \dot V_2), \quad
///     (\delta_4, r_4, V_4) = (h\, e_3,\ r_0 + h\, \dot r_3,\ V_0 + h\, \dot V_3). \f]
/// The step ends with
/// \f$\mathfrak q_1 = \mathfrak q_0 \otimes \exp(\tfrac h6 (e_1 + 2e_2 + 2e_3 + e_4))\f$,
/// \f$r_1 = r_0 + \tfrac h6 (\dot r_1 + 2\dot r_2 + 2\dot r_3 + \dot r_4)\f$ and \f$V_1\f$
/// likewise. Reproduces soa::rk4_step (which you must not call).
FreeBodyState rk4_torque_free(const SpatialInertia& M, const FreeBodyState& x0, double h);

/// **Exercise 2.5: the equations of motion in body coordinates.**
/// A body with spatial inertia \p M \f$= M(x)\f$ about its point x moves with
/// \p V \f$= V(x) = [\omega; v]\f$, both in body coordinates, and \p V_dot
/// \f$= \dot V = [\dot\omega; \dot v]\f$ holds the rates of those body-frame components (the
/// derivative in the body frame, what a simulation integrates). Return the spatial force at x
/// in the body-frame form of lesson 2, section 4:
/// \f[ f(x) = M(x)\,\dot V + \bar V\, M(x)\, V, \qquad
///     \bar V = \begin{pmatrix} \tilde\omega & \tilde v \\ 0 & \tilde\omega \end{pmatrix}
///     = -\tilde V^* , \f]
/// the force cross product of slide 55 acting on the momentum \f$h(x) = M(x)\,V\f$. Form
/// \f$\bar V\f$ from its blocks yourself (do not call soa::cross_bar), and do not call
/// soa::rigid_body_force: the test compares your force with
/// \f$M(x)\,\alpha(x) + b(x)\f$ at \f$\alpha(x) = [\dot\omega;\ \dot v + \omega \times v]\f$.
Force body_frame_force(const SpatialInertia& M, const Velocity& V, const Acceleration& V_dot);

}  // namespace soa::ex02
