// Scene files: the strict JSON reader (the format is on the notes' page docs/scenes.md).
//
// Every problem becomes one soa::Error "<file>: <json path>: <problem>". The reader walks the
// document once, checking each value where it is read, then checks the chain as a whole
// (parents, loops, branches) and builds the model base first.
#include "soa/scene.hpp"

#include <Eigen/Eigenvalues>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <utility>

namespace soa {
namespace {

using json = nlohmann::json;

/// Tolerances of the format (docs/scenes.md states them).
constexpr double kUnitTol = 1e-6;       // quaternions: | |q| - 1 | <= 1e-6
constexpr double kZeroAxis = 1e-9;      // an axis shorter than this is "zero"
constexpr double kParallel = 1e-6;      // universal hinge: |a1 x a2| below this is parallel
constexpr double kSymmetricTol = 1e-9;  // inertia: |J - J*| <= 1e-9 max|J|
constexpr double kTriangleTol = 1e-9;   // inertia: a + b >= c (1 - 1e-9)

/// A short number for messages.
std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

/// "1 number", "3 numbers".
std::string count(std::size_t n, const char* noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

/// "a.b", "a[3]": JSON paths as messages show them; the root is "top level".
std::string key_path(const std::string& path, const std::string& key) {
  return path.empty() || path == "top level" ? key : path + "." + key;
}
std::string index_path(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

/// What a JSON value is, for "expected ..., got ..." messages.
std::string describe(const json& j) {
  switch (j.type()) {
    case json::value_t::string: {
      std::string s = j.get<std::string>();
      if (s.size() > 24) s = s.substr(0, 21) + "...";
      return "the string \"" + s + "\"";
    }
    case json::value_t::boolean:
      return j.get<bool>() ? "true" : "false";
    case json::value_t::array:
      return "an array";
    case json::value_t::object:
      return "an object";
    case json::value_t::null:
      return "null";
    default:
      return "the number " + j.dump();
  }
}

/// The hinge types by their names in scene files.
const std::map<std::string, HingeType>& hinge_types() {
  static const std::map<std::string, HingeType> types = {
      {"revolute", HingeType::Revolute},   {"prismatic", HingeType::Prismatic},
      {"helical", HingeType::Helical},     {"universal", HingeType::Universal},
      {"spherical", HingeType::Spherical}, {"free", HingeType::Free},
      {"locked", HingeType::Locked}};
  return types;
}

bool has_quaternion(HingeType t) {
  return t == HingeType::Spherical || t == HingeType::Free;
}

/// Reads values out of the document, failing with the file name and the JSON path.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw Error(file_ + ": " + path + ": " + problem);
  }

  void expect_object(const json& j, const std::string& path) const {
    if (!j.is_object()) fail(path, "expected an object, got " + describe(j));
  }

  /// Refuses a field that is not in \p allowed (a typo must not be silently ignored).
  void only_fields(const json& obj, const std::string& path,
                   std::initializer_list<const char*> allowed) const {
    for (const auto& item : obj.items()) {
      bool ok = false;
      for (const char* a : allowed) ok = ok || item.key() == a;
      if (!ok) fail(path, "unknown field \"" + item.key() + "\"");
    }
  }

  const json& required(const json& obj, const std::string& path, const char* key) const {
    const auto it = obj.find(key);
    if (it == obj.end()) fail(path, std::string("missing field \"") + key + "\"");
    return *it;
  }
  static const json* optional(const json& obj, const char* key) {
    const auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
  }

  double number(const json& j, const std::string& path) const {
    if (!j.is_number()) fail(path, "expected a number, got " + describe(j));
    const double x = j.get<double>();
    if (!std::isfinite(x)) fail(path, "not a finite number");
    return x;
  }
  std::string string(const json& j, const std::string& path) const {
    if (!j.is_string()) fail(path, "expected a string, got " + describe(j));
    return j.get<std::string>();
  }
  /// An array of numbers; \p n < 0 for any length, else exactly n (\p what explains n).
  std::vector<double> numbers(const json& j, const std::string& path, int n = -1,
                              const std::string& what = "") const {
    if (!j.is_array())
      fail(path, "expected an array of " + (n < 0 ? std::string("numbers") : count(n, "number")) +
                     ", got " + describe(j));
    if (n >= 0 && int(j.size()) != n)
      fail(path, "expected " + count(n, "number") + what + ", got " + std::to_string(j.size()));
    std::vector<double> x;
    for (std::size_t i = 0; i < j.size(); ++i) x.push_back(number(j[i], index_path(path, i)));
    return x;
  }
  Vec3<double> vec3(const json& j, const std::string& path) const {
    const std::vector<double> x = numbers(j, path, 3);
    return Vec3<double>(x[0], x[1], x[2]);
  }
  /// A direction: any non-zero 3-vector, normalized.
  Vec3<double> axis(const json& j, const std::string& path) const {
    const Vec3<double> a = vec3(j, path);
    if (!(a.norm() > kZeroAxis)) fail(path, "zero axis; an axis needs a direction");
    return a.normalized();
  }
  /// A unit quaternion [x, y, z, w], vector part first, norm 1 within 1e-6.
  UnitQuaternion quaternion(const json& j, const std::string& path) const {
    const std::vector<double> c = numbers(j, path, 4, " [x, y, z, w]");
    check_unit(c.data(), path, "");
    return UnitQuaternion(Vec3<double>(c[0], c[1], c[2]), c[3]);
  }
  void check_unit(const double* c, const std::string& path, const std::string& which) const {
    const double norm = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2] + c[3] * c[3]);
    if (!(std::abs(norm - 1) <= kUnitTol))
      fail(path, "not a unit quaternion" + which + " (norm " + num(norm) +
                     "; the norm must be 1 within 1e-6)");
  }

