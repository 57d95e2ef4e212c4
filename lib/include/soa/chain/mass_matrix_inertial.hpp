/// \file
/// The O(N^2) mass matrix with its products hoisted to the inertial frame (lesson 5).
#pragma once

#include <vector>

#include "soa/chain/composite.hpp"

namespace soa {

/// Workspace of mass_matrix_inertial(), sized once for a model: the composite inertias and,
/// row r for degree of freedom r, the hinge column \f$s_r\f$ and the force column \f$f_r\f$
/// seen at the inertial origin (two \f$n_v \times 6\f$ blocks, column-major, so that each
/// of the six components is a contiguous array).
template <class S>
struct MassMatrixInertialT {
  explicit MassMatrixInertialT(const ModelT<S>& m) : R(m.n()), s(m.nv(), 6), f(m.nv(), 6) {}
  std::vector<SpatialInertiaT<S>> R;  ///< \f$R(k)\f$, the composite inertias
  MatX<S> s;                          ///< row r: \f$s_r^*\f$ (motion at the inertial origin)
  MatX<S> f;                          ///< row r: \f$f_r^*\f$ (force at the inertial origin)
};
using MassMatrixInertial = MassMatrixInertialT<double>;

namespace detail {

/// \f$y = X\,c\f$ for the rows \f$[r_0, r_0 + len)\f$ of an \f$n_v \times 6\f$ block \p X
/// and a 6-vector \p c: the dot products of \f$c\f$ with those rows, one vectorized loop over
/// the rows (six contiguous columns read, one written).
template <class S>
EIGEN_ALWAYS_INLINE void rows_dot(const MatX<S>& X, Eigen::Index r0, Eigen::Index len, const S* c,
                                  S* __restrict y) {
  const Eigen::Index ld = X.rows();
  const S* __restrict x0 = X.data() + r0;
  const S* __restrict x1 = x0 + ld, * __restrict x2 = x0 + 2 * ld, * __restrict x3 = x0 + 3 * ld;
  const S* __restrict x4 = x0 + 4 * ld, * __restrict x5 = x0 + 5 * ld;
  const S c0 = c[0], c1 = c[1], c2 = c[2], c3 = c[3], c4 = c[4], c5 = c[5];
  for (Eigen::Index i = 0; i < len; ++i)
    y[i] = ((c0 * x0[i] + c1 * x1[i]) + (c2 * x2[i] + c3 * x3[i])) + (c4 * x4[i] + c5 * x5[i]);
}

}  // namespace detail

/// The mass matrix of lesson 5 with the products hoisted, \f$O(N^2)\f$. Lesson 5 writes
/// \f$\mathcal M(i,j) = H(i)\,\phi(i,j)\,R(j)\,H^*(j)\f$ for \f$i > j\f$ and carries the force
/// column \f$R(j)H^*(j)\f$ inboard one \f$\phi(i,i-1)\f$ at a time: every entry waits for the
/// one before it. Splitting \f$\phi(i,j) = \phi(i,\mathbb I)\,\phi(\mathbb I,j)\f$ at the
/// inertial origin \f$\mathbb I\f$ (slide 45) and \f$\phi(i,\mathbb I) =
/// \phi^{-1}(\mathbb I, i)\f$ (slide 44) gives
/// \f[ \mathcal M(i,j) = s^*(i)\, f(j), \qquad s(i) = \phi^{-*}(\mathbb I,i)\,H^*(i), \qquad
///     f(j) = \phi(\mathbb I,j)\,R(j)\,H^*(j), \f]
/// the hinge map of hinge i as a velocity seen at \f$\mathbb I\f$ and the force column of
/// hinge j moved to \f$\mathbb I\f$, both in inertial coordinates: O(N) work to form, then
/// one independent 6-term dot product per entry. With the pose \f$({}^{\mathbb I}R_k,
/// p_k)\f$ of \f$O_k\f$ and a column \f$[\omega; v]\f$ of \f$H^*(k)\f$, or \f$[N; F]\f$ of
/// \f$R(k)H^*(k)\f$, at \f$O_k\f$: \f$s = [R\omega;\ Rv + p \times R\omega]\f$ and \f$f =
/// [RN + p \times RF;\ RF]\f$. The diagonal blocks \f$H(k)R(k)H^*(k)\f$ are formed at
/// \f$O_k\f$ as in lesson 5.
///
/// Rounding: a moment about \f$\mathbb I\f$ is of size \f$|p|\,|F|\f$, so an entry far out
/// on a long chain carries an error of about \f$\varepsilon\,|p|\,|f|\f$ where lesson 5's
/// carries \f$\varepsilon\,|f|\f$ times the links between i and j; both are tested against
/// each other. Both triangles are computed, each column as a contiguous vectorized loop (no
/// strided transpose). Needs update_phi().
template <class S>
void mass_matrix_inertial(const ModelT<S>& m, const StateT<S>& x, const WorkspaceT<S>& ws,
                          MassMatrixInertialT<S>& w, MatX<S>& Mass) {
  const int n = m.n(), nv = m.nv();
  Mass.resize(nv, nv);
  composite_inertias(m, ws, w.R);
  // Base to tip: the pose (R_k, p_k) of O_k (slides 25-27), then for each column
  // [w; v] of H*(k) and its force [N; F] = R(k) [w; v] at O_k the rows s and f, and the
  // diagonal block H(k) R(k) H*(k).
  PoseT<S> T;  // {}^I T_{O_k}
  auto put_rows = [&](int r, const Vec3<S>& w_k, const Vec3<S>& v_k, const Vec3<S>& N,
                      const Vec3<S>& F) {
    const Mat3<S>& R = T.R();
    const Vec3<S>& p = T.l();
    const Vec3<S> a = R * w_k, v = R * v_k + p.cross(a), Fw = R * F, Nw = R * N + p.cross(Fw);
    for (int i = 0; i < 3; ++i) {
      w.s(r, i) = a[i], w.s(r, 3 + i) = v[i];
      w.f(r, i) = Nw[i], w.f(r, 3 + i) = Fw[i];
    }
  };
  for (int k = n; k >= 1; --k) {
    const BodyT<S>& B = m.body(k);
    const SpatialInertiaT<S>& Rk = w.R[k - 1];
    T = T * ws.phi[k - 1].pose();
    const int o = B.v_offset;
    if (B.hinge.type == HingeType::Revolute) {  // [N; F] = R(k) [a; 0] = [J a; a x h]
      const Vec3<S>& a = B.hinge.axis;
      const Vec3<S> N = Rk.J() * a;
      Mass(o, o) = a.dot(N);
      put_rows(o, a, Vec3<S>::Zero(), N, a.cross(Rk.h()));
      continue;
    }
    const JointMap<S> Hs = B.hinge.H_star(x.theta.data() + B.q_offset);
    for (int c = 0; c < B.hinge.nv(); ++c) {
      const MomentumT<S> hc = Rk * VelocityT<S>(Vec6<S>(Hs.col(c)));
      for (int r = 0; r <= c; ++r)
        Mass(o + r, o + c) = Mass(o + c, o + r) = Hs.col(r).dot(hc.vector());
      put_rows(o + c, Hs.col(c).template head<3>(), Hs.col(c).template tail<3>(), hc.angular(),
               hc.linear());
    }
  }
  // The columns of hinge k: below its block M(i,k) = s^*(i) f(k) for the inboard hinges,
  // above it M(j,k) = M(k,j) = f^*(j) s(k) for the outboard ones; each a contiguous loop.
  for (int k = 1; k <= n; ++k) {
    const BodyT<S>& B = m.body(k);
    const int o = B.v_offset, nk = B.hinge.nv(), below = o + nk;
    for (int c = o; c < below; ++c) {
      S fc[6], sc[6];
      for (int i = 0; i < 6; ++i) fc[i] = w.f(c, i), sc[i] = w.s(c, i);
      S* col = Mass.col(c).data();
      detail::rows_dot(w.s, below, nv - below, fc, col + below);
      detail::rows_dot(w.f, 0, o, sc, col);
    }
  }
}

}  // namespace soa
