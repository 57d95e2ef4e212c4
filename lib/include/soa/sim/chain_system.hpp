/// \file
/// A chain as an ordinary differential equation on its configuration manifold: the
/// accelerations by the forward dynamics (lesson 8), the configuration moved in local
/// coordinates, and the energy (simulation).
#pragma once

#include <cmath>
#include <functional>
#include <utility>

#include "soa/chain/forward_dynamics.hpp"
#include "soa/chain/kinetic_gradient.hpp"
#include "soa/chain/mass_matrix_inverse_times.hpp"
#include "soa/free_body.hpp"

namespace soa {

/// \f$\theta \oplus u\f$: the configuration reached from \p theta0 by the local coordinates
/// \p u (one entry per degree of freedom, like \f$\beta\f$), hinge by hinge: quaternion
/// hinges turn by \f$\mathfrak q_0 \otimes \exp(u_\omega)\f$ (a product of unit quaternions:
/// unit by construction), the free hinge's position adds \f$u_l\f$, every other coordinate
/// adds \f$u\f$. Writes \p theta (size nq).
template <class S>
void retract(const ModelT<S>& m, const VecX<S>& theta0, const VecX<S>& u, VecX<S>& theta) {
  theta = theta0;
  for (const BodyT<S>& B : m.bodies()) {
    const S* du = u.data() + B.v_offset;
    S* th = theta.data() + B.q_offset;
    switch (B.hinge.type) {
      case HingeType::Spherical:
      case HingeType::Free: {
        const UnitQuaternionT<S> q = HingeT<S>::quaternion(theta0.data() + B.q_offset) *
                                     UnitQuaternionT<S>::exp(Vec3<S>(du[0], du[1], du[2]));
        for (int i = 0; i < 3; ++i) th[i] = q.q()[i];
        th[3] = q.q0();
        if (B.hinge.type == HingeType::Free)
          for (int i = 0; i < 3; ++i) th[4 + i] += du[3 + i];
        break;
      }
      default:
        for (int i = 0; i < B.hinge.nv(); ++i) th[i] += du[i];
    }
  }
}

/// retract() of Eigen expressions \p theta0, \p u: forwards to retract(m, const VecX<S>&, ...).
template <class S, class D1, class D2>
void retract(const ModelT<S>& m, const Eigen::MatrixBase<D1>& theta0,
             const Eigen::MatrixBase<D2>& u, VecX<S>& theta) {
  retract(m, VecX<S>(theta0), VecX<S>(u), theta);
}

/// The rate of the local coordinates \f$\dot u\f$ at \f$\theta = \theta_0 \oplus u\f$ with
/// velocity \p beta: \f$\mathrm{dexp}^{-1}_{-u_\omega}\,\omega\f$ for a quaternion hinge
/// (Runge-Kutta-Munthe-Kaas, as the free body of lesson 2), \f$R(\mathfrak q)\,v\f$ for the
/// free hinge's position, \f$\beta\f$ for every other coordinate.
template <class S>
void local_rate(const ModelT<S>& m, const VecX<S>& theta, const VecX<S>& u, const VecX<S>& beta,
                VecX<S>& u_dot) {
  for (const BodyT<S>& B : m.bodies()) {
    const int o = B.v_offset;
    switch (B.hinge.type) {
      case HingeType::Spherical:
      case HingeType::Free: {
        const Vec3<S> w = dexp_inv_right<S>(u.template segment<3>(o), beta.template segment<3>(o));
        u_dot.template segment<3>(o) = w;
        if (B.hinge.type == HingeType::Free)
          u_dot.template segment<3>(o + 3) = HingeT<S>::quaternion(theta.data() + B.q_offset)
                                                 .rotate(beta.template segment<3>(o + 3));
        break;
      }
      default:
        u_dot.segment(o, B.hinge.nv()) = beta.segment(o, B.hinge.nv());
    }
  }
}

/// A chain as a differential equation: \f$\dot\beta\f$ by soa::forward_dynamics() under the
/// scene's external forces and the hinge forces of an optional control law, with the
/// workspaces allocated once. Counts its evaluations.
template <class S>
class ChainSystemT {
 public:
  /// Hinge forces \f$T(t, x)\f$ (size nv); absent means none.
  using Control = std::function<void(S t, const StateT<S>& x, VecX<S>& T)>;

  explicit ChainSystemT(const ModelT<S>& m, ExternalForces<S> f_ext = {}, Control control = {})
      : m_(m),
        f_ext_(std::move(f_ext)),
        control_(std::move(control)),
        ws_(m),
        fd_(ForwardDynamicsT<S>::lean(m)),
        fd_full_(m),
        T_(VecX<S>::Zero(m.nv())),
        rest_(StateT<S>::rest(m)),
        zero_(VecX<S>::Zero(m.nv())),
        p_(m.nv()),
        Q_(m.nv()) {}

  const ModelT<S>& model() const { return m_; }
  long evaluations() const { return evaluations_; }

  /// \f$\dot\beta\f$ at time \p t and state \p x: forward dynamics with the lean
  /// storage (ForwardDynamicsT::lean(); a simulation reads no per-body quantity, and the
  /// result is the same bit for bit), which keeps a long chain's pass in cache.
  void acceleration(S t, const StateT<S>& x, VecX<S>& beta_dot);

  /// The canonical momentum \f$p = \partial T/\partial\beta = \mathcal M(\theta)\beta\f$
  /// (soa::kinetic_gradient(), O(N)); hinges whose coordinates add only.
  void momentum(const StateT<S>& x, VecX<S>& p);

