/// \file
/// The benchmark chain: a revolute chain of n links with alternating axes and a random state
/// from a fixed seed, as `make bench`, the peers' comparison and the timing and work labs use
/// it (lessons 4-8).
#pragma once

#include <random>
#include <string>
#include <vector>

#include "soa/chain.hpp"

namespace soa::bench {

/// n revolute links of 0.3 m, axes alternating z and y, masses 1, 1.1, 1.2 in turn; a random
/// pose, rates, accelerations and hinge forces drawn from one seed, body by body.
struct Chain {
  soa::Model model;
  soa::State x;
  soa::VecX<double> beta_dot;  ///< random accelerations (inverse dynamics)
  soa::VecX<double> T;         ///< random hinge forces (forward dynamics)
  soa::ExternalForces<double> f_ext;

  Chain(int n, bool gravity) {
    std::mt19937 g(11);
    std::normal_distribution<double> N;
    std::vector<soa::Body> bodies(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      soa::Body& b = bodies[std::size_t(i)];
      b.name = "link" + std::to_string(i);
      b.M = soa::SpatialInertia::from_cm(
          1.0 + 0.1 * (i % 3), soa::Vec3<double>(0.15, 0, 0.01),
          soa::Mat3<double>(soa::Vec3<double>(0.01, 0.02, 0.02).asDiagonal()));
      b.placement =
          soa::Pose(soa::Mat3<double>::Identity(), soa::Vec3<double>(i == 0 ? 0 : 0.3, 0, 0));
      b.hinge.type = soa::HingeType::Revolute;
      b.hinge.axis = i % 2 ? soa::Vec3<double>::UnitY() : soa::Vec3<double>::UnitZ();
    }
    model = soa::Model::from_base_first(bodies);
    if (gravity) model.gravity = soa::Vec3<double>(0, 0, -9.81);
    x = soa::State::rest(model);
    beta_dot.resize(model.nv());
    T.resize(model.nv());
    for (int i = 0; i < model.nq(); ++i) x.theta[i] = N(g);
    for (int i = 0; i < model.nv(); ++i) x.beta[i] = N(g), beta_dot[i] = N(g), T[i] = N(g);
  }
};

}  // namespace soa::bench
