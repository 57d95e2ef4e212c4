/// \file
/// The default scenes (`lib/scenes/`, shown in lesson 3), loaded by the
/// lessons that compute on them, as a check: a file that does not load is a failed check
/// naming its problem, not a crash of the lecture.
#pragma once

#include <exception>
#include <optional>
#include <string>

#include "checklist.hpp"
#include "soa/scene.hpp"

namespace soa::lesson {

/// The path of the default scene \p file ("arm7.json", "panda.urdf"). Needs SOA_SCENE_DIR,
/// which soa_support gives every lesson target.
inline std::string lesson3_scene(const std::string& file) {
  return std::string(SOA_SCENE_DIR) + "/" + file;
}

/// Lesson 3's scene \p file with \p nv coordinates, checked in \p checks ("panda.urdf loads
/// (7 coordinates)"); empty when it does not load or has another size.
inline std::optional<Scene> load_lesson3_scene(Checklist& checks, const std::string& file, int nv) {
  std::optional<Scene> s;
  std::string why;
  try {
    s = load_scene(lesson3_scene(file));
    if (s->model.nv() != nv) why = std::to_string(s->model.nv()) + " coordinates";
  } catch (const std::exception& e) {
    why = e.what();
  }
  checks.check(file + " loads (" + std::to_string(nv) + " coordinates)" +
                   (why.empty() ? std::string() : ": " + why),
               why.empty());
  if (!why.empty()) s.reset();
  return s;
}

}  // namespace soa::lesson
