/// \file
/// The serial-chain model: what does not change from call to call (lesson 3).
#pragma once

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "soa/chain/hinge.hpp"
#include "soa/spatial_inertia.hpp"

namespace soa {

/// One body k of the chain with its inboard hinge k (numbering of \ref conventions).
template <class S>
struct BodyT {
  std::string name;
  /// \f$M(k)\f$ about the hinge frame \f$O_k\f$, in \f$O_k\f$ coordinates.
  SpatialInertiaT<S> M;
  /// Where hinge k sits on body k+1: \f${}^{O_{k+1}}T_{O_k^+}\f$ (for the body next to the
  /// base, relative to the inertial frame).
  PoseT<S> placement;
  HingeT<S> hinge;
  /// Joint spring and damper, the same on each degree of freedom: hinge force
  /// \f$-k\,\delta(\theta) - c\,\beta\f$ with \f$\delta\f$ the displacement from rest
  /// (\f$\theta - \theta_0\f$ for 1-dof and universal hinges, the rotation vector of the
  /// quaternion for spherical, and rotation vector then \f$R^* l\f$ for free hinges).
  S stiffness = S(0);
  S damping = S(0);
  Eigen::Matrix<S, Eigen::Dynamic, 1, 0, 2, 1> rest;  ///< \f$\theta_0\f$ (1-dof, universal)
  int q_offset = 0;  ///< where \f$\theta(k)\f$ starts in \f$\theta\f$ (tip first)
  int v_offset = 0;  ///< where \f$\beta(k)\f$ starts in \f$\beta\f$ (tip first)
};

/// A serial chain: bodies stored tip first, `body(k)` for k = 1 (tip) ... n (next to the
/// base), as the course numbers them. Built by from_base_first() from the base out.
template <class S>
class ModelT {
 public:
  int n() const { return int(bodies_.size()); }  ///< number of bodies
  int nq() const { return nq_; }                 ///< size of \f$\theta\f$
  int nv() const { return nv_; }                 ///< size of \f$\beta\f$ (dofs)
  /// Body k, 1-based and tip first as in the course.
  const BodyT<S>& body(int k) const { return bodies_[k - 1]; }
  BodyT<S>& body(int k) { return bodies_[k - 1]; }
  const std::vector<BodyT<S>>& bodies() const { return bodies_; }

  /// Gravity \f$g\f$ in inertial coordinates; it enters as the base acceleration
  /// \f$\alpha(n+1) = [0; -g]\f$. Zero means no gravity pass at all.
  Vec3<S> gravity = Vec3<S>::Zero();
  bool has_gravity() const { return gravity.squaredNorm() > S(0); }
  /// The recursions' fast paths for hinges about a coordinate axis (a column of \f$P\f$ for
  /// \f$P H^*\f$, plane rotations of the inertias): on by default; off, every body takes
  /// the general path, against which the tests check them.
  bool fast_paths = true;
  /// True when some hinge has a spring or a damper.
  bool has_springs() const {
    for (const auto& b : bodies_)
      if (b.stiffness != S(0) || b.damping != S(0)) return true;
    return false;
  }

  /// The 1-based index of the body called \p name (bodies merged through locked hinges
  /// answer with the body they were merged into); 0 when there is none.
  int find(const std::string& name) const {
    for (int k = 1; k <= n(); ++k)
      if (body(k).name == name) return k;
    for (const auto& [merged, k] : merged_)
      if (merged == name) return k;
    return 0;
  }

  /// A chain made of \p base_first bodies (index 0 next to the base). Locked hinges are
  /// merged into their inboard neighbour: its inertia gains \f$\phi M \phi^*\f$ of the
  /// locked body (slide 74) and the next placement is composed through it.
  static ModelT from_base_first(std::vector<BodyT<S>> base_first) {
    ModelT m;
    PoseT<S> carry;  // placement of a locked run, to prepend to the next real hinge
    bool carrying = false;
    // The kept bodies are compacted in place, base_first[0, n): one copy of the chain in
    // memory, not three (a million bodies are hundreds of MB each).
    std::size_t n_kept = 0;
    for (std::size_t i = 0; i < base_first.size(); ++i) {
      BodyT<S>& b = base_first[i];
      if (b.hinge.type == HingeType::Locked) {
        if (n_kept == 0)
          throw Error("body '" + b.name + "': a locked hinge next to the base fixes the body " +
                      "to the ground; remove it from the chain");
        BodyT<S>& inboard = base_first[n_kept - 1];
        const PoseT<S> T = (carrying ? carry : PoseT<S>()) * b.placement;  // O_parent -> O_b
        inboard.M = inboard.M + transform(PhiT<S>(T), b.M);
        m.merged_.emplace_back(b.name, int(n_kept) - 1);  // base-first index, for now
        carry = T;
        carrying = true;
        continue;
      }
      if (carrying) b.placement = carry * b.placement;
      carrying = false;
      carry = PoseT<S>();
      const int n_rest = b.hinge.nq() <= 2 ? b.hinge.nq() : 0;
      if (b.rest.size() != n_rest) b.rest.setZero(n_rest);
      if (n_kept != i) base_first[n_kept] = std::move(b);
      ++n_kept;
    }
    // merged_ refer to base-first parents; bodies are stored tip first.
    const int n = int(n_kept);
    base_first.resize(n_kept);
    std::reverse(base_first.begin(), base_first.end());
    m.bodies_ = std::move(base_first);
    for (auto& mm : m.merged_) mm.second = n - mm.second;  // course number k
    int q = 0, v = 0;
    for (int k = 1; k <= n; ++k) {  // coordinates in course order: tip (k = 1) first
      m.body(k).q_offset = q;
      m.body(k).v_offset = v;
      q += m.body(k).hinge.nq();
      v += m.body(k).hinge.nv();
    }
    m.nq_ = q;
    m.nv_ = v;
    return m;
  }

  /// The neutral configuration: zero angles and offsets, identity quaternions.
  VecX<S> neutral() const {
    VecX<S> theta = VecX<S>::Zero(nq_);
    for (const auto& b : bodies_)
      if (b.hinge.type == HingeType::Spherical || b.hinge.type == HingeType::Free)
        theta[b.q_offset + 3] = S(1);
    return theta;
  }

 private:
  std::vector<BodyT<S>> bodies_;
  std::vector<std::pair<std::string, int>> merged_;
  int nq_ = 0, nv_ = 0;
};
using Model = ModelT<double>;
using Body = BodyT<double>;

}  // namespace soa
