/// \file
/// Lesson 8 exercises: the sweeps of the O(N) articulated body forward dynamics, the
/// inter-body forces, and a simulation step.
///
/// Conventions (the notes' page "Conventions", docs/conventions.md): body 1 is the tip, body n is
/// next to the base; hinge k joins body k+1 to body k; \f$\theta\f$, \f$\beta\f$, \f$T\f$ are
/// stacked tip first (body k's entries start at `m.body(k).q_offset` and `m.body(k).v_offset`).
/// Spatial vectors are angular part first; body k's quantities are at its hinge frame \f$O_k\f$,
/// in \f$O_k\f$ coordinates. `ws.phi[k-1]` is \f$\phi(k+1,k)\f$ (for k = n, relative to the
/// inertial frame), so \f$\phi(k,k-1)\f$ is `ws.phi[k-2]`; `phi.apply(f)` is \f$\phi f\f$,
/// `phi.transpose_apply(V)` is \f$\phi^* V\f$, `phi.matrix()` the 6x6 matrix. \f$H^*(k)\f$ is
/// the 6 x n_k matrix `m.body(k).hinge.H_star(theta.data() + m.body(k).q_offset)`,
/// \f$H(k)\f$ its transpose.
/// soa::update_phi fills `ws.phi`, soa::update_velocities fills `ws.V` and the Coriolis
/// terms `ws.a`; soa::gyroscopic_force gives the gyroscopic term of \f$b(k)\f$;
/// soa::articulated_inertias gives \f$P, D, G, P^+\f$ (lesson 6).
///
/// Under each title: the exercise's level (1 of 3: apply a formula; 2: put several together;
/// 3: work it out: derive, or find the bug), the time it usually takes, and the exercises it
/// builds on ("uses 8.3": the same idea, done there first; never a call to your code of that
/// exercise).
///
/// The stubs in exercises.cpp throw soa::exercise::NotDone; replace each body with your code
/// and run `make exercises`. Do not call the library function an exercise reproduces (named
/// in its statement); the other library functions are yours to use.
#pragma once

#include <vector>

#include "soa/chain.hpp"
#include "soa/soa.hpp"