  /// \f$\beta = \mathcal M^{-1}(\theta)\,p\f$ at the configuration \p x.theta
  /// (soa::mass_matrix_inverse_times(), O(N)); counted as an evaluation.
  void velocity(const StateT<S>& x, const VecX<S>& p, VecX<S>& beta);

  /// The generalized forces \f$Q(t,\theta,\beta)\f$, everything but the inertia:
  /// \f$Q = -T_{\rm ID}(\theta, \beta = 0, \dot\beta = 0) - c\,\beta + T(t, x)\f$, where the
  /// inverse dynamics at rest (soa::inverse_dynamics()) is the hinge force that holds the
  /// chain against gravity, the springs and the external forces, \f$c\f$ the dampers and
  /// \f$T\f$ the control law. O(N).
  void generalized_force(S t, const StateT<S>& x, VecX<S>& Q);

  /// The rate of the canonical momentum (Lagrange's equations, \f$L = T - U\f$, the
  /// potential \f$U\f$ and the non-conservative forces in \f$Q\f$):
  /// \f$\dot p = \partial T/\partial\theta\,(\theta, \beta) + Q(t, \theta, \beta)\f$
  /// (soa::kinetic_gradient(), generalized_force()). O(N); hinges whose coordinates add only.
  void momentum_rate(S t, const StateT<S>& x, VecX<S>& p_dot);

  /// The total energy: kinetic \f$\tfrac12\sum_k V^*(k) M(k) V(k)\f$, the potential of
  /// gravity \f$-\sum_k m_k\, g \cdot p_{C_k}\f$ and of the joint springs \f$\tfrac12 k
  /// |\delta|^2\f$ (\f$\delta\f$ as in BodyT; the spring force is its negative gradient).
  S energy(const StateT<S>& x);

 private:
  // |delta|^2 / 2 of the spring of body B.
  static S spring_displacement_squared(const BodyT<S>& B, const VecX<S>& theta) {
    const S* th = theta.data() + B.q_offset;
    S d2 = S(0);
    switch (B.hinge.type) {
      case HingeType::Spherical:
      case HingeType::Free:
        d2 = HingeT<S>::quaternion(th).log().squaredNorm();
        if (B.hinge.type == HingeType::Free) d2 += Vec3<S>(th[4], th[5], th[6]).squaredNorm();
        break;
      default:
        for (int i = 0; i < B.hinge.nv(); ++i) d2 += (th[i] - B.rest[i]) * (th[i] - B.rest[i]);
    }
    return d2 / S(2);
  }

  const ModelT<S>& m_;
  ExternalForces<S> f_ext_;
  Control control_;
  WorkspaceT<S> ws_;
  ForwardDynamicsT<S> fd_;       // acceleration(): lean storage
  ForwardDynamicsT<S> fd_full_;  // velocity(): mass_matrix_inverse_times() needs the full one
  VecX<S> T_;
  StateT<S> rest_;        // generalized_force(): (theta, 0)
  VecX<S> zero_, p_, Q_;  // beta_dot = 0; momentum_rate()'s p and Q
  long evaluations_ = 0;
};

// The members are defined out of the class, not inline: the library compiles them once
// (soa/instantiations.hpp), and the programs, which declare them extern, do not compile them
// again.

template <class S>
void ChainSystemT<S>::acceleration(S t, const StateT<S>& x, VecX<S>& beta_dot) {
  ++evaluations_;
  if (control_) control_(t, x, T_);
  forward_dynamics(m_, x, T_, f_ext_, ws_, fd_, beta_dot);
}

template <class S>
void ChainSystemT<S>::momentum(const StateT<S>& x, VecX<S>& p) {
  p.resize(m_.nv());
  kinetic_gradient(m_, x, ws_, p, Q_);
}

template <class S>
void ChainSystemT<S>::velocity(const StateT<S>& x, const VecX<S>& p, VecX<S>& beta) {
  ++evaluations_;
  beta.resize(m_.nv());
  mass_matrix_inverse_times(m_, x, p, ws_, fd_full_, beta);
}

template <class S>
void ChainSystemT<S>::generalized_force(S t, const StateT<S>& x, VecX<S>& Q) {
  rest_.theta = x.theta;
  Q.resize(m_.nv());
  inverse_dynamics(m_, rest_, zero_, f_ext_, ws_, Q);
  Q = -Q;
  for (const BodyT<S>& B : m_.bodies())
    if (B.damping != S(0))
      Q.segment(B.v_offset, B.hinge.nv()) -= B.damping * x.beta.segment(B.v_offset, B.hinge.nv());
  if (control_) {
    control_(t, x, T_);
    Q += T_;
  }
}

template <class S>
void ChainSystemT<S>::momentum_rate(S t, const StateT<S>& x, VecX<S>& p_dot) {
  p_dot.resize(m_.nv());
  kinetic_gradient(m_, x, ws_, p_, p_dot);
  generalized_force(t, x, Q_);
  p_dot += Q_;
}

template <class S>
S ChainSystemT<S>::energy(const StateT<S>& x) {
  update_phi(m_, x.theta, ws_);
  update_poses(m_, ws_);
  update_velocities(m_, x, ws_);
  S E = S(0);
  for (int k = 1; k <= m_.n(); ++k) {
    const BodyT<S>& B = m_.body(k);
    E += B.M.kinetic_energy(ws_.V[k - 1]);
    if (m_.has_gravity()) {
      const PoseT<S>& T = ws_.pose[k - 1];
      E -= m_.gravity.dot(B.M.mass() * T.l() + T.R() * B.M.h());
    }
    if (B.stiffness != S(0)) E += B.stiffness * spring_displacement_squared(B, x.theta);
  }
  return E;
}
using ChainSystem = ChainSystemT<double>;

}  // namespace soa
