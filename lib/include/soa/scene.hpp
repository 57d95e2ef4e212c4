/// \file
/// Scene files: a serial chain and what to do with it, read from JSON (lessons 3-4).
///
/// The format is documented, with a commented example, on the "Scene files" page of the
/// notes (docs/scenes.md). Reading is strict: any problem is one soa::Error whose message
/// names the file and the JSON path, e.g. `arm.json: bodies[3].inertia: not positive
/// definite`.
#pragma once

#include <string>
#include <vector>

#include "soa/chain/inverse_dynamics.hpp"
#include "soa/chain/model.hpp"
#include "soa/chain/workspace.hpp"

namespace soa {

/// A scene: the chain, its initial state and the optional parts (gravity lives in the model,
/// springs and dampers on its bodies).
struct Scene {
  std::string name;  ///< the file name as given (used in messages)
  Model model;
  State state;  ///< initial state (the neutral configuration at rest when the file has none)
  VecX<double> beta_dot;         ///< \f$\dot\beta\f$ for inverse dynamics (zero when absent)
  ExternalForces<double> f_ext;  ///< empty when the scene applies none
  std::vector<std::string> compute;  ///< what the scene asks to compute (may be empty)
  /// The bodies in the order of the file (base first), as course numbers k: the order of
  /// `--q/--qd/--qdd` on the command line and of per-body output.
  std::vector<int> file_order;
};

/// Reads and checks a scene file. Throws soa::Error("<file>: <json path>: <problem>").
Scene load_scene(const std::string& path);

/// The same from JSON text; \p name stands for the file in messages.
Scene parse_scene(const std::string& json_text, const std::string& name);

}  // namespace soa