  /// The inertia about the centre of mass: a 3x3 matrix (rows) or {Ixx, ..., Iyz}; symmetric,
  /// positive definite, principal moments obeying the triangle inequality.
  Mat3<double> inertia(const json& j, const std::string& path) const {
    Mat3<double> J;
    if (j.is_array()) {
      if (j.size() != 3) fail(path, "expected 3 rows, got " + std::to_string(j.size()));
      for (int r = 0; r < 3; ++r) J.row(r) = vec3(j[r], index_path(path, r)).transpose();
    } else if (j.is_object()) {
      only_fields(j, path, {"Ixx", "Iyy", "Izz", "Ixy", "Ixz", "Iyz"});
      auto get = [&](const char* key) {
        const json* v = optional(j, key);
        return v ? number(*v, key_path(path, key)) : 0.0;
      };
      for (const char* key : {"Ixx", "Iyy", "Izz"}) required(j, path, key);
      J << get("Ixx"), get("Ixy"), get("Ixz"), get("Ixy"), get("Iyy"), get("Iyz"), get("Ixz"),
          get("Iyz"), get("Izz");
    } else {
      fail(path, "expected a 3x3 matrix (3 rows) or an object {\"Ixx\", ..., \"Iyz\"}, got " +
                     describe(j));
    }
    const double scale = J.cwiseAbs().maxCoeff();
    for (int r = 0; r < 3; ++r)
      for (int c = r + 1; c < 3; ++c)
        if (std::abs(J(r, c) - J(c, r)) > kSymmetricTol * scale)
          fail(path, "not symmetric ([" + std::to_string(r) + "][" + std::to_string(c) +
                         "] = " + num(J(r, c)) + " but [" + std::to_string(c) + "][" +
                         std::to_string(r) + "] = " + num(J(c, r)) + ")");
    J = (0.5 * (J + J.transpose())).eval();
    const Eigen::SelfAdjointEigenSolver<Mat3<double>> es(J, Eigen::EigenvaluesOnly);
    const Vec3<double> l = es.eigenvalues();  // ascending
    const std::string moments = num(l[0]) + ", " + num(l[1]) + ", " + num(l[2]);
    if (!(l[0] > 0)) fail(path, "not positive definite (principal moments " + moments + ")");
    if (l[0] + l[1] < l[2] * (1 - kTriangleTol))
      fail(path, "principal moments " + moments + " break the triangle inequality (" + num(l[0]) +
                     " + " + num(l[1]) + " < " + num(l[2]) + ")");
    return J;
  }

