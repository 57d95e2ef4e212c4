/// \file
/// Support for the viewer's tests: random scenes as files give them (every hinge type,
/// locked bodies, springs, gravity, external forces), and the poses of a frame.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "random_chain.hpp"
#include "scene_support.hpp"
#include "soa/sim/chain_system.hpp"
#include "soa/view.hpp"

namespace soa::test {

/// A scene read from the text of a random chain, with the bodies it was written from.
struct RandomScene {
  Scene scene;
  std::vector<Body> base_first;  ///< the file's bodies (placements relative to the parent)
};

/// A random scene of \p n bodies: hinge types drawn from all seven (locked ones anywhere but
/// next to the base, several in a row, last ones too), springs and dampers, gravity, and an
/// external force on about a third of the bodies (locked ones included).
inline RandomScene random_scene(Random<double>& rnd, int n) {
  ChainOptions opt;
  opt.springs = true;
  std::vector<Body> bodies;
  for (int i = 0; i < n; ++i)
    bodies.push_back(detail::random_body(rnd, i, HingeType(rnd.engine()() % 7), opt));
  nlohmann::json doc = chain_json(bodies);
  doc["gravity"] = {0, 0, -9.81};
  doc["external_forces"] = nlohmann::json::array();
  for (const Body& b : bodies)
    if (rnd.engine()() % 3 == 0)
      doc["external_forces"].push_back(
          {{"body", b.name}, {"moment", to_json(rnd.vec3())}, {"force", to_json(rnd.vec3())}});
  return {parse_scene(doc.dump(), "random.json"), std::move(bodies)};
}

/// The pose of file body \p i in a viewer frame: \f${}^I T_F\f$ from position and quaternion.
inline Pose pose_of(const view::Frame& f, std::size_t i) {
  const double* p = f.pose.data() + 7 * i;
  return Pose(UnitQuaternion(Vec3<double>(p[3], p[4], p[5]), p[6]).matrix(),
              Vec3<double>(p[0], p[1], p[2]));
}

/// Part \p j (0: angular, 1: linear) of body \p i's 6-vector in \p x (V or f of a frame).
inline Vec3<double> part(const std::vector<double>& x, std::size_t i, int j) {
  return Vec3<double>(x[6 * i + 3 * j], x[6 * i + 3 * j + 1], x[6 * i + 3 * j + 2]);
}

/// The single frame a recorder makes of state \p x at time \p t.
inline view::Frame frame_of(const Scene& s, const State& x, view::Quantities q = {}, double t = 0) {
  view::Recorder rec(s, 1.0, 2, q);
  rec.record(t, x);
  return rec.take("one").frames.at(0);
}

}  // namespace soa::test
