// What the two scene readers share: the JSON reader (scene.cpp) and the URDF reader
// (urdf.cpp), which checks a link's inertia with the same rules before it writes the scene.
#pragma once

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

/// A URDF file as the JSON scene text `soa convert` prints, and the (link, joint) names of
/// its bodies in order (to name them in the JSON reader's messages). urdf.cpp.
struct UrdfText {
  std::string json;
  std::vector<std::pair<std::string, std::string>> bodies;
};
UrdfText convert_urdf(const std::string& path, const UrdfOptions& options);

}  // namespace soa::detail
