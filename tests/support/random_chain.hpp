/// \file
/// Random serial chains for property tests (lessons 3-8).
#pragma once

#include <string>
#include <utility>
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

namespace detail {
/// Body \p i of a random chain, with a hinge of type \p type (the draws, in this order:
/// inertia, placement rotation and offset, axes, pitch, then stiffness and damping).
template <class S>
BodyT<S> random_body(Random<S>& rnd, int i, HingeType type, const ChainOptions& opt) {
  BodyT<S> b;
  b.name = "body" + std::to_string(i);
  b.M = rnd.inertia();
  const Vec3<S> position = rnd.vec3();  // drawn before the rotation, as in Random
  b.placement = PoseT<S>(rnd.rotation(), position);
  b.hinge.type = type;
  if (i == 0 && b.hinge.type == HingeType::Locked) b.hinge.type = HingeType::Revolute;
  b.hinge.axis = rnd.unit3();
  b.hinge.axis2 = rnd.unit3();
  b.hinge.pitch = rnd.uniform(S(-0.5), S(0.5));
  if (opt.springs) {
    b.stiffness = rnd.uniform(S(0.5), S(5));
    b.damping = rnd.uniform(S(0), S(1));
  }
  return b;
}

template <class S>
ModelT<S> finish_chain(std::vector<BodyT<S>> bodies, const ChainOptions& opt) {
  ModelT<S> m = ModelT<S>::from_base_first(std::move(bodies));
  if (opt.gravity) m.gravity = Vec3<S>(S(0), S(0), S(-9.81));
  return m;
}
}  // namespace detail

/// A random chain of \p n bodies (fewer after locked hinges merge) with physically valid
/// inertias, random placements and axes; hinge i has type i mod 7 when all_hinge_types, else
/// revolute.
template <class S>
ModelT<S> random_chain(Random<S>& rnd, int n, const ChainOptions& opt = {}) {
  std::vector<BodyT<S>> bodies;
  for (int i = 0; i < n; ++i)
    bodies.push_back(detail::random_body(
        rnd, i, opt.all_hinge_types ? HingeType(i % 7) : HingeType::Revolute, opt));
  return detail::finish_chain(std::move(bodies), opt);
}

/// A random chain of \p n bodies whose hinges are all of type \p type (opt.all_hinge_types
/// is ignored). A locked type keeps a revolute first hinge and merges every other body into
/// it: one body.
template <class S>
ModelT<S> random_chain_of_type(Random<S>& rnd, int n, HingeType type,
                               const ChainOptions& opt = {}) {
  std::vector<BodyT<S>> bodies;
  for (int i = 0; i < n; ++i) bodies.push_back(detail::random_body(rnd, i, type, opt));
  return detail::finish_chain(std::move(bodies), opt);
}

/// A random chain of \p n bodies whose hinge types are drawn at random (revolute,
/// prismatic, helical, universal, spherical, free; revolute only when
/// !opt.all_hinge_types), so that across cases the hinge types and the number of bodies vary
/// independently (the exercise checker tells symptoms apart by them).
template <class S>
ModelT<S> random_chain_mixed(Random<S>& rnd, int n, const ChainOptions& opt = {}) {
  std::vector<BodyT<S>> bodies;
  for (int i = 0; i < n; ++i) {
    const auto type = opt.all_hinge_types ? HingeType(rnd.engine()() % 6) : HingeType::Revolute;
    bodies.push_back(detail::random_body(rnd, i, type, opt));
  }
  return detail::finish_chain(std::move(bodies), opt);
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

/// Random spatial forces, one per body of \p m (entry k-1 acts on body k at \f$O_k\f$, in
/// \f$O_k\f$ coordinates, as inverse_dynamics() takes them).
template <class S>
ExternalForces<S> random_forces(Random<S>& rnd, const ModelT<S>& m) {
  ExternalForces<S> f;
  for (int k = 1; k <= m.n(); ++k) f.push_back(rnd.force());
  return f;
}

/// \f$\dot\theta\f$ of the whole chain from \f$\beta\f$ (HingeT::theta_dot() per body).
template <class S>
VecX<S> theta_dot(const ModelT<S>& m, const StateT<S>& x) {
  VecX<S> qd(m.nq());
  for (int k = 1; k <= m.n(); ++k) {
    const BodyT<S>& B = m.body(k);
    B.hinge.theta_dot(x.theta.data() + B.q_offset, x.beta.data() + B.v_offset,
                      qd.data() + B.q_offset);
  }
  return qd;
}

/// The configuration \f$\theta + t\,\dot\theta\f$ with every quaternion renormalized: a
/// smooth curve through \p theta with tangent \p theta_dot at t = 0 (the tangent of a
/// quaternion, \f$\tfrac12\mathfrak q\otimes[\omega;0]\f$, is orthogonal to it, so the
/// renormalization keeps it). For finite differences along a motion.
template <class S>
VecX<S> advance(const ModelT<S>& m, const VecX<S>& theta, const VecX<S>& theta_dot, S t) {
  VecX<S> q = theta + t * theta_dot;
  for (int k = 1; k <= m.n(); ++k) {
    const BodyT<S>& B = m.body(k);
    if (B.hinge.type == HingeType::Spherical || B.hinge.type == HingeType::Free)
      q.segment(B.q_offset, 4).normalize();
  }
  return q;
}

}  // namespace soa::test
