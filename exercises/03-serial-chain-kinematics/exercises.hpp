/// \file
/// Lesson 3 exercises: serial-chain kinematics in minimal coordinates, hinges and joint maps,
/// the scatter recursion of the velocities, the operators \f$\mathcal E_\phi\f$ and
/// \f$\phi\f$, Jacobians, and the Coriolis term \f$a(k)\f$.
///
/// Conventions (the notes' page "Conventions", docs/conventions.md): spatial vectors angular part
/// first, \f$V = [\omega; v]\f$, \f$f = [N; F]\f$. Bodies are numbered from the tip: body 1 is the
/// tip, body n is next to the base, and hinge k joins body k+1 (inboard) to body k. Lists of
/// per-body quantities are indexed tip first: entry `k - 1` belongs to body k. \f$\phi(k+1,k)\f$
/// is stored as a soa::Phi (rotation \f$R = {}^{k+1}R_k\f$ and offset
/// \f$l = {}^{k+1}l(O_{k+1}, O_k)\f$): `phi.R()`, `phi.l()`, `phi.matrix()` (the 6x6),
/// `phi.transpose_apply(V)` (\f$\phi^* V\f$), `phi.apply(f)` (\f$\phi f\f$). Every \f$V(k)\f$ is
/// in the coordinates of \f$O_k\f$.
///
/// Under each title: the exercise's level (1 of 3: apply a formula; 2: put several together;
/// 3: work it out: derive the formula, predict then check, or find the bug in given code),
/// the time it usually takes, and the exercises it builds on ("uses 3.2": the same idea, done
/// there first; never a call to your code of that exercise). `make exercises HINT=3.7` prints
/// the next hint of an exercise (exercises/03-serial-chain-kinematics/hints.md).
///
/// The stubs in exercises.cpp throw soa::exercise::NotDone; replace each body with your code
/// and run `make exercises`. Do not call the library function an exercise reproduces (named
/// in its statement); the other library functions are yours to use.
#pragma once

#include <vector>

#include "soa/chain.hpp"
#include "soa/soa.hpp"

