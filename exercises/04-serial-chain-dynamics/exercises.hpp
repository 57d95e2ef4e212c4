/// \file
/// Lesson 4 exercises: the equations of motion of a serial chain, by the Newton–Euler
/// recursions and with spatial operators, \f$T = \mathcal M\dot\beta + \mathcal C\f$.
///
/// Conventions (the notes' page "Conventions", docs/conventions.md): body 1 is the tip, body n is
/// next to the base (the inertial frame is body n+1); hinge k joins body k+1 to body k;
/// \f$\theta\f$, \f$\beta\f$ and \f$T\f$ are stacked tip first (body k's entries start at
/// `m.body(k).q_offset` and `m.body(k).v_offset`). Spatial vectors are angular part first; body
/// k's quantities are at its hinge frame \f$O_k\f$, in \f$O_k\f$ coordinates. `ws.phi[k-1]` (or
/// `phi[k-1]`) is \f$\phi(k+1,k)\f$: `.apply(f)` is \f$\phi(k+1,k)\,f\f$ (forces, outward to
/// inward) and `.transpose_apply(V)` is \f$\phi^*(k+1,k)\,V\f$ (velocities, inward to outward).
/// Stacked 6n-vectors and the dense operators of soa::OperatorsT put body k at rows
/// \f$6(k-1) \dots 6k-1\f$.
///
/// Under each title: the exercise's level (1 of 3: apply a formula; 2: put several together;
/// 3: work it out), the time it usually takes, and the exercises it builds on ("uses 4.1":
/// the same idea, done there first; never a call to your code of that exercise).
///
/// The stubs in exercises.cpp throw soa::exercise::NotDone; replace each body with your code
/// and run `make exercises`. Do not call the library function an exercise reproduces (named
/// in its statement); the other library functions are yours to use.
#pragma once

#include <vector>

#include "soa/chain.hpp"
#include "soa/chain/energy_structure.hpp"
#include "soa/soa.hpp"

