/// \file
/// Lesson 5 exercises: the composite rigid body inertias and the mass matrix from them.
///
/// Conventions (the notes' page "Conventions", docs/conventions.md): body 1 is the tip, body n is
/// next to the base; hinge k joins body k+1 to body k; \f$\theta\f$ and \f$\beta\f$ are stacked
/// tip first (body k's entries start at `m.body(k).q_offset` and `m.body(k).v_offset`). Body k's
/// quantities are at its hinge frame \f$O_k\f$, in \f$O_k\f$ coordinates. `phi[k-1]` is
/// \f$\phi(k+1,k)\f$: `.apply(f)` is \f$\phi(k+1,k)\,f\f$ and `.matrix()` its 6x6 matrix;
/// `soa::transform(phi, M)` is \f$\phi M \phi^*\f$ for a spatial inertia \f$M\f$ (the parallel
/// axis theorem). The dense operators of soa::OperatorsT put body k at rows
/// \f$6(k-1) \dots 6k-1\f$.
///
/// Under each title: the exercise's level (1 of 3: apply a formula; 2: put several together;
/// 3: work it out: derive the formula, predict then check, or find the bug in given code),
/// the time it usually takes, and the exercises it builds on ("uses 5.1": the same idea, done
/// there first; never a call to your code of that exercise). `make exercises HINT=5.5` prints
/// the next hint of an exercise (exercises/05-mass-matrix/hints.md).
///
/// The stubs in exercises.cpp throw soa::exercise::NotDone; replace each body with your code
/// and run `make exercises`. Do not call the library function an exercise reproduces (named
/// in its statement).
#pragma once

#include <vector>

#include "soa/chain.hpp"
#include "soa/soa.hpp"

