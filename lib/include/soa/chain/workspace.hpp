/// \file
/// Per-call data of the chain algorithms, allocated once (model vs workspace, lesson 3).
#pragma once

#include <vector>

#include "soa/chain/model.hpp"
#include "soa/phi.hpp"

namespace soa {

/// The joint state: configuration \f$\theta\f$ and generalized velocity \f$\beta\f$.
template <class S>
struct StateT {
  VecX<S> theta;  ///< \f$\theta\f$, size nq
  VecX<S> beta;   ///< \f$\beta\f$, size nv
  /// The neutral configuration of \p m at rest.
  static StateT rest(const ModelT<S>& m) { return {m.neutral(), VecX<S>::Zero(m.nv())}; }
};
using State = StateT<double>;

/// Everything the recursions compute per body, sized once for a model so that no call
/// allocates. Entry i holds body k = i + 1 (tip first).
template <class S>
struct WorkspaceT {
  explicit WorkspaceT(const ModelT<S>& m)
      : phi(m.n()),
        pose(m.n()),
        V(m.n()),
        a(m.n()),
        alpha(m.n()),
        b(m.n()),
        f(m.n()),
        hinge_sin(m.n()),
        hinge_cos(m.n()) {}
  /// A workspace whose parts are sized by the first function that fills them (each filling
  /// function calls size()), so that it holds only what the computation uses: the `soa`
  /// command on a chain of a million bodies (no poses unless asked for).
  static WorkspaceT lazy() { return WorkspaceT(); }

  /// Sizes \p part for \p m when it is not (once: nothing is allocated per call after).
  template <class T>
  static void size(std::vector<T>& part, const ModelT<S>& m) {
    if (part.size() != std::size_t(m.n())) part.resize(std::size_t(m.n()));
  }

  std::vector<PhiT<S>> phi;             ///< \f$\phi(k+1,k)\f$, as \f$(R, l)\f$
  std::vector<PoseT<S>> pose;           ///< \f${}^I T_{O_k}\f$, the pose of body k
  std::vector<VelocityT<S>> V;          ///< \f$V(k)\f$ at \f$O_k\f$, body coordinates
  std::vector<AccelerationT<S>> a;      ///< Coriolis term \f$a(k)\f$
  std::vector<AccelerationT<S>> alpha;  ///< \f$\alpha(k)\f$
  std::vector<ForceT<S>> b;             ///< \f$b(k)\f$ (gyroscopic, less external forces)
  std::vector<ForceT<S>> f;             ///< inter-body force \f$f(k)\f$ on body k at \f$O_k\f$
  /// \f$\sin\theta(k)\f$ and \f$\cos\theta(k)\f$ of a revolute hinge k, by
  /// hinge_sin_cos() (the entries of other hinges are unused).
  std::vector<S> hinge_sin, hinge_cos;

 private:
  WorkspaceT() = default;
};
using Workspace = WorkspaceT<double>;

}  // namespace soa