namespace soa::ex04 {

/// The result of exercise 4.1: the inter-body forces and the hinge forces.
struct Gathered {
  std::vector<Force> f;  ///< \f$f(k)\f$ at entry k−1, the force on body k through hinge k
  VecX<double> T;        ///< \f$T\f$, size nv, tip first
};

/// **Exercise 4.1: the gather recursion.**
/// *Level 1 of 3, about 20 min.*
/// The scatter sweep of lesson 3 has already given, for each body k, \f$\phi(k+1,k)\f$
/// (\p phi, entry k−1) and the spatial acceleration \f$\alpha(k)\f$ (\p alpha); \p b holds
/// \f$b(k)\f$, the gyroscopic term less any external force. Return, tip to base
/// (lesson 4, section 1, "One body of the chain: the Newton–Euler recursions"),
/// \f[ f(k) = \phi(k,k-1)\, f(k-1) + M(k)\,\alpha(k) + b(k), \quad f(0) = 0, \qquad
///     T(k) = H(k)\, f(k), \f]
/// with \f$M(k)\f$ = `m.body(k).M` and \f$H(k)\f$ applied by
/// `m.body(k).hinge.H_times(theta.data() + q_offset, f, T.data() + v_offset)` (the hinge
/// map may depend on \p theta). Mind the index: \f$\phi(k,k-1)\f$ is `phi[k-2]`. Reproduces the
/// tip-to-base sweep of soa::reference::inverse_dynamics() (its fast form:
/// soa::inverse_dynamics); call neither.
Gathered gather_forces(const Model& m, const VecX<double>& theta, const std::vector<Phi>& phi,
                       const std::vector<Acceleration>& alpha, const std::vector<Force>& b);

/// **Exercise 4.2: Newton–Euler inverse dynamics of a revolute chain.**
/// *Level 2 of 3, about 45 min; uses 4.1.*
/// Every hinge of \p m is revolute about the unit axis \f$a_k\f$ = `m.body(k).hinge.axis`
/// (so \f$H^*(k) = [a_k; 0]\f$ and \f$\theta(k)\f$, \f$\beta(k)\f$ are scalars); no springs,
/// no external forces; gravity `m.gravity` (possibly zero). Return the hinge forces \f$T\f$
/// that give the chain at the state \p x the accelerations \p beta_dot, in two sweeps
/// (lesson 4, sections 1, "One body of the chain: the Newton–Euler recursions", and 5, "Gravity as
/// a base acceleration"):
/// 1. base to tip, k = n ... 1, from \f$V(n+1) = 0\f$ and \f$\alpha(n+1) = [0; -g]\f$:
///    \f$\phi(k+1,k)\f$ = `Phi(B.placement * Pose(exp_so3(theta_k * a_k)))`, whose
///    `R()` and `l()` are \f$R = {}^{k+1}R_k\f$ and \f$\ell = {}^{k+1}l(O_{k+1}, O_k)\f$;
///    \f[ V(k) = \phi^*(k+1,k)\, V(k+1) + [\beta_k a_k; 0], \qquad
///        \alpha(k) = \phi^*(k+1,k)\, \alpha(k+1) + [\dot\beta_k a_k; 0] + a(k), \f]
///    where the Coriolis term of a revolute hinge is, with \f$\omega' = R^*\omega(k+1)\f$
///    the angular velocity of body k+1 and \f$l = R^*\ell\f$, both in \f$O_k\f$ coordinates,
///    \f[ a(k) = \begin{pmatrix} \omega' \times \beta_k a_k
///        \\ \omega' \times (\omega' \times l) \end{pmatrix} ; \f]
/// 2. tip to base: \f$f(k) = \phi(k,k-1)\, f(k-1) + M(k)\,\alpha(k) + b(k)\f$ with the
///    gyroscopic term \f$b(k)\f$ of lesson 2 (soa::gyroscopic_force), and
///    \f$T(k) = a_k^*\, N(k)\f$, the moment of \f$f(k) = [N(k); F(k)]\f$ about the axis.
///
/// Do not call soa::inverse_dynamics, soa::update_velocities, soa::update_accelerations or
/// soa::OperatorsT.
VecX<double> newton_euler(const Model& m, const State& x, const VecX<double>& beta_dot);

/// **Exercise 4.3: the mass matrix from the operators.**
/// *Level 1 of 3, about 20 min.*
/// \p op holds the dense operators of a chain at one state (soa::OperatorsT): the shift
/// operator `op.E_phi` \f$= \mathcal E_\phi\f$, `op.H` \f$= H\f$ (nv x 6n) and `op.M`
/// \f$= M\f$ (6n x 6n). Its `op.phi` is **not** given (the tests set it to zero). Compute
/// \f$\phi = (I - \mathcal E_\phi)^{-1}\f$ (solve, or use \f$\phi(i,j) = \phi(i,i-1)\,
/// \phi(i-1,j)\f$ block by block) and return the Newton–Euler factorization of the mass
/// matrix (lesson 4, section 3, "T = M β̇ + C: the Newton–Euler factorization of the mass matrix")
/// \f[ \mathcal M = H\phi\, M\, \phi^* H^* . \f]
/// Do not call soa::Operators::mass_matrix() (`op.mass_matrix()`).
MatX<double> mass_matrix_operators(const Operators& op);

/// **Exercise 4.4: the mass matrix, column by column, from inverse dynamics.**
/// *Level 1 of 3, about 20 min.*
/// With \f$T = \mathcal M(\theta)\dot\beta + \mathcal C(\theta,\beta)\f$, column j of
/// \f$\mathcal M\f$ is \f$T(\dot\beta = e_j) - T(\dot\beta = 0)\f$ at any \f$\beta\f$ (take
/// \f$\beta = 0\f$): the difference removes gravity, springs and everything else in
/// \f$\mathcal C\f$ (lesson 4, section 3, "T = M β̇ + C: the Newton–Euler factorization of the
/// mass matrix"). Return \f$\mathcal M(\theta)\f$ for the chain
/// \p m (any hinge types, gravity and springs possible) at the configuration \p theta, with
/// nv + 1 calls of soa::inverse_dynamics. Do not use soa::OperatorsT.
MatX<double> mass_matrix_columns(const Model& m, const VecX<double>& theta);

/// **Exercise 4.5: the bias from the operators.**
/// *Level 1 of 3, about 15 min; uses 4.3.*
/// As in 4.3, \p op holds \f$\mathcal E_\phi\f$, \f$H\f$ and \f$M\f$ (`op.phi` zeroed), and
/// also the stacked Coriolis terms `op.a` \f$= a\f$ (with gravity folded into the block of
/// body n: \f$a(n) \mathrel{+}= \phi^*(n+1,n)\,[0; -g]\f$) and `op.b` \f$= b\f$ (gyroscopic
/// terms less the external forces). Return (lesson 4, section 3, "T = M β̇ + C: the Newton–Euler
/// factorization of the mass matrix")
/// \f[ \mathcal C = H\phi\,(M\phi^* a + b), \f]
/// the hinge forces at \f$\dot\beta = 0\f$. Do not call soa::Operators::bias(),
/// soa::Operators::T(), soa::Operators::f() or soa::Operators::alpha() (`op.bias()`, ...).
VecX<double> bias_operators(const Operators& op);

/// **Exercise 4.6: gravity torques from the Jacobians of the centres of mass.**
/// *Level 2 of 3, about 30 min.*
/// Gravity pulls body k with the force \f$m_k g\f$ at its centre of mass \f$C_k\f$
/// (\f$g\f$ = `m.gravity`, inertial coordinates). An external force \f$f_F\f$ at a frame F
/// costs the hinge forces \f$-J^*(F)\, f_F\f$ (lesson 4, section 6, "External forces enter b"), so
/// the hinge forces that hold the chain still at \p theta are
/// \f[ \mathcal G(\theta) = -\sum_k J^*(C_k) \begin{pmatrix} 0 \\ m_k\, {}^{C_k}g
///     \end{pmatrix} , \f]
/// with \f$J(C_k)\f$ the 6 x nv Jacobian of the frame at \f$C_k\f$ with the axes of
/// \f$O_k\f$ (`soa::jacobian(m, theta, ws, k, Pose(I, p_k), J)`, \f$p_k\f$ =
/// `m.body(k).M.p()`, after `soa::update_phi` and `soa::update_poses`) and
/// \f${}^{C_k}g = R_k^*\, g\f$, \f$R_k\f$ = `ws.pose[k-1].R()`. The chain has no springs.
/// Do not call soa::inverse_dynamics or soa::OperatorsT.
VecX<double> gravity_torques(const Model& m, const VecX<double>& theta);

/// **Exercise 4.7: the Coriolis matrix from the operators.**
/// *Level 2 of 3, about 40 min; uses 4.3.*
/// \p es holds, at one state of a chain (soa::EnergyStructureT, lesson 4, section 11, "The energy
/// structure: the Coriolis matrix and the rate of the mass matrix"), the operators `es.op`
/// (\f$\phi\f$ = `es.op.phi`, \f$H\f$ = `es.op.H`, \f$M\f$ = `es.op.M`), `es.Delta_bar`
/// \f$= \bar\Delta_V = \mathrm{diag}(\bar\Delta_V(k))\f$, `es.H_dot` \f$= \dot H\f$ (nv x 6n, the
/// transpose of \f$\dot H^*\f$) and `es.h_breve` \f$= \breve h = \mathrm{diag}(\breve h(k))\f$
/// with \f$h(k) = M(k)V(k)\f$. Return
/// \f[ \mathcal C_v = B^*\bigl(M\dot B + \breve h B\bigr), \qquad B = \phi^* H^*, \qquad
///     \dot B = \dot\phi^* H^* + \phi^*\dot H^*, \qquad \dot\phi = \tilde\phi\,\bar\Delta_V\,
///     \phi, \quad \tilde\phi = \phi - I, \f]
/// the Coriolis matrix with \f$\mathcal C_v\beta = \mathcal C(\theta,\beta) -
/// \mathcal C(\theta,0)\f$ and \f$\dot{\mathcal M} - 2\,\mathcal C_v\f$ skew-symmetric. Do not
/// call soa::EnergyStructure::coriolis_matrix(), soa::EnergyStructure::B_dot(),
/// soa::EnergyStructure::phi_dot() or soa::EnergyStructure::mass_matrix_rate() (`es.B_dot()`, ...).
MatX<double> coriolis_matrix_operators(const EnergyStructure& es);

/// **Exercise 4.8: the Coriolis term of a helical hinge.**
/// *Level 3 of 3, about 45 min; uses 4.2.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 4 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=4.8`).*
/// Hinge k is a screw: it turns about the unit axis \f$a\f$ (\p axis) and slides along it by
/// the pitch \f$h\f$ (\p pitch) per radian, so \f$H^*(k) = [a;\ h\,a]\f$ and
/// \f$\Delta_V(k) = H^*(k)\beta(k) = [\beta a;\ h\beta a]\f$ with \f$\beta = \beta(k)\f$
/// (\p beta). As in exercise 4.2, \p omega_parent is \f$\omega' = R^*\omega(k+1)\f$, the
/// angular velocity of body k+1, and \p l is \f$l = R^*\ell\f$, the vector from
/// \f$O_{k+1}\f$ to \f$O_k\f$, both in \f$O_k\f$ coordinates. Return the Coriolis term
/// \f$a(k)\f$ of the acceleration recursion
/// \f[ \alpha(k) = \phi^*(k+1,k)\,\alpha(k+1) + H^*(k)\,\dot\beta(k) + a(k) \f]
/// in \f$O_k\f$ coordinates, angular part first. Exercise 4.2 gives it for a revolute hinge
/// (\f$h = 0\f$); derive the helical one by differentiating \f$V(k) = \phi^*(k+1,k)\,V(k+1) +
/// H^*(k)\beta(k)\f$ in the inertial frame (lesson 3, section 7, "Accelerations and the Coriolis
/// term"; lesson 4, section 1, "One body of the chain: the Newton–Euler recursions"). It does not
/// depend on the linear velocity of body k+1 (your derivation should show why), so these inputs are
/// all it needs. Do not call soa::coriolis_term or soa::update_velocities.
Acceleration helical_coriolis(const Vec3<double>& omega_parent, const Vec3<double>& l,
                              const Vec3<double>& axis, double pitch, double beta);

/// **Exercise 4.9: predict which way each hinge holds the chain up.**
/// *Level 3 of 3, about 40 min; uses 4.6.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 4 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=4.9`).*
/// Every hinge of \p m is revolute about its unit axis \f$a_k\f$ = `m.body(k).hinge.axis`
/// (in \f$O_k\f$ coordinates); gravity `m.gravity` is not zero; there are no springs. The
/// chain is held still at the configuration \p theta by the hinge forces \f$\mathcal
/// G(\theta) = \mathcal C(\theta,
/// 0)\f$ (lesson 4, section 5, "Gravity as a base acceleration"). Which way does each hinge push,
/// and which hinges feel no gravity torque at all? Predict it from the statics of the bodies each
/// hinge carries, not from the recursions: return, tip first (size nv), for each hinge k \f$+1\f$
/// when \f$\mathcal G(k) > 0\f$, \f$-1\f$ when \f$\mathcal G(k) < 0\f$ and \f$0\f$ when gravity
/// gives hinge k no torque, taken as \f$|\mathcal G(k)| \le 10^{-9} W_k\f$ with
/// \f$W_k = |g| \sum_i m_i\,(1 + |l(O_k, C_i)|)\f$ over the bodies i that hinge k carries (so that
/// rounding does not decide). soa::update_phi and soa::update_poses give \f${}^I T_{O_k}\f$ =
/// `ws.pose[k-1]` (`.R()`, `.l()`, `.apply(p)`); the centre of mass of body k is at
/// `m.body(k).M.p()` in \f$O_k\f$ coordinates. The test checks your signs against
/// soa::inverse_dynamics (a pendulum hanging straight down, a hinge with a vertical axis: think
/// them through first). Do not call soa::inverse_dynamics, soa::jacobian or soa::OperatorsT.
VecX<double> gravity_torque_signs(const Model& m, const VecX<double>& theta);

}  // namespace soa::ex04