namespace soa::ex03 {

/// A 6 x n matrix: joint maps and Jacobians.
using Matrix6X = Eigen::Matrix<double, 6, Eigen::Dynamic>;

/// **Exercise 3.1: the joint map \f$H^*(k)\f$ of a hinge.**
/// *Level 1 of 3, about 20 min.*
/// Return the 6 x \f$n_k\f$ joint map of \p hinge at its coordinates \p theta
/// (\f$\theta(k)\f$, `hinge.nq()` entries), so that the velocity of \f$O_k\f$ relative to
/// \f$O_k^+\f$, in \f$O_k\f$ coordinates, is \f$\Delta_V = H^*(k)\,\beta(k)\f$ (lesson 3,
/// section 2, "Hinges and their joint maps"). With the unit axis \f$a\f$ = `hinge.axis`, the
/// second axis \f$a_2\f$ = `hinge.axis2` and the pitch \f$h\f$ = `hinge.pitch`:
/// - revolute: \f$[a;\ 0]\f$; prismatic: \f$[0;\ a]\f$; helical: \f$[a;\ h\, a]\f$ (one
///   turn about \f$a\f$ advances \f$2\pi h\f$ along it);
/// - universal (turns \f$\theta_1\f$ about \f$a\f$, then \f$\theta_2\f$ about \f$a_2\f$):
///   the columns \f$[e^{-\theta_2\tilde a_2}\, a;\ 0]\f$ and \f$[a_2;\ 0]\f$
///   (soa::exp_so3 gives \f$e^{\tilde w}\f$);
/// - spherical: \f$[I_3;\ 0]\f$ (6 x 3); free: \f$I_6\f$; locked: no columns (6 x 0).
///
/// Reproduces soa::Hinge::H_star: do not call soa::Hinge::H_star, nor soa::Hinge::H_star_times.
Matrix6X joint_map(const Hinge& hinge, const VecX<double>& theta);

/// **Exercise 3.2: the velocity scatter recursion.**
/// *Level 1 of 3, about 15 min.*
/// A chain of n = `phi.size()` bodies: `phi[k-1]` is \f$\phi(k+1,k)\f$ (for k = n, relative
/// to the inertial frame) and `dV[k-1]` is the hinge velocity \f$H^*(k)\beta(k)\f$ of body k.
/// Return the body velocities \f$V(k)\f$ (entry `k - 1`), base to tip (lesson 3, section 6,
/// "Velocities: the scatter recursion"):
/// \f[ V(k) = \phi^*(k+1,k)\, V(k+1) + H^*(k)\beta(k), \qquad k = n, \dots, 1, \qquad
///     V(n+1) = 0 . \f]
/// Reproduces the velocity part of soa::reference::velocities() (its fast form:
/// soa::update_velocities); call neither.
std::vector<Velocity> scatter_velocities(const std::vector<Phi>& phi,
                                         const std::vector<Velocity>& dV);

/// **Exercise 3.3: the shift operator \f$\mathcal E_\phi\f$.**
/// *Level 1 of 3, about 10 min.*
/// For the same `phi` as in 3.2, return the 6n x 6n matrix \f$\mathcal E_\phi\f$ whose only
/// non-zero blocks are \f$\phi(k+1,k)\f$ (the 6x6 `phi[k-1].matrix()`) at block row k+1,
/// block column k, for k = 1 ... n-1 (lesson 3, section 9, "The first spatial operators"). Block k
/// is rows and columns \f$6(k-1) \dots 6k-1\f$. (\f$\phi(n+1,n)\f$ does not appear: body n+1 is
/// not in the chain.) Reproduces soa::Operators::E_phi.
MatX<double> shift_operator(const std::vector<Phi>& phi);

/// **Exercise 3.4: the operator \f$\phi\f$, block by block.**
/// *Level 2 of 3, about 20 min; uses 3.3.*
/// Return \f$\phi = (I - \mathcal E_\phi)^{-1}\f$, without inverting a matrix: it is block
/// lower triangular with the blocks
/// \f[ \phi(i,j) = \phi(i,i-1)\,\phi(i-1,i-2) \cdots \phi(j+1,j) \ (i > j), \qquad
///     \phi(i,i) = I, \qquad 0 \ (i < j) \f]
/// at block row i, column j (lesson 3, section 9, "The first spatial operators"). Compute each
/// column of blocks with one product per block: \f$\phi(i+1,j) = \phi(i+1,i)\,\phi(i,j)\f$.
/// Reproduces soa::Operators::phi.
MatX<double> phi_operator(const std::vector<Phi>& phi);

/// **Exercise 3.5: the Jacobian of a frame.**
/// *Level 2 of 3, about 40 min; uses 3.4.*
/// A frame F is fixed on body \p k of the chain \p m at the pose \p frame \f$= {}^{O_k}T_F\f$.
/// Return its Jacobian J (6 x `m.nv()`), \f$V(F) = J\beta\f$ with \f$V(F)\f$ in F
/// coordinates: \f$J = B^*\phi^*H^*\f$ (lesson 3, section 10, "Jacobians"), whose column block of
/// hinge i is
/// \f[ \phi^*(O_i, F)\, H^*(i) \quad (i \ge k), \qquad 0 \quad (i < k), \f]
/// with \f$\phi(O_i, F)\f$ from the poses: \f${}^{O_i}T_F = ({}^I T_{O_i})^{-1}\, {}^I T_{O_k}\,
/// {}^{O_k}T_F\f$. Get the poses with soa::update_phi and soa::update_poses (a soa::Workspace
/// `ws` holds them: `ws.pose[i-1]` is \f${}^I T_{O_i}\f$); hinge i's columns are
/// `m.body(i).v_offset` ... `+ m.body(i).hinge.nv() - 1`, its coordinates start at
/// `theta.data() + m.body(i).q_offset`, and `hinge.H_star(...)` gives \f$H^*(i)\f$.
/// Reproduces soa::reference::jacobian() (its fast form: soa::jacobian); call neither.
Matrix6X frame_jacobian(const Model& m, const VecX<double>& theta, int k, const Pose& frame);

/// **Exercise 3.6: the Coriolis term \f$a(k)\f$.**
/// *Level 2 of 3, about 30 min; uses 3.2.*
/// Body k+1 moves with \p V_parent \f$= V(k+1)\f$ (in \f$O_{k+1}\f$ coordinates; zero for
/// k = n), hinge k with \p dV \f$= \Delta_V = H^*(k)\beta(k) = [\Delta_\omega; \Delta_v]\f$
/// and \p Hdot_beta \f$= \mathring H^*(k)\beta(k)\f$ (both in \f$O_k\f$ coordinates), and
/// \p phi is \f$\phi(k+1,k)\f$. Return the Coriolis term of the acceleration recursion
/// \f$\alpha(k) = \phi^*(k+1,k)\alpha(k+1) + H^*(k)\dot\beta(k) + a(k)\f$, in \f$O_k\f$
/// coordinates, from its coordinate-free form (lesson 3, section 7, "Accelerations and the
/// Coriolis term"):
/// \f[ a(k) = \begin{pmatrix} \omega(k+1) \times \Delta_\omega
///     \\ \omega(k) \times \Delta_v + \omega(k+1) \times \big(v(k) - v(k+1)\big) \end{pmatrix}
///     + \mathring H^*(k)\beta(k), \f]
/// where \f$V(k) = [\omega(k); v(k)] = \phi^*(k+1,k)V(k+1) + \Delta_V\f$, and
/// \f$\omega(k+1)\f$, \f$v(k+1)\f$ are the halves of \f$V(k+1)\f$ brought to \f$O_k\f$
/// coordinates by the rotation alone, \f$R^* = ({}^{k+1}R_k)^*\f$ (\f$v(k+1)\f$ is the
/// velocity of the point \f$O_{k+1}\f$, \f$v(k)\f$ that of \f$O_k\f$).
/// Reproduces soa::coriolis_term: do not call soa::coriolis_term.
Acceleration coriolis_acceleration(const Phi& phi, const Velocity& V_parent, const Velocity& dV,
                                   const Acceleration& Hdot_beta);

/// The result of exercise 3.7: the joint map of a planar hinge and the rate of its entries.
struct PlanarJointMap {
  Matrix6X H_star;         ///< \f$H^*(\theta)\f$, 6 x 3, column i for \f$\beta_i\f$
  Acceleration Hdot_beta;  ///< \f$\mathring H^*(\theta)\,\beta\f$, in \f$O_k\f$ coordinates
};

/// **Exercise 3.7: derive the joint map of a planar hinge.**
/// *Level 3 of 3, about 45 min; uses 3.1.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 4 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=3.7`).*
/// A planar hinge lets body k turn about a unit axis \f$a\f$ and slide in the plane
/// perpendicular to it (a puck on a table, a mobile robot on the floor). Its coordinates
/// \f$\theta = (\theta_1, \theta_2, \theta_3)\f$ are an angle and two offsets: with the unit
/// vector \p b \f$= b \perp a\f$ and \f$c = a \times b\f$, the joint transform is
/// \f[ {}^{O_k^+}T_{O_k}(\theta) = (R,\ l), \qquad R = e^{\theta_1 \tilde a}, \qquad
///     l = {}^{O_k^+}l(O_k^+, O_k) = \theta_2\, b + \theta_3\, c , \f]
/// with \f$a\f$, \f$b\f$, \f$c\f$ and \f$l\f$ in \f$O_k^+\f$ coordinates (the axis of
/// \f$R\f$ has the same coordinates \f$a\f$ in \f$O_k\f$), and \f$\beta = \dot\theta\f$
/// (\p theta, \p beta: three entries each). The library has no such hinge: derive and return
/// (lesson 3, sections 2, "Hinges and their joint maps", and 7, "Accelerations and the Coriolis
/// term")
/// - `H_star`: the 6 x 3 joint map \f$H^*(\theta)\f$, with \f$\Delta_V = H^*(\theta)\,\beta\f$
///   the spatial velocity of \f$O_k\f$ relative to \f$O_k^+\f$ **in \f$O_k\f$ coordinates**,
///   angular part first (the definition of lesson 1: \f$\tilde\omega = R^*\dot R\f$,
///   \f$v = R^*\dot l\f$);
/// - `Hdot_beta`: \f$\mathring H^*(\theta)\,\beta = \big(\tfrac{d}{dt} H^*(\theta(t))\big)\,
///   \beta\f$ along \f$\dot\theta = \beta\f$ (the rate of the entries of \f$H^*\f$, seen from
///   \f$O_k\f$, times \f$\beta\f$: the term that enters \f$a(k)\f$, as the universal hinge's
///   does).
///
/// Both in closed form, without differencing numerically (the test checks them to rounding).
/// `soa::exp_so3<double>(theta[0] * a)` is \f$e^{\theta_1\tilde a}\f$.
PlanarJointMap planar_joint_map(const Vec3<double>& a, const Vec3<double>& b,
                                const Vec3<double>& theta, const Vec3<double>& beta);

/// **Exercise 3.8: find the bug: the velocity of a point of the chain.**
/// *Level 3 of 3, about 30 min; uses 3.2.*
/// *Feedback: the first messages say where your result goes wrong, not what the mistake
/// is; the checker names a mistake it knows after 3 failed runs of `make exercises`, or
/// once you have read all the hints (`make exercises HINT=3.8`).*
/// A point P is fixed on body \p k of the chain \p m at \p p \f$= {}^{O_k}l(O_k, P)\f$, in
/// \f$O_k\f$ coordinates (a tool tip, a marker). Return its velocity in inertial coordinates,
/// \f${}^I v(P) = \tfrac{d}{dt}\,{}^I l(I, P)\f$, at the state \p x (lesson 3, sections 5, "Poses:
/// the first scatter recursion", and 6, "Velocities: the scatter recursion"; lesson 1, moving a
/// spatial velocity to another point).
///
/// The stub in exercises.cpp already holds code for it, after the `throw` line: it compiles,
/// it runs, and it has **one** bug. Delete the `throw` line, run the test (its report says
/// what your wrong answer looks like), then find the bug and fix it. Any library function
/// may be used.
Vec3<double> point_velocity(const Model& m, const State& x, int k, const Vec3<double>& p);

}  // namespace soa::ex03
