/// \file
/// The O(N^2) mass matrix with its products hoisted to the inertial frame (lesson 5).
#pragma once

#include <vector>

#include "soa/chain/composite.hpp"
#include "soa/detail/plane.hpp"

namespace soa {

/// Workspace of mass_matrix_inertial(), sized once for a model: the composite inertias and,
/// row r for degree of freedom r, the hinge column \f$s_r\f$ and the force column \f$f_r\f$
/// seen at the inertial origin (two \f$n_v \times 6\f$ blocks, column-major, so that each
/// of the six components is a contiguous array).
template <class S>
struct MassMatrixInertialT {
  explicit MassMatrixInertialT(const ModelT<S>& m)
      : R(m.n()), axis(m.n()), s(m.nv(), 6), f(m.nv(), 6) {}
  std::vector<SpatialInertiaT<S>> R;  ///< \f$R(k)\f$, the composite inertias
  /// entry k - 1: the coordinate axis \f$\phi(k+1,k)\f$ turns about, or -1
  /// (detail::plane_rotation_axis(); -1 when Model::fast_paths is off)
  std::vector<int> axis;
  MatX<S> s;  ///< row r: \f$s_r^*\f$ (motion at the inertial origin)
  MatX<S> f;  ///< row r: \f$f_r^*\f$ (force at the inertial origin)
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

/// Row \p r of \f$s\f$, \f$[a; v]\f$, and of \f$f\f$, \f$[N; F]\f$, in \p work.
template <class S>
EIGEN_ALWAYS_INLINE void put_rows(MassMatrixInertialT<S>& work, int r, const Vec3<S>& a,
                                  const Vec3<S>& v, const Vec3<S>& N, const Vec3<S>& F) {
  const Eigen::Index ld = work.s.rows();
  S* const s = work.s.data() + r;
  S* const f = work.f.data() + r;
  for (int i = 0; i < 3; ++i) {
    s[i * ld] = a[i], s[(3 + i) * ld] = v[i];
    f[i * ld] = N[i], f[(3 + i) * ld] = F[i];
  }
}

/// The dot product of row \p i of the column-major \p X (leading dimension \p ld) with
/// \p c, summed as rows_dot() sums it.
template <class S>
EIGEN_ALWAYS_INLINE S row_dot(const S* X, Eigen::Index ld, Eigen::Index i, const S* c) {
  const S* x = X + i;
  return ((c[0] * x[0] + c[1] * x[ld]) + (c[2] * x[2 * ld] + c[3] * x[3 * ld])) +
         (c[4] * x[4 * ld] + c[5] * x[5 * ld]);
}

}  // namespace detail

/// The fast form of soa::reference::mass_matrix().
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
/// each other. A long matrix is computed in both triangles, each column a contiguous
/// vectorized loop (no strided transpose); a short one (at most 32 degrees of freedom) in its
/// lower triangle, mirrored: the same products summed in the same order either way, so
/// \f$\mathcal M\f$ is exactly symmetric. With Model::fast_paths a \f$\phi\f$ turning about a
/// coordinate axis composes the poses and moves the composite inertias in its plane
/// (detail::plane_times(), soa::transform()), and a revolute hinge about \f$\pm e_i\f$ takes
/// its columns of the pose and of \f$J\f$ (the fast paths). Needs update_phi().
template <class S>
void mass_matrix_inertial(const ModelT<S>& m, const StateT<S>& x, const WorkspaceT<S>& ws,
                          MassMatrixInertialT<S>& work, MatX<S>& Mass) {
  const int n = m.n(), nv = m.nv();
  const bool fast = m.fast_paths;
  Mass.resize(nv, nv);
  // composite_inertias(), with the plane axis of each phi for the poses below
  detail::composite_sweep(m, ws, work.R.data(), work.axis.data());
  // Base to tip: the pose (R, p) of O_k (slides 25-27), then for each column [w; v] of
  // H*(k) and its force [N; F] = R(k) [w; v] at O_k the rows s = [a; v'] and f = [N'; F'],
  // and the diagonal block H(k) R(k) H*(k).
  Mat3<S> R = Mat3<S>::Identity();  // {}^I R_{O_k}
  Vec3<S> p = Vec3<S>::Zero();      // {}^I l(I, O_k)
  for (int k = n; k >= 1; --k) {
    const BodyT<S>& B = m.body(k);
    const SpatialInertiaT<S>& Rk = work.R[k - 1];
    // {}^I T_{O_k} = {}^I T_{O_{k+1}} phi(k+1, k).pose(): p += R l, then R = R R_phi, in the
    // plane of R_phi only when it turns about a coordinate axis (detail::plane_times(), the
    // general products less those with an exact 0 or 1: the same bits, or an ulp apart where
    // Eigen's product fuses a multiply-add).
    const PoseT<S>& Tk = ws.phi[k - 1].pose();
    p += R * Tk.l();
    if (!(detail::with_plane_axis(work.axis[k - 1], [&](auto axis_c) {
          R = detail::plane_times<decltype(axis_c)::value>(R, Tk.R());
        })))
      R = R * Tk.R();
    const int o = B.v_offset;
    if (B.hinge.type == HingeType::Revolute) {  // [N; F] = R(k) [a; 0] = [J a; a x h]
      const Vec3<S>& a = B.hinge.axis;
      // About +-e_i (sign sg): a' = sg R e_i, N = sg J e_i, a x h has two entries, and
      // M(k,k) = J_ii; each product left out has an exact 0 or 1 (the same bits up to the
      // fused multiply-adds of Eigen's general products). (i, u, w) cyclic, as in
      // soa/detail/plane.hpp.
      const bool axis_path =
          fast && detail::with_plane_axis(detail::coordinate_axis(a), [&](auto axis_c) {
            constexpr int i = decltype(axis_c)::value, u = i == 2 ? 0 : i + 1,
                          w = u == 2 ? 0 : u + 1;
            const S sg = a[i];
            const Vec3<S>& h = Rk.h();
            const Vec3<S> aw = sg * R.col(i), N = sg * Rk.J().col(i);
            const Vec3<S> Fw = R.col(u) * (-(sg * h[w])) + R.col(w) * (sg * h[u]);
            Mass(o, o) = Rk.J()(i, i);
            detail::put_rows<S>(work, o, aw, p.cross(aw), R * N + p.cross(Fw), Fw);
          });
      if (axis_path) continue;
      const Vec3<S> N = Rk.J() * a, aw = R * a, Fw = R * a.cross(Rk.h());
      Mass(o, o) = a.dot(N);
      detail::put_rows<S>(work, o, aw, p.cross(aw), R * N + p.cross(Fw), Fw);
      continue;
    }
    const JointMap<S> Hs = B.hinge.H_star(x.theta.data() + B.q_offset);
    for (int c = 0; c < B.hinge.nv(); ++c) {
      const MomentumT<S> hc = Rk * VelocityT<S>(Vec6<S>(Hs.col(c)));
      for (int r = 0; r <= c; ++r)
        Mass(o + r, o + c) = Mass(o + c, o + r) = Hs.col(r).dot(hc.vector());
      const Vec3<S> aw = R * Hs.col(c).template head<3>(), Fw = R * hc.linear();
      detail::put_rows<S>(work, o + c, aw, R * Hs.col(c).template tail<3>() + p.cross(aw),
                          R * hc.angular() + p.cross(Fw), Fw);
    }
  }
  // The columns of hinge k: below its block M(i,k) = s^*(i) f(k) for the inboard hinges,
  // above it M(j,k) = M(k,j) = f^*(j) s(k) for the outboard ones. A short matrix takes the
  // lower triangle entry by entry and mirrors it (half the dot products; the vector loops'
  // set-up dominates below kMirrorMax dofs); a long one computes both triangles, each column
  // a contiguous vectorized loop (no strided transpose). The two give the same bits:
  // M(j,k) and M(k,j) are the same six products summed in the same order.
  constexpr int kMirrorMax = 32;
  if (nv <= kMirrorMax) {
    S* const Mass_data = Mass.data();
    const S *const s = work.s.data(), *const f = work.f.data();
    const Eigen::Index ld = nv;
    for (int k = 1; k <= n; ++k) {  // hinge k's columns [o, below), tip first
      const int o = m.body(k).v_offset, below = k < n ? m.body(k + 1).v_offset : nv;
      for (int c = o; c < below; ++c) {
        S fc[6];
        for (int i = 0; i < 6; ++i) fc[i] = f[c + i * ld];
        S* const col = Mass_data + c * ld;
        for (int i = below; i < nv; ++i)
          Mass_data[c + i * ld] = col[i] = detail::row_dot(s, ld, i, fc);
      }
    }
    return;
  }
  for (int k = 1; k <= n; ++k) {
    const BodyT<S>& B = m.body(k);
    const int o = B.v_offset, below = o + B.hinge.nv();
    for (int c = o; c < below; ++c) {
      S fc[6], sc[6];
      for (int i = 0; i < 6; ++i) fc[i] = work.f(c, i), sc[i] = work.s(c, i);
      S* col = Mass.col(c).data();
      detail::rows_dot(work.s, below, nv - below, fc, col + below);
      detail::rows_dot(work.f, 0, o, sc, col);
    }
  }
}

}  // namespace soa
