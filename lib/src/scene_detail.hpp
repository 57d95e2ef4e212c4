// What the two scene readers share: the JSON reader (scene.cpp) and the URDF reader
// (urdf.cpp), which builds the same document from urdfdom's model and has the JSON reader
// check and assemble it, as a structure, without a round trip through text.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "soa/scene.hpp"

#include "soa/types.hpp"

namespace soa::detail {

/// The problem of an inertia \f$J(C)\f$ about the centre of mass, or "" when it is physical:
/// symmetric within 1e-9 max|J| (then made exactly symmetric), positive definite, principal
/// moments obeying the triangle inequality, none overflowing (docs/scenes.md).
std::string inertia_problem(Mat3<double>& J);

/// A URDF file as the JSON reader's document (docs/scenes.md), and the comments `soa
/// convert` writes above it. urdf.cpp.
struct UrdfScene {
  nlohmann::json top;                           ///< "name" and "gravity"
  std::vector<nlohmann::json> bodies;           ///< the elements of "bodies", base first
  std::vector<std::string> header;              ///< comments above the scene, one line each
  std::vector<std::vector<std::string>> notes;  ///< comments above each body
  /// (link, joint) of each body: the JSON reader's messages name them for "bodies[i]".
  std::vector<std::pair<std::string, std::string>> names;
};
UrdfScene convert_urdf(const std::string& path, const UrdfOptions& options);

/// The scene of a document given as a structure, with the JSON reader's checks; a message
/// names link names[i].first for "bodies[i]" and joint names[i].second for
/// "bodies[i].hinge". scene.cpp.
Scene scene_from_urdf(const UrdfScene& u, const std::string& file);

}  // namespace soa::detail
