/// \file
/// O(N) articulated body forward dynamics of a serial chain (lesson 8). Names: with the
/// tip-to-base numbering (\ref conventions_chain), `_next` is a value of body k+1 (inboard)
/// and `_prev` of body k-1 (outboard); `_plus` is the \f$^+\f$ of the lesson.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "soa/chain/articulated.hpp"

namespace soa {

/// An \f$n_k\f$-vector of one hinge (at most 6, no heap).
template <class S>
using HingeVector = Eigen::Matrix<S, Eigen::Dynamic, 1, 0, 6, 1>;

/// Per-body results of the forward dynamics, sized once for a model (nothing is allocated
/// per call). `art` holds \f$P, P^+, D, G\f$ of the Riccati recursion (lesson 6).
///
/// Lean storage (ForwardDynamicsT::lean()) keeps only what the last pass needs, \f$G(k)\f$ and
/// \f$\nu(k)\f$, packed (\f$6 n_v + n_v\f$ numbers), with `art` rolling over the last two
/// bodies and no \f$z, z^+, \alpha^+\f$: seven numbers a revolute body instead of every
/// per-body quantity of the full storage (their sizes: README "Speed"), for chains of a
/// million bodies (`soa forward-dynamics`). The arithmetic is the same, so is the result, bit
/// for bit (tested).
template <class S>
struct ForwardDynamicsT {
  explicit ForwardDynamicsT(const ModelT<S>& m)
      : art(m),
        z(m.n()),
        z_plus(m.n()),
        nu(m.n()),
        alpha_plus(m.n()),
        G_packed(6 * std::size_t(m.nv())),
        nu_packed(std::size_t(m.nv())) {
    for (int k = 1; k <= m.n(); ++k) nu[k - 1].resize(m.body(k).hinge.nv());  // sized once
  }
  /// The lean storage described above.
  static ForwardDynamicsT lean(const ModelT<S>& m) { return ForwardDynamicsT(m, true); }
  bool is_lean() const { return lean_; }

  ArticulatedT<S> art;
  std::vector<ForceT<S>> z;                  ///< \f$z(k)\f$
  std::vector<ForceT<S>> z_plus;             ///< \f$z^+(k) = z(k) + G(k)\,\epsilon(k)\f$
  std::vector<HingeVector<S>> nu;            ///< \f$\nu(k) = D^{-1}(k)\,\epsilon(k)\f$
  std::vector<AccelerationT<S>> alpha_plus;  ///< \f$\alpha^+(k) = \phi^*(k+1,k)\alpha(k+1)\f$
  /// \f$G(k)\f$ column by column at 6 v_offset, \f$\nu(k)\f$ at v_offset, in both
  /// storages: the last pass reads them from here, in order, rather than from `art.G` and
  /// `nu` (one or two cache lines a body each, out of cache once the full storage of a long
  /// chain outgrows the L2 cache).
  std::vector<S> G_packed, nu_packed;

