/// \file
/// Lesson 2 exercises: the equations of motion of one rigid body about an arbitrary body
/// point x, \f$f(x) = M(x)\,\alpha(x) + b(x)\f$, and the simulation of a free body.
///
/// Conventions (the notes' page "Conventions", docs/conventions.md): spatial vectors angular part
/// first, \f$V = [\omega; v]\f$, \f$f = [N; F]\f$; \f$\tilde a\, b = a \times b\f$;
/// \f$p(x) = l(x, C)\f$ is the vector from the body point x to the centre of mass C; \f$M(x)\f$ is
/// stored as \f$(m,\ m p(x),\ J(x))\f$ (soa::SpatialInertia: `M.mass()`, `M.p()`, `M.J()`,
/// `M.J_cm()`, `M.matrix()`). Every vector of one exercise is in one frame (the body frame).
///
/// Under each title: the exercise's level (1 of 3: apply a formula; 2: put several together;
/// 3: work it out: derive, predict then check, or find the bug in given code), the time it
/// usually takes, and the exercises it builds on ("uses 2.3": the same idea, done there
/// first; never a call to your code of that exercise). `make exercises HINT=2.6` prints the
/// hints of an exercise one at a time (exercises/02-single-rigid-body/hints.md).
///
/// The stubs in exercises.cpp throw soa::exercise::NotDone; replace each body with your code
/// and run `make exercises`. Do not call the library function an exercise reproduces (named
/// in its statement); the other library functions are yours to use.
#pragma once

#include "soa/soa.hpp"

