/// \file
/// Lesson 6 exercises: the articulated body inertias of a serial chain by the Riccati
/// recursion, and the projection \f$\bar\tau\f$.
///
/// Conventions (the notes' page "Conventions", docs/conventions.md): body 1 is the tip, body n is next to the base; hinge k
/// joins body k+1 to body k; \f$\theta\f$ is stacked tip first (body k's entries start at
/// `m.body(k).q_offset`). Spatial vectors are angular part first; body k's quantities are at
/// its hinge frame \f$O_k\f$, in \f$O_k\f$ coordinates. `ws.phi[k-1]` is \f$\phi(k+1,k)\f$,
/// so \f$\phi(k,k-1)\f$ is `ws.phi[k-2]`; `phi.R()` and `phi.l()` are its rotation
/// \f$R = {}^{k}R_{k-1}\f$ and offset \f$\ell = {}^{k}l(O_k, O_{k-1})\f$, and
/// `phi.matrix()` is the 6x6 \f$\begin{pmatrix} I & \tilde\ell \\ 0 & I\end{pmatrix}
/// \begin{pmatrix} R & 0 \\ 0 & R\end{pmatrix}\f$. \f$H^*(k)\f$ is the 6 x n_k matrix
/// `m.body(k).hinge.H_star(theta + q_offset)`, \f$H(k)\f$ its transpose.
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
/// Given \f$P^+(k-1)\f$ (\p P_plus_prev; zero for the tip, k = 1), \f$\phi(k,k-1)\f$
/// (\p phi), \f$M(k)\f$ (\p M) and \f$H^*(k)\f$ (\p H_star, 6 x n_k), return (lesson 6,
/// section 2)
/// \f[ P(k) = \phi(k,k-1)\,P^+(k-1)\,\phi^*(k,k-1) + M(k), \quad D(k) = H(k)P(k)H^*(k), \f]
/// \f[ G(k) = P(k)H^*(k)D^{-1}(k), \quad P^+(k) = P(k) - G(k)D(k)G^*(k). \f]
/// Do not call soa::articulated_inertias.
RiccatiStep riccati_step(const Mat6& P_plus_prev, const Phi& phi, const SpatialInertia& M,
                         const MatX<double>& H_star);

/// **Exercise 6.2: the projection \f$\bar\tau\f$.**
/// For an articulated inertia \p P (symmetric, with \f$H P H^*\f$ positive definite) and a
/// hinge map \p H_star (6 x n_k), return (lesson 6, section 3)
/// \f[ \bar\tau = I - G H, \qquad G = P H^* (H P H^*)^{-1} . \f]
/// It is a projection, \f$\bar\tau^2 = \bar\tau\f$, with \f$H\bar\tau P = 0\f$: the tests
/// check both. Do not call soa::ArticulatedT::tau_bar.
Mat6 tau_bar(const Mat6& P, const MatX<double>& H_star);

/// **Exercise 6.3: the articulated hinge inertias of a revolute chain.**
/// Every hinge of \p m is revolute about the unit axis \f$a_k\f$ = `m.body(k).hinge.axis`
/// (\f$H^*(k) = [a_k; 0]\f$, so \f$D(k)\f$ is a scalar). Run the Riccati recursion tip to
/// base at \p theta and return \f$D(k)\f$ at entry k−1 (size n): the inertia hinge k feels
/// about its axis with every hinge outboard of it free. \f$\phi(k,k-1)\f$ from
/// soa::update_phi (allowed). Do not call soa::articulated_inertias.
VecX<double> revolute_D(const Model& m, const VecX<double>& theta);

/// **Exercise 6.4: \f$\phi P \phi^*\f$ without the 6x6 \f$\phi\f$.**
/// For a symmetric 6x6 \p P with blocks \f$\begin{pmatrix} A & B \\ B^* & C\end{pmatrix}\f$
/// return \f$\phi\, P\, \phi^*\f$ from \f$R\f$ = `phi.R()` and \f$L = \tilde\ell\f$
/// (\f$\ell\f$ = `phi.l()`): rotate the blocks, \f$A' = RAR^*\f$, \f$B' = RBR^*\f$,
/// \f$C' = RCR^*\f$, then shift (lesson 6, section 2)
/// \f[ \phi P \phi^* = \begin{pmatrix} A' + LB'^* - B'L - LC'L & B' + LC' \\ (B' + LC')^*
///     & C' \end{pmatrix} . \f]
/// Do not call `phi.matrix()` or soa::transform_symmetric.
Mat6 transform_symmetric(const Phi& phi, const Mat6& P);

/// **Exercise 6.5: the inter-body forces from the articulated sweeps.**
/// For the chain \p m (gravity as \p m says) at the state \p x with hinge forces \p T and no
/// external forces, run soa::forward_dynamics (allowed) and return, at entry k−1 (size n),
/// the force across hinge k from the inter-body forces identity (lesson 6, sections 2 and 8)
/// \f[ f(k) = P^+(k)\,\alpha^+(k) + z^+(k), \f]
/// with \f$P^+(k)\f$, \f$\alpha^+(k)\f$, \f$z^+(k)\f$ as the forward dynamics leaves them in
/// soa::ForwardDynamics (`fd.art.P_plus`, `fd.alpha_plus`, `fd.z_plus`). The test compares
/// them with the Newton–Euler \f$f(k)\f$ at the same \f$\dot\beta\f$ and with \f$R\alpha^+ +
/// y\f$ of the composite inertias.
std::vector<Vec6<double>> articulated_forces(const Model& m, const State& x, const VecX<double>& T);

/// **Exercise 6.6: the composite-body bias \f$y\f$.**
/// For the chain \p m (gravity as \p m says) at the state \p x with hinge accelerations
/// \p beta_dot and no external forces, return \f$y(k)\f$ at entry k−1 (size n) such that
/// \f$f(k) = R(k)\,\alpha^+(k) + y(k)\f$ (lesson 6, section 8):
/// \f[ y(k) = \phi(k,k-1)\,y(k-1) + R(k)\bigl(\alpha(k) - \alpha^+(k)\bigr) + b(k), \quad
///     y(0) = 0, \quad \alpha^+(k) = \phi^*(k+1,k)\,\alpha(k+1),\ \alpha(n+1) = [0; -g], \f]
/// with \f$b(k)\f$ the gyroscopic force (soa::gyroscopic_force of \f$M(k)\f$ and \f$V(k)\f$).
/// \f$\phi\f$, \f$V(k)\f$ and \f$\alpha(k)\f$ from soa::inverse_dynamics (`ws.phi`, `ws.V`,
/// `ws.alpha`), \f$R(k)\f$ from soa::composite_inertias and the base acceleration from
/// soa::gravity_base_acceleration are allowed; do not call soa::composite_bias,
/// soa::alpha_plus or soa::inverse_dynamics_composite.
std::vector<Vec6<double>> composite_bias(const Model& m, const State& x,
                                         const VecX<double>& beta_dot);

}  // namespace soa::ex06
