/// \file
/// O(N) Newton-Euler inverse dynamics of a serial chain (lesson 4). Names: with the
/// tip-to-base numbering (\ref conventions_chain), `_next` is a value of body k+1 (inboard)
/// and `_prev` of body k-1 (outboard).
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
      const Vec3<S> rot = q.log();  // the rotation vector of q
      for (int i = 0; i < 3; ++i) tau[i] -= B.stiffness * rot[i];
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

namespace detail {

/// The force body k needs for its own motion (lesson 2), \f$M(k)\,\alpha(k) + b(k)\f$ with the
/// gyroscopic term \f$b = [\tilde\omega J \omega;\ m\tilde\omega\tilde\omega p]\f$ (zero at
/// rest, \f$\omega = 0\f$), from \f$(m, h = mp, J)\f$, on the parts:
/// \f[ N = J\dot\omega + h \times \dot v + \omega \times J\omega, \qquad
///     F = m\dot v - h \times \dot\omega + \omega \times (\omega \times h). \f]
template <class S>
EIGEN_ALWAYS_INLINE void body_force(const SpatialInertiaT<S>& M, const Vec3<S>& w,
                                    const Vec3<S>& dw, const Vec3<S>& dv, bool moving, Vec3<S>& N,
                                    Vec3<S>& F) {
  const Vec3<S>& h = M.h();
  N = M.J() * dw + h.cross(dv);
  F = M.mass() * dv - h.cross(dw);
  if (moving) {
    N += w.cross(M.J() * w);
    F += w.cross(w.cross(h));
  }
}

}  // namespace detail

/// The fast form of soa::reference::inverse_dynamics().
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
  WorkspaceT<S>::size(ws.phi, m);
  WorkspaceT<S>::size(ws.V, m);
  WorkspaceT<S>::size(ws.f, m);
  WorkspaceT<S>::size(ws.a, m);
  WorkspaceT<S>::size(ws.alpha, m);
  // At rest (beta = 0) V(k), a(k) and the gyroscopic term are exactly zero: their products
  // are skipped, and the zeros they would give are stored.
  const bool moving = !x.beta.isZero(0);
  // Base to tip, in one pass: phi(k+1,k), V(k), a(k), alpha(k) (the scatter recursions of
  // update_phi(), update_velocities() and update_accelerations(), fused, so that each body's
  // phi, V and alpha are used while in registers), and the body's own force M(k) alpha(k) +
  // b(k) into ws.f. Spatial vectors are held as their angular and linear 3-vectors, the
  // 6-vector products written out by parts. The revolute hinges' sines and cosines first, in
  // one batch (hinge_sin_cos(): SLEEF's vector sincos in double, within an ulp of std::sin and
  // std::cos), rather than two libm calls a body inside the loop.
  hinge_sin_cos(m, x.theta.data(), ws);
  const S* const sin_h = ws.hinge_sin.data();
  const S* const cos_h = ws.hinge_cos.data();
  const Vec3<S> zero = Vec3<S>::Zero();
  // V(k+1) and alpha(k+1), from V(n+1) = 0 and alpha(n+1) = [0; -g] (zero without gravity)
  Vec3<S> w_next = zero, v_next = zero, dw_next = zero, dv_next = zero;
  if (m.has_gravity()) dv_next = gravity_base_acceleration(m).linear();
  for (int k = m.n(); k >= 1; --k) {
    const BodyT<S>& B = m.body(k);
    const S* th = x.theta.data() + B.q_offset;
    ws.phi[k - 1] = joint_phi(B, th, sin_h[k - 1], cos_h[k - 1]);
    const PhiT<S>& phi = ws.phi[k - 1];
    // alpha(k) = phi*(k+1,k) alpha(k+1) + H*(k) beta_dot(k) + a(k)
    Vec3<S> dw, dv, hw, hv;
    detail::transpose_apply(phi, dw_next, dv_next, dw, dv);
    detail::hinge_rate(B.hinge, th, beta_dot.data() + B.v_offset, hw, hv);
    dw += hw;
    dv += hv;
    Vec3<S> w = zero, v = zero, a_w = zero, a_v = zero;
    if (moving) {
      const S* be = x.beta.data() + B.v_offset;
      detail::hinge_rate(B.hinge, th, be, hw, hv);
      detail::velocity_and_coriolis(phi, w_next, v_next, hw, hv, w, v, a_w, a_v);
      // Hdot^*(k) beta(k) (lesson 3, section 7): of the hinges here only the universal joint's
      // map changes with theta.
      if (B.hinge.type == HingeType::Universal) {
        const AccelerationT<S> Hdot_beta = B.hinge.H_star_dot_times(th, be);
        a_w += Hdot_beta.angular();
        a_v += Hdot_beta.linear();
      }
      dw += a_w;
      dv += a_v;
    }
    ws.V[k - 1] = VelocityT<S>(w, v);
    ws.a[k - 1] = AccelerationT<S>(a_w, a_v);
    ws.alpha[k - 1] = AccelerationT<S>(dw, dv);
    Vec3<S> N, F;
    detail::body_force(B.M, w, dw, dv, moving, N, F);
    // No external forces: f_ext is empty, and b(k) is the gyroscopic term alone.
    if (!f_ext.empty()) N -= f_ext[k - 1].angular(), F -= f_ext[k - 1].linear();
    ws.f[k - 1] = ForceT<S>(N, F);
    w_next = w, v_next = v, dw_next = dw, dv_next = dv;
  }
  // Tip to base: the gather recursion for f(k) and T(k).
  Vec3<S> N_prev = zero, F_prev = zero;  // f(k-1)
  for (int k = 1; k <= m.n(); ++k) {
    const BodyT<S>& B = m.body(k);
    Vec3<S> Nk = ws.f[k - 1].angular(), Fk = ws.f[k - 1].linear();
    if (k > 1) detail::add_apply(ws.phi[k - 2], N_prev, F_prev, Nk, Fk);
    ws.f[k - 1] = ForceT<S>(Nk, Fk);
    N_prev = Nk, F_prev = Fk;
    // T(k) = H(k) f(k): a revolute hinge's is a . N(k), the product with H's zeros dropped; a
    // body without spring or damper adds no force.
    S* Tk = T.data() + B.v_offset;
    if (B.hinge.type == HingeType::Revolute)
      Tk[0] = B.hinge.axis.dot(Nk);
    else
      B.hinge.H_times(x.theta.data() + B.q_offset, ws.f[k - 1], Tk);
    if (B.stiffness != S(0) || B.damping != S(0)) {
      S tau[6] = {0, 0, 0, 0, 0, 0};
      add_spring_force(B, x.theta.data() + B.q_offset, x.beta.data() + B.v_offset, tau);
      for (int i = 0; i < B.hinge.nv(); ++i) Tk[i] -= tau[i];
    }
  }
}

/// inverse_dynamics() of an Eigen expression \p beta_dot: forwards to the `const VecX<S>&` one.
template <class S, class D>
void inverse_dynamics(const ModelT<S>& m, const StateT<S>& x, const Eigen::MatrixBase<D>& beta_dot,
                      const ExternalForces<S>& f_ext, WorkspaceT<S>& ws, VecX<S>& T) {
  inverse_dynamics(m, x, VecX<S>(beta_dot), f_ext, ws, T);
}

}  // namespace soa