namespace soa::ex02 {

/// **Exercise 2.1: the gyroscopic term.**
/// *Level 1 of 3, about 10 min.*
/// A body with spatial inertia \f$M(x)\f$ about its point x moves with \f$V(x) = [\omega; v]\f$.
/// Return the gyroscopic term of its equations of motion about x (lesson 2, section 3, "The
/// equations of motion about x"):
/// \f[ b(x) = \begin{pmatrix} \tilde\omega\, J(x)\, \omega
///     \\ m\, \tilde\omega\tilde\omega\, p(x) \end{pmatrix}. \f]
/// (It does not depend on v.) Reproduces soa::gyroscopic_force.
Force gyroscopic_term(const SpatialInertia& M, const Velocity& V);

/// **Exercise 2.2: the spatial force, through the centre of mass.**
/// *Level 2 of 3, about 30 min; uses 1.1.*
/// A body of mass \p m with inertia \p J_C about its centre of mass C has its frame at the
/// point x, with \p p \f$= p(x) = l(x, C)\f$. At some instant x moves with \p V \f$= V(x) =
/// [\omega; v(x)]\f$ and \p alpha \f$= \alpha(x) = [\dot\omega; \dot v(x)]\f$ (inertial
/// derivative). Return the spatial force \f$f(x)\f$ that produces this motion, computed
/// through C (lesson 2, sections 1, "Newton and Euler at the centre of mass", to 3, "The equations
/// of motion about x"):
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
/// *Level 2 of 3, about 30 min.*
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
/// *Level 2 of 3, about 45 min; uses 2.3.*
/// Advance the torque-free body from \p x0 by the step \p h. Over the step the attitude is
/// \f$\mathfrak q_0 \otimes \exp(\delta)\f$ with a rotation vector \f$\delta\f$ that starts at
/// 0 and moves as \f$\dot\delta = \mathrm{dexp}^{-1}_{-\delta}\,\omega\f$; classical RK4 runs
/// on \f$(\delta, r, V)\f$ (lesson 2, section 6, "A Lie-group Runge-Kutta method"). Stage i =
/// 1..4, at the stage values \f$(\delta_i, r_i, V_i)\f$, takes
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
/// *Level 1 of 3, about 20 min; uses 1.8.*
/// A body with spatial inertia \p M \f$= M(x)\f$ about its point x moves with
/// \p V \f$= V(x) = [\omega; v]\f$, both in body coordinates, and \p V_dot
/// \f$= \dot V = [\dot\omega; \dot v]\f$ holds the rates of those body-frame components (the
/// derivative in the body frame, what a simulation integrates). Return the spatial force at x
/// in the body-frame form of lesson 2, section 4, "The same law in body coordinates":
/// \f[ f(x) = M(x)\,\dot V + \bar V\, M(x)\, V, \qquad
///     \bar V = \begin{pmatrix} \tilde\omega & \tilde v \\ 0 & \tilde\omega \end{pmatrix}
///     = -\tilde V^* , \f]
/// the force cross product of slide 55 acting on the momentum \f$h(x) = M(x)\,V\f$. Form
/// \f$\bar V\f$ from its blocks yourself (do not call soa::cross_bar), and do not call
/// soa::rigid_body_force: the test compares your force with
/// \f$M(x)\,\alpha(x) + b(x)\f$ at \f$\alpha(x) = [\dot\omega;\ \dot v + \omega \times v]\f$.
Force body_frame_force(const SpatialInertia& M, const Velocity& V, const Acceleration& V_dot);

/// The prediction of exercise 2.6.
struct SpinStability {
  bool stable;  ///< true when a small perturbation stays small (it oscillates)
  double rate;  ///< unstable: the growth rate \f$\lambda\f$ (1/s) of \f$e^{\lambda t}\f$;
                ///< stable: the angular frequency \f$\nu\f$ (rad/s) of the wobble
};

/// **Exercise 2.6: predict whether a spin about a principal axis is stable.**
/// *Level 3 of 3, about 40 min.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 4 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=2.6`).*
/// A torque-free rigid body, its body axes along the principal axes of inertia at its centre
/// of mass, has the principal moments \p J \f$= (J_0, J_1, J_2)\f$ (positive, all different).
/// It spins at the rate \p spin \f$= \Omega\f$ (rad/s, either sign, not zero) about the
/// principal axis number \p axis (0, 1 or 2): \f$\omega = \Omega\, e_{axis}\f$. Give the
/// angular velocity a small nudge \f$\delta\omega\f$. To first order in \f$\delta\omega\f$,
/// the nudge either grows like \f$e^{\lambda t}\f$ (the spin is unstable) or oscillates like
/// \f$\cos(\nu t)\f$ (stable). Predict which, and how fast: return `stable` and `rate`
/// (\f$\lambda\f$ when unstable, \f$\nu\f$ when stable).
///
/// The statement does not give the formula: derive it by linearizing Euler's equation at the
/// centre of mass, \f$J\dot\omega + \omega \times J\omega = 0\f$ (lesson 2, section 1, "Newton and
/// Euler at the centre of mass"), about \f$\omega = \Omega e_{axis}\f$: write the two components
/// of \f$\delta\omega\f$ across the spin axis, differentiate once more, and read off the sign of
/// the coefficient. Lesson 2, section 7, "The Dzhanibekov flip, simulated about a point away from
/// C" quotes the answer for one case (the intermediate axis, \f$J_0 < J_1 < J_2\f$); yours must
/// hold for every axis and every order of the moments. Then check your prediction against a
/// simulation of your own (soa::rk4_step, as in section 7, "The Dzhanibekov flip, simulated about
/// a point away from C") before you run the test.
///
/// The test linearizes the library's soa::rigid_body_acceleration numerically about the spin
/// and compares with the eigenvalues \f$\pm\lambda\f$ or \f$\pm i\nu\f$ of that linear system.
SpinStability spin_stability(const Vec3<double>& J, int axis, double spin);

/// **Exercise 2.7: find the bug in a Lie-group Euler step.**
/// *Level 3 of 3, about 30 min; uses 2.3.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 3 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=2.7`).*
/// One step of the explicit Euler method for the free body of exercise 2.3 (state \p x0: the
/// attitude \f$\mathfrak q = {}^I R_B\f$, the position \f${}^I l(I, x)\f$, the body-frame
/// velocity \f$V = [\omega; v]\f$), under the applied force \p f at x in body coordinates held
/// constant over the step \p h: every rate is taken at \p x0 (the rates of exercise 2.3,
/// lesson 2, section 5, "The free body: state and rates"), the position and the velocity move
/// along a straight line, \f$r_1 = r_0 + h\,\dot r\f$ and \f$V_1 = V_0 + h\,\dot V\f$, and the
/// attitude moves along the exact rotation of a body turning with the constant body-frame angular
/// velocity \f$\omega\f$ for the time h (it stays a unit quaternion).
///
/// The stub in exercises.cpp already holds such a step, below its `throw` line, and it has
/// exactly one bug. Find it (read each line against lesson 2, sections 4, "The same law in body
/// coordinates", and 5, "The free body: state and rates"), fix it, and delete the `throw`. Check
/// yourself: the step must agree with soa::rk4_step to first order in h, and a body spinning about
/// a fixed axis must keep turning about that axis.
FreeBodyState lie_euler_step(const SpatialInertia& M, const FreeBodyState& x0, const Force& f,
                             double h);

}  // namespace soa::ex02
