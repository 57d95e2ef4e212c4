// The viewer's data checked before anything is written: every number finite (JSON has no
// NaN nor Infinity, and the page must never draw one), every frame of the documented size.
#include <cmath>
#include <cstdio>

#include "detail.hpp"

namespace soa::view::detail {
namespace {

std::string quoted(const std::string& s) {
  return "\"" + s + "\"";
}

/// "view: body 3 \"link3\"".
std::string body_where(const View& v, std::size_t i) {
  return "view: body " + std::to_string(i) + " " + quoted(v.bodies[i].name);
}

/// "view: run 0 \"RK4\", frame 12 (t = 0.3)".
std::string frame_where(const Run& r, std::size_t ri, std::size_t fi) {
  char t[40];
  std::snprintf(t, sizeof t, "%.9g", r.frames[fi].t);
  return "view: run " + std::to_string(ri) + " " + quoted(r.label) + ", frame " +
         std::to_string(fi) + " (t = " + t + ")";
}

template <class Vector>
bool finite(const Vector& x) {
  for (double xi : x)
    if (!std::isfinite(xi)) return false;
  return true;
}

void require(bool ok, const std::string& where, const std::string& what) {
  if (!ok) throw Error(where + ": " + what + " is not finite");
}

/// A per-body quantity of a frame: \p per numbers for each of \p nb bodies, or (when
/// \p optional) none, the same in every frame of the run (\p present).
void check_per_body(const std::vector<double>& x, std::size_t per, const View& v,
                    const std::string& where, const char* what, bool present) {
  const std::size_t nb = v.bodies.size();
  if (!present) {
    if (!x.empty()) throw Error(where + ": has " + what + " where the run's first frame has none");
    return;
  }
  if (x.size() != per * nb)
    throw Error(where + ": " + what + " has " + std::to_string(x.size()) + " numbers, expected " +
                std::to_string(per * nb) + " (" + std::to_string(per) + " for each of " +
                std::to_string(nb) + " bodies)");
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i]))
      throw Error(where + ": " + what + " of body " + quoted(v.bodies[i / per].name) +
                  " is not finite");
}

}  // namespace

void check(const View& v) {
  require(finite(v.gravity), "view", "gravity");
  for (std::size_t i = 0; i < v.bodies.size(); ++i) {
    const Body& b = v.bodies[i];
    const std::string w = body_where(v, i);
    require(finite(b.axis), w, "axis");
    require(finite(b.segment), w, "segment");
    require(finite(b.com), w, "com");
    require(std::isfinite(b.mass), w, "mass");
    require(finite(b.radii), w, "radii");
    require(finite(b.axes_quaternion), w, "axes_quaternion");
  }
  if (v.tip_body < -1 || v.tip_body >= int(v.bodies.size()))
    throw Error("view: tip body " + std::to_string(v.tip_body) + " is not a body (there are " +
                std::to_string(v.bodies.size()) + ")");
  require(finite(v.tip_point), "view", "the tip point");
  for (std::size_t i = 0; i < v.fixed.size(); ++i) {
    const std::string w =
        "view: fixed vector " + std::to_string(i) + " " + quoted(v.fixed[i].label);
    require(finite(v.fixed[i].origin), w, "origin");
    require(finite(v.fixed[i].vector), w, "vector");
  }
  for (std::size_t ri = 0; ri < v.runs.size(); ++ri) {
    const Run& r = v.runs[ri];
    const bool has_V = !r.frames.empty() && !r.frames[0].V.empty();
    const bool has_f = !r.frames.empty() && !r.frames[0].f.empty();
    for (std::size_t fi = 0; fi < r.frames.size(); ++fi) {
      const Frame& f = r.frames[fi];
      const std::string w = frame_where(r, ri, fi);
      require(std::isfinite(f.t), w, "the time");
      require(std::isfinite(f.energy), w, "the energy");
      check_per_body(f.pose, 7, v, w, "pose", true);
      check_per_body(f.V, 6, v, w, "V", has_V);
      check_per_body(f.f, 6, v, w, "f", has_f);
      require(finite(f.tip), w, "the tip");
    }
  }
}

}  // namespace soa::view::detail