 private:
  std::string file_;
};

/// One body as the file gives it, before the chain is assembled.
struct FileBody {
  Body body;
  std::string parent;
  std::string path;                // "bodies[i]"
  std::vector<double> q, qd, qdd;  // per-hinge state, empty when absent
  bool has_q = false, has_qd = false, has_qdd = false;
};

/// Follows the JSON path while nlohmann parses (its callback sees every key and value), to
/// refuse a field given twice in one object (nlohmann would silently keep the last) and to
/// say where a number overflowed (nlohmann refuses 1e999 without saying where).
class PathTracker {
 public:
  explicit PathTracker(const Reader& r) : r_(r), stack_(std::make_shared<std::vector<Level>>()) {}

  bool operator()(int, json::parse_event_t ev, json& parsed) {
    std::vector<Level>& stack = *stack_;
    switch (ev) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        if (!stack.empty() && !stack.back().object) ++stack.back().index;
        stack.push_back({ev == json::parse_event_t::object_start, {}, {}, -1});
        break;
      case json::parse_event_t::key: {
        const std::string k = parsed.get<std::string>();
        if (!stack.back().keys.insert(k).second)
          r_.fail(path(stack.size() - 1), "field \"" + k + "\" given twice");
        stack.back().key = k;
        break;
      }
      case json::parse_event_t::value:
        if (!stack.empty() && !stack.back().object) ++stack.back().index;
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        stack.pop_back();
        break;
    }
    return true;
  }

  /// The path of the value being read when the parser stopped.
  std::string current() const { return path(stack_->size(), 1); }

 private:
  struct Level {
    bool object;
    std::set<std::string> keys;
    std::string key;  // the last key read (objects)
    int index;        // the index of the last element read (arrays)
  };
  /// The path of the value inside the first \p levels open containers (the next array
  /// element when \p next is 1).
  std::string path(std::size_t levels, int next = 0) const {
    std::string p;
    for (std::size_t i = 0; i < levels; ++i) {
      const Level& l = (*stack_)[i];
      p = l.object ? key_path(p, l.key) : index_path(p, l.index + (i + 1 == levels ? next : 0));
    }
    return p.empty() ? "top level" : p;
  }
  const Reader& r_;
  std::shared_ptr<std::vector<Level>> stack_;  // shared with the copy nlohmann keeps
};

