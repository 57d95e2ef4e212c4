/// \file
/// A random case of a chain exercise (lessons 3-8): the chain, its state, the accelerations
/// and the external forces, with what the case has (tags, for the exercise checker's
/// symptoms) and the case as code a student can paste into a program.
///
/// Features vary independently across the cases i = 0, 1, ...: 1 + i mod 7 bodies with hinge
/// types drawn at random, at rest when i mod 5 = 0, no accelerations when i mod 4 = 1,
/// gravity when i mod 2 = 1, external forces when i mod 3 = 0, each where the exercise
/// allows it.
#pragma once

#include <string>

#include "exercise_check.hpp"
#include "random_chain.hpp"

namespace soa::test {

/// What an exercise's cases may have.
struct CaseOptions {
  bool all_hinge_types = true;  ///< else revolute chains only
  bool gravity = true;
  bool moving = true;  ///< else every case at rest
  bool external_forces = false;
  bool springs = false;
  int max_bodies = 7;
};

struct ChainCase {
  Model m;
  State x;
  VecX<double> beta_dot;
  ExternalForces<double> f_ext;  ///< empty when none
  unsigned tags = 0;

  /// The case as code: `soa::Model m = ...; soa::State x = ...; ...`.
  std::string code() const {
    std::string s =
        soa::test::code("m", m) + soa::test::code("x", x) + soa::test::code("beta_dot", beta_dot);
    s += "soa::ExternalForces<double> f_ext;";
    if (f_ext.empty()) s += "  // none";
    s += "\n";
    for (std::size_t k = 0; k < f_ext.size(); ++k)
      s += "f_ext.push_back(soa::Force(soa::Vec3<double>" + list(Vec3<double>(f_ext[k].angular())) +
           ", soa::Vec3<double>" + list(Vec3<double>(f_ext[k].linear())) + "));  // body " +
           std::to_string(k + 1) + "\n";
    return s;
  }
};

/// Case \p i of an exercise (see the file's comment).
inline ChainCase draw_chain_case(Random<double>& rnd, int i, const CaseOptions& o) {
  ChainCase c;
  ChainOptions co;
  co.all_hinge_types = o.all_hinge_types;
  co.gravity = o.gravity && i % 2 == 1;
  co.springs = o.springs;
  c.m = random_chain_mixed(rnd, 1 + i % o.max_bodies, co);
  c.x = random_state(rnd, c.m);
  if (!o.moving || i % 5 == 0) c.x.beta.setZero();
  c.beta_dot = random_vector(rnd, c.m.nv());
  if (i % 4 == 1) c.beta_dot.setZero();
  if (o.external_forces && i % 3 == 0) c.f_ext = random_forces(rnd, c.m);
  c.tags = chain_tags(c.m, c.x);
  if (c.beta_dot.size() && c.beta_dot.cwiseAbs().maxCoeff() > 0) c.tags |= kAccelerating;
  if (!c.f_ext.empty()) c.tags |= kExternalForces;
  return c;
}

}  // namespace soa::test
