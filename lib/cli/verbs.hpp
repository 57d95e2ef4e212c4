// The six computations of `soa`, each from a scene and a state to a JSON result.
#pragma once

#include <string>

#include "json_out.hpp"
#include "soa/scene.hpp"
#include "soa/sim.hpp"

namespace soa::cli {

/// The frame of the body called \p name in \p scene; throws soa::Error("--body: ...").
const Scene::Frame& find_frame(const Scene& scene, const std::string& name);

/// Poses, velocities and accelerations (gravity not included) of every body in file order,
/// or of \p only when it is not null.
Json kinematics(const Scene& scene, const State& x, const VecX<double>& beta_dot,
                const Scene::Frame* only);

/// The Jacobian of \p frame: 6 rows, one column per coordinate of beta in file order.
Json jacobian(const Scene& scene, const State& x, const Scene::Frame& frame);

/// The hinge forces T per body and as one vector in file order.
Json inverse_dynamics(const Scene& scene, const State& x, const VecX<double>& beta_dot);

/// The accelerations at the state \p x under the hinge forces \p tau (articulated body
/// algorithm), per body and in file order, with the difference from CRB + LDLT.
Json forward_dynamics(const Scene& scene, const State& x, const VecX<double>& tau);

/// Integrates the scene's motion from \p x (simulate): the trajectory as CSV into \p csv_path
/// (none when empty), the summary as JSON.
Json simulate(const Scene& scene, const State& x, const SimulationOptions& opt,
              const std::string& csv_path);

/// The mass matrix in file order, with its symmetry and definiteness; with \p inverse, also
/// its inverse by the O(N^2) algorithm of lesson 7.
Json mass_matrix(const Scene& scene, const State& x, bool inverse);

}  // namespace soa::cli