json parse_json(const std::string& text, const Reader& r) {
  const PathTracker tracker(r);
  try {
    return json::parse(text, tracker, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const json::parse_error& e) {
    // "[json.exception.parse_error.101] parse error at line 3, column 5: <detail>"
    const std::string w = e.what();
    const std::size_t at = w.find(" at line ");
    const std::size_t colon = at == std::string::npos ? at : w.find(": ", at);
    if (colon == std::string::npos) r.fail("top level", std::string("invalid JSON: ") + w);
    r.fail(w.substr(at + 4, colon - at - 4), "invalid JSON: " + w.substr(colon + 2));
  } catch (const json::out_of_range& e) {
    // "[json.exception.out_of_range.406] number overflow parsing '1e999'"
    const std::string w = e.what();
    const std::size_t quote = w.find('\'');
    const std::string number =
        quote == std::string::npos ? "a number" : w.substr(quote + 1, w.size() - quote - 2);
    r.fail(tracker.current(),
           "not a finite number (" + number + " is out of the range of a double)");
  }
}

/// The hinge of a body: type, axes, pitch and placement.
void read_hinge(const Reader& r, const json& j, const std::string& path, Body& b) {
  r.expect_object(j, path);
  const std::string type_path = key_path(path, "type");
  const std::string type = r.string(r.required(j, path, "type"), type_path);
  const auto it = hinge_types().find(type);
  if (it == hinge_types().end())
    r.fail(type_path, "unknown hinge type \"" + type +
                          "\" (expected revolute, prismatic, helical, universal, spherical, "
                          "free or locked)");
  b.hinge.type = it->second;
  const HingeType t = b.hinge.type;
  const bool one_axis = t == HingeType::Revolute || t == HingeType::Prismatic ||
                        t == HingeType::Helical || t == HingeType::Universal;
  for (const auto& item : j.items()) {
    const std::string& k = item.key();
    const bool applies = k == "type" || k == "placement" || (k == "axis" && one_axis) ||
                         (k == "axis2" && t == HingeType::Universal) ||
                         (k == "pitch" && t == HingeType::Helical);
    if (applies) continue;
    if (k == "axis" || k == "axis2" || k == "pitch")
      r.fail(path, "field \"" + k + "\" does not apply to a " + type + " hinge");
    r.fail(path, "unknown field \"" + k + "\"");
  }
  if (one_axis) b.hinge.axis = r.axis(r.required(j, path, "axis"), key_path(path, "axis"));
  if (t == HingeType::Universal) {
    const std::string p2 = key_path(path, "axis2");
    b.hinge.axis2 = r.axis(r.required(j, path, "axis2"), p2);
    if (b.hinge.axis.cross(b.hinge.axis2).norm() < kParallel)
      r.fail(p2, "parallel to axis; a universal hinge needs two different axes");
  }
  if (t == HingeType::Helical)
    b.hinge.pitch = r.number(r.required(j, path, "pitch"), key_path(path, "pitch"));
  if (const json* p = Reader::optional(j, "placement")) {
    const std::string pp = key_path(path, "placement");
    r.expect_object(*p, pp);
    r.only_fields(*p, pp, {"position", "rotation"});
    Vec3<double> l = Vec3<double>::Zero();
    Mat3<double> R = Mat3<double>::Identity();
    if (const json* x = Reader::optional(*p, "position")) l = r.vec3(*x, key_path(pp, "position"));
    if (const json* x = Reader::optional(*p, "rotation"))
      R = r.quaternion(*x, key_path(pp, "rotation")).matrix();
    b.placement = Pose(R, l);
  }
}

/// The optional joint spring and damper.
void read_spring(const Reader& r, const json& j, const std::string& path, Body& b) {
  r.expect_object(j, path);
  r.only_fields(j, path, {"stiffness", "damping", "rest"});
  const HingeType t = b.hinge.type;
  if (t == HingeType::Locked) r.fail(path, "a locked hinge has no spring");
  auto coefficient = [&](const char* key) {
    const json* v = Reader::optional(j, key);
    const double x = v ? r.number(*v, key_path(path, key)) : 0.0;
    if (x < 0) r.fail(key_path(path, key), "must not be negative (got " + num(x) + ")");
    return x;
  };
  b.stiffness = coefficient("stiffness");
  b.damping = coefficient("damping");
  if (const json* v = Reader::optional(j, "rest")) {
    if (has_quaternion(t))
      r.fail(key_path(path, "rest"), std::string("a ") + hinge_type_name(t) +
                                         " spring pulls toward the identity; \"rest\" applies "
                                         "to 1-dof and universal hinges only");
    const int n = b.hinge.nq();
    const std::vector<double> x = r.numbers(*v, key_path(path, "rest"), n,
                                            std::string(" for a ") + hinge_type_name(t) + " hinge");
    b.rest = Eigen::Map<const VecX<double>>(x.data(), n);
  }
}

/// A per-body state vector ("q", "qd", "qdd") of the hinge's size.
std::vector<double> read_state(const Reader& r, const json& j, const std::string& path,
                               const Hinge& h, bool configuration) {
  const int n = configuration ? h.nq() : h.nv();
  std::vector<double> x =
      r.numbers(j, path, n, std::string(" for a ") + hinge_type_name(h.type) + " hinge");
  if (configuration && has_quaternion(h.type)) {
    r.check_unit(x.data(), path, " in entries 0-3");
    const UnitQuaternion q(Vec3<double>(x[0], x[1], x[2]), x[3]);
    for (int i = 0; i < 4; ++i) x[i] = q.coeffs()[i];
  }
  return x;
}

FileBody read_body(const Reader& r, const json& j, const std::string& path) {
  r.expect_object(j, path);
  r.only_fields(j, path,
                {"name", "parent", "mass", "com", "inertia", "hinge", "spring", "q", "qd", "qdd"});
  FileBody fb;
  fb.path = path;
  Body& b = fb.body;
  b.name = r.string(r.required(j, path, "name"), key_path(path, "name"));
  if (b.name.empty()) r.fail(key_path(path, "name"), "empty name");
  if (b.name == "base") r.fail(key_path(path, "name"), "\"base\" names the ground; pick another");
  fb.parent = r.string(r.required(j, path, "parent"), key_path(path, "parent"));
  const double m = r.number(r.required(j, path, "mass"), key_path(path, "mass"));
  if (!(m > 0)) r.fail(key_path(path, "mass"), "must be positive (got " + num(m) + ")");
  const Vec3<double> com = r.vec3(r.required(j, path, "com"), key_path(path, "com"));
  const Mat3<double> J = r.inertia(r.required(j, path, "inertia"), key_path(path, "inertia"));
  b.M = SpatialInertia::from_cm(m, com, J);
  read_hinge(r, r.required(j, path, "hinge"), key_path(path, "hinge"), b);
  if (const json* s = Reader::optional(j, "spring"))
    read_spring(r, *s, key_path(path, "spring"), b);
  if (const json* v = Reader::optional(j, "q")) {
    fb.q = read_state(r, *v, key_path(path, "q"), b.hinge, true);
    fb.has_q = true;
  }
  if (const json* v = Reader::optional(j, "qd")) {
    fb.qd = read_state(r, *v, key_path(path, "qd"), b.hinge, false);
    fb.has_qd = true;
  }
  if (const json* v = Reader::optional(j, "qdd")) {
    fb.qdd = read_state(r, *v, key_path(path, "qdd"), b.hinge, false);
    fb.has_qdd = true;
  }
  return fb;
}

/// The chain from the base out, as indices into \p bodies; refuses unknown parents, branches,
/// loops, and a file that does not list the chain base first.
std::vector<std::size_t> chain_order(const Reader& r, const std::vector<FileBody>& bodies) {
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < bodies.size(); ++i) index[bodies[i].body.name] = i;
  std::map<std::string, std::size_t> child;  // parent name -> the body hanging from it
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const FileBody& b = bodies[i];
    const std::string path = key_path(b.path, "parent");
    if (b.parent != "base" && index.count(b.parent) == 0)
      r.fail(path, "no body named \"" + b.parent + "\" (a parent is \"base\" or a body's name)");
    const auto [it, fresh] = child.emplace(b.parent, i);
    if (!fresh)
      r.fail(path, "\"" + b.parent + "\" already has a child (" + bodies[it->second].path +
                       "); serial chains only, no branches");
  }
  std::vector<std::size_t> order;
  for (auto it = child.find("base"); it != child.end();
       it = child.find(bodies[it->second].body.name))
    order.push_back(it->second);
  if (order.size() == bodies.size()) {
    // The chain is sound; the file must list it base first, so that "file order" (of --q,
    // of the output) is the order of the chain.
    for (std::size_t i = 0; i < order.size(); ++i)
      if (order[i] != i)
        r.fail(key_path(bodies[i].path, "parent"),
               "\"" + bodies[i].parent + "\" is listed after this body (" +
                   bodies[index.at(bodies[i].parent)].path +
                   "); list the bodies base first, each after its parent");
    return order;
  }
  // Every parent exists and none has two children: the bodies not reached form a loop.
  std::vector<bool> reached(bodies.size(), false);
  for (std::size_t i : order) reached[i] = true;
  std::size_t first = 0;
  while (reached[first]) ++first;
  std::string cycle = bodies[first].body.name;
  for (std::size_t i = index.at(bodies[first].parent); i != first; i = index.at(bodies[i].parent))
    cycle += " -> " + bodies[i].body.name;
  cycle += " -> " + bodies[first].body.name;
  r.fail(key_path(bodies[first].path, "parent"),
         "loop (" + cycle + ", following parents) never reaches \"base\"");
}

