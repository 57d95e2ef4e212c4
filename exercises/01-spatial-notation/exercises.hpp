/// \file
/// Lesson 1 exercises: spatial notation (slides 8-77). Each function below has its statement
/// in its comment; write it in `exercises.cpp` (replace the `throw NotDone`), then run
/// `make exercises` to see which ones pass. The tests compare your function with the library
/// on many random cases.
///
/// Rules of the game: write each one from the formula on its slide (the level 3 ones: from
/// the formula you work out). You may use the library's
/// types (soa::Phi, soa::Force, ...), their accessors (R(), l(), angular(), linear(), mass(),
/// h(), J(), ...), soa::tilde() for 3-vectors and Eigen, but not the library function that
/// the exercise asks you to reproduce (named in each statement): the test compares with it.
///
/// Conventions (the notes' page "Conventions", docs/conventions.md): spatial vectors angular
/// first, \f$V = [\omega; v]\f$, \f$f = [N; F]\f$; \f${}^x R_y\f$ maps y-coordinates to
/// x-coordinates; a soa::Phi \f$\phi(x,y)\f$ holds \f$R = {}^x R_y\f$ and \f$l = {}^x l(x,y)\f$
/// (slide 43).
///
/// Under each title: the exercise's level (1 of 3: apply a formula; 2: put several together;
/// 3: work it out: derive the formula, predict then check, or find the bug in given code),
/// the time it usually takes, and the exercises it builds on ("uses 1.2": the same idea, done
/// there first; never a call to your code of that exercise). Stuck on one?
/// `make exercises HINT=1.8` prints its hints one at a time
/// (exercises/01-spatial-notation/hints.md).
#pragma once

#include "soa/soa.hpp"

