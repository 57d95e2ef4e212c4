/// \file
/// Serial-chain kinematics: the O(N) scatter recursions, base to tip (lesson 3). Names: with
/// the tip-to-base numbering (\ref conventions_chain), `_next` is a value of body k+1
/// (inboard); `Rp` is a placement's rotation \f$R_p\f$ (slides 25-27).
#pragma once

#include <cmath>
#include <type_traits>

#include "soa/chain/workspace.hpp"
#include "soa/detail/sin_cos.hpp"
#include "soa/spatial_cross.hpp"
#include "soa/tilde.hpp"

namespace soa {

namespace detail {

/// \f$R^* x\f$ as three column dot products.
template <class S>
EIGEN_ALWAYS_INLINE Vec3<S> transpose_times(const Mat3<S>& R, const Vec3<S>& x) {
  return Vec3<S>(R.col(0).dot(x), R.col(1).dot(x), R.col(2).dot(x));
}

/// \f$R_p\, e^{\theta \tilde a}\f$ for a unit axis \f$a\f$ from \f$c = \cos\theta\f$ and
/// \f$s = \sin\theta\f$, by Rodrigues (lesson 1):
/// \f$e^{\theta\tilde a} = c I + s\tilde a + (1 - c)\, a a^*\f$. About a coordinate axis
/// \f$\pm e_i\f$ only two columns of \f$R_p\f$ turn: with \f$(i, u, w)\f$ cyclic,
/// \f$c_u' = c\, c_u + s\, c_w\f$ and \f$c_w' = c\, c_w - s\, c_u\f$ (\f$s\f$ taking the
/// sign of the axis), the general product less its products with \f$e^{\theta\tilde a}\f$'s
/// exact zeros and ones.
template <class S>
EIGEN_ALWAYS_INLINE Mat3<S> rotate_about_axis(const Mat3<S>& Rp, const Vec3<S>& a, S c, S s) {
  using std::abs;
  const int i = a[0] != S(0) ? 0 : a[1] != S(0) ? 1 : 2;
  const int u = i == 2 ? 0 : i + 1, w = u == 2 ? 0 : u + 1;
  if (a[u] == S(0) && a[w] == S(0) && abs(a[i]) == S(1)) {
    const S si = a[i] * s;
    Mat3<S> R;
    R.col(i) = Rp.col(i);
    R.col(u) = c * Rp.col(u) + si * Rp.col(w);
    R.col(w) = c * Rp.col(w) - si * Rp.col(u);
    return R;
  }
  Mat3<S> E = (S(1) - c) * a * a.transpose() + s * tilde(a);
  E.diagonal().array() += c;
  return Rp * E;
}

/// \f$R_p\, e^{\theta \tilde a}\f$ with std::cos and std::sin of \p theta.
template <class S>
EIGEN_ALWAYS_INLINE Mat3<S> rotate_about_axis(const Mat3<S>& Rp, const Vec3<S>& a, S theta) {
  using std::cos;
  using std::sin;
  return rotate_about_axis(Rp, a, S(cos(theta)), S(sin(theta)));
}

}  // namespace detail

/// \f$\phi(k+1,k) = {}^{O_{k+1}}T_{O_k^+}\; {}^{O_k^+}T_{O_k}(\theta(k))\f$ of body k (slides
/// 25-27: \f$R = R_p R_h\f$, \f$l = l_p + R_p l_h\f$); a revolute hinge has \f$l_h = 0\f$.
/// The recursions take the other joint_phi(), from hinge_sin_cos()'s sines and cosines: in
/// double the two may differ in the last bit (SLEEF's sine is not glibc's:
/// soa/detail/sin_cos.hpp).
template <class S>
EIGEN_ALWAYS_INLINE PhiT<S> joint_phi(const BodyT<S>& B, const S* theta) {
  if (B.hinge.type == HingeType::Revolute)
    return PhiT<S>(detail::rotate_about_axis(B.placement.R(), B.hinge.axis, theta[0]),
                   B.placement.l());
  return PhiT<S>(B.placement * B.hinge.transform(theta));
}

/// joint_phi() of body k with \p sin_theta and \p cos_theta of its angle, when its hinge is
/// revolute (hinge_sin_cos()); other hinges ignore them.
template <class S>
EIGEN_ALWAYS_INLINE PhiT<S> joint_phi(const BodyT<S>& B, const S* theta, S sin_theta, S cos_theta) {
  if (B.hinge.type == HingeType::Revolute)
    return PhiT<S>(detail::rotate_about_axis(B.placement.R(), B.hinge.axis, cos_theta, sin_theta),
                   B.placement.l());
  return PhiT<S>(B.placement * B.hinge.transform(theta));
}

/// \f$\sin\theta(k)\f$ and \f$\cos\theta(k)\f$ of every revolute hinge k into
/// ws.hinge_sin and ws.hinge_cos (entry k - 1), for joint_phi(). In double the angles are
/// gathered in body order and take one batch of detail::sin_cos() (SLEEF's vector sincos,
/// 1.0 ulp): several angles a vector instruction, instead of two scalar libm calls a joint
/// inside the recursions; the results may differ from std::sin's in the last bit. Other
/// scalars take std::sin and std::cos of the revolute angles only.
template <class S>
void hinge_sin_cos(const ModelT<S>& m, const S* theta, WorkspaceT<S>& ws) {
  WorkspaceT<S>::size(ws.hinge_sin, m);
  WorkspaceT<S>::size(ws.hinge_cos, m);
  const BodyT<S>* const bodies = m.bodies().data();
  S* const sin_h = ws.hinge_sin.data();
  S* const cos_h = ws.hinge_cos.data();
  if constexpr (detail::batched_sin_cos<S>) {
    for (int i = 0; i < m.n(); ++i)  // the angles (0 for other hinges), then cos in place
      cos_h[i] = bodies[i].hinge.type == HingeType::Revolute ? theta[bodies[i].q_offset] : S(0);
    detail::sin_cos(cos_h, m.n(), sin_h, cos_h);
  } else {
    using std::cos;
    using std::sin;
    for (int i = 0; i < m.n(); ++i)
      if (bodies[i].hinge.type == HingeType::Revolute) {
        const S th = theta[bodies[i].q_offset];
        sin_h[i] = sin(th);
        cos_h[i] = cos(th);
      }
  }
}

/// The fast form of soa::reference::joint_transforms().
/// \f$\phi(k+1,k)\f$ for every body (joint_phi(), after hinge_sin_cos()).
template <class S>
void update_phi(const ModelT<S>& m, const VecX<S>& theta, WorkspaceT<S>& ws) {
  WorkspaceT<S>::size(ws.phi, m);
  hinge_sin_cos(m, theta.data(), ws);
  for (int k = m.n(); k >= 1; --k) {
    const BodyT<S>& B = m.body(k);
    ws.phi[k - 1] =
        joint_phi(B, theta.data() + B.q_offset, ws.hinge_sin[k - 1], ws.hinge_cos[k - 1]);
  }
}

/// update_phi() of an Eigen expression \p theta: forwards to update_phi(m, const VecX<S>&, ws).
template <class S, class D>
void update_phi(const ModelT<S>& m, const Eigen::MatrixBase<D>& theta, WorkspaceT<S>& ws) {
  update_phi(m, VecX<S>(theta), ws);
}

/// Poses by the scatter recursion (slides 25-27), base to tip:
/// \f${}^I T_{O_k} = {}^I T_{O_{k+1}}\; {}^{O_{k+1}}T_{O_k}\f$. Needs update_phi().
template <class S>
void update_poses(const ModelT<S>& m, WorkspaceT<S>& ws) {
  const int n = m.n();
  WorkspaceT<S>::size(ws.pose, m);
  if (n == 0) return;
  ws.pose[n - 1] = ws.phi[n - 1].pose();
  for (int k = n - 1; k >= 1; --k) ws.pose[k - 1] = ws.pose[k] * ws.phi[k - 1].pose();
}

/// The Coriolis term of the acceleration recursion (lesson 3, derived there from slide 61):
/// with \f$\Delta_V = H^*(k)\beta(k)\f$ and \f$V(k) = [\omega_k; v_k]\f$,
/// \f[ a(k) = \tilde V(k)\,\Delta_V + \mathring H^*(k)\beta(k) +
///     \begin{pmatrix} 0 \\ \omega_k \times v_k - R^*(\omega_{k+1} \times v_{k+1})
///     \end{pmatrix}, \f]
/// \f$R = {}^{k+1}R_k\f$; equal to the coordinate-free
/// \f$[\omega_{k+1}\times\Delta_\omega;\ \omega_k\times\Delta_v + \omega_{k+1}\times
/// (v(k) - v(k+1))] + \mathring H^*\beta\f$, where \f$\omega_k\times\Delta_v =
/// \omega_{k+1}\times\Delta_v + \Delta_\omega\times\Delta_v\f$ and the last term is non-zero
/// only for free hinges (\f$\mathring H^*\f$ is the rate seen from \f$O_k\f$).
template <class S>
AccelerationT<S> coriolis_term(const PhiT<S>& phi, const VelocityT<S>& V_next,
                               const VelocityT<S>& V, const VelocityT<S>& dV,
                               const AccelerationT<S>& Hdot_beta) {
  const Vec3<S> w = V.angular(), v = V.linear();
  const Vec3<S> w_next = V_next.angular(), v_next = V_next.linear();
  const Vec3<S> wv_next = phi.R().transpose() * w_next.cross(v_next);
  return cross(V, dV) + Hdot_beta + AccelerationT<S>(Vec3<S>::Zero(), w.cross(v) - wv_next);
}

namespace detail {

/// \f$\Delta_V = H^*(k)\beta(k) = [\Delta_\omega; \Delta_v]\f$ as its two parts; a revolute
/// hinge gives \f$[\beta a; 0]\f$ without the general switch on the hinge type (the same
/// products: \f$H^*(k) = [a; 0]\f$).
template <class S>
EIGEN_ALWAYS_INLINE void hinge_rate(const HingeT<S>& h, const S* theta, const S* beta, Vec3<S>& dw,
                                    Vec3<S>& dv) {
  if (h.type == HingeType::Revolute) {
    dw = beta[0] * h.axis;
    dv.setZero();
  } else {
    const VelocityT<S> dV = h.H_star_times(theta, beta);
    dw = dV.angular();
    dv = dV.linear();
  }
}

/// \f$\phi^*(x,y) V\f$ on the parts of \f$V = [\omega; v]\f$ (slide 41):
/// \f$\omega' = R^*\omega\f$, \f$v' = R^*(v + \omega \times l)\f$.
template <class S>
EIGEN_ALWAYS_INLINE void transpose_apply(const PhiT<S>& phi, const Vec3<S>& w, const Vec3<S>& v,
                                         Vec3<S>& w_out, Vec3<S>& v_out) {
  w_out = transpose_times(phi.R(), w);
  v_out = transpose_times(phi.R(), Vec3<S>(v + w.cross(phi.l())));
}

/// \f$\phi(x,y) f\f$ on the parts of \f$f = [N; F]\f$ (slide 49): \f$F' = RF\f$,
/// \f$N' = RN + l \times F'\f$; added into \p N_out, \p F_out.
template <class S>
EIGEN_ALWAYS_INLINE void add_apply(const PhiT<S>& phi, const Vec3<S>& N, const Vec3<S>& F,
                                   Vec3<S>& N_out, Vec3<S>& F_out) {
  const Vec3<S> RF = phi.R() * F;
  N_out += phi.R() * N + phi.l().cross(RF);
  F_out += RF;
}

/// \f$V(k) = \phi^*(k+1,k)\,V(k+1) + \Delta_V\f$ (slide 41) and the Coriolis term \f$a(k)\f$
/// in the coordinate-free form of coriolis_term(), on the parts, with \f$\omega' =
/// R^*\omega_{k+1}\f$ and \f$u = R^*(\omega_{k+1} \times l)\f$ (so \f$v(k) - v(k+1) = u +
/// \Delta_v\f$ in \f$O_k\f$ coordinates):
/// \f[ a(k) = \begin{pmatrix} \omega' \times \Delta_\omega \\ \omega_k \times \Delta_v +
///     \omega' \times (u + \Delta_v) \end{pmatrix} + \mathring H^*(k)\beta(k), \f]
/// the last term added by the caller (universal hinges only).
template <class S>
EIGEN_ALWAYS_INLINE void velocity_and_coriolis(const PhiT<S>& phi, const Vec3<S>& w_next,
                                               const Vec3<S>& v_next, const Vec3<S>& dw,
                                               const Vec3<S>& dv, Vec3<S>& w, Vec3<S>& v,
                                               Vec3<S>& a_w, Vec3<S>& a_v) {
  const Mat3<S>& R = phi.R();
  const Vec3<S> w1 = transpose_times(R, w_next);
  const Vec3<S> u_dv = transpose_times(R, Vec3<S>(w_next.cross(phi.l()))) + dv;
  w = w1 + dw;
  v = transpose_times(R, v_next) + u_dv;
  a_w = w1.cross(dw);
  a_v = w.cross(dv) + w1.cross(u_dv);
}

}  // namespace detail

/// The fast form of soa::reference::velocities().
/// Velocities \f$V(k) = \phi^*(k+1,k)\,V(k+1) + H^*(k)\beta(k)\f$ and Coriolis terms
/// \f$a(k)\f$, base to tip (\f$V(n+1) = 0\f$). Needs update_phi(). At rest (\f$\beta = 0\f$)
/// every \f$V\f$ and \f$a\f$ is exactly zero: they are stored and nothing else is computed.
template <class S>
void update_velocities(const ModelT<S>& m, const StateT<S>& x, WorkspaceT<S>& ws) {
  const bool at_rest = x.beta.isZero(0);
  WorkspaceT<S>::size(ws.V, m);
  WorkspaceT<S>::size(ws.a, m);
  VelocityT<S> V_next;
  for (int k = m.n(); k >= 1; --k) {
    if (at_rest) {
      ws.V[k - 1] = VelocityT<S>();
      ws.a[k - 1] = AccelerationT<S>();
      continue;
    }
    const BodyT<S>& B = m.body(k);
    const S* th = x.theta.data() + B.q_offset;
    const S* be = x.beta.data() + B.v_offset;
    const VelocityT<S> dV = B.hinge.H_star_times(th, be);
    const PhiT<S>& phi = ws.phi[k - 1];
    ws.V[k - 1] = phi.transpose_apply(V_next) + dV;
    ws.a[k - 1] = coriolis_term(phi, V_next, ws.V[k - 1], dV, B.hinge.H_star_dot_times(th, be));
    V_next = ws.V[k - 1];
  }
}

/// The fast form of soa::reference::kinematics().
/// Accelerations \f$\alpha(k) = \phi^*(k+1,k)\,\alpha(k+1) + H^*(k)\dot\beta(k) + a(k)\f$,
/// base to tip, from the base acceleration \f$\alpha(n+1) = [0; -g]\f$ (gravity, lesson 4)
/// given in inertial coordinates. \p beta_dot may be null for \f$\dot\beta = 0\f$.
/// Needs update_velocities().
template <class S>
void update_accelerations(const ModelT<S>& m, const StateT<S>& x, const S* beta_dot,
                          const AccelerationT<S>& alpha_base, WorkspaceT<S>& ws) {
  AccelerationT<S> alpha_next = alpha_base;
  WorkspaceT<S>::size(ws.alpha, m);
  for (int k = m.n(); k >= 1; --k) {
    const BodyT<S>& B = m.body(k);
    AccelerationT<S> alpha = ws.phi[k - 1].transpose_apply(alpha_next) + ws.a[k - 1];
    if (beta_dot)
      alpha += AccelerationT<S>(
          B.hinge.H_star_times(x.theta.data() + B.q_offset, beta_dot + B.v_offset).vector());
    ws.alpha[k - 1] = alpha;
    alpha_next = alpha;
  }
}

/// update_accelerations() with `nullptr` (\f$\dot\beta = 0\f$): forwards to the `const S*` one.
template <class S, class N, std::enable_if_t<std::is_null_pointer_v<N>, int> = 0>
void update_accelerations(const ModelT<S>& m, const StateT<S>& x, N,
                          const AccelerationT<S>& alpha_base, WorkspaceT<S>& ws) {
  update_accelerations(m, x, static_cast<const S*>(nullptr), alpha_base, ws);
}

/// update_accelerations() of a vector or Eigen expression \p beta_dot: forwards its data().
template <class S, class D>
void update_accelerations(const ModelT<S>& m, const StateT<S>& x,
                          const Eigen::MatrixBase<D>& beta_dot, const AccelerationT<S>& alpha_base,
                          WorkspaceT<S>& ws) {
  const VecX<S> bd(beta_dot);
  update_accelerations(m, x, bd.data(), alpha_base, ws);
}

/// The base acceleration that stands for gravity: \f$\alpha(n+1) = [0; -g]\f$ (lesson 4).
template <class S>
AccelerationT<S> gravity_base_acceleration(const ModelT<S>& m) {
  return AccelerationT<S>(Vec3<S>::Zero(), -m.gravity);
}

}  // namespace soa