Scene read_scene(const json& doc, const Reader& r, const std::string& file) {
  Scene s;
  s.name = file;
  const std::string top = "top level";
  r.expect_object(doc, top);
  r.only_fields(doc, top, {"name", "gravity", "bodies", "external_forces", "compute"});
  if (const json* v = Reader::optional(doc, "name")) {
    s.title = r.string(*v, "name");
  } else {
    const std::size_t slash = file.find_last_of("/\\");
    s.title = file.substr(slash == std::string::npos ? 0 : slash + 1);
    const std::size_t dot = s.title.rfind('.');
    if (dot != std::string::npos && dot > 0) s.title.resize(dot);
  }
  Vec3<double> gravity = Vec3<double>::Zero();
  if (const json* v = Reader::optional(doc, "gravity")) gravity = r.vec3(*v, "gravity");

  // The bodies, each checked on its own, in file order.
  const json& jb = r.required(doc, top, "bodies");
  if (!jb.is_array()) r.fail("bodies", "expected an array of bodies, got " + describe(jb));
  if (jb.empty()) r.fail("bodies", "empty; a scene needs at least one body");
  std::vector<FileBody> bodies;
  std::map<std::string, std::string> seen;  // name -> path
  for (std::size_t i = 0; i < jb.size(); ++i) {
    bodies.push_back(read_body(r, jb[i], index_path("bodies", i)));
    const FileBody& b = bodies.back();
    const auto [it, fresh] = seen.emplace(b.body.name, b.path);
    if (!fresh)
      r.fail(key_path(b.path, "name"),
             "duplicate name \"" + b.body.name + "\" (" + it->second + " has it too)");
  }

  // The chain, base first; locked bodies merge into their inboard neighbour.
  const std::vector<std::size_t> order = chain_order(r, bodies);
  if (bodies[order[0]].body.hinge.type == HingeType::Locked)
    r.fail(key_path(bodies[order[0]].path, "hinge.type"),
           "a locked hinge next to the base fixes the body to the ground; remove the body or "
           "give it another hinge");
  int n = 0;
  for (const FileBody& b : bodies) n += b.body.hinge.type != HingeType::Locked;
  std::vector<Scene::Frame> frame(bodies.size());
  std::vector<Body> base_first;
  int kept = 0;
  for (std::size_t c = 0; c < order.size(); ++c) {
    const FileBody& b = bodies[order[c]];
    Scene::Frame& f = frame[order[c]];
    f.name = b.body.name;
    if (b.body.hinge.type == HingeType::Locked) {
      const Scene::Frame& inboard = frame[order[c - 1]];
      f.k = inboard.k;
      f.offset = inboard.offset * b.body.placement;
      f.locked = true;
    } else {
      f.k = n - kept++;
    }
    base_first.push_back(b.body);
  }
  s.model = Model::from_base_first(std::move(base_first));
  s.model.gravity = gravity;
  s.frames = frame;
  for (const Scene::Frame& f : frame)
    if (!f.locked) s.file_order.push_back(f.k);

  // The initial state, body by body (model order is tip first).
  s.state = State::rest(s.model);
  s.beta_dot = VecX<double>::Zero(s.model.nv());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (frame[i].locked) continue;
    const Body& B = s.model.body(frame[i].k);
    const FileBody& b = bodies[i];
    if (b.has_q)
      s.state.theta.segment(B.q_offset, B.hinge.nq()) =
          Eigen::Map<const VecX<double>>(b.q.data(), B.hinge.nq());
    if (b.has_qd)
      s.state.beta.segment(B.v_offset, B.hinge.nv()) =
          Eigen::Map<const VecX<double>>(b.qd.data(), B.hinge.nv());
    if (b.has_qdd)
      s.beta_dot.segment(B.v_offset, B.hinge.nv()) =
          Eigen::Map<const VecX<double>>(b.qdd.data(), B.hinge.nv());
  }

  // External forces, moved to O_k of the model body (a locked body's force by phi(O_k, F)).
  if (const json* v = Reader::optional(doc, "external_forces")) {
    if (!v->is_array())
      r.fail("external_forces", "expected an array of forces, got " + describe(*v));
    if (!v->empty()) s.f_ext.assign(s.model.n(), Force());
    for (std::size_t i = 0; i < v->size(); ++i) {
      const std::string path = index_path("external_forces", i);
      const json& e = (*v)[i];
      r.expect_object(e, path);
      r.only_fields(e, path, {"body", "moment", "force"});
      const std::string name = r.string(r.required(e, path, "body"), key_path(path, "body"));
      std::size_t b = 0;
      while (b < bodies.size() && bodies[b].body.name != name) ++b;
      if (b == bodies.size()) r.fail(key_path(path, "body"), "no body named \"" + name + "\"");
      Vec3<double> N = Vec3<double>::Zero(), F = Vec3<double>::Zero();
      if (const json* x = Reader::optional(e, "moment")) N = r.vec3(*x, key_path(path, "moment"));
      if (const json* x = Reader::optional(e, "force")) F = r.vec3(*x, key_path(path, "force"));
      s.f_ext[frame[b].k - 1] += Phi(frame[b].offset).apply(Force(N, F));
    }
  }

  if (const json* v = Reader::optional(doc, "compute")) {
    if (!v->is_array()) r.fail("compute", "expected an array of strings, got " + describe(*v));
    for (std::size_t i = 0; i < v->size(); ++i) {
      const std::string what = r.string((*v)[i], index_path("compute", i));
      if (what != "kinematics" && what != "jacobian" && what != "inverse-dynamics" &&
          what != "mass-matrix")
        r.fail(index_path("compute", i),
               "unknown computation \"" + what +
                   "\" (expected kinematics, jacobian, inverse-dynamics or mass-matrix)");
      s.compute.push_back(what);
    }
  }
  return s;
}

}  // namespace

