/// \file
/// Bad scene files: each file under tests/scenes/bad/ is refused with exactly the one-line
/// message of the table below, `<file>: <json path>: <problem>`; and every file there has
/// its line in the table. Suite scene_errors.
#include <filesystem>
#include <map>

#include "scene_support.hpp"

namespace soa::test {
namespace {

/// File (without .json) -> the message after "<file>: ".
const std::map<std::string, std::string>& expected_messages() {
  static const std::map<std::string, std::string> table = {
      // JSON itself
      {"invalid_json",
       "line 4, column 53: invalid JSON: syntax error while parsing object - unexpected string "
       "literal; expected '}'"},
      {"empty_file",
       "line 1, column 1: invalid JSON: syntax error while parsing value - unexpected end of "
       "input; expected '[', '{', or a literal"},
      {"top_level_array", "top level: expected an object, got an array"},
      {"duplicate_key", "bodies[0]: field \"mass\" given twice"},
      {"unknown_field", "bodies[1].spring: unknown field \"stifness\""},
      // values
      {"missing_mass", "bodies[1]: missing field \"mass\""},
      {"mass_nan_string", "bodies[1].mass: expected a number, got the string \"NaN\""},
      {"zero_mass", "bodies[1].mass: must be positive (got 0)"},
      {"infinite_number",
       "bodies[1].com[1]: not a finite number (1e999 is out of the range of a double)"},
      {"gravity_wrong_size", "gravity: expected 3 numbers, got 2"},
      {"negative_damping", "bodies[1].spring.damping: must not be negative (got -0.5)"},
      // inertia
      {"inertia_wrong_shape", "bodies[1].inertia: expected 3 rows, got 2"},
      {"inertia_not_symmetric",
       "bodies[1].inertia: not symmetric ([0][1] = 0.01 but [1][0] = 0.02)"},
      {"inertia_not_positive_definite",
       "bodies[1].inertia: not positive definite (principal moments -0.1, 0.1, 0.3)"},
      {"inertia_triangle",
       "bodies[1].inertia: principal moments 0.1, 0.1, 0.3 break the triangle inequality "
       "(0.1 + 0.1 < 0.3)"},
      // hinges
      {"unknown_hinge_type",
       "bodies[1].hinge.type: unknown hinge type \"rotary\" (expected revolute, prismatic, "
       "helical, universal, spherical, free or locked)"},
      {"zero_axis", "bodies[1].hinge.axis: zero axis; an axis needs a direction"},
      {"axis_on_spherical", "bodies[1].hinge: field \"axis\" does not apply to a spherical hinge"},
      {"universal_parallel_axes",
       "bodies[1].hinge.axis2: parallel to axis; a universal hinge needs two different axes"},
      {"non_unit_quaternion",
       "bodies[1].hinge.placement.rotation: not a unit quaternion (norm 0.99999; the norm "
       "must be 1 within 1e-6)"},
      {"locked_at_base",
       "bodies[0].hinge.type: a locked hinge next to the base fixes the body to the ground; "
       "remove the body or give it another hinge"},
      // the chain
      {"empty_bodies", "bodies: empty; a scene needs at least one body"},
      {"unknown_parent",
       "bodies[1].parent: no body named \"aa\" (a parent is \"base\" or a body's name)"},
      {"duplicate_name", "bodies[1].name: duplicate name \"a\" (bodies[0] has it too)"},
      {"branch",
       "bodies[2].parent: \"a\" already has a child (bodies[1]); serial chains only, no "
       "branches"},
      {"loop", "bodies[1].parent: loop (b -> c -> b, following parents) never reaches \"base\""},
      {"not_base_first",
       "bodies[0].parent: \"a\" is listed after this body (bodies[1]); list the bodies base "
       "first, each after its parent"},
      // state, forces, compute
      {"state_wrong_size", "bodies[1].q: expected 1 number for a revolute hinge, got 2"},
      {"state_quaternion_not_unit",
       "bodies[1].q: not a unit quaternion in entries 0-3 (norm 0.707107; the norm must be 1 "
       "within 1e-6)"},
      {"external_force_unknown_body", "external_forces[0].body: no body named \"c\""},
      {"unknown_compute",
       "compute[1]: unknown computation \"dynamics\" (expected kinematics, jacobian, "
       "inverse-dynamics or mass-matrix)"},
  };
  return table;
}

/// The message load_scene() throws for \p path ("" when it does not throw).
std::string message_of(const std::string& path) {
  try {
    load_scene(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(scene_errors, EachBadSceneHasItsMessage) {
  for (const auto& [name, expected] : expected_messages()) {
    const std::string path = bad_scene(name + ".json");
    const std::string got = message_of(path);
    EXPECT_EQ(got, path + ": " + expected) << name;
    EXPECT_EQ(got.find('\n'), std::string::npos) << name << ": one line";
  }
}

// A bad scene without a line in the table would go unchecked.
TEST(scene_errors, EveryBadFileIsInTheTable) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(bad_scene(""))) {
    if (entry.path().extension() != ".json") continue;
    ++files;
    EXPECT_EQ(expected_messages().count(entry.path().stem().string()), 1u)
        << entry.path() << " has no expected message";
  }
  EXPECT_EQ(files, int(expected_messages().size()));
}

TEST(scene_errors, MissingFile) {
  const std::string path = bad_scene("no_such_scene.json");
  EXPECT_EQ(message_of(path), path + ": cannot open the file (No such file or directory)");
}

// parse_scene() names the file as given; the errors of values given in file order.
TEST(scene_errors, ValuesInFileOrder) {
  const Scene s = parse_scene(R"({"bodies": [
      {"name": "a", "parent": "base", "mass": 1, "com": [0, 0, 0],
       "inertia": {"Ixx": 1, "Iyy": 1, "Izz": 1}, "hinge": {"type": "revolute", "axis": [0, 0, 1]}},
      {"name": "b", "parent": "a", "mass": 1, "com": [0, 0, 0],
       "inertia": {"Ixx": 1, "Iyy": 1, "Izz": 1}, "hinge": {"type": "spherical"}}]})",
                              "two.json");
  auto message = [](auto f) -> std::string {
    try {
      f();
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(message([&] {
              theta_from_file_order(s, {0.1, 0, 0, 0});
            }),
            "expected 5 numbers, got 4");
  EXPECT_EQ(message([&] {
              theta_from_file_order(s, {0.1, 0, 0, 0, 2});
            }),
            "the quaternion of body \"b\" is not of unit norm (norm 2; the norm must be 1 "
            "within 1e-6)");
  EXPECT_EQ(message([&] {
              beta_from_file_order(s, {0.1, 0, 0, INFINITY});
            }),
            "entry 3 is not finite");
  // File order: a's angle first, then b's quaternion, though the model keeps b (k = 1) first.
  const VecX<double> theta = theta_from_file_order(s, {0.5, 0, 0, 0, 1});
  EXPECT_EQ(theta[s.model.body(2).q_offset], 0.5);
  EXPECT_EQ(theta[s.model.body(1).q_offset + 3], 1.0);
  EXPECT_EQ(message([&] { parse_scene("{", "x.json"); }),
            "x.json: line 1, column 2: invalid JSON: syntax error while parsing object key - "
            "unexpected end of input; expected string literal");
}

}  // namespace
}  // namespace soa::test