 private:
  ForwardDynamicsT(const ModelT<S>& m, bool)
      : art(ArticulatedT<S>::rolling()),
        G_packed(6 * std::size_t(m.nv())),
        nu_packed(std::size_t(m.nv())),
        lean_(true) {}
  bool lean_ = false;
};
using ForwardDynamics = ForwardDynamicsT<double>;

/// Reports what made a forward dynamics result non-finite: a non-finite input (naming it
/// and, for hinge quantities, the body), else the first body whose \f$\dot\beta\f$ is not.
template <class S>
[[noreturn]] void throw_non_finite(const ModelT<S>& m, const StateT<S>& x, const VecX<S>& T,
                                   const ExternalForces<S>& f_ext, const VecX<S>& beta_dot) {
  auto where = [&](const VecX<S>& v, bool q) -> std::string {
    for (int k = 1; k <= m.n(); ++k) {
      const BodyT<S>& B = m.body(k);
      const int off = q ? B.q_offset : B.v_offset, len = q ? B.hinge.nq() : B.hinge.nv();
      if (!v.segment(off, len).allFinite()) return "body '" + B.name + "'";
    }
    return "a body";
  };
  if (!x.theta.allFinite())
    throw Error("forward dynamics: theta of " + where(x.theta, true) + " is not finite");
  if (!x.beta.allFinite())
    throw Error("forward dynamics: beta of " + where(x.beta, false) + " is not finite");
  if (!T.allFinite())
    throw Error("forward dynamics: the hinge force T of " + where(T, false) + " is not finite");
  for (std::size_t i = 0; i < f_ext.size(); ++i)
    if (!f_ext[i].vector().allFinite())
      throw Error("forward dynamics: the external force on body '" + m.body(int(i) + 1).name +
                  "' is not finite");
  throw Error("forward dynamics: beta_dot of " + where(beta_dot, false) +
              " is not finite (overflow: check the scale of masses, forces and rates)");
}

/// The fast form of soa::reference::forward_dynamics().
/// The articulated body forward dynamics (lesson 8), O(N): the accelerations
/// \f$\dot\beta = \mathcal M^{-1}(T - \mathcal C)\f$ without forming \f$\mathcal M\f$.
///
/// Base to tip (lesson 3): \f$\phi(k+1,k)\f$, \f$V(k)\f$, \f$a(k)\f$ and the gyroscopic
/// term less the external force, \f$b(k)\f$. Tip to base, with the Riccati recursion of
/// lesson 6:
/// \f[ z(k) = \phi(k,k-1)\,z^+(k-1) + P(k)\,a(k) + b(k), \quad
///     \epsilon(k) = T(k) - H(k)\,z(k), \quad \nu(k) = D^{-1}(k)\,\epsilon(k), \quad
///     z^+(k) = z(k) + G(k)\,\epsilon(k). \f]
/// Base to tip, from \f$\alpha(n+1) = [0; -g]\f$:
/// \f[ \alpha^+(k) = \phi^*(k+1,k)\,\alpha(k+1), \quad
///     \dot\beta(k) = \nu(k) - G^*(k)\,\alpha^+(k), \quad
///     \alpha(k) = \alpha^+(k) + H^*(k)\,\dot\beta(k) + a(k). \f]
/// Springs and dampers add their hinge force to \f$T\f$. Parts the scene does not use are
/// skipped (no velocity terms at rest, no gravity, no external forces when \p f_ext is
/// empty). A singular \f$D(k)\f$ stops with the message of articulated_inertias(); a
/// non-finite input or result with soa::Error naming it. Fills ws.phi, V, a, b, alpha (and
/// hinge_sin, hinge_cos).
template <class S>
void forward_dynamics(const ModelT<S>& m, const StateT<S>& x, const VecX<S>& T,
                      const ExternalForces<S>& f_ext, WorkspaceT<S>& ws, ForwardDynamicsT<S>& fd,
                      VecX<S>& beta_dot) {
  const int n = m.n();
  WorkspaceT<S>::size(ws.phi, m);
  WorkspaceT<S>::size(ws.V, m);
  WorkspaceT<S>::size(ws.a, m);
  WorkspaceT<S>::size(ws.b, m);
  WorkspaceT<S>::size(ws.alpha, m);
  // The per-body arrays that a later pass reads back (the model's bodies, phi, a, b), by their
  // first element: indexing them reloads no vector per body.
  const BodyT<S>* const bodies = m.bodies().data();
  PhiT<S>* const phi = ws.phi.data();
  AccelerationT<S>* const a = ws.a.data();
  ForceT<S>* const b = ws.b.data();
  // A non-finite theta would stop the joint transforms with a message that names no body.
  if (!x.theta.allFinite()) throw_non_finite(m, x, T, f_ext, beta_dot);
  // At rest (beta = 0) V(k), a(k) and the gyroscopic term are exactly zero: their products
  // are skipped, and the zeros they would give are stored.
  const bool moving = !x.beta.isZero(0);
  const Vec3<S> zero = Vec3<S>::Zero();
  // Base to tip: phi(k+1,k), V(k), a(k), b(k). Spatial vectors are held as their angular and
  // linear 3-vectors ([w; v], [N; F]), which stay in registers across the loop; the products
  // are the 6-vector ones written out by parts. The revolute hinges' sines and cosines come
  // first, in one batch (hinge_sin_cos(): SLEEF's vector sincos in double, within an ulp of
  // std::sin and std::cos), rather than two libm calls a body inside the loop.
  hinge_sin_cos(m, x.theta.data(), ws);
  const S* const sin_h = ws.hinge_sin.data();
  const S* const cos_h = ws.hinge_cos.data();
  Vec3<S> w_next = zero, v_next = zero;  // V(k+1)
  for (int k = n; k >= 1; --k) {
    const BodyT<S>& B = bodies[k - 1];
    const S* th = x.theta.data() + B.q_offset;
    phi[k - 1] = joint_phi(B, th, sin_h[k - 1], cos_h[k - 1]);
    Vec3<S> w = zero, v = zero, a_w = zero, a_v = zero, N = zero, F = zero;
    if (moving) {
      const S* be = x.beta.data() + B.v_offset;
      Vec3<S> dw, dv;
      detail::hinge_rate(B.hinge, th, be, dw, dv);
      detail::velocity_and_coriolis(phi[k - 1], w_next, v_next, dw, dv, w, v, a_w, a_v);
      // Hdot^*(k) beta(k), the rate of the joint map seen from O_k (lesson 3, section 7): of
      // the hinges here only the universal joint's map changes with theta.
      if (B.hinge.type == HingeType::Universal) {
        const AccelerationT<S> Hdot_beta = B.hinge.H_star_dot_times(th, be);
        a_w += Hdot_beta.angular();
        a_v += Hdot_beta.linear();
      }
      // b(k) = [w x J w; w x (w x h)] (lesson 2)
      N = w.cross(B.M.J() * w);
      F = w.cross(w.cross(B.M.h()));
      w_next = w, v_next = v;
    }
    // No external forces: f_ext is empty, and b(k) is the gyroscopic term alone.
    if (!f_ext.empty()) N -= f_ext[k - 1].angular(), F -= f_ext[k - 1].linear();
    ws.V[k - 1] = VelocityT<S>(w, v);
    a[k - 1] = AccelerationT<S>(a_w, a_v);
    b[k - 1] = ForceT<S>(N, F);
  }
  // Tip to base: P, D, G, P+ (riccati_step()) and z, epsilon, nu, z+. Lean storage: `art`
  // rolls over two slots and z, z+, nu are not stored (fd.z, fd.z_plus, fd.nu are empty).
  ArticulatedT<S>& art = fd.art;
  const bool lean = fd.is_lean();
  CompositeTraceT<S> guard;
  Vec3<S> N_prev = zero, F_prev = zero;  // z+(k-1)
  for (int k = 1; k <= n; ++k) {
    const BodyT<S>& B = bodies[k - 1];
    const S* th = x.theta.data() + B.q_offset;
    const S d_min = riccati_step(m, x, ws, k, art, guard);
    const int slot = art.slot(k);
    if (!std::isfinite(double(d_min))) throw_non_finite(m, x, T, f_ext, beta_dot);
    // z(k) = phi(k,k-1) z+(k-1) + P(k) a(k) + b(k)
    Vec3<S> N = b[k - 1].angular(), F = b[k - 1].linear();
    if (k > 1) detail::add_apply(phi[k - 2], N_prev, F_prev, N, F);
    if (moving) {  // a(k) = 0 at rest
      const Mat6<S>& P = art.P[slot];
      const Vec3<S> a_w = a[k - 1].angular(), a_v = a[k - 1].linear();
      N += P.template topLeftCorner<3, 3>() * a_w + P.template topRightCorner<3, 3>() * a_v;
      F += P.template bottomLeftCorner<3, 3>() * a_w + P.template bottomRightCorner<3, 3>() * a_v;
    }
    const ForceT<S> z(N, F);
    if (!lean) fd.z[k - 1] = z;
    // epsilon(k) = T(k) + spring force - H(k) z(k). One-dof hinges (nv == 1) take scalar
    // statements instead of loops of one; a revolute hinge's H(k) z(k) is a . N, the product
    // with H's three zeros dropped; a body without spring or damper adds no force.
    const int nv = B.hinge.nv();
    S e[6], Hz[6];
    if (nv == 1)
      e[0] = T[B.v_offset];
    else
      for (int i = 0; i < nv; ++i) e[i] = T[B.v_offset + i];
    if (B.stiffness != S(0) || B.damping != S(0))
      add_spring_force(B, th, x.beta.data() + B.v_offset, e);
    if (B.hinge.type == HingeType::Revolute)
      Hz[0] = B.hinge.axis.dot(N);
    else
      B.hinge.H_times(th, z, Hz);
    if (nv == 1)
      e[0] -= Hz[0];
    else
      for (int i = 0; i < nv; ++i) e[i] -= Hz[i];
    // nu(k) = D^{-1}(k) epsilon(k), z+(k) = z(k) + G(k) epsilon(k). One-dof hinge: D^{-1} is
    // 1x1 (riccati_step()), so nu is a product and G epsilon a 6-vector times a scalar.
    const JointMap<S>& G = art.G[slot];
    S nu_k[6];
    if (nv == 1) {
      nu_k[0] = art.D_inv[slot](0, 0) * e[0];
      N += G.col(0).template head<3>() * e[0];
      F += G.col(0).template tail<3>() * e[0];
    } else {
      const Eigen::Map<const HingeVector<S>> eps(e, nv);
      Eigen::Map<HingeVector<S>>(nu_k, nv).noalias() = art.D_inv[slot] * eps;
      const Vec6<S> Ge = G * eps;
      N += Ge.template head<3>();
      F += Ge.template tail<3>();
    }
    // G(k) and nu(k) packed for the last pass (ForwardDynamicsT::G_packed): read there in
    // order, from consecutive memory, in both storages.
    for (int i = 0; i < nv; ++i) {
      fd.nu_packed[B.v_offset + i] = nu_k[i];
      Eigen::Map<Vec6<S>>(fd.G_packed.data() + 6 * (B.v_offset + i)) = G.col(i);
    }
    if (!lean) {
      HingeVector<S>& nu = fd.nu[k - 1];
      if (nu.size() != nv) nu.resize(nv);
      for (int i = 0; i < nv; ++i) nu[i] = nu_k[i];
      fd.z_plus[k - 1] = ForceT<S>(N, F);
    }
    N_prev = N, F_prev = F;
  }
  // Base to tip: alpha+(k), beta_dot(k), alpha(k), from alpha(n+1) = [0; -g] (zero without
  // gravity).
  Vec3<S> dw_next = zero, dv_next = zero;  // alpha(k+1)
  if (m.has_gravity()) dv_next = gravity_base_acceleration(m).linear();
  for (int k = n; k >= 1; --k) {
    const BodyT<S>& B = bodies[k - 1];
    const S* th = x.theta.data() + B.q_offset;
    // alpha+(k) = phi*(k+1,k) alpha(k+1)
    Vec3<S> dw, dv;
    detail::transpose_apply(phi[k - 1], dw_next, dv_next, dw, dv);
    if (!lean) fd.alpha_plus[k - 1] = AccelerationT<S>(dw, dv);
    // beta_dot(k) = nu(k) - G*(k) alpha+(k)
    S* bd = beta_dot.data() + B.v_offset;
    const int nv = B.hinge.nv();
    // G(k) column by column (6 numbers each) and nu(k), packed.
    const S* G = fd.G_packed.data() + 6 * B.v_offset;
    const S* nu = fd.nu_packed.data() + B.v_offset;
    for (int i = 0; i < nv; ++i) {
      const Eigen::Map<const Vec6<S>> Gi(G + 6 * i);
      bd[i] = nu[i] - (Gi.template head<3>().dot(dw) + Gi.template tail<3>().dot(dv));
    }
    // alpha(k) = alpha+(k) + H*(k) beta_dot(k) + a(k); a(k) = 0 at rest. detail::hinge_rate():
    // a revolute hinge's H^* beta_dot is [beta_dot a; 0], without the general switch.
    Vec3<S> hw, hv;
    detail::hinge_rate(B.hinge, th, bd, hw, hv);
    dw += hw;
    dv += hv;
    if (moving) dw += a[k - 1].angular(), dv += a[k - 1].linear();
    ws.alpha[k - 1] = AccelerationT<S>(dw, dv);
    dw_next = dw, dv_next = dv;
  }
  if (!beta_dot.allFinite()) throw_non_finite(m, x, T, f_ext, beta_dot);
}

/// forward_dynamics() of an Eigen expression \p T: forwards to the `const VecX<S>&` one.
template <class S, class D>
void forward_dynamics(const ModelT<S>& m, const StateT<S>& x, const Eigen::MatrixBase<D>& T,
                      const ExternalForces<S>& f_ext, WorkspaceT<S>& ws, ForwardDynamicsT<S>& fd,
                      VecX<S>& beta_dot) {
  forward_dynamics(m, x, VecX<S>(T), f_ext, ws, fd, beta_dot);
}

}  // namespace soa
