/// \file
/// Lesson 7 exercises: the spatial operators \f$K\f$ and \f$\psi\f$, the innovations
/// factorization of the mass matrix and its inverse, the diagonal of \f$\mathcal M^{-1}\f$ in
/// \f$O(N)\f$, solving \f$\mathcal M y = b\f$ without forming \f$\mathcal M\f$, the operator
/// \f$\Omega\f$ from \f$\Upsilon\f$, \f$\mathcal M^{-1}\f$ from \f$\Upsilon\f$, the
/// operational-space inverse inertia and the innovations coordinates; then two to work out
/// (level 3): which blocks of \f$\mathcal M^{-1}\f$ are zero, the dense operator of the
/// tip-to-base sweep of 7.4, and a bug to find in the way back from innovations coordinates.
///
/// Conventions (the notes' page "Conventions", docs/conventions.md): body 1 is the tip, body n is
/// next to the base; hinge k joins body k+1 to body k; \f$\theta\f$ and \f$\beta\f$ are stacked
/// tip first (body k's entries start at `m.body(k).q_offset` and `m.body(k).v_offset`). Spatial
/// stacks have body k at rows 6(k-1)..6k-1. `ws.phi[k-1]` is \f$\phi(k+1,k)\f$ after
/// soa::update_phi (`.matrix()` the 6x6, `.apply(f)` and `.transpose_apply(a)` without it). From
/// lesson 6, soa::articulated_inertias fills soa::ArticulatedT: `art.P[k-1]`, `art.D[k-1]`,
/// `art.D_inv[k-1]`, `art.G[k-1]` (6 x n_k) and `art.tau_bar(m, theta, k)`. From lessons 3-4,
/// soa::OperatorsT::build gives the dense \f$\mathcal E_\phi\f$, \f$\phi\f$, \f$H\f$, \f$M\f$.
/// \f$H^*(k)\f$ is the 6 x n_k matrix
/// `m.body(k).hinge.H_star(theta.data() + m.body(k).q_offset)`.
///
/// Under each title: the exercise's level (1 of 3: apply a formula; 2: put several together;
/// 3: work it out: derive a formula, predict a result), the time it usually takes, and the
/// exercises it builds on ("uses 7.3": the same idea, done there first; never a call to your
/// code of that exercise). `make exercises HINT=7.10` prints the next hint of a ladder
/// (exercises/07-mass-matrix-factorization/hints.md).
///
/// The stubs in exercises.cpp throw soa::exercise::NotDone; replace each body with your code
/// and run `make exercises`. Do not call the library function an exercise reproduces (named
/// in its statement); the other library functions are yours to use.
#pragma once

#include <vector>

#include "soa/chain.hpp"
#include "soa/chain/mass_matrix_inverse_upsilon.hpp"
#include "soa/soa.hpp"

