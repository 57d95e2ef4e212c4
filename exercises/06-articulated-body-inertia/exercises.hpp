/// \file
/// Lesson 6 exercises: the articulated body inertias of a serial chain by the Riccati
/// recursion, and the projection \f$\bar\tau\f$.
///
/// Conventions (the notes' page "Conventions", docs/conventions.md): body 1 is the tip, body
/// n is next to the base (the inertial frame is body n+1); hinge k joins body k+1 to body k;
/// \f$\theta\f$ and \f$\beta\f$ are stacked tip first (body k's entries start at
/// `m.body(k).q_offset` and `m.body(k).v_offset`). Spatial vectors are angular part first;
/// body k's quantities are at its hinge frame \f$O_k\f$, in \f$O_k\f$ coordinates.
/// `ws.phi[k-1]` is \f$\phi(k+1,k)\f$, so \f$\phi(k,k-1)\f$ is `ws.phi[k-2]`; `phi.R()` and
/// `phi.l()` are its rotation \f$R = {}^{k}R_{k-1}\f$ and offset \f$\ell = {}^{k}l(O_k,
/// O_{k-1})\f$, and `phi.matrix()` is the 6x6 \f$\begin{pmatrix} I & \tilde\ell \\ 0 & I
/// \end{pmatrix} \begin{pmatrix} R & 0 \\ 0 & R\end{pmatrix}\f$. \f$H^*(k)\f$ is the 6 x n_k
/// matrix `m.body(k).hinge.H_star(theta.data() + m.body(k).q_offset)`, \f$H(k)\f$ its
/// transpose.
///
/// Under each title: the exercise's level (1 of 3: apply a formula; 2: put several together;
/// 3: work it out: derive, predict, or find the bug), the time it usually takes, and the
/// exercises it builds on ("uses 6.1": the same idea, done there first; never a call to your
/// code of that exercise). `make exercises HINT=6.7` prints the hints of an exercise one at a
/// time (exercises/06-articulated-body-inertia/hints.md).
///
/// The stubs in exercises.cpp throw soa::exercise::NotDone; replace each body with your code
/// and run `make exercises`. Do not call the library function an exercise reproduces (named
/// in its statement); the other library functions are yours to use.
#pragma once

#include <vector>

#include "soa/chain.hpp"
#include "soa/soa.hpp"

