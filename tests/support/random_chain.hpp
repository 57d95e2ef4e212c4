/// \file
/// Random serial chains for property tests (lessons 3-8).
#pragma once

#include <string>
#include <vector>

#include "property.hpp"
#include "soa/chain.hpp"

namespace soa::test {

/// Options of random_chain().
struct ChainOptions {
  bool all_hinge_types = true;  ///< cycle through every hinge type (locked ones get merged)
  bool gravity = false;
  bool springs = false;
};

/// A random chain of \p n bodies (fewer after locked hinges merge) with physically valid
/// inertias, random placements and axes; hinge i has type i mod 7 when all_hinge_types, else
/// revolute.
template <class S>
ModelT<S> random_chain(Random<S>& rnd, int n, const ChainOptions& opt = {}) {
  std::vector<BodyT<S>> bodies;
  for (int i = 0; i < n; ++i) {
    BodyT<S> b;
    b.name = "body" + std::to_string(i);
    b.M = rnd.inertia();
    b.placement = PoseT<S>(rnd.rotation(), rnd.vec3());
    b.hinge.type = opt.all_hinge_types ? HingeType(i % 7) : HingeType::Revolute;
    if (i == 0 && b.hinge.type == HingeType::Locked) b.hinge.type = HingeType::Revolute;
    b.hinge.axis = rnd.unit3();
    b.hinge.axis2 = rnd.unit3();
    b.hinge.pitch = rnd.uniform(S(-0.5), S(0.5));
    if (opt.springs) {
      b.stiffness = rnd.uniform(S(0.5), S(5));
      b.damping = rnd.uniform(S(0), S(1));
    }
    bodies.push_back(b);
  }
  ModelT<S> m = ModelT<S>::from_base_first(bodies);
  if (opt.gravity) m.gravity = Vec3<S>(S(0), S(0), S(-9.81));
  return m;
}

/// A random state of \p m: angles and offsets ~ N(0,1), unit quaternions, rates ~ N(0,1).
template <class S>
StateT<S> random_state(Random<S>& rnd, const ModelT<S>& m) {
  StateT<S> x = StateT<S>::rest(m);
  for (int i = 0; i < m.nq(); ++i) x.theta[i] = rnd.normal();
  for (int k = 1; k <= m.n(); ++k) {
    const BodyT<S>& B = m.body(k);
    if (B.hinge.type == HingeType::Spherical || B.hinge.type == HingeType::Free)
      x.theta.segment(B.q_offset, 4).normalize();
  }
  for (int i = 0; i < m.nv(); ++i) x.beta[i] = rnd.normal();
  return x;
}

/// A random vector of size \p n, entries ~ N(0,1).
template <class S>
VecX<S> random_vector(Random<S>& rnd, int n) {
  VecX<S> v(n);
  for (int i = 0; i < n; ++i) v[i] = rnd.normal();
  return v;
}

}  // namespace soa::test
