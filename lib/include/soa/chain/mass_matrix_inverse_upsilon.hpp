/// \file
/// The operator \f$\Upsilon\f$ (the diagonal blocks of \f$\Omega = \psi^* H^* D^{-1} H\psi\f$)
/// by its base-to-tip Lyapunov recursion, and the inverse of the mass matrix in
/// \f$O(N^2)\f$ built on it (lesson 7, sections 6-7; Jain 2011, chapter 7).
#pragma once

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "soa/chain/articulated.hpp"
#include "soa/chain/mass_matrix_inverse.hpp"

namespace soa {

/// Per-body results of upsilons(), sized once for a model: the Riccati results, and base
/// to tip \f$\Upsilon(k)\f$, \f$\mathcal M^{-1}(k,k)\f$ and the row map \f$L^*(k)\f$.
template <class S>
struct UpsilonT {
  explicit UpsilonT(const ModelT<S>& m) : art(m), Upsilon(m.n()), Minv_kk(m.n()), L_star(m.n()) {}
  ArticulatedT<S> art;                  ///< \f$P, D, D^{-1}, G\f$ (riccati_step())
  std::vector<Mat6<S>> Upsilon;         ///< \f$\Upsilon(k)\f$, entry k - 1
  std::vector<HingeMatrix<S>> Minv_kk;  ///< \f$\mathcal M^{-1}(k,k)\f$, entry k - 1
  /// \f$L^*(k) = \Upsilon^+(k) G(k) - H^*(k)\,\mathcal M^{-1}(k,k)\f$ (6 x \f$n_k\f$), the map
  /// of upsilon_row() from \f$z_j(k)\f$ to \f$\mathcal M^{-1}(k,j)\f$
  std::vector<JointMap<S>> L_star;
};
using Upsilon = UpsilonT<double>;

/// \f$\phi^*\, U\, \phi\f$ for a symmetric 6x6 \f$U\f$ and \f$\phi = (R, l)\f$, without the
/// 6x6 \f$\phi\f$ (lesson 7, section 6): with the block swap
/// \f$J = \begin{pmatrix} 0 & I \\ I & 0 \end{pmatrix}\f$,
/// \f$J\phi^*J = \phi^{-1} = (R^*, -R^*l)\f$, so
/// \f$\phi^* U\phi = J\,[\phi^{-1}\,(JUJ)\,\phi^{-*}]\,J\f$, one transform_symmetric().
/// Writes \p out, which must not be \p U. \p fast_path as in transform_symmetric().
template <class S>
void transpose_transform_symmetric(const PhiT<S>& phi, const Mat6<S>& U, Mat6<S>& out,
                                   bool fast_path = true) {
  const auto swap_blocks = [](const Mat6<S>& a, Mat6<S>& b) {
    b.template topLeftCorner<3, 3>() = a.template bottomRightCorner<3, 3>();
    b.template topRightCorner<3, 3>() = a.template bottomLeftCorner<3, 3>();
    b.template bottomLeftCorner<3, 3>() = a.template topRightCorner<3, 3>();
    b.template bottomRightCorner<3, 3>() = a.template topLeftCorner<3, 3>();
  };
  Mat6<S> JUJ, T;
  swap_blocks(U, JUJ);
  transform_symmetric(phi.inverse(), JUJ, T, fast_path);
  swap_blocks(T, out);
}

/// One step k of the Lyapunov recursion of \f$\Upsilon\f$ (lesson 7, section 6), base to
/// tip after step k+1 (\f$\Upsilon(n+1) = 0\f$; \p Upsilon_next is null at k = n):
/// \f[ \Upsilon^+(k) = \phi^*(k+1,k)\,\Upsilon(k+1)\,\phi(k+1,k), \quad Y = \Upsilon^+(k)G(k),
///     \quad \mathcal M^{-1}(k,k) = D^{-1}(k) + G^*(k)\,Y, \f]
/// \f[ \Upsilon(k) = \bar\tau^*(k)\,\Upsilon^+(k)\,\bar\tau(k) + H^*(k)D^{-1}(k)H(k)
///     = \Upsilon^+(k) + Q + Q^*, \quad Q = H^*(k)\,[\tfrac12\mathcal M^{-1}(k,k)H(k) - Y^*],
/// \f]
/// which is \f$\psi^*(k+1,k)\Upsilon(k+1)\psi(k+1,k) + H^*D^{-1}H\f$ with \f$\psi(k+1,k) =
/// \phi(k+1,k)\bar\tau(k)\f$, symmetric by construction; and the row map
/// \f$L^*(k) = Y - H^*(k)\,\mathcal M^{-1}(k,k)\f$ of upsilon_row(). Needs the Riccati
/// results of body k in \p w.art.
template <class S>
void upsilon_step(const ModelT<S>& m, const StateT<S>& x, const WorkspaceT<S>& ws, int k,
                  UpsilonT<S>& w) {
  const BodyT<S>& B = m.body(k);
  const int i = k - 1;
  Mat6<S>& U = w.Upsilon[i];
  if (k < m.n())
    transpose_transform_symmetric(ws.phi[i], w.Upsilon[i + 1], U, m.fast_paths);  // Upsilon+(k)
  else
    U.setZero();
  const JointMap<S>& G = w.art.G[i];
  const JointMap<S> Hs = B.hinge.H_star(x.theta.data() + B.q_offset);
  const JointMap<S> Y = U * G;
  HingeMatrix<S>& Mkk = w.Minv_kk[i];
  Mkk = w.art.D_inv[i] + G.transpose() * Y;
  Mkk = S(0.5) * (Mkk + Mkk.transpose()).eval();
  w.L_star[i] = Y - Hs * Mkk;
  const Mat6<S> Q = Hs * (S(0.5) * Mkk * Hs.transpose() - Y.transpose());
  U += Q + Q.transpose();
}

/// The Riccati recursion tip to base (riccati_step(), as in articulated_inertias() but
/// without the composite inertias), then upsilon_step() base to tip for k = n ... \p k_end
/// (lesson 7, section 6): \f$\Upsilon(k)\f$, \f$\mathcal M^{-1}(k,k)\f$ and \f$L^*(k)\f$ in
/// \p w, \f$O(N)\f$. A singular \f$D(k)\f$ throws as in articulated_inertias(). Needs
/// update_phi().
template <class S>
void upsilons(const ModelT<S>& m, const StateT<S>& x, const WorkspaceT<S>& ws, UpsilonT<S>& w,
              int k_end = 1) {
  CompositeTraceT<S> guard;
  for (int k = 1; k <= m.n(); ++k) {
    const S d_min = riccati_step(m, x, ws, k, w.art, guard);
    if (!std::isfinite(double(d_min)))
      throw Error("body '" + m.body(k).name + "': articulated inertia D(" + std::to_string(k) +
                  ") is not finite (check theta and the inertias)");
  }
  for (int k = m.n(); k >= k_end; --k) upsilon_step(m, x, ws, k, w);
}

/// Workspace of mass_matrix_inverse_upsilon(): UpsilonT and two \f$n_v \times 6\f$ blocks.
template <class S>
struct MassMatrixInverseUpsilonT {
  explicit MassMatrixInverseUpsilonT(const ModelT<S>& m) : ups(m), Z(m.nv(), 6), Zn(m.nv(), 6) {}
  UpsilonT<S> ups;
  /// Row j of \p Z is \f$z_j^*(k)\f$, the spatial force that column j of \f$G\f$ carries to
  /// body k (upsilon_row()); \p Zn is the buffer of the next body.
  MatX<S> Z, Zn;
};
using MassMatrixInverseUpsilon = MassMatrixInverseUpsilonT<double>;

/// Step k of the column pass of mass_matrix_inverse_upsilon() (lesson 7, section 7), on
/// rows \f$[0, c)\f$ of \p Z, \f$c = \f$ `v_offset(k)`, which hold \f$z_j^*(k)\f$ for the
/// hinge coordinates j of bodies 1..k-1, \f$z_j(k) = \psi(k,i+1)\,\phi(i+1,i)\,G(i)e_j\f$
/// (j a coordinate of body i):
/// \f[ \mathcal M^{-1}(j,k) = z_j^*(k)\,L^*(k), \qquad z_j(k+1) = \phi(k+1,k)\,[z_j(k) -
///     G(k)\,H(k)z_j(k)], \qquad z_{j}(k+1) = \phi(k+1,k)G(k)e_j \text{ for j of body k}. \f]
/// Writes rows \f$[0, c)\f$ of the columns of hinge k of \p Minv (the upper triangle) and
/// rows \f$[0, c + n_k)\f$ of \p Zn (\f$z^*(k+1)\f$; not at k = n). Column operations only.
template <class S>
void upsilon_row(const ModelT<S>& m, const StateT<S>& x, const WorkspaceT<S>& ws, int k,
                 const UpsilonT<S>& u, MatX<S>& Z, MatX<S>& Zn, MatX<S>& Minv) {
  const BodyT<S>& B = m.body(k);
  const int c = B.v_offset, nk = B.hinge.nv(), i = k - 1;
  const JointMap<S>& L = u.L_star[i];
  const JointMap<S>& G = u.art.G[i];
  const JointMap<S> Hs = B.hinge.H_star(x.theta.data() + B.q_offset);
  auto Zc = Z.topRows(c);
  for (int j = 0; j < nk; ++j) {
    auto Mj = Minv.col(c + j).head(c);
    Mj.setZero();
    for (int r = 0; r < 6; ++r)
      if (L(r, j) != S(0)) Mj += L(r, j) * Zc.col(r);
  }
  Minv.block(c, c, nk, nk) = u.Minv_kk[i];
  if (k == m.n()) return;
  // z <- tau_bar(k) z = z - G (H z), in place on rows [0, c); then G(k)^* as rows [c, c + nk).
  for (int j = 0; j < nk && c > 0; ++j) {
    auto e = Zn.col(0).head(c);  // H(k) z for coordinate j, in the spare buffer
    e.setZero();
    for (int r = 0; r < 6; ++r)
      if (Hs(r, j) != S(0)) e += Hs(r, j) * Zc.col(r);
    for (int r = 0; r < 6; ++r) Zc.col(r) -= G(r, j) * e;
  }
  Z.block(c, 0, nk, 6) = G.transpose();
  auto Zk = Z.topRows(c + nk);
  auto Zo = Zn.topRows(c + nk);
  detail::apply_phi_rows(ws.phi[i], Zk, Zo);
}

/// The inverse of the mass matrix (lesson 7, section 7), \f$O(N^2)\f$, from
/// \f$\mathcal M^{-1} = [I - H\psi K]^* D^{-1} [I - H\psi K] = D^{-1} - D^{-1}H\psi K -
/// K^*\psi^*H^*D^{-1} + K^*\Omega K\f$ with \f$\Omega = \Upsilon + \tilde\psi^*\Upsilon +
/// \Upsilon\tilde\psi\f$: the diagonal blocks \f$\mathcal M^{-1}(k,k) = D^{-1}(k) +
/// G^*(k)\Upsilon^+(k)G(k)\f$ from upsilons(), and for \f$k > i\f$
/// \f[ \mathcal M^{-1}(k,i) = L(k)\,\psi(k,i+1)\,\phi(i+1,i)\,G(i), \qquad L(k) =
///     G^*(k)\Upsilon^+(k) - \mathcal M^{-1}(k,k)H(k), \f]
/// one tip-to-base propagation for all columns at once (upsilon_row()); the lower triangle
/// by symmetry. The same result as mass_matrix_inverse(). Needs update_phi(); a singular
/// \f$D(k)\f$ throws as in articulated_inertias().
template <class S>
void mass_matrix_inverse_upsilon(const ModelT<S>& m, const StateT<S>& x, const WorkspaceT<S>& ws,
                                 MassMatrixInverseUpsilonT<S>& w, MatX<S>& Minv) {
  Minv.resize(m.nv(), m.nv());
  upsilons(m, x, ws, w.ups);
  for (int k = 1; k <= m.n(); ++k) {
    upsilon_row(m, x, ws, k, w.ups, w.Z, w.Zn, Minv);
    std::swap(w.Z, w.Zn);
  }
  Minv.template triangularView<Eigen::StrictlyLower>() = Minv.transpose();
}

}  // namespace soa