namespace soa::ex08 {

using Vec6 = soa::Vec6<double>;

/// The result of exercise 8.1, per body k at entry k−1.
struct TipToBase {
  std::vector<Vec6> z;       ///< \f$z(k)\f$
  std::vector<Vec6> z_plus;  ///< \f$z^+(k)\f$
  VecX<double> eps;          ///< \f$\epsilon(k)\f$ (a scalar per revolute hinge), size n
  VecX<double> nu;           ///< \f$\nu(k)\f$, size n
};

/// **Exercise 8.1: the tip-to-base sweep of a revolute chain.**
/// *Level 2 of 3, about 40 min.*
/// Every hinge of \p m is revolute (\f$H^*(k) = [a_k; 0]\f$, \f$a_k\f$ =
/// `m.body(k).hinge.axis`); no gravity, no external forces, no springs. At the state \p x
/// with hinge torques \p T, return for k = 1 (tip) ... n (lesson 8, section 2, "The Riccati sweep")
/// \f[ z(k) = \phi(k,k-1)\,z^+(k-1) + P(k)\,a(k) + b(k), \quad \epsilon(k) = T(k) - H(k)z(k),
///     \quad \nu(k) = \epsilon(k)/D(k), \quad z^+(k) = z(k) + G(k)\,\epsilon(k), \f]
/// with \f$z^+(0) = 0\f$ and \f$b(k)\f$ the gyroscopic term of lesson 2. \f$P, D, G\f$ from
/// soa::articulated_inertias and \f$a(k)\f$ from soa::update_velocities are allowed.
/// Do not call soa::reference::forward_dynamics() or its fast form soa::forward_dynamics.
TipToBase tip_to_base(const Model& m, const State& x, const VecX<double>& T);

/// **Exercise 8.2: the base-to-tip sweep.**
/// *Level 1 of 3, about 25 min.*
/// Hinges of any type. Given `ws.phi` (\f$\phi(k+1,k)\f$) and `ws.a` (\f$a(k)\f$) filled,
/// the gains \f$G(k)\f$ = `art.G[k-1]` (6 x n_k), \f$\nu(k)\f$ = `nu[k-1]` (n_k entries)
/// and the base acceleration \f$\alpha(n+1)\f$ = \p alpha_base (\f$[0; -g]\f$ for gravity,
/// in inertial coordinates), return \f$\dot\beta\f$ (size nv, tip first) and fill \p alpha
/// (size n) with \f$\alpha(k)\f$, for k = n ... 1 (lesson 8, section 2, "The Riccati sweep"):
/// \f[ \alpha^+(k) = \phi^*(k+1,k)\,\alpha(k+1), \quad \dot\beta(k) = \nu(k) -
///     G^*(k)\,\alpha^+(k), \quad \alpha(k) = \alpha^+(k) + H^*(k)\dot\beta(k) + a(k). \f]
/// Do not call soa::reference::forward_dynamics() or its fast form soa::forward_dynamics.
VecX<double> base_to_tip(const Model& m, const State& x, const Workspace& ws,
                         const Articulated& art, const std::vector<VecX<double>>& nu,
                         const Acceleration& alpha_base, std::vector<Acceleration>& alpha);

/// **Exercise 8.3: forward dynamics of a chain of one-degree-of-freedom hinges.**
/// *Level 2 of 3, about 60 min; uses 8.1 and 8.2.*
/// Every hinge of \p m is revolute, prismatic or helical: \f$H^*(k)\f$ is one 6-vector
/// \f$s_k\f$ and \f$D(k) = s_k^* P(k) s_k\f$ a scalar. With gravity (`m.gravity`, as the base
/// acceleration \f$[0; -g]\f$) and the external forces \p f_ext (empty: none; else entry
/// k−1 acts on body k at \f$O_k\f$, and \f$b(k) = b_{\rm gyro}(k) - f_{\rm ext}(k)\f$), no
/// springs, return \f$\dot\beta = \mathcal M^{-1}(T - \mathcal C)\f$ by the three sweeps of
/// lesson 8, running the Riccati recursion of lesson 6 yourself in the tip-to-base sweep:
/// \f[ P(k) = \phi(k,k-1)P^+(k-1)\phi^*(k,k-1) + M(k), \quad D = s^*Ps, \quad G = Ps/D,
///     \quad P^+ = P - G D G^* . \f]
/// Do not call soa::forward_dynamics, soa::articulated_inertias or soa::riccati_step.
VecX<double> forward_dynamics_1dof(const Model& m, const State& x, const VecX<double>& T,
                                   const ExternalForces<double>& f_ext);

/// **Exercise 8.4: the inter-body forces.**
/// *Level 1 of 3, about 15 min.*
/// \p fd holds the results of soa::forward_dynamics at some state \p x: \f$P^+(k)\f$ =
/// `fd.art.P_plus[k-1]`, \f$\alpha^+(k)\f$ = `fd.alpha_plus[k-1]`, \f$z^+(k)\f$ =
/// `fd.z_plus[k-1]`. Return the spatial force \f$f(k)\f$ that body k+1 exerts on body k
/// through hinge k (lesson 8, sections 2, "The Riccati sweep", and 3, "The inter-body forces"),
/// \f[ f(k) = P^+(k)\,\alpha^+(k) + z^+(k), \f]
/// and fill \p T_hinge (size nv) with \f$H(k)f(k)\f$, the part of it along the hinge's free
/// directions (it equals \f$T + \tau_s\f$, the hinge forces with the springs' force).
/// Do not call soa::inverse_dynamics.
std::vector<Force> inter_body_forces(const Model& m, const State& x, const ForwardDynamics& fd,
                                     VecX<double>& T_hinge);

/// **Exercise 8.5: a simulation step.**
/// *Level 1 of 3, about 25 min.*
/// Every hinge of \p m has \f$\dot\theta = \beta\f$ (revolute, prismatic, helical,
/// universal). Return the state after one step \p h of the classical Runge–Kutta method
/// (RK4) for \f$\dot\theta = \beta\f$, \f$\dot\beta = \mathrm{FD}(\theta, \beta, T)\f$ with
/// the hinge forces \p T held constant and no external forces (lesson 8, section 7, "A short
/// simulation"):
/// \f[ k_1 = F(y), \; k_2 = F(y + \tfrac h2 k_1), \; k_3 = F(y + \tfrac h2 k_2), \;
///     k_4 = F(y + h k_3), \quad y' = y + \tfrac h6 (k_1 + 2k_2 + 2k_3 + k_4), \f]
/// \f$y = (\theta, \beta)\f$, \f$F(y) = (\beta, \mathrm{FD}(\theta, \beta, T))\f$.
/// soa::forward_dynamics is yours to use here.
State rk4_step(const Model& m, const State& x, const VecX<double>& T, double h);

/// **Exercise 8.6: find the bug in an articulated body forward dynamics.**
/// *Level 3 of 3, about 30 min; uses 8.1 and 8.2.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 3 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=8.6`).*
/// The stub of this function in exercises.cpp holds, below its `throw` line, a complete
/// forward dynamics by the three sweeps of lesson 8, section 2, "The Riccati sweep", for hinges of
/// any type, with gravity (`m.gravity`), the external forces \p f_ext (empty: none; else entry k−1
/// acts on body k at \f$O_k\f$) and the hinges' springs and dampers, with \f$P, D, G\f$ from
/// soa::articulated_inertias. It compiles and runs, and it has **one bug**: on many chains
/// its \f$\dot\beta\f$ is wrong. Delete the `throw` line, run `make exercises EX=8.6` and read
/// the symptom (which cases fail, which pass), find the bug with the formulas of the lesson
/// and fix it (one line). Return \f$\dot\beta = \mathcal M^{-1}(T + \tau_s - \mathcal C)\f$,
/// size nv, tip first. Do not call soa::forward_dynamics.
VecX<double> forward_dynamics_fixed(const Model& m, const State& x, const VecX<double>& T,
                                    const ExternalForces<double>& f_ext);

/// The result of exercise 8.7: both vectors complete, size nv, tip first.
struct Hybrid {
  VecX<double> beta_dot;  ///< \f$\dot\beta\f$: given (prescribed hinges) or computed
  VecX<double> T;         ///< \f$T\f$: computed (prescribed hinges) or given
};

/// **Exercise 8.7: hybrid dynamics, some hinges driven by their accelerations.**
/// *Level 3 of 3, about 60 min; uses 8.3.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 5 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=8.7`).*
/// Servos hold some hinges of the chain \p m on a prescribed motion. For body k with
/// `prescribed[k-1]` true, the accelerations \f$\dot\beta(k)\f$ of hinge k are given (the
/// entries of \p beta_dot from `m.body(k).v_offset` on) and its hinge force \f$T(k)\f$ is
/// unknown; for every other hinge \f$T(k)\f$ is given (the entries of \p T) and
/// \f$\dot\beta(k)\f$ is unknown. Entries that are not given are to be ignored, whatever
/// they hold. The chain has hinges of any type, gravity `m.gravity` (possibly zero), no
/// springs and no external forces, and is at the state \p x. Return the complete
/// \f$\dot\beta\f$ and \f$T\f$ with \f$T = \mathcal M\dot\beta + \mathcal C\f$ for the
/// whole chain, the given entries copied through.
///
/// Derive it from lesson 8, section 2, "The Riccati sweep" (with lesson 6's derivation of the
/// Riccati sweep): by induction from the tip, the force across hinge k is
/// \f$f(k) = P(k)\,(\alpha(k) - a(k)) + z(k) = P^+(k)\,\alpha^+(k) + z^+(k)\f$. Work out what
/// \f$P^+(k)\f$ and \f$z^+(k)\f$ are across a prescribed hinge, where \f$\dot\beta(k)\f$ is known,
/// and how the base-to-tip sweep gets its \f$T(k)\f$; free hinges keep the sweeps of section 2,
/// "The Riccati sweep". After the velocities, one sweep tip to base and one base to tip, O(N): no
/// mass matrix. soa::update_phi, soa::update_velocities (\f$V\f$, \f$a\f$), soa::gyroscopic_force,
/// soa::gravity_base_acceleration, `phi.matrix()` and `hinge.H_star(...)` are yours to use; do
/// not call soa::forward_dynamics, soa::articulated_inertias, soa::riccati_step,
/// soa::inverse_dynamics, soa::mass_matrix_crb or soa::OperatorsT.
Hybrid hybrid_dynamics(const Model& m, const State& x, const std::vector<bool>& prescribed,
                       const VecX<double>& T, const VecX<double>& beta_dot);

}  // namespace soa::ex08