Scene parse_scene(const std::string& json_text, const std::string& name) {
  const Reader r(name);
  try {
    return read_scene(parse_json(json_text, r), r, name);
  } catch (const json::exception& e) {  // not expected: every value is checked before use
    r.fail("top level", e.what());
  }
}

Scene load_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the file (" + std::strerror(errno) + ")");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(path + ": cannot read the file");
  return parse_scene(text.str(), path);
}

std::vector<int> file_q_index(const Scene& scene) {
  std::vector<int> idx;
  for (int k : scene.file_order)
    for (int i = 0; i < scene.model.body(k).hinge.nq(); ++i)
      idx.push_back(scene.model.body(k).q_offset + i);
  return idx;
}

std::vector<int> file_v_index(const Scene& scene) {
  std::vector<int> idx;
  for (int k : scene.file_order)
    for (int i = 0; i < scene.model.body(k).hinge.nv(); ++i)
      idx.push_back(scene.model.body(k).v_offset + i);
  return idx;
}

namespace {

VecX<double> from_file_order(const std::vector<int>& idx, const std::vector<double>& x) {
  if (x.size() != idx.size())
    throw Error("expected " + count(idx.size(), "number") + ", got " + std::to_string(x.size()));
  VecX<double> out(idx.size());
  for (std::size_t i = 0; i < idx.size(); ++i) {
    if (!std::isfinite(x[i])) throw Error("entry " + std::to_string(i) + " is not finite");
    out[idx[i]] = x[i];
  }
  return out;
}

}  // namespace

VecX<double> theta_from_file_order(const Scene& scene, const std::vector<double>& q) {
  VecX<double> theta = from_file_order(file_q_index(scene), q);
  for (int k : scene.file_order) {
    const Body& B = scene.model.body(k);
    if (!has_quaternion(B.hinge.type)) continue;
    double* c = theta.data() + B.q_offset;
    const double norm = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2] + c[3] * c[3]);
    if (!(std::abs(norm - 1) <= kUnitTol))
      throw Error("the quaternion of body \"" + B.name + "\" is not of unit norm (norm " +
                  num(norm) + "; the norm must be 1 within 1e-6)");
    const UnitQuaternion u(Vec3<double>(c[0], c[1], c[2]), c[3]);
    for (int i = 0; i < 4; ++i) c[i] = u.coeffs()[i];
  }
  return theta;
}

VecX<double> beta_from_file_order(const Scene& scene, const std::vector<double>& v) {
  return from_file_order(file_v_index(scene), v);
}

}  // namespace soa
