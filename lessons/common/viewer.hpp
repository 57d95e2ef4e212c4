/// \file
/// A lesson's 3D viewers (soa::view, notes page "Viewing a chain in 3D"): the page and its
/// data in a folder of the lesson's output, listed in `views.txt` with the query of its
/// still image, which the tour (lessons/tour.cmake) takes with Chromium as `<folder>.png`.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "checklist.hpp"
#include "soa/view.hpp"

namespace soa::lesson {

/// Writes \p view into `out/name/` and records `name query` in `out/views.txt` (replacing an
/// earlier line of the same name). \p query is the still image's URL query, e.g.
/// `paused=1&t=1.5&show=ellipsoids,fixed`. Returns false, with the reason in \p why, when
/// the folder could not be written.
inline bool write_viewer(const std::filesystem::path& out, const std::string& name,
                         const soa::view::View& view, const std::string& query, std::string& why) {
  try {
    soa::view::write(view, out / name);
  } catch (const std::exception& e) {
    why = e.what();
    return false;
  }
  const std::filesystem::path list = out / "views.txt";
  std::vector<std::string> lines;
  {
    std::ifstream in(list);
    for (std::string line; std::getline(in, line);)
      if (!line.empty() && line.rfind(name + " ", 0) != 0 && line != name) lines.push_back(line);
  }
  lines.push_back(name + " " + query);
  std::ofstream o(list, std::ios::trunc);
  for (const std::string& line : lines) o << line << "\n";
  o.close();
  if (!o) {
    why = "cannot write " + list.string();
    return false;
  }
  return true;
}

/// A scene for a chain built in code (no locked bodies): its bodies in file order base first,
/// at rest in the neutral configuration, so that soa::view::view_of() and
/// soa::view::Recorder can draw it as they draw a scene file's chain.
inline soa::Scene scene_of(const soa::Model& m, const std::string& title) {
  soa::Scene s;
  s.name = s.title = title;
  s.model = m;
  s.state = soa::State::rest(m);
  s.beta_dot = soa::VecX<double>::Zero(m.nv());
  for (int k = m.n(); k >= 1; --k) {
    s.file_order.push_back(k);
    soa::Scene::Frame F;
    F.name = m.body(k).name;
    F.k = k;
    s.frames.push_back(F);
  }
  return s;
}

/// Makes the tip path that of \p point fixed in file body \p body: every frame's tip
/// \f$p + \mathfrak q\, \text{point}\, \mathfrak q^{-1}\f$ from that body's pose (as the
/// page computes it).
inline void set_tip(soa::view::View& view, int body, const soa::Vec3<double>& point) {
  view.tip_body = body;
  view.tip_point = point;
  for (soa::view::Run& run : view.runs)
    for (soa::view::Frame& f : run.frames) {
      const double* p = f.pose.data() + 7 * std::size_t(body);
      const soa::UnitQuaternion q(soa::Vec3<double>(p[3], p[4], p[5]), p[6]);
      f.tip = soa::Vec3<double>(p[0], p[1], p[2]) + q.rotate(point);
    }
}

/// The hinge forces that the inter-body forces of a viewer frame carry,
/// \f$T(k) = H(k)\,f(k)\f$ (lesson 3's gather; without springs and dampers): for a revolute
/// hinge \f$h^* N(k)\f$, for a prismatic one \f$h^* F(k)\f$, with the axis h and
/// \f$f(k) = [N; F]\f$ in world axes; indexed as \f$\beta\f$. Other hinges are left at 0.
inline soa::VecX<double> hinge_forces(const soa::Scene& scene, const soa::view::Frame& f) {
  soa::VecX<double> T = soa::VecX<double>::Zero(scene.model.nv());
  for (std::size_t b = 0; b < scene.frames.size(); ++b) {
    const soa::Scene::Frame& F = scene.frames[b];
    const soa::Body& B = scene.model.body(F.k);
    const bool revolute = B.hinge.type == soa::HingeType::Revolute;
    if (F.locked || !(revolute || B.hinge.type == soa::HingeType::Prismatic)) continue;
    const double* p = f.pose.data() + 7 * b;  // O_k: position, quaternion
    const soa::Vec3<double> h =
        soa::UnitQuaternion(soa::Vec3<double>(p[3], p[4], p[5]), p[6]).rotate(B.hinge.axis);
    const double* part = f.f.data() + 6 * b + (revolute ? 0 : 3);
    T[B.v_offset] = h.dot(soa::Vec3<double>(part[0], part[1], part[2]));
  }
  return T;
}

/// write_viewer() as the lesson check "viewer written: <name>" (with the reason when it fails).
inline bool check_viewer(Checklist& checks, const std::filesystem::path& out,
                         const std::string& name, const soa::view::View& view,
                         const std::string& query) {
  std::string why;
  const bool ok = write_viewer(out, name, view, query, why);
  return checks.check("viewer written: " + name + (ok ? "" : " (" + why + ")"), ok);
}

}  // namespace soa::lesson