namespace soa::ex05 {

/// **Exercise 5.1: the composite inertia recursion.**
/// *Level 1 of 3, about 15 min.*
/// Given \f$\phi(k+1,k)\f$ (\p phi, entry k−1) of a chain, return its composite rigid body
/// inertias, entry k−1 = \f$R(k)\f$, the inertia about \f$O_k\f$ of bodies 1..k welded
/// together (lesson 5, section 1, "The composite rigid body inertia"), tip to base:
/// \f[ R(k) = \phi(k,k-1)\, R(k-1)\, \phi^*(k,k-1) + M(k), \qquad R(0) = 0 , \f]
/// with \f$M(k)\f$ = `m.body(k).M`. Mind the index: \f$\phi(k,k-1)\f$ is `phi[k-2]`.
/// Do not call soa::composite_inertias, soa::composite_inertia_operator or
/// soa::mass_matrix_crb.
std::vector<SpatialInertia> composite_inertias(const Model& m, const std::vector<Phi>& phi);

/// **Exercise 5.2: a diagonal block of the mass matrix.**
/// *Level 1 of 3, about 10 min; uses 5.1.*
/// Return the n_k x n_k diagonal block of body k (\p k from 1 to n) of the mass matrix
/// (lesson 5, section 3, "The mass matrix from the composite inertias"),
/// \f[ \mathcal M(k,k) = H(k)\, R(k)\, H^*(k), \f]
/// with \f$R(k)\f$ = `R[k-1]` and the dense \f$H^*(k)\f$ (6 x n_k) =
/// `m.body(k).hinge.H_star(theta.data() + m.body(k).q_offset)` (it may depend on
/// \f$\theta\f$). Do not call soa::mass_matrix_crb or soa::OperatorsT.
MatX<double> mass_matrix_diagonal(const Model& m, const VecX<double>& theta,
                                  const std::vector<SpatialInertia>& R, int k);

/// **Exercise 5.3: the composite rigid body mass matrix of a revolute chain.**
/// *Level 2 of 3, about 40 min; uses 5.1.*
/// Every hinge of \p m is revolute about the unit axis \f$a_k\f$ = `m.body(k).hinge.axis`,
/// so \f$H^*(k) = [a_k; 0]\f$ and the mass matrix is n x n. With \f$\phi(k+1,k)\f$ =
/// `Phi(m.body(k).placement * Pose(exp_so3(theta[k-1] * a_k)))` and the composite
/// inertias \f$R(k)\f$ (exercise 5.1 or soa::composite_inertias), return (lesson 5,
/// section 3, "The mass matrix from the composite inertias"), in \f$O(N^2)\f$,
/// \f[ \mathcal M(k,k) = H(k) R(k) H^*(k), \qquad
///     \mathcal M(i,j) = \mathcal M(j,i) = H(i)\, \phi(i,j)\, R(j)\, H^*(j), \ i > j, \f]
/// carrying the force \f$R(j) H^*(j)\f$ inboard one body at a time,
/// \f$\phi(i,j)\,F = \phi(i,i-1)\,\phi(i-1,j)\,F\f$. Do not call soa::mass_matrix_crb,
/// soa::inverse_dynamics or soa::OperatorsT.
MatX<double> crb_mass_matrix_revolute(const Model& m, const VecX<double>& theta);

/// **Exercise 5.4: the decomposition of \f$\phi M \phi^*\f$.**
/// *Level 2 of 3, about 30 min; uses 5.1.*
/// \p op holds the dense operators of a chain (soa::OperatorsT): `op.E_phi`
/// \f$= \mathcal E_\phi\f$, `op.phi` \f$= \phi\f$ and `op.M` \f$= M\f$ (6n x 6n). Solve the
/// forward Lyapunov equation \f$R = \mathcal E_\phi R \mathcal E_\phi^* + M\f$ for the
/// block-diagonal \f$R\f$ block by block (its block k is \f$R(k)\f$, from the blocks
/// \f$\phi(k,k-1)\f$ of \f$\mathcal E_\phi\f$), and return the right-hand side of
/// (lesson 5, section 2, "The forward Lyapunov equation and the decomposition of
/// \f$\phi M\phi^*\f$")
/// \f[ \phi M \phi^* = R + \tilde\phi R + R \tilde\phi^*, \qquad \tilde\phi = \phi - I , \f]
/// as a dense 6n x 6n matrix. Do not form \f$\phi M \phi^*\f$, and do not call
/// soa::composite_inertias or soa::composite_inertia_operator.
MatX<double> decomposition(const Operators& op);

/// **Exercise 5.5: derive a block of \f$\phi M \phi^*\f$.**
/// *Level 3 of 3, about 40 min; uses 5.4.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 4 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=5.5`).*
/// \p phi holds \f$\phi(k+1,k)\f$ (entry k−1) of a chain of n = `phi.size()` bodies and \p R
/// its composite inertias \f$R(k)\f$ (entry k−1, as soa::composite_inertias gives them).
/// Return the 6x6 block (i, j) of the 6n x 6n operator \f$\phi M \phi^*\f$ (block row i,
/// block column j; any i and j from 1 to n; \f$M = \mathrm{diag}(M(k))\f$ and
/// \f$\phi = (I - \mathcal E_\phi)^{-1}\f$ as in lessons 3 and 4) with at most
/// \f$|i - j|\f$ products by a \f$\phi(k+1,k)\f$. Derive its closed form from the
/// decomposition of lesson 5, section 2, "The forward Lyapunov equation and the decomposition of
/// \f$\phi M\phi^*\f$": which blocks of \f$\tilde\phi\f$ are non-zero, and what, then, is block
/// (i, j) of each of its three terms? The bodies' own inertias \f$M(k)\f$ are not given, and none
/// is needed. Do not form a 6n x 6n matrix, and do not call soa::composite_inertia_operator or
/// soa::OperatorsT.
Mat6<double> phi_M_phi_star_block(const std::vector<Phi>& phi, const std::vector<SpatialInertia>& R,
                                  int i, int j);

/// **Exercise 5.6: predict the mass matrix of a chain of sliders.**
/// *Level 3 of 3, about 30 min; uses 5.3.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 3 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=5.6`).*
/// Every hinge of a chain is prismatic: hinge k lets body k slide along a unit axis, whose
/// direction in inertial coordinates is \p axis[k-1] (it never changes: nothing in this chain
/// turns), and \p mass[k-1] is the mass \f$m_k\f$ of body k (tip first, as always; n =
/// `mass.size()`). Predict the n x n mass matrix \f$\mathcal M\f$ of the chain
/// (\f$\beta\f$ = the n sliding rates, tip first) from these numbers alone: the centres of
/// mass, the rotational inertias and the placements of the bodies are not given. Before you
/// write the code, decide why they cannot matter (lesson 5, sections 1, "The composite rigid body
/// inertia", and 3, "The mass matrix from the composite inertias": which part of \f$R(j)\f$ does a
/// prismatic \f$H^*(j)\f$ see, and what does \f$\phi(i,j)\f$ do to a pure force?). The test checks
/// your prediction against soa::mass_matrix_crb on random chains of sliders.
MatX<double> slider_mass_matrix(const std::vector<double>& mass,
                                const std::vector<Vec3<double>>& axis);

/// **Exercise 5.7: a block column of the mass matrix, both triangles.**
/// *Level 2 of 3, about 30 min; uses 5.3.*
/// Return the nv x n_j block column j of the mass matrix (\p j from 1 to n; every hinge type)
/// from \f$\phi(k+1,k)\f$ (\p phi, entry k−1) and the composite inertias \f$R(k)\f$ (\p R,
/// entry k−1, as soa::composite_inertias gives them), without the symmetry of \f$\mathcal M\f$
/// (lesson 5, section 3, "The mass matrix from the composite inertias"; Jain 2011, chapter 5):
/// \f[ \mathcal M(i,j) = H(i)\, \phi(i,j)\, R(j)\, H^*(j), \ i \ge j, \qquad
///     \mathcal M(i,j) = H(i)\, R(i)\, \phi^*(j,i)\, H^*(j), \ i < j . \f]
/// Below the diagonal, carry the forces \f$R(j) H^*(j)\f$ inboard,
/// \f$\phi(i,j) = \phi(i,i-1)\, \phi(i-1,j)\f$; above it, carry the motions \f$H^*(j)\f$
/// outboard, \f$\phi^*(j,i) = \phi^*(i+1,i)\, \phi^*(j,i+1)\f$. The dense \f$H^*(k)\f$
/// (6 x n_k) is `m.body(k).hinge.H_star(theta.data() + m.body(k).q_offset)`, and the rows of
/// body i start at `m.body(i).v_offset`. Do not call soa::mass_matrix_crb or soa::OperatorsT.
MatX<double> mass_matrix_column(const Model& m, const VecX<double>& theta,
                                const std::vector<Phi>& phi, const std::vector<SpatialInertia>& R,
                                int j);

}  // namespace soa::ex05
