/// \file
/// The reference tier's per-call data, apart from the model and sized once (lesson 3).
#pragma once

#include <vector>

#include "soa/chain/forward_dynamics.hpp"

/// The reference recursions: each O(N) algorithm of the course written as its lesson
/// derives it, in the lesson's symbols, with one storage and no fast path. The functions
/// of namespace soa with the same names are their fast forms.
namespace soa::reference {

/// Everything the reference recursions compute per body, sized once for a model: entry
/// k - 1 holds body k (tip first, \ref conventions). No reference function allocates.
template <class S>
struct WorkspaceT {
  explicit WorkspaceT(const ModelT<S>& m)
      : phi(m.n()),
        V(m.n()),
        a(m.n()),
        a_rest(m.n()),
        alpha(m.n()),
        f(m.n()),
        R(m.n()),
        P(m.n()),
        P_plus(m.n()),
        D(m.n()),
        D_inv(m.n()),
        G(m.n()),
        z(m.n()),
        z_plus(m.n()),
        epsilon(m.n()),
        nu(m.n()),
        alpha_plus(m.n()),
        phi_K_v(m.n()),
        unit(VecX<S>::Zero(m.nv())),
        column(m.nv()) {
    for (int k = 1; k <= m.n(); ++k) {
      const int nk = m.body(k).hinge.nv();
      D[k - 1].resize(nk, nk), D_inv[k - 1].resize(nk, nk), G[k - 1].resize(6, nk);
      epsilon[k - 1].resize(nk), nu[k - 1].resize(nk);
    }
  }
  std::vector<PhiT<S>> phi;                  ///< \f$\phi(k+1,k)\f$
  std::vector<VelocityT<S>> V;               ///< \f$V(k)\f$
  std::vector<AccelerationT<S>> a;           ///< \f$a(k)\f$, the Coriolis term
  std::vector<AccelerationT<S>> a_rest;      ///< \f$a(k) = 0\f$, at rest (articulated_solve())
  std::vector<AccelerationT<S>> alpha;       ///< \f$\alpha(k)\f$
  std::vector<ForceT<S>> f;                  ///< \f$f(k)\f$, the inter-body force
  std::vector<SpatialInertiaT<S>> R;         ///< \f$R(k)\f$, the composite inertia
  std::vector<Mat6<S>> P, P_plus;            ///< \f$P(k)\f$, \f$P^+(k)\f$
  std::vector<HingeMatrix<S>> D, D_inv;      ///< \f$D(k)\f$, \f$D^{-1}(k)\f$
  std::vector<JointMap<S>> G;                ///< \f$G(k)\f$
  std::vector<ForceT<S>> z, z_plus;          ///< \f$z(k)\f$, \f$z^+(k)\f$
  std::vector<HingeVector<S>> epsilon, nu;   ///< \f$\epsilon(k)\f$, \f$\nu(k)\f$
  std::vector<AccelerationT<S>> alpha_plus;  ///< \f$\alpha^+(k)\f$
  std::vector<ForceT<S>> phi_K_v;            ///< \f$(\phi K v)(k)\f$ (innovations_factor_times())
  VecX<S> unit;    ///< a unit hinge force \f$e_j\f$ (mass_matrix_inverse())
  VecX<S> column;  ///< \f$\mathcal M^{-1} e_j\f$ (mass_matrix_inverse())
};
using Workspace = WorkspaceT<double>;

}  // namespace soa::reference