namespace soa::ex07 {

using MatX = soa::MatX<double>;
using VecX = soa::VecX<double>;

/// The result of exercise 7.1.
struct KAndPsi {
  MatX K;    ///< \f$K = \mathcal E_\phi G\f$, 6n x nv
  MatX psi;  ///< \f$\psi = (I - \mathcal E_\phi\bar\tau)^{-1}\f$, 6n x 6n
};

/// **Exercise 7.1: the operators \f$K\f$ and \f$\psi\f$.**
/// *Level 1 of 3, about 20 min.*
/// For the chain \p m at state \p x, return the dense \f$K = \mathcal E_\phi G\f$ (non-zero
/// blocks \f$K(k+1,k) = \phi(k+1,k)G(k)\f$ at block row k+1, block column k) and
/// \f$\psi = (I - \mathcal E_\psi)^{-1}\f$ with \f$\mathcal E_\psi = \mathcal E_\phi\bar\tau\f$
/// (lesson 7, section 1, "The operators, and the chains of this lesson"). The tests check them
/// against the library and check the identity \f$\phi^{-1} - \psi^{-1} = -KH\f$ with your
/// matrices. Use soa::OperatorsT and soa::articulated_inertias; do not call
/// soa::InnovationsOperatorsT.
KAndPsi k_and_psi(const Model& m, const State& x);

/// The result of exercise 7.2.
struct InnovationsFactor {
  MatX L;      ///< \f$[I + H\phi K]\f$, nv x nv
  MatX L_inv;  ///< \f$[I - H\psi K]\f$, nv x nv
  MatX D;      ///< \f$D = \mathrm{diag}(D(k))\f$, nv x nv
};

/// **Exercise 7.2: the innovations factor and its inverse.**
/// *Level 2 of 3, about 25 min; uses 7.1.*
/// Return \f$L = I + H\phi K\f$, its inverse in closed form \f$L^{-1} = I - H\psi K\f$ (no
/// matrix inversion other than \f$\psi\f$'s), and \f$D\f$ (lesson 7, sections 3, "The innovations
/// factorization", and 4, "Inverting the factor and the mass matrix"). The tests check
/// \f$\mathcal M = L D L^*\f$ against the mass matrix of lesson 5, that \f$L\f$ is block lower
/// triangular with identity diagonal blocks, and \f$L L^{-1} = I\f$. Do not call
/// soa::InnovationsOperatorsT.
InnovationsFactor innovations_factor(const Model& m, const State& x);

/// **Exercise 7.3: the diagonal blocks of \f$\mathcal M^{-1}\f$ in \f$O(N)\f$.**
/// *Level 2 of 3, about 40 min.*
/// From \f$\mathcal M^{-1} = [I - H\psi K]^* D^{-1} [I - H\psi K]\f$, the diagonal block of
/// hinge k is (\f$H\psi K\f$ is strictly lower triangular)
/// \f[ \mathcal M^{-1}(k,k) = D^{-1}(k) + G^*(k)\,\phi^*(k+1,k)\,\Upsilon(k+1)\,
///     \phi(k+1,k)\,G(k), \f]
/// where \f$\Upsilon(k)\f$, the diagonal blocks of \f$\psi^*H^*D^{-1}H\psi\f$, follow base to
/// tip from \f$\Upsilon(n+1) = 0\f$:
/// \f[ \Upsilon(k) = \psi^*(k+1,k)\,\Upsilon(k+1)\,\psi(k+1,k) + H^*(k)D^{-1}(k)H(k), \qquad
///     \psi(k+1,k) = \phi(k+1,k)\,\bar\tau(k) . \f]
/// Return the n_k x n_k blocks \f$\mathcal M^{-1}(k,k)\f$ at entry k−1 (size n), in O(n):
/// one Riccati pass tip to base, one pass base to tip. Do not call
/// soa::mass_matrix_inverse, soa::InnovationsOperatorsT or soa::OperatorsT.
std::vector<MatX> minv_diagonal(const Model& m, const State& x);

/// **Exercise 7.4: solve \f$\mathcal M y = b\f$ with the factorization.**
/// *Level 2 of 3, about 40 min.*
/// Return \f$y = \mathcal M^{-1} b = [I - H\psi K]^* D^{-1} [I - H\psi K]\, b\f$ by the
/// recursions of lesson 7, section 4, "Inverting the factor and the mass matrix", in O(n), without
/// forming \f$\mathcal M\f$ or any dense operator: tip to base \f$z(k) = \phi(k,k-1)z^+(k-1)\f$,
/// \f$\epsilon(k) = b(k) - H(k)z(k)\f$, \f$\nu(k) = D^{-1}(k)\epsilon(k)\f$,
/// \f$z^+(k) = z(k) + G(k)\epsilon(k)\f$; base to tip
/// \f$\alpha^+(k) = \phi^*(k+1,k)\alpha(k+1)\f$, \f$y(k) = \nu(k) - G^*(k)\alpha^+(k)\f$,
/// \f$\alpha(k) = \alpha^+(k) + H^*(k)y(k)\f$: soa::reference::articulated_solve(). Do not call
/// it, soa::mass_matrix_inverse, soa::forward_dynamics, soa::mass_matrix_crb, soa::OperatorsT
/// or soa::InnovationsOperatorsT.
VecX solve(const Model& m, const State& x, const VecX& b);

/// **Exercise 7.5: the determinant of the mass matrix.**
/// *Level 1 of 3, about 10 min.*
/// \f$[I + H\phi K]\f$ is block unit lower triangular, so \f$\det\mathcal M = \prod_k \det
/// D(k)\f$ (lesson 7, section 3, "The innovations factorization"). Return
/// \f$\log\det\mathcal M = \sum_k \log\det D(k)\f$ (the logarithm: the product over- or
/// underflows on long chains), without forming \f$\mathcal M\f$.
double log_det_mass_matrix(const Model& m, const State& x);

/// **Exercise 7.6: \f$\Omega\f$ from its diagonal \f$\Upsilon\f$.**
/// *Level 2 of 3, about 30 min.*
/// Return the dense 6n x 6n \f$\Omega = \psi^*H^*D^{-1}H\psi\f$ assembled block by block
/// from \f$\Omega = \Upsilon + \tilde\psi^*\Upsilon + \Upsilon\tilde\psi\f$ (lesson 7, section
/// 6, "The operator \f$\Omega\f$ and its diagonal \f$\Upsilon\f$"):
/// \f$\Omega(i,j) = \Upsilon(i)\,\psi(i,j)\f$ for \f$i \ge j\f$ and
/// \f$\Omega(j,i) = \Omega^*(i,j)\f$, with \f$\psi(i,j) = \psi(i,i-1)\cdots\psi(j+1,j)\f$,
/// \f$\psi(k+1,k) = \phi(k+1,k)\bar\tau(k)\f$. \f$\Upsilon(k)\f$ may come from soa::upsilons()
/// (`w.Upsilon[k-1]`). The tests compare it with \f$\phi^*H^*\mathcal M^{-1}H\phi\f$ and with the
/// library. Do not call soa::InnovationsOperatorsT.
MatX omega_from_upsilon(const Model& m, const State& x);

/// **Exercise 7.7: \f$\mathcal M^{-1}\f$ from \f$\Upsilon\f$.**
/// *Level 2 of 3, about 50 min; uses 7.3.*
/// Return \f$\mathcal M^{-1}\f$ (nv x nv) by the \f$O(N^2)\f$ algorithm of lesson 7, section
/// 7, "\f$\mathcal M^{-1}\f$ in \f$O(N^2)\f$ from \f$\Upsilon\f$":
/// \f$\mathcal M^{-1}(k,k) = D^{-1}(k) + G^*(k)\Upsilon^+(k)G(k)\f$ with
/// \f$\Upsilon^+(k) = \phi^*(k+1,k)\Upsilon(k+1)\phi(k+1,k)\f$, and for \f$k > i\f$
/// \f$\mathcal M^{-1}(k,i) = L(k)\,z_i(k)\f$, \f$L(k) = G^*(k)\Upsilon^+(k) -
/// \mathcal M^{-1}(k,k)H(k)\f$, \f$z_i(i+1) = \phi(i+1,i)G(i)\f$, \f$z_i(k+1) =
/// \phi(k+1,k)[z_i(k) - G(k)H(k)z_i(k)]\f$; the upper triangle by symmetry. Without forming
/// \f$\mathcal M\f$. soa::upsilons() may give \f$\Upsilon\f$; do not call
/// soa::mass_matrix_inverse, soa::mass_matrix_inverse_upsilon, soa::mass_matrix_crb,
/// soa::OperatorsT or soa::InnovationsOperatorsT.
MatX minv_from_upsilon(const Model& m, const State& x);

/// **Exercise 7.8: the operational-space inverse inertia.**
/// *Level 2 of 3, about 30 min; uses 7.3.*
/// For the frame F fixed on body \p k at \f${}^{O_k}T_F\f$ = \p frame, return
/// \f$J\mathcal M^{-1}J^* = \phi^*(O_k,F)\,\Upsilon(k)\,\phi(O_k,F)\f$ (6x6, lesson 7,
/// section 8, "The operational-space inverse inertia in \f$O(N)\f$") in \f$O(N)\f$: the Riccati
/// recursion, then the \f$\Upsilon\f$ recursion base to tip down to body k (write it yourself, as
/// in exercise 7.3), then the transform (\f$\phi(O_k,F)\f$ is `Phi(frame)`). The tests compare it
/// with the dense \f$J\mathcal M^{-1}J^*\f$ (soa::jacobian()). Do not call soa::upsilons,
/// soa::operational_space_inverse_inertia, soa::mass_matrix_inverse or soa::OperatorsT.
soa::Mat6<double> operational_inverse_inertia(const Model& m, const State& x, int k,
                                              const Pose& frame);

/// **Exercise 7.9: the innovations coordinates.**
/// *Level 1 of 3, about 15 min.*
/// Return \f$\eta = [I + H\phi K]^*\beta\f$ at the state \p x (\f$\beta\f$ = `x.beta`) in
/// \f$O(N)\f$ by \f$\eta(k) = G^*(k)\,V(k)\f$ (lesson 7, section 9, "Innovations coordinates"),
/// \f$V\f$ from soa::update_velocities(). The tests check \f$\tfrac12\beta^*\mathcal M\beta =
/// \tfrac12\eta^*D\eta\f$ and compare with the dense \f$[I + H\phi K]^*\beta\f$. Do not call
/// soa::InnovationsOperatorsT or soa::OperatorsT.
VecX innovations_coordinates(const Model& m, const State& x);

/// **Exercise 7.10: predict the zeros of \f$\mathcal M^{-1}\f$.**
/// *Level 3 of 3, about 30 min.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 3 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=7.10`).*
/// The mass matrix is dense (lesson 5): a force at any hinge is felt at every other. Its
/// inverse need not be. The block \f$\mathcal M^{-1}(i,j)\f$ (\f$n_i \times n_j\f$, rows of
/// hinge i, columns of hinge j) maps a hinge force at hinge j to the accelerations it gives
/// hinge i when the chain is at rest. Predict, from the hinge types alone, which blocks are
/// zero for every chain with these hinges, whatever its inertias, placements, axes and
/// configuration, and which are non-zero for a generic one. \p hinges lists the hinge types
/// tip first: `hinges[k-1]` is hinge k's, one of revolute, prismatic, helical, universal,
/// spherical and free (no locked hinges). Return the n x n matrix (n = `hinges.size()`) with
/// entry (i−1, j−1) equal to 1 where \f$\mathcal M^{-1}(i,j)\f$ is non-zero and 0 where it is
/// zero. The test builds random chains with these hinge types and compares your prediction
/// with the library's \f$\mathcal M^{-1}\f$ (soa::mass_matrix_inverse; a block counts as
/// zero below \f$10^{-9}\,|\mathcal M^{-1}|\f$). What you need is in lesson 7, sections 4,
/// "Inverting the factor and the mass matrix", and 6, "The operator \f$\Omega\f$ and its diagonal
/// \f$\Upsilon\f$": \f$\mathcal M^{-1} = [I - H\psi K]^* D^{-1} [I - H\psi K]\f$, the blocks of
/// \f$H\psi K\f$, and \f$\psi(k+1,k) = \phi(k+1,k)\,\bar\tau(k)\f$ with
/// \f$\bar\tau(k) = I - G(k)H(k)\f$. Work it out on paper first; then say in a comment what your
/// rule means for the motion of the chain.
MatX minv_zero_pattern(const std::vector<HingeType>& hinges);

/// **Exercise 7.11: the dense operator of the tip-to-base sweep.**
/// *Level 3 of 3, about 45 min; uses 7.4.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 4 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=7.11`).*
/// The first sweep of exercise 7.4 (lesson 7, section 4, "Inverting the factor and the mass
/// matrix"), tip to base from \f$z^+(0) = 0\f$,
/// \f[ z(k) = \phi(k,k-1)\,z^+(k-1), \qquad \epsilon(k) = b(k) - H(k)\,z(k), \qquad
///     z^+(k) = z(k) + G(k)\,\epsilon(k) , \f]
/// maps the hinge forces \f$b\f$ (size nv, tip first) linearly to the innovations
/// \f$\epsilon = A\,b\f$: \f$A\f$ is nv x nv, block lower triangular (\f$\epsilon(k)\f$ depends
/// on \f$b(i)\f$ for \f$i \le k\f$ only) with identity blocks \f$A(k,k)\f$. Work out from the
/// recursion the block \f$A(k,i)\f$ for \f$k > i\f$ (\f$n_k \times n_i\f$) as a product of
/// the per-body matrices \f$H(k)\f$, \f$G(i)\f$, \f$\phi(j+1,j)\f$ and \f$\bar\tau(j) = I -
/// G(j)H(j)\f$ (follow a force at hinge i alone up the chain), and return the dense \f$A\f$
/// assembled block by block from your formula: block (k, i) at rows `m.body(k).v_offset`,
/// columns `m.body(i).v_offset`. Given: \f$\phi(j+1,j)\f$ = `ws.phi[j-1].matrix()` after
/// soa::update_phi; \f$G(j)\f$ = `art.G[j-1]` and \f$\bar\tau(j)\f$ = `art.tau_bar(m,
/// x.theta, j)` after soa::articulated_inertias; \f$H^*(k)\f$ as in the file's comment. Do not
/// run the recursion on the columns of the identity, do not invert a matrix, and do not call
/// soa::InnovationsOperatorsT or soa::OperatorsT. The test compares \f$A\f$ with one of the
/// operators of lesson 7 (which one? your block formula tells), and checks that \f$A\f$
/// inverts the innovations factor: \f$A\,[I + H\phi K] = I\f$.
MatX sweep_operator(const Model& m, const State& x);

/// **Exercise 7.12: find the bug: hinge velocities from innovations coordinates.**
/// *Level 3 of 3, about 25 min; uses 7.9.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 3 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=7.12`).*
/// The innovations coordinates of exercise 7.9, \f$\eta = [I + H\phi K]^*\beta\f$, go back
/// to the hinge velocities by the inverse factor of lesson 7, section 4, "Inverting the factor and
/// the mass matrix": \f$\beta = [I - H\psi K]^*\eta\f$. The stub of this exercise (exercises.cpp,
/// below its `throw` line) computes it in \f$O(N)\f$ in one sweep base to tip, through the body
/// velocities \f$V(k)\f$ of lesson 3, but has one bug. Find it by reading the code against
/// lesson 3 (the velocity recursion) and lesson 7, section 9, "Innovations coordinates"
/// (\f$\eta(k) = G^*(k)V(k)\f$), fix it, delete the `throw` line, and say in a comment what was
/// wrong. Return \f$\beta\f$ (size nv, tip first) for the chain \p m at the configuration
/// `x.theta` (`x.beta` is not used) from \p eta. The test draws \f$\beta\f$, gives you
/// \f$\eta = [I + H\phi K]^*\beta\f$ and compares your result with \f$\beta\f$. Do not call
/// soa::InnovationsOperatorsT or soa::OperatorsT.
VecX beta_from_eta(const Model& m, const State& x, const VecX& eta);

}  // namespace soa::ex07
