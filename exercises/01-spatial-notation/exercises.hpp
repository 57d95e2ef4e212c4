/// \file
/// Lesson 1 exercises: spatial notation (slides 8-77). Each function below has its statement
/// in its comment; write it in `exercises.cpp` (replace the `throw NotDone`), then run
/// `make exercises` to see which ones pass. The tests compare your function with the library
/// on many random cases.
///
/// Rules of the game: write each one from the formula on its slide. You may use the library's
/// types (soa::Phi, soa::Force, ...), their accessors (R(), l(), angular(), linear(), mass(),
/// h(), J(), ...), soa::tilde() for 3-vectors and Eigen, but not the library function that
/// the exercise asks you to reproduce (named in each statement): the test compares with it.
///
/// Conventions (the notes' page "Conventions", docs/conventions.md): spatial vectors angular first, \f$V = [\omega; v]\f$,
/// \f$f = [N; F]\f$; \f${}^x R_y\f$ maps y-coordinates to x-coordinates; a soa::Phi
/// \f$\phi(x,y)\f$ holds \f$R = {}^x R_y\f$ and \f$l = {}^x l(x,y)\f$ (slide 43).
#pragma once

#include "soa/soa.hpp"

namespace soa::ex01 {

/// **Exercise 1.1 — Move a spatial force across a rigid body (slides 48-49, 43).**
///
/// Return \f$f(x) = \phi(x,y)\, f(y)\f$, in x-coordinates, for the force \p f_y given in
/// y-coordinates. Work from the blocks of slide 43,
/// \f[ \phi(x,y) = \begin{pmatrix} I & \tilde l \\ 0 & I \end{pmatrix}
///     \begin{pmatrix} R & 0 \\ 0 & R \end{pmatrix}, \f]
/// i.e. first rotate both parts into x-coordinates, then add the moment of the offset force
/// (slide 48: \f$N(x) = N(y) + l(x,y) \times F(y)\f$, \f$F(x) = F(y)\f$).
///
/// Do not call Phi::apply() or Phi::matrix(). Hint: `phi_xy.R()`, `phi_xy.l()`,
/// `f_y.angular()`, `f_y.linear()`, and soa::Force(N, F).
Force apply_phi(const Phi& phi_xy, const Force& f_y);

/// **Exercise 1.2 — The spatial cross product (slide 53).**
///
/// Return \f$\tilde X\, Y\f$ for the motion vectors \f$X = [x; y]\f$ and
/// \f$Y = [\omega; v]\f$, with
/// \f[ \tilde X = \begin{pmatrix} \tilde x & 0 \\ \tilde y & \tilde x \end{pmatrix} . \f]
/// The result is a rate of change of a motion vector, so it is returned as a
/// soa::Acceleration. Check yourself: \f$\tilde X X = 0\f$ and \f$\tilde X Y = -\tilde Y X\f$
/// (slide 54).
///
/// Do not call soa::cross() or the 6x6 soa::tilde(const SpatialVector&).
Acceleration spatial_cross(const Velocity& X, const Velocity& Y);

/// **Exercise 1.3 — The parallel axis theorem for spatial inertias (slides 66, 70).**
///
/// Given the spatial inertia \p M_y about point y, as its ten numbers \f$(m,\ h(y) = m\,
/// p(y),\ J(y))\f$ in y-coordinates, and \f$\phi(x,y)\f$ (\f$R = {}^x R_y\f$, \f$l = {}^x
/// l(x,y)\f$), return \f$M(x) = \phi(x,y)\, M(y)\, \phi^*(x,y)\f$ in the same
/// \f$(m, m\,p(x), J(x))\f$ form, in x-coordinates: `SpatialInertia(m, h_x, J_x)`.
///
/// Hints: the mass does not change; the centre of mass is the same point, so
/// \f$p(x) = l(x,C) = l(x,y) + R\, p(y)\f$. For \f$J\f$, either go through the centre of
/// mass with slide 66 twice (\f$J(y) = J(C) - m\,\tilde p(y)\tilde p(y)\f$, rotate \f$J(C)\f$
/// with \f$R\, J\, R^*\f$, then move it to x), or multiply out the 6x6 product by blocks.
/// Careful with a zero mass: the first route divides by m (you may assume \f$m > 0\f$).
///
/// Do not call soa::transform(), SpatialInertia::from_cm(), J_cm() or matrix().
SpatialInertia parallel_axis(const Phi& phi_xy, const SpatialInertia& M_y);

/// **Exercise 1.4 — A unit quaternion from axis and angle (slide 19).**
///
/// Return the unit quaternion of the rotation through \p theta (radians, any sign) about the
/// axis \p n, vector part first:
/// \f[ \begin{pmatrix} q \\ q_0 \end{pmatrix} = \begin{pmatrix} \sin(\theta/2)\, n
///     \\ \cos(\theta/2) \end{pmatrix} . \f]
/// \p n may have any non-zero length: normalize it first. A zero axis, or a non-finite axis
/// or angle, names no rotation: throw soa::Error with a message saying so (never return
/// NaN). Build the result with soa::UnitQuaternion(q, q0).
///
/// Do not call UnitQuaternion::exp(), AxisAngle or exp_so3(). Check yourself: its matrix()
/// is the Rodrigues formula \f$\cos\theta\, I + (1-\cos\theta)\, n n^* + \sin\theta\,
/// \tilde n\f$.
UnitQuaternion quaternion_from_axis_angle(const Vec3<double>& n, double theta);

/// **Exercise 1.5 — Kinetic energy about a point that is not the centre of mass
/// (slides 67-73).**
///
/// Return the kinetic energy \f$T = \tfrac12 V^*(x)\, M(x)\, V(x)\f$ of a body with spatial
/// inertia \p M_x about x and spatial velocity \p V_x at x, from the ten numbers
/// \f$(m, h = m\,p(x), J(x))\f$ and without forming the 6x6. Multiply out the blocks of
/// \f[ M(x) = \begin{pmatrix} J(x) & \tilde h \\ -\tilde h & m I \end{pmatrix} \f]
/// (slide 68): you should find three terms, one of which couples \f$\omega\f$ and \f$v\f$.
/// Check yourself with the centre of mass form of slide 67: \f$v(C) = v(x) + \omega \times
/// p(x)\f$ and \f$T = \tfrac12 \omega^* J(C)\, \omega + \tfrac12 m\, v^*(C)\, v(C)\f$.
///
/// Do not call SpatialInertia::kinetic_energy(), operator*, or matrix().
double kinetic_energy(const SpatialInertia& M_x, const Velocity& V_x);

/// **Exercise 1.6 — Reversing a spatial velocity (slides 46, 36).**
///
/// Frames x and y move relative to each other. Given \f$\phi(x,y)\f$ (\f$R = {}^x R_y\f$,
/// \f$l = {}^x l(x,y)\f$) and \f$V(x,y)\f$, the velocity of y relative to x, in
/// y-coordinates, return \f$V(y,x)\f$, the velocity of x relative to y, in x-coordinates:
/// \f[ V(y,x) = -\phi^*(y,x)\, V(x,y), \qquad \text{i.e.}\quad \omega(y,x) = -\omega(x,y),
///     \quad v(y,x) = -v(x,y) + \omega(x,y) \times l(x,y) . \f]
/// Hint: bring \f$\omega(x,y)\f$ and \f$v(x,y)\f$ to x-coordinates with R first; then
/// \f$l(x,y)\f$ is already there.
///
/// Do not call Phi::transpose_apply(), Phi::inverse() or Phi::matrix().
Velocity reverse_velocity(const Phi& phi_xy, const Velocity& V_xy);

/// **Exercise 1.7 — The exponential of SE(3) (slide 63).**
///
/// Return the pose \f$\exp(\hat\xi) = (R, l)\f$ of the twist \f$\xi = [\omega; v]\f$,
/// \f$\hat\xi = \begin{pmatrix} \tilde\omega & v \\ 0 & 0 \end{pmatrix}\f$, from its closed form
/// (lesson 1, section "The Lie group connection: SE(3)"): with \f$\theta = |\omega|\f$,
/// \f[ R = I + g_1\,\tilde\omega + g_2\,\tilde\omega^2, \qquad
///     l = \big(I + g_2\,\tilde\omega + g_3\,\tilde\omega^2\big)\, v, \f]
/// \f[ g_1 = \frac{\sin\theta}{\theta}, \quad g_2 = \frac{1 - \cos\theta}{\theta^2}, \quad
///     g_3 = \frac{\theta - \sin\theta}{\theta^3} . \f]
/// Derive it first: sum the series \f$\sum_k \hat\xi^k / k!\f$ block by block, using
/// \f$\tilde\omega^3 = -\theta^2\tilde\omega\f$. Then make it accurate for every angle: the
/// test includes \f$\theta\f$ down to \f$10^{-9}\f$ and \f$\theta = 0\f$, where the quotients
/// above lose every digit or divide by zero; near zero use their Taylor series
/// (\f$g_1 = 1 - \theta^2/6 + \dots\f$, \f$g_2 = 1/2 - \theta^2/24 + \dots\f$,
/// \f$g_3 = 1/6 - \theta^2/120 + \dots\f$; how many terms, and below which \f$\theta\f$?).
///
/// Do not call soa::exp_se3(), soa::exp_so3(), soa::dexp_so3() or soa::g_series().
Pose exp_twist(const Velocity& xi);

}  // namespace soa::ex01
