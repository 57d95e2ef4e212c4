/// \file
/// Support for the scene tests: where the scene files are, reading a file, and a writer of
/// scene JSON from library bodies (the test's own, independent of the reader).
#pragma once

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "random_chain.hpp"
#include "soa/scene.hpp"

namespace soa::test {

/// lib/scenes/NAME.
inline std::string default_scene(const std::string& name) {
  return std::string(SOA_SCENE_DIR) + "/" + name;
}
/// tests/scenes/bad/NAME.
inline std::string bad_scene(const std::string& name) {
  return std::string(SOA_SOURCE_DIR) + "/tests/scenes/bad/" + name;
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.good()) << "cannot open " << path;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline nlohmann::json to_json(const Vec3<double>& v) {
  return {v[0], v[1], v[2]};
}

/// The scene-file body of a library body hanging from \p parent: mass, centre of mass and
/// inertia about it (from M about O_k), hinge with its placement (rotation as a quaternion
/// [x, y, z, w]), spring and damper.
inline nlohmann::json body_json(const Body& b, const std::string& parent) {
  nlohmann::json j;
  j["name"] = b.name;
  j["parent"] = parent;
  j["mass"] = b.M.mass();
  j["com"] = to_json(b.M.p());
  const Mat3<double> J = b.M.J_cm();
  j["inertia"] = {
      {J(0, 0), J(0, 1), J(0, 2)}, {J(1, 0), J(1, 1), J(1, 2)}, {J(2, 0), J(2, 1), J(2, 2)}};
  nlohmann::json h;
  h["type"] = hinge_type_name(b.hinge.type);
  switch (b.hinge.type) {
    case HingeType::Universal:
      h["axis2"] = to_json(b.hinge.axis2);
      h["axis"] = to_json(b.hinge.axis);
      break;
    case HingeType::Helical:
      h["pitch"] = b.hinge.pitch;
      h["axis"] = to_json(b.hinge.axis);
      break;
    case HingeType::Revolute:
    case HingeType::Prismatic:
      h["axis"] = to_json(b.hinge.axis);
      break;
    default:
      break;
  }
  const Eigen::Matrix<double, 4, 1> q = UnitQuaternion::from_matrix(b.placement.R()).coeffs();
  h["placement"] = {{"position", to_json(b.placement.l())}, {"rotation", {q[0], q[1], q[2], q[3]}}};
  j["hinge"] = h;
  if (b.hinge.type != HingeType::Locked && (b.stiffness != 0 || b.damping != 0))
    j["spring"] = {{"stiffness", b.stiffness}, {"damping", b.damping}};
  return j;
}

/// A scene of \p base_first bodies (each hanging from the previous one).
inline nlohmann::json chain_json(const std::vector<Body>& base_first) {
  nlohmann::json doc;
  doc["name"] = "random chain";
  doc["bodies"] = nlohmann::json::array();
  for (std::size_t i = 0; i < base_first.size(); ++i)
    doc["bodies"].push_back(body_json(base_first[i], i ? base_first[i - 1].name : "base"));
  return doc;
}

/// The text of a scene of \p n revolute bodies b0, b1, ... (each hanging from the one before,
/// q = 0.1), written directly: fast enough for 10^5 bodies. \p extra is added to the last
/// body's fields (`, "mass": 2` gives a field twice).
inline std::string revolute_chain_text(std::size_t n, const std::string& extra = "") {
  std::string s = "{\"name\": \"chain\", \"gravity\": [0, 0, -9.81], \"bodies\": [\n";
  for (std::size_t i = 0; i < n; ++i) {
    s += "{\"name\": \"b" + std::to_string(i) + "\", \"parent\": \"" +
         (i ? "b" + std::to_string(i - 1) : std::string("base")) +
         "\", \"mass\": 1.5, \"com\": [0, 0, 0.15], "
         "\"inertia\": {\"Ixx\": 0.012, \"Iyy\": 0.012, \"Izz\": 0.002}, "
         "\"hinge\": {\"type\": \"revolute\", \"axis\": [0, 0, 1], "
         "\"placement\": {\"position\": [0, 0, 0.3]}}, \"q\": [0.1]";
    if (i + 1 == n) s += extra;
    s += i + 1 < n ? "},\n" : "}\n";
  }
  return s + "]}";
}

/// The message of the soa::Error \p f throws ("" when it does not throw).
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

/// The hinge forces of a scene at its own state.
inline VecX<double> scene_torques(const Scene& s) {
  Workspace ws(s.model);
  VecX<double> T(s.model.nv());
  inverse_dynamics(s.model, s.state, s.beta_dot, s.f_ext, ws, T);
  return T;
}

}  // namespace soa::test