namespace soa::ex01 {

/// **Exercise 1.1: Move a spatial force across a rigid body (slides 48-49, 43).**
/// *Level 1 of 3, about 15 min.*
///
/// Return \f$f(x) = \phi(x,y)\, f(y)\f$, in x-coordinates, for the force \p f_y given in
/// y-coordinates. Work from the blocks of slide 43,
/// \f[ \phi(x,y) = \begin{pmatrix} I & \tilde l \\ 0 & I \end{pmatrix}
///     \begin{pmatrix} R & 0 \\ 0 & R \end{pmatrix}, \f]
/// i.e. first rotate both parts into x-coordinates, then add the moment of the offset force
/// (slide 48: \f$N(x) = N(y) + l(x,y) \times F(y)\f$, \f$F(x) = F(y)\f$).
///
/// Do not call soa::Phi::apply() or soa::Phi::matrix(). Hint: `phi_xy.R()`, `phi_xy.l()`,
/// `f_y.angular()`, `f_y.linear()`, and soa::Force(N, F).
Force apply_phi(const Phi& phi_xy, const Force& f_y);

/// **Exercise 1.2: The spatial cross product (slide 53).**
/// *Level 1 of 3, about 10 min.*
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

/// **Exercise 1.3: The parallel axis theorem for spatial inertias (slides 66, 70).**
/// *Level 2 of 3, about 40 min; uses 1.1.*
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
/// Do not call soa::transform(), soa::SpatialInertia::from_cm(), soa::SpatialInertia::J_cm()
/// or soa::SpatialInertia::matrix().
SpatialInertia parallel_axis(const Phi& phi_xy, const SpatialInertia& M_y);

/// **Exercise 1.4: A unit quaternion from axis and angle (slide 19).**
/// *Level 1 of 3, about 15 min.*
///
/// Return the unit quaternion of the rotation through \p theta (radians, any sign) about the
/// axis \p n, vector part first:
/// \f[ \begin{pmatrix} q \\ q_0 \end{pmatrix} = \begin{pmatrix} \sin(\theta/2)\, n
///     \\ \cos(\theta/2) \end{pmatrix} . \f]
/// \p n may have any non-zero length: normalize it first. A zero axis, or a non-finite axis
/// or angle, names no rotation: throw soa::Error with a message saying so (never return
/// NaN). Build the result with soa::UnitQuaternion(q, q0).
///
/// Do not call soa::UnitQuaternion::exp(), soa::AxisAngle or soa::exp_so3(). Check yourself:
/// its matrix()
/// is the Rodrigues formula \f$\cos\theta\, I + (1-\cos\theta)\, n n^* + \sin\theta\,
/// \tilde n\f$.
UnitQuaternion quaternion_from_axis_angle(const Vec3<double>& n, double theta);

/// **Exercise 1.5: Kinetic energy about a point that is not the centre of mass (slides 67-73).**
/// *Level 2 of 3, about 25 min.*
///
/// Return the kinetic energy \f$T = \tfrac12 V^*(x)\, M(x)\, V(x)\f$ of a body with spatial
/// inertia \p M_x about x and spatial velocity \p V_x at x, from the ten numbers
/// \f$(m, h = m\,p(x), J(x))\f$ and without forming the 6x6. Multiply out the blocks of
/// \f[ M(x) = \begin{pmatrix} J(x) & \tilde h \\ -\tilde h & m I \end{pmatrix} \f]
/// (slide 68): you should find three terms, one of which couples \f$\omega\f$ and \f$v\f$.
/// Check yourself with the centre of mass form of slide 67: \f$v(C) = v(x) + \omega \times
/// p(x)\f$ and \f$T = \tfrac12 \omega^* J(C)\, \omega + \tfrac12 m\, v^*(C)\, v(C)\f$.
///
/// Do not call soa::SpatialInertia::kinetic_energy(), soa::SpatialInertia::operator*() or
/// soa::SpatialInertia::matrix().
double kinetic_energy(const SpatialInertia& M_x, const Velocity& V_x);

/// **Exercise 1.6: Reversing a spatial velocity (slides 46, 36).**
/// *Level 1 of 3, about 15 min.*
///
/// Frames x and y move relative to each other. Given \f$\phi(x,y)\f$ (\f$R = {}^x R_y\f$,
/// \f$l = {}^x l(x,y)\f$) and \f$V(x,y)\f$, the velocity of y relative to x, in
/// y-coordinates, return \f$V(y,x)\f$, the velocity of x relative to y, in x-coordinates:
/// \f[ V(y,x) = -\phi^*(y,x)\, V(x,y), \qquad \text{i.e.}\quad \omega(y,x) = -\omega(x,y),
///     \quad v(y,x) = -v(x,y) + \omega(x,y) \times l(x,y) . \f]
/// Hint: bring \f$\omega(x,y)\f$ and \f$v(x,y)\f$ to x-coordinates with R first; then
/// \f$l(x,y)\f$ is already there.
///
/// Do not call soa::Phi::transpose_apply(), soa::Phi::inverse() or soa::Phi::matrix().
Velocity reverse_velocity(const Phi& phi_xy, const Velocity& V_xy);

/// **Exercise 1.7: The exponential of SE(3) (slide 63).**
/// *Level 2 of 3, about 45 min.*
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

/// **Exercise 1.8: The cross product of forces, worked out from power (slides 53-55).**
/// *Level 3 of 3, about 30 min; uses 1.2.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 3 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=1.8`).*
///
/// The spatial cross product \f$\tilde X\f$ of exercise 1.2 acts on motion vectors. Forces
/// get their own operator, \f$\bar X\f$, defined by the power it pairs with (lesson 1, section
/// "Spatial cross products"): for the motion vector \f$X\f$, \f$\bar X\f$ is the 6x6 operator
/// on forces with
/// \f[ (\bar X f)^* Y = -f^* (\tilde X Y) \qquad \text{for every force } f
///     \text{ and every motion vector } Y . \f]
/// Given \p X \f$= [x; y]\f$ (angular part first) and the force \p f \f$= [N; F]\f$ (moment
/// first), return \f$\bar X f\f$ as a soa::Force, moment part first.
///
/// The statement does not give the blocks of \f$\bar X\f$: work them out from the definition
/// (write \f$\tilde X\f$ by its 3x3 blocks, see what the definition says about \f$\bar X\f$
/// and \f$\tilde X^*\f$, and use \f$\tilde a^* = -\tilde a\f$ for 3-vectors), then write
/// \f$\bar X f\f$ with 3D cross products. Check yourself: with \f$Y = X\f$ the definition
/// and \f$\tilde X X = 0\f$ give \f$(\bar X f)^* X = 0\f$ for every f.
///
/// Do not call soa::cross_bar(), soa::bar(), soa::tilde(const SpatialVector&) or soa::cross():
/// the test compares with soa::cross_bar() and checks the definition on random Y.
Force force_cross(const Velocity& X, const Force& f);

/// **Exercise 1.9: Predict the rank of a spatial cross product (slides 53-54).**
/// *Level 3 of 3, about 25 min; uses 1.2.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 3 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=1.9`).*
///
/// For the motion vector \p X \f$= [x; y]\f$ the 6x6 matrix
/// \f$\tilde X = \begin{pmatrix} \tilde x & 0 \\ \tilde y & \tilde x \end{pmatrix}\f$
/// (slide 53) sends some motion vectors \f$Y\f$ to zero: \f$X\f$ itself, by slide 54, and
/// which others? Predict the rank of \f$\tilde X\f$, that is 6 minus the dimension of the
/// space of solutions \f$Y = [\omega; v]\f$ of \f$\tilde X Y = 0\f$, and return it.
///
/// Work it out on paper first: solve \f$\tilde X Y = 0\f$ block row by block row (the first
/// row constrains \f$\omega\f$ alone), and count the free parameters. The answer depends on
/// which of x and y are zero, not otherwise on their values. \p X has exact zeros where a
/// part vanishes (test with `x.isZero(0.0)`, or compare with `Vec3<double>::Zero()`).
///
/// Do not form the 6x6 matrix or call a rank-revealing decomposition: decide from x and y.
/// The test computes the rank of soa::tilde(X) with Eigen's FullPivLU and compares.
int spatial_cross_rank(const Velocity& X);

}  // namespace soa::ex01
