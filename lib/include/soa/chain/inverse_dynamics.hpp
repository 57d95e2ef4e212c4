/// \file
/// O(N) Newton-Euler inverse dynamics of a serial chain (lesson 4).
#pragma once

#include "soa/chain/kinematics.hpp"
#include "soa/rigid_body.hpp"

namespace soa {

/// The hinge force of the spring and damper of body k: \f$-k\,\delta(\theta) - c\,\beta\f$
/// (see BodyT), added into \p tau (n_k entries).
template <class S>
void add_spring_force(const BodyT<S>& B, const S* theta, const S* beta, S* tau) {
  const int nv = B.hinge.nv();
  if (B.damping != S(0))
    for (int i = 0; i < nv; ++i) tau[i] -= B.damping * beta[i];
  if (B.stiffness == S(0)) return;
  switch (B.hinge.type) {
    case HingeType::Spherical:
    case HingeType::Free: {
      const UnitQuaternionT<S> q = HingeT<S>::quaternion(theta);
      const Vec3<S> w = q.log();
      for (int i = 0; i < 3; ++i) tau[i] -= B.stiffness * w[i];
      if (B.hinge.type == HingeType::Free) {
        const Vec3<S> l = q.conjugate().rotate(Vec3<S>(theta[4], theta[5], theta[6]));
        for (int i = 0; i < 3; ++i) tau[3 + i] -= B.stiffness * l[i];
      }
      break;
    }
    default:
      for (int i = 0; i < nv; ++i) tau[i] -= B.stiffness * (theta[i] - B.rest[i]);
  }
}

/// External spatial forces on the bodies: entry k-1 is the force on body k at \f$O_k\f$ in
/// \f$O_k\f$ coordinates. An empty list means none (and costs nothing).
template <class S>
using ExternalForces = std::vector<ForceT<S>>;

/// Newton-Euler inverse dynamics (lesson 4): the hinge forces \f$T\f$ that give the chain
/// the accelerations \f$\dot\beta\f$ at the state \p x.
///
/// Base to tip (lesson 3): \f$V(k)\f$, \f$a(k)\f$, \f$\alpha(k)\f$ with \f$\alpha(n+1) =
/// [0;-g]\f$. Tip to base: \f[ f(k) = \phi(k,k-1)\, f(k-1) + M(k)\,\alpha(k) + b(k), \qquad
/// T(k) = H(k)\, f(k) - \tau_s(k), \f] with \f$b(k)\f$ the gyroscopic term of lesson 2 less
/// the external force on body k, and \f$\tau_s\f$ the spring and damper force.
/// Parts the scene does not use are skipped: no gravity, no external forces (\p f_ext
/// empty), no velocity terms at rest, no springs.
/// \p T must have size nv; nothing is allocated.
template <class S>
void inverse_dynamics(const ModelT<S>& m, const StateT<S>& x, const VecX<S>& beta_dot,
                      const ExternalForces<S>& f_ext, WorkspaceT<S>& ws, VecX<S>& T) {
  const bool moving = !x.beta.isZero(0);
  // Base to tip, in one pass: phi(k+1,k), V(k), a(k), alpha(k) (the scatter recursions of
  // update_phi(), update_velocities() and update_accelerations(), fused).
  VelocityT<S> V_parent;
  AccelerationT<S> alpha_parent =
      m.has_gravity() ? gravity_base_acceleration(m) : AccelerationT<S>();
  for (int k = m.n(); k >= 1; --k) {
    const BodyT<S>& B = m.body(k);
    const S* th = x.theta.data() + B.q_offset;
    ws.phi[k - 1] = PhiT<S>(B.placement * B.hinge.transform(th));
    const PhiT<S>& phi = ws.phi[k - 1];
    AccelerationT<S> alpha = phi.transpose_apply(alpha_parent);
    alpha += AccelerationT<S>(B.hinge.H_star_times(th, beta_dot.data() + B.v_offset).vector());
    if (moving) {
      const S* be = x.beta.data() + B.v_offset;
      const VelocityT<S> dV = B.hinge.H_star_times(th, be);
      const VelocityT<S> V = phi.transpose_apply(V_parent) + dV;
      const AccelerationT<S> a =
          coriolis_term(phi, V_parent, V, dV, B.hinge.H_star_dot_times(th, be));
      alpha += a;
      ws.V[k - 1] = V;
      ws.a[k - 1] = a;
      V_parent = V;
    } else {
      ws.V[k - 1] = VelocityT<S>();
      ws.a[k - 1] = AccelerationT<S>();
    }
    ws.alpha[k - 1] = alpha;
    alpha_parent = alpha;
  }
  // Tip to base: the gather recursion for f(k) and T(k).
  for (int k = 1; k <= m.n(); ++k) {
    const BodyT<S>& B = m.body(k);
    ForceT<S> f = B.M * ws.alpha[k - 1];
    if (moving) f += gyroscopic_force(B.M, ws.V[k - 1]);
    if (!f_ext.empty()) f -= f_ext[k - 1];
    if (k > 1) f += ws.phi[k - 2].apply(ws.f[k - 2]);
    ws.f[k - 1] = f;
    S* Tk = T.data() + B.v_offset;
    B.hinge.H_times(x.theta.data() + B.q_offset, f, Tk);
    if (B.stiffness != S(0) || B.damping != S(0)) {
      S tau[6] = {0, 0, 0, 0, 0, 0};
      add_spring_force(B, x.theta.data() + B.q_offset, x.beta.data() + B.v_offset, tau);
      for (int i = 0; i < B.hinge.nv(); ++i) Tk[i] -= tau[i];
    }
  }
}

}  // namespace soa
