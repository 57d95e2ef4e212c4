/// \file
/// The scenes of the simulation report: the default scenes of lesson 3 (double pendulum,
/// seven-joint arm, 50-link chain) and a stiff-spring chain built in code.
#pragma once

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "support.hpp"

namespace soa::lesson::sim {

/// A default scene (`lib/scenes/NAME.json`) as a problem over
/// [0, \p t_end], from the state the file gives.
inline SimProblem default_scene(const std::string& name, const std::string& title, double t_end) {
  const soa::Scene sc = soa::load_scene(std::string(SOA_SCENE_DIR) + "/" + name + ".json");
  return SimProblem{name, title, sc.model, sc.f_ext, sc.state, t_end};
}

/// The stiff-spring chain: \p n revolute links of 0.5 m moving in a horizontal plane (axes
/// along z, no gravity), masses 1 kg with the centre of mass mid-link and
/// \f$J = 10^{-2}\f$ kg m² about it, joint springs whose stiffness grows geometrically from
/// \f$k = 1\f$ N m/rad at the base joint to \p k_max at the tip joint (stiffness ratio
/// \p k_max), and light dampers, damping ratio \p zeta of each joint's own oscillation:
/// \f$c_i = 2\zeta\sqrt{k_i I_i}\f$ with \f$I_i\f$ the link's inertia about its joint.
/// Starts from a random pose within 0.1 rad of rest and random rates up to 1 rad/s (seed 3).
inline SimProblem stiff_chain(double k_max, int n = 6, double zeta = 0.02, double t_end = 1) {
  std::vector<soa::Body> bodies(static_cast<std::size_t>(n));
  const double len = 0.5, mass = 1, J = 1e-2;
  const double I_joint = J + mass * (len / 2) * (len / 2);
  for (int i = 0; i < n; ++i) {  // i = 0 next to the base
    soa::Body& b = bodies[std::size_t(i)];
    b.name = "link" + std::to_string(i + 1);
    b.M = soa::SpatialInertia::from_cm(mass, soa::Vec3<double>(len / 2, 0, 0),
                                       J * soa::Mat3<double>::Identity());
    b.placement = soa::Pose(soa::Mat3<double>::Identity(),
                            i == 0 ? soa::Vec3<double>::Zero() : soa::Vec3<double>(len, 0, 0));
    b.hinge.type = soa::HingeType::Revolute;
    b.hinge.axis = soa::Vec3<double>::UnitZ();
    b.stiffness = n > 1 ? std::pow(k_max, double(i) / (n - 1)) : k_max;
    b.damping = 2 * zeta * std::sqrt(b.stiffness * I_joint);
  }
  SimProblem p;
  p.name = "stiff_chain";
  char title[80];
  std::snprintf(title, sizeof title, "stiff-spring chain (%d links, k = 1 ... %.0e)", n, k_max);
  p.title = title;
  p.m = soa::Model::from_base_first(std::move(bodies));
  p.m.gravity.setZero();
  p.x0 = soa::State::rest(p.m);
  std::mt19937 g(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < p.m.nv(); ++i) {
    p.x0.theta[i] = 0.1 * u(g);
    p.x0.beta[i] = u(g);
  }
  p.t_end = t_end;
  return p;
}

}  // namespace soa::lesson::sim
