/// \file
/// The inverse of the mass matrix in O(N^2), without forming the mass matrix (lesson 7).
#pragma once

#include <cmath>
#include <string>
#include <type_traits>

#include "soa/chain/articulated.hpp"
#include "soa/detail/plane.hpp"

namespace soa {

/// Workspace of mass_matrix_inverse(): the Riccati results and two nv x 6 blocks, sized once.
template <class S>
struct MassMatrixInverseT {
  explicit MassMatrixInverseT(const ModelT<S>& m)
      : art(m), Y(m.nv(), 6), Z(m.nv(), 6), E(m.nv(), 6) {}
  ArticulatedT<S> art;
  /// Columns of the tip-to-base pass, stored transposed: row j of \p Y is \f$z^{+*}\f$ for
  /// the unit hinge force \f$T = e_j\f$ (an \f$n_v \times 6\f$ block, no 6x6 operator).
  /// Transposed, so that \f$\phi\f$ acts on contiguous columns (a loop over the rows that
  /// vectorizes) rather than on rows of six scattered numbers.
  MatX<S> Y, Z, E;
};
using MassMatrixInverse = MassMatrixInverseT<double>;

namespace detail {

/// Rows of \p X (each the transpose of a spatial force) moved by \f$\phi = (R, l)\f$:
/// \f$N' = RN + l \times RF,\ F' = RF\f$, written into \p out (same rows). Column
/// operations only, so that every line is a vectorized loop over the rows.
template <class S, class In, class Out>
void apply_phi_rows(const PhiT<S>& phi, const In& X, Out& out) {
  const Mat3<S>& R = phi.R();
  const Vec3<S>& l = phi.l();
  for (int i = 0; i < 3; ++i) {
    out.col(i) = R(i, 0) * X.col(0) + R(i, 1) * X.col(1) + R(i, 2) * X.col(2);
    out.col(3 + i) = R(i, 0) * X.col(3) + R(i, 1) * X.col(4) + R(i, 2) * X.col(5);
  }
  // N' += l x F' = (l1 F2 - l2 F1, l2 F0 - l0 F2, l0 F1 - l1 F0)
  out.col(0) += l[1] * out.col(5) - l[2] * out.col(4);
  out.col(1) += l[2] * out.col(3) - l[0] * out.col(5);
  out.col(2) += l[0] * out.col(4) - l[1] * out.col(3);
}

/// Rows of \p X (each the transpose of a spatial acceleration) moved by \f$\phi^* =
/// (R, l)^*\f$: \f$\omega' = R^*\omega,\ v' = R^*(v + \omega \times l)\f$, written into
/// \p out.
template <class S, class In, class Out>
void transpose_apply_phi_rows(const PhiT<S>& phi, In& X, Out& out) {
  const Mat3<S>& R = phi.R();
  const Vec3<S>& l = phi.l();
  // v += w x l = (w1 l2 - w2 l1, w2 l0 - w0 l2, w0 l1 - w1 l0)
  X.col(3) += l[2] * X.col(1) - l[1] * X.col(2);
  X.col(4) += l[0] * X.col(2) - l[2] * X.col(0);
  X.col(5) += l[1] * X.col(0) - l[0] * X.col(1);
  for (int i = 0; i < 3; ++i) {
    out.col(i) = R(0, i) * X.col(0) + R(1, i) * X.col(1) + R(2, i) * X.col(2);
    out.col(3 + i) = R(0, i) * X.col(3) + R(1, i) * X.col(4) + R(2, i) * X.col(5);
  }
}

/// One-degree-of-freedom hinge k, tip to base, on rows \f$[0, c)\f$ of \f$Y = Z^{+*}\f$ (in
/// place) and of column \p Minv_col of \f$\mathcal M^{-1}\f$, row by row (each row is one unit hinge
/// force, so the loop vectorizes over rows): with \f$s = H^*(k)\f$, \f$g = G(k)\f$,
/// \f$Z = \phi(k,k-1) Z^+\f$ (\f$F' = RF,\ N' = RN + l \times F'\f$), \f$\epsilon = -s^* Z\f$,
/// \f$\nu = D^{-1}\epsilon\f$, \f$Z^+ = Z + g\,\epsilon\f$.
template <class S>
void tip_to_base_rows_1dof(int c, const PhiT<S>& phi, const Vec6<S>& s, S D_inv, const Vec6<S>& g,
                           S* __restrict y0, S* __restrict y1, S* __restrict y2, S* __restrict y3,
                           S* __restrict y4, S* __restrict y5, S* __restrict Minv_col) {
  const Mat3<S>& R = phi.R();
  const Vec3<S>& l = phi.l();
  for (int r = 0; r < c; ++r) {
    const S F0 = R(0, 0) * y3[r] + R(0, 1) * y4[r] + R(0, 2) * y5[r];
    const S F1 = R(1, 0) * y3[r] + R(1, 1) * y4[r] + R(1, 2) * y5[r];
    const S F2 = R(2, 0) * y3[r] + R(2, 1) * y4[r] + R(2, 2) * y5[r];
    const S N0 = R(0, 0) * y0[r] + R(0, 1) * y1[r] + R(0, 2) * y2[r] + (l[1] * F2 - l[2] * F1);
    const S N1 = R(1, 0) * y0[r] + R(1, 1) * y1[r] + R(1, 2) * y2[r] + (l[2] * F0 - l[0] * F2);
    const S N2 = R(2, 0) * y0[r] + R(2, 1) * y1[r] + R(2, 2) * y2[r] + (l[0] * F1 - l[1] * F0);
    const S e = -(s[0] * N0 + s[1] * N1 + s[2] * N2 + s[3] * F0 + s[4] * F1 + s[5] * F2);
    Minv_col[r] = D_inv * e;
    y0[r] = N0 + g[0] * e;
    y1[r] = N1 + g[1] * e;
    y2[r] = N2 + g[2] * e;
    y3[r] = F0 + g[3] * e;
    y4[r] = F1 + g[4] * e;
    y5[r] = F2 + g[5] * e;
  }
}

/// One-degree-of-freedom hinge k, base to tip, on rows \f$[0, c)\f$ of \f$A^*\f$ (in place)
/// and of column \p Minv_col of \f$\mathcal M^{-1}\f$: \f$A^+ = \phi^*(k+1,k) A\f$ (\f$v' = R^*(v +
/// \omega \times l),\ \omega' = R^*\omega\f$; \f$A^+ = 0\f$ when \p phi is null, at the
/// base), \f$\mathcal M^{-1}(k,\cdot) = \nu - g^* A^+\f$, \f$A = A^+ + s\, \mathcal
/// M^{-1}(k,\cdot)\f$.
template <class S>
void base_to_tip_rows_1dof(int c, const PhiT<S>* phi, const Vec6<S>& s, const Vec6<S>& g,
                           S* __restrict a0, S* __restrict a1, S* __restrict a2, S* __restrict a3,
                           S* __restrict a4, S* __restrict a5, S* __restrict Minv_col) {
  if (!phi) {
    for (int r = 0; r < c; ++r) {
      const S mr = Minv_col[r];
      a0[r] = s[0] * mr, a1[r] = s[1] * mr, a2[r] = s[2] * mr;
      a3[r] = s[3] * mr, a4[r] = s[4] * mr, a5[r] = s[5] * mr;
    }
    return;
  }
  const Mat3<S>& R = phi->R();
  const Vec3<S>& l = phi->l();
  for (int r = 0; r < c; ++r) {
    const S w0 = a0[r], w1 = a1[r], w2 = a2[r];
    const S v0 = a3[r] + (w1 * l[2] - w2 * l[1]);
    const S v1 = a4[r] + (w2 * l[0] - w0 * l[2]);
    const S v2 = a5[r] + (w0 * l[1] - w1 * l[0]);
    const S W0 = R(0, 0) * w0 + R(1, 0) * w1 + R(2, 0) * w2;
    const S W1 = R(0, 1) * w0 + R(1, 1) * w1 + R(2, 1) * w2;
    const S W2 = R(0, 2) * w0 + R(1, 2) * w1 + R(2, 2) * w2;
    const S V0 = R(0, 0) * v0 + R(1, 0) * v1 + R(2, 0) * v2;
    const S V1 = R(0, 1) * v0 + R(1, 1) * v1 + R(2, 1) * v2;
    const S V2 = R(0, 2) * v0 + R(1, 2) * v1 + R(2, 2) * v2;
    const S mr =
        Minv_col[r] - (g[0] * W0 + g[1] * W1 + g[2] * W2 + g[3] * V0 + g[4] * V1 + g[5] * V2);
    Minv_col[r] = mr;
    a0[r] = W0 + s[0] * mr, a1[r] = W1 + s[1] * mr, a2[r] = W2 + s[2] * mr;
    a3[r] = V0 + s[3] * mr, a4[r] = V1 + s[4] * mr, a5[r] = V2 + s[5] * mr;
  }
}

/// detail::tip_to_base_rows_1dof() when \f$\phi\f$ turns about the coordinate axis Axis
/// (plane_rotation_axis()) and, for UnitCol \f$\ge 0\f$, \f$H^*(k) = s = \pm e_{UnitCol}\f$ (a
/// revolute or prismatic hinge about a coordinate axis; UnitCol = -1: any \f$H^*(k)\f$).
/// Both are template parameters, so that the products with the exact zeros and ones of
/// \f$R\f$ and \f$s\f$ are dropped at compile time, not tested per row. Each sum is the
/// general kernel's, in its order, less those products: the general result bit for bit (up
/// to the sign of a zero). Per row 49 flops instead of 67, 38 with \f$s = \pm e_{UnitCol}\f$.
/// Index names as in soa/detail/plane.hpp.
template <int Axis, int UnitCol, class S>
void tip_to_base_rows_plane(int c, const PhiT<S>& phi, const Vec6<S>& s, S D_inv, const Vec6<S>& g,
                            S* __restrict y0, S* __restrict y1, S* __restrict y2, S* __restrict y3,
                            S* __restrict y4, S* __restrict y5, S* __restrict Minv_col) {
  constexpr int U = Axis == 2 ? 0 : Axis + 1, W = U == 2 ? 0 : U + 1;
  const S RUU = phi.R()(U, U), RUW = phi.R()(U, W), RWU = phi.R()(W, U), RWW = phi.R()(W, W);
  const Vec3<S>& l = phi.l();
  const S s_unit = UnitCol >= 0 ? s[UnitCol] : S(0);
  for (int r = 0; r < c; ++r) {
    const S y[6] = {y0[r], y1[r], y2[r], y3[r], y4[r], y5[r]};
    S F[3], N[3];
    F[Axis] = y[3 + Axis];
    F[U] = RUU * y[3 + U] + RUW * y[3 + W];
    F[W] = RWU * y[3 + U] + RWW * y[3 + W];
    N[Axis] = y[Axis];
    N[U] = RUU * y[U] + RUW * y[W];
    N[W] = RWU * y[U] + RWW * y[W];
    N[0] += l[1] * F[2] - l[2] * F[1];
    N[1] += l[2] * F[0] - l[0] * F[2];
    N[2] += l[0] * F[1] - l[1] * F[0];
    const S x[6] = {N[0], N[1], N[2], F[0], F[1], F[2]};
    S e;
    if constexpr (UnitCol >= 0)
      e = -(s_unit * x[UnitCol]);
    else
      e = -(s[0] * x[0] + s[1] * x[1] + s[2] * x[2] + s[3] * x[3] + s[4] * x[4] + s[5] * x[5]);
    Minv_col[r] = D_inv * e;
    y0[r] = x[0] + g[0] * e;
    y1[r] = x[1] + g[1] * e;
    y2[r] = x[2] + g[2] * e;
    y3[r] = x[3] + g[3] * e;
    y4[r] = x[4] + g[4] * e;
    y5[r] = x[5] + g[5] * e;
  }
}

/// detail::base_to_tip_rows_1dof() when \f$\phi\f$ (not null) turns about the coordinate
/// axis Axis and, for UnitCol \f$\ge 0\f$, \f$H^*(k) = \pm e_{UnitCol}\f$: the general
/// kernel's sums, in its order, less their products with an exact 0 or 1 of \f$R\f$ or of
/// \f$s\f$ (bit for bit, up to the sign of a zero). Per row 48 flops instead of 66, 38 with
/// \f$s = \pm e_{UnitCol}\f$.
template <int Axis, int UnitCol, class S>
void base_to_tip_rows_plane(int c, const PhiT<S>& phi, const Vec6<S>& s, const Vec6<S>& g,
                            S* __restrict a0, S* __restrict a1, S* __restrict a2, S* __restrict a3,
                            S* __restrict a4, S* __restrict a5, S* __restrict Minv_col) {
  constexpr int U = Axis == 2 ? 0 : Axis + 1, W = U == 2 ? 0 : U + 1;
  const S RUU = phi.R()(U, U), RUW = phi.R()(U, W), RWU = phi.R()(W, U), RWW = phi.R()(W, W);
  const Vec3<S>& l = phi.l();
  const S s_unit = UnitCol >= 0 ? s[UnitCol] : S(0);
  for (int r = 0; r < c; ++r) {
    const S w[3] = {a0[r], a1[r], a2[r]};
    const S v[3] = {a3[r] + (w[1] * l[2] - w[2] * l[1]), a4[r] + (w[2] * l[0] - w[0] * l[2]),
                    a5[r] + (w[0] * l[1] - w[1] * l[0])};
    S x[6];  // R^* [w; v], the rotated parts of A^+(k)
    x[Axis] = w[Axis];
    x[U] = RUU * w[U] + RWU * w[W];
    x[W] = RUW * w[U] + RWW * w[W];
    x[3 + Axis] = v[Axis];
    x[3 + U] = RUU * v[U] + RWU * v[W];
    x[3 + W] = RUW * v[U] + RWW * v[W];
    const S mr = Minv_col[r] - (g[0] * x[0] + g[1] * x[1] + g[2] * x[2] + g[3] * x[3] +
                                g[4] * x[4] + g[5] * x[5]);
    Minv_col[r] = mr;
    if constexpr (UnitCol >= 0) {
      x[UnitCol] += s_unit * mr;
    } else {
      for (int i = 0; i < 6; ++i) x[i] += s[i] * mr;
    }
    a0[r] = x[0], a1[r] = x[1], a2[r] = x[2];
    a3[r] = x[3], a4[r] = x[4], a5[r] = x[5];
  }
}

/// Calls \p f with std::integral_constant<int, unit_col> for \p unit_col in {0, ..., 5}, and
/// with -1 for any other value: the UnitCol of the row kernels as a compile-time index.
template <class F>
EIGEN_ALWAYS_INLINE void with_unit_column(int unit_col, F&& f) {
  switch (unit_col) {
    case 0:
      f(std::integral_constant<int, 0>());
      break;
    case 1:
      f(std::integral_constant<int, 1>());
      break;
    case 2:
      f(std::integral_constant<int, 2>());
      break;
    case 3:
      f(std::integral_constant<int, 3>());
      break;
    case 4:
      f(std::integral_constant<int, 4>());
      break;
    case 5:
      f(std::integral_constant<int, 5>());
      break;
    default:
      f(std::integral_constant<int, -1>());
  }
}

/// The index \f$c\f$ of a one-dof hinge's \f$H^*(k) = \pm e_c\f$ (a revolute or prismatic
/// hinge about a coordinate axis, as riccati_step() takes it), or -1.
template <class S>
EIGEN_ALWAYS_INLINE int unit_column(const HingeT<S>& h) {
  if (h.type != HingeType::Revolute && h.type != HingeType::Prismatic) return -1;
  const int i = coordinate_axis(h);
  return i < 0 ? -1 : h.type == HingeType::Prismatic ? i + 3 : i;
}

}  // namespace detail

/// The fast form of soa::reference::mass_matrix_inverse().
/// The inverse of the mass matrix (lesson 7), \f$O(N^2)\f$, from the innovations
/// factorization \f$\mathcal M^{-1} = [I - H\psi K]^* D^{-1} [I - H\psi K]\f$: the forward
/// dynamics of lesson 8 with the bias terms dropped and all unit hinge forces \f$T = e_j\f$
/// at once. Tip to base, with the Riccati recursion (riccati_step()):
/// \f[ Z(k) = \phi(k,k-1) Z^+(k-1), \quad \nu(k) = D^{-1}(k)\,[E_k - H(k) Z(k)], \quad
///     Z^+(k) = Z(k) + G(k)\,[E_k - H(k) Z(k)] , \f]
/// where only the columns of the hinges outboard of k are non-zero; base to tip,
/// \f[ A^+(k) = \phi^*(k+1,k)\,A(k+1), \quad \mathcal M^{-1}(k,\cdot) = \nu(k) - G^*(k)\,A^+(k),
///     \quad A(k) = A^+(k) + H^*(k)\,\mathcal M^{-1}(k,\cdot), \f]
/// kept to the columns of hinges k..1 (the rest follow by symmetry). Blocks are stored
/// transposed (\f$n_v \times 6\f$) so that \f$\phi\f$ acts on contiguous columns. Needs
/// update_phi(); a singular \f$D(k)\f$ throws as in articulated_inertias().
template <class S>
void mass_matrix_inverse(const ModelT<S>& m, const StateT<S>& x, const WorkspaceT<S>& ws,
                         MassMatrixInverseT<S>& mmi, MatX<S>& Minv) {
  const int n = m.n(), nv = m.nv();
  Minv.resize(nv, nv);
  ArticulatedT<S>& art = mmi.art;
  CompositeTraceT<S> guard;
  // The row kernels specialized on a rotation about a coordinate axis and on H^*(k) = +-e_c
  // (detail::tip_to_base_rows_plane(), detail::base_to_tip_rows_plane()): the same sums less
  // their products with exact zeros and ones.
  const bool fast = m.fast_paths;
  // Tip to base. Rows [0, c) of Y hold Z+(k-1)^*, c = v_offset(k): the unit forces of the
  // hinges outboard of k, the only non-zero ones, so each step costs O(c), not O(n_v).
  for (int k = 1; k <= n; ++k) {
    const BodyT<S>& B = m.body(k);
    const S d_min = riccati_step(m, x, ws, k, art, guard);
    if (!std::isfinite(double(d_min)))
      throw Error("body '" + B.name + "': articulated inertia D(" + std::to_string(k) +
                  ") is not finite (check theta and the inertias)");
    const int c = B.v_offset, nk = B.hinge.nv();
    // One-dof hinge: epsilon, nu and Z+ of all rows in one pass over the rows, on the
    // 6-vectors s = H^*(k) and g = G(k) and the scalar D^{-1}(k) (detail::tip_to_base_rows_1dof(),
    // the general branch's sums for n_k = 1), then hinge k's own row.
    if (nk == 1) {
      const Vec6<S> s = one_dof_map(B.hinge), g = art.G[k - 1].col(0);
      const S D_inv = art.D_inv[k - 1](0, 0);
      const int unit_col = fast ? detail::unit_column(B.hinge) : -1;
      S* Y = mmi.Y.data();
      const Eigen::Index ld = mmi.Y.rows();
      S* Minv_k = Minv.col(B.v_offset).data();
      if (k > 1) {
        const PhiT<S>& phi = ws.phi[k - 2];
        S *y0 = Y, *y1 = Y + ld, *y2 = Y + 2 * ld, *y3 = Y + 3 * ld, *y4 = Y + 4 * ld,
          *y5 = Y + 5 * ld;
        if (!(fast &&
              detail::with_plane_axis(detail::plane_rotation_axis(phi.R()), [&](auto axis_c) {
                detail::with_unit_column(unit_col, [&](auto unit_c) {
                  detail::tip_to_base_rows_plane<decltype(axis_c)::value, decltype(unit_c)::value>(
                      c, phi, s, D_inv, g, y0, y1, y2, y3, y4, y5, Minv_k);
                });
              })))
          detail::tip_to_base_rows_1dof(c, phi, s, D_inv, g, y0, y1, y2, y3, y4, y5, Minv_k);
      }
      Minv_k[c] = D_inv;                               // epsilon = 1 for T = e_k
      for (int r = 0; r < 6; ++r) mmi.Y(c, r) = g[r];  // Z+ = G
      continue;
    }
    auto Z = mmi.Z.topRows(c);
    if (k > 1) {
      auto Yc = mmi.Y.topRows(c);
      detail::apply_phi_rows(ws.phi[k - 2], Yc, Z);
    }
    // epsilon^* = [E_k - H Z]^*: rows [0, c) are -(Z H^*), rows of hinge k the identity.
    const JointMap<S> Hs = B.hinge.H_star(x.theta.data() + B.q_offset);
    auto E = mmi.E.topLeftCorner(c + nk, nk);
    for (int i = 0; i < nk; ++i) {
      auto Ei = E.col(i).head(c);
      Ei.setZero();
      for (int r = 0; r < 6; ++r)
        if (Hs(r, i) != S(0)) Ei -= Hs(r, i) * Z.col(r);
    }
    E.bottomRows(nk).setIdentity();
    // nu(k)^* = epsilon^* D^{-1} into the columns of hinge k of Minv, rows [0, c + nk).
    const HingeMatrix<S>& D_inv = art.D_inv[k - 1];
    for (int j = 0; j < nk; ++j) {
      auto Minv_j = Minv.col(B.v_offset + j).head(c + nk);
      Minv_j = D_inv(0, j) * E.col(0);
      for (int i = 1; i < nk; ++i) Minv_j += D_inv(i, j) * E.col(i);
    }
    // Z+(k)^* = Z^* + epsilon^* G^*
    auto Y = mmi.Y.topRows(c + nk);
    const JointMap<S>& G = art.G[k - 1];
    for (int r = 0; r < 6; ++r) {
      Y.col(r).head(c) = Z.col(r);
      Y.col(r).tail(nk).setZero();
      for (int i = 0; i < nk; ++i) Y.col(r) += G(r, i) * E.col(i);
    }
  }
  // Base to tip. Rows [0, c + nk) of Y hold A(k)^*, restricted to hinges k..1.
  for (int k = n; k >= 1; --k) {
    const BodyT<S>& B = m.body(k);
    const int nk = B.hinge.nv(), c = B.v_offset + nk;
    // One-dof hinge: A+, M^{-1}(k, .) and A of all rows in one pass over the rows
    // (detail::base_to_tip_rows_1dof(), the general branch's sums for n_k = 1).
    if (nk == 1) {
      S* A = mmi.Y.data();
      const Eigen::Index ld = mmi.Y.rows();
      const Vec6<S> s = one_dof_map(B.hinge), g = art.G[k - 1].col(0);
      S *a0 = A, *a1 = A + ld, *a2 = A + 2 * ld, *a3 = A + 3 * ld, *a4 = A + 4 * ld,
        *a5 = A + 5 * ld, *Minv_k = Minv.col(B.v_offset).data();
      const PhiT<S>* phi = k == n ? nullptr : &ws.phi[k - 1];
      const int unit_col = fast ? detail::unit_column(B.hinge) : -1;
      if (!(fast && phi &&
            detail::with_plane_axis(detail::plane_rotation_axis(phi->R()), [&](auto axis_c) {
              detail::with_unit_column(unit_col, [&](auto unit_c) {
                detail::base_to_tip_rows_plane<decltype(axis_c)::value, decltype(unit_c)::value>(
                    c, *phi, s, g, a0, a1, a2, a3, a4, a5, Minv_k);
              });
            })))
        detail::base_to_tip_rows_1dof(c, phi, s, g, a0, a1, a2, a3, a4, a5, Minv_k);
      continue;
    }
    auto A = mmi.Y.topRows(c);
    auto A_plus = mmi.Z.topRows(c);  // A+(k)^*
    if (k == n)
      A_plus.setZero();
    else
      detail::transpose_apply_phi_rows(ws.phi[k - 1], A, A_plus);
    const JointMap<S>& G = art.G[k - 1];
    const JointMap<S> Hs = B.hinge.H_star(x.theta.data() + B.q_offset);
    for (int j = 0; j < nk; ++j) {
      auto Minv_j = Minv.col(B.v_offset + j).head(c);
      for (int r = 0; r < 6; ++r) Minv_j -= G(r, j) * A_plus.col(r);
    }
    for (int r = 0; r < 6; ++r) {
      A.col(r) = A_plus.col(r);
      for (int j = 0; j < nk; ++j)
        if (Hs(r, j) != S(0)) A.col(r) += Hs(r, j) * Minv.col(B.v_offset + j).head(c);
    }
  }
  Minv.template triangularView<Eigen::StrictlyLower>() = Minv.transpose();
}

}  // namespace soa