namespace soa::ex06 {

using Mat6 = soa::Mat6<double>;

/// The result of exercise 6.1: one step of the Riccati recursion at body k.
struct RiccatiStep {
  Mat6 P;          ///< \f$P(k)\f$
  MatX<double> D;  ///< \f$D(k)\f$, n_k x n_k
  MatX<double> G;  ///< \f$G(k)\f$, 6 x n_k
  Mat6 P_plus;     ///< \f$P^+(k)\f$
};

/// **Exercise 6.1: one Riccati step.**
/// *Level 1 of 3, about 20 min.*
/// Given \f$P^+(k-1)\f$ (\p P_plus_prev; zero for the tip, k = 1), \f$\phi(k,k-1)\f$
/// (\p phi), \f$M(k)\f$ (\p M) and \f$H^*(k)\f$ (\p H_star, 6 x n_k), return (lesson 6,
/// section 2, "The Riccati recursion")
/// \f[ P(k) = \phi(k,k-1)\,P^+(k-1)\,\phi^*(k,k-1) + M(k), \quad D(k) = H(k)P(k)H^*(k), \f]
/// \f[ G(k) = P(k)H^*(k)D^{-1}(k), \quad P^+(k) = P(k) - G(k)D(k)G^*(k). \f]
/// \f$\phi P^+ \phi^*\f$ may use `phi.matrix()` or soa::transform_symmetric (exercise 6.4
/// does it by blocks). Do not call soa::reference::articulated_inertias, nor its fast form
/// soa::articulated_inertias or soa::riccati_step.
RiccatiStep riccati_step(const Mat6& P_plus_prev, const Phi& phi, const SpatialInertia& M,
                         const MatX<double>& H_star);

/// **Exercise 6.2: the projection \f$\bar\tau\f$.**
/// *Level 1 of 3, about 10 min.*
/// For an articulated inertia \p P (symmetric, with \f$H P H^*\f$ positive definite) and a
/// hinge map \p H_star (6 x n_k), return (lesson 6, section 3, "Properties")
/// \f[ \bar\tau = I - G H, \qquad G = P H^* (H P H^*)^{-1} . \f]
/// It is a projection, \f$\bar\tau^2 = \bar\tau\f$, with \f$H\bar\tau P = 0\f$: the tests
/// check both. Do not call soa::ArticulatedT::tau_bar.
Mat6 tau_bar(const Mat6& P, const MatX<double>& H_star);

/// **Exercise 6.3: the articulated hinge inertias of a revolute chain.**
/// *Level 2 of 3, about 30 min; uses 6.1.*
/// Every hinge of \p m is revolute about the unit axis \f$a_k\f$ = `m.body(k).hinge.axis`
/// (\f$H^*(k) = [a_k; 0]\f$, so \f$D(k)\f$ is a scalar). Run the Riccati recursion tip to
/// base at \p theta and return \f$D(k)\f$ at entry k−1 (size n): the inertia hinge k feels
/// about its axis with every hinge outboard of it free. \f$\phi(k,k-1)\f$ from
/// soa::update_phi and \f$\phi P \phi^*\f$ from soa::transform_symmetric are allowed. Do not
/// call soa::reference::articulated_inertias, nor its fast form soa::articulated_inertias or
/// soa::riccati_step.
VecX<double> revolute_D(const Model& m, const VecX<double>& theta);

/// **Exercise 6.4: \f$\phi P \phi^*\f$ without the 6x6 \f$\phi\f$.**
/// *Level 2 of 3, about 30 min.*
/// For a symmetric 6x6 \p P with blocks \f$\begin{pmatrix} A & B \\ B^* & C\end{pmatrix}\f$
/// return \f$\phi\, P\, \phi^*\f$ from \f$R\f$ = `phi.R()` and \f$L = \tilde\ell\f$
/// (\f$\ell\f$ = `phi.l()`): rotate the blocks, \f$A' = RAR^*\f$, \f$B' = RBR^*\f$,
/// \f$C' = RCR^*\f$, then shift (lesson 6, section 2, "The Riccati recursion")
/// \f[ \phi P \phi^* = \begin{pmatrix} A' + LB'^* - B'L - LC'L & B' + LC' \\ (B' + LC')^*
///     & C' \end{pmatrix} . \f]
/// Do not call soa::Phi::matrix() (`phi.matrix()`) or soa::transform_symmetric.
Mat6 transform_symmetric(const Phi& phi, const Mat6& P);

/// **Exercise 6.5: the inter-body forces from the articulated sweeps.**
/// *Level 1 of 3, about 15 min.*
/// For the chain \p m (gravity as \p m says) at the state \p x with hinge forces \p T and no
/// external forces, run soa::forward_dynamics (allowed) and return, at entry k−1 (size n),
/// the force across hinge k from the inter-body forces identity (lesson 6, sections 2, "The Riccati
/// recursion", and 8, "Alternative force decompositions")
/// \f[ f(k) = P^+(k)\,\alpha^+(k) + z^+(k), \f]
/// with \f$P^+(k)\f$, \f$\alpha^+(k)\f$, \f$z^+(k)\f$ as the forward dynamics leaves them in
/// soa::ForwardDynamics (`fd.art.P_plus`, `fd.alpha_plus`, `fd.z_plus`). The test compares
/// them with the Newton–Euler \f$f(k)\f$ at the same \f$\dot\beta\f$ and with \f$R\alpha^+ +
/// y\f$ of the composite inertias.
std::vector<Vec6<double>> articulated_forces(const Model& m, const State& x, const VecX<double>& T);

/// **Exercise 6.6: the composite-body bias \f$y\f$.**
/// *Level 2 of 3, about 40 min; uses 4.1.*
/// For the chain \p m (gravity as \p m says) at the state \p x with hinge accelerations
/// \p beta_dot and no external forces, return \f$y(k)\f$ at entry k−1 (size n) such that
/// \f$f(k) = R(k)\,\alpha^+(k) + y(k)\f$ (lesson 6, section 8, "Alternative force decompositions"):
/// \f[ y(k) = \phi(k,k-1)\,y(k-1) + R(k)\bigl(\alpha(k) - \alpha^+(k)\bigr) + b(k), \quad
///     y(0) = 0, \quad \alpha^+(k) = \phi^*(k+1,k)\,\alpha(k+1),\ \alpha(n+1) = [0; -g], \f]
/// with \f$b(k)\f$ the gyroscopic force (soa::gyroscopic_force of \f$M(k)\f$ and \f$V(k)\f$).
/// \f$\phi\f$, \f$V(k)\f$ and \f$\alpha(k)\f$ from soa::inverse_dynamics (`ws.phi`, `ws.V`,
/// `ws.alpha`), \f$R(k)\f$ from soa::composite_inertias and the base acceleration from
/// soa::gravity_base_acceleration are allowed; do not call soa::composite_bias,
/// soa::alpha_plus or soa::inverse_dynamics_composite.
std::vector<Vec6<double>> composite_bias(const Model& m, const State& x,
                                         const VecX<double>& beta_dot);

/// **Exercise 6.7: find the bug in a Riccati sweep.**
/// *Level 3 of 3, about 30 min; uses 6.1.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 3 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=6.7`).*
/// The stub of `riccati_sweep` in exercises.cpp holds, under its `throw` line, code that is
/// meant to run the Riccati recursion of lesson 6 (section 2, "The Riccati recursion") tip to base
/// over the chain
/// \p m (any hinge types) at \p theta and return \f$P(k)\f$ at entry k−1 (size n). It
/// compiles and runs, but it has one bug. Find it and fix it, then delete the `throw`. No
/// reference result is needed to find it: the properties of lesson 6, section 3, "Properties",
/// checked on the quantities the code computes, point to the line. Do not call
/// soa::articulated_inertias or soa::riccati_step.
std::vector<Mat6> riccati_sweep(const Model& m, const VecX<double>& theta);

/// **Exercise 6.8: predict what \f$P^+(k)\f$ cannot feel.**
/// *Level 3 of 3, about 30 min; uses 6.2.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 3 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=6.8`).*
/// \f$P^+(k)\f$ is the inertia that the bodies 1..k, hinge k free as well, present to body
/// k+1: the force across hinge k is \f$f(k) = P^+(k)\,\alpha^+(k) + z^+(k)\f$ (lesson 6,
/// sections 2, "The Riccati recursion", and 3, "Properties"). It is singular: some
/// accelerations \f$\alpha^+(k)\f$ of body k+1 cost no force at all. Predict which, from the hinges
/// alone, before computing any inertia: for the chain \p m at \p theta (every body with a positive
/// definite \f$M(k)\f$) return, at entry k−1 (size n), a 6 x \f$r_k\f$ matrix whose \f$r_k\f$
/// columns are a basis of the null space of \f$P^+(k)\f$ (the 6-vectors \f$x\f$ with
/// \f$P^+(k)\,x = 0\f$; \f$r_k\f$ is for you to predict too). The answer does not depend on the
/// masses: do not compute any inertia of the chain (soa::articulated_inertias, soa::riccati_step,
/// soa::composite_inertias, soa::forward_dynamics, `m.body(k).M`). The test checks your columns
/// against the library's \f$P^+(k)\f$: their number is 6 − rank \f$P^+(k)\f$, \f$P^+(k)\f$ maps
/// each to zero, and they are independent.
std::vector<MatX<double>> P_plus_null_spaces(const Model& m, const VecX<double>& theta);

/// **Exercise 6.9: the shaken base.**
/// *Level 3 of 3, about 45 min; uses 6.1.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 4 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=6.9`).*
/// The chain \p m hangs at rest (\f$\beta = 0\f$) at \p theta: no gravity (ignore
/// `m.gravity`, it is zero), no springs, no external forces, and no hinge forces
/// (\f$T = 0\f$: every hinge is free). At one instant the base (body n+1, the inertial
/// frame) is given the spatial acceleration \f$\alpha(n+1) = [0; a_0]\f$, \p a0 in inertial
/// coordinates (it translates, it does not rotate). Return the hinge accelerations
/// \f$\dot\beta\f$ of that instant (size nv, tip first), in O(n). Derive them from the
/// articulated body relations of lesson 6, section 2, "The Riccati recursion": what are
/// \f$z(k)\f$, \f$\epsilon(k)\f$ and \f$\nu(k)\f$ here, and how does the acceleration reach body k
/// from the base? \f$P(k)\f$, \f$D(k)\f$, \f$G(k)\f$ from soa::articulated_inertias (after
/// soa::update_phi) are allowed. Do not call soa::forward_dynamics, soa::inverse_dynamics,
/// soa::OperatorsT, soa::mass_matrix_crb or soa::mass_matrix_inverse.
VecX<double> shaken_base(const Model& m, const VecX<double>& theta, const Vec3<double>& a0);

}  // namespace soa::ex06
