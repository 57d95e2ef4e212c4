// Scene files: the strict JSON reader (the format is on the notes' page docs/scenes.md).
//
// Every problem becomes one soa::Error "<file>: <json path>: <problem>". Reading is O(n) in
// time and memory: the bytes come through a small buffer (Bytes), nlohmann's SAX events build
// the document (SceneSax, which also refuses a key given twice, says where a number
// overflowed and bounds the nesting), and each element of the top-level "bodies" array is
// checked (read_body) and dropped as soon as it is complete, so that only its Body is kept.
// The chain is then checked as a whole (parents, loops, branches) and built base first.
#include "soa/scene.hpp"

#include "scene_detail.hpp"
#include "soa/printable.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <new>
#include <nlohmann/json.hpp>
#include <unordered_map>
#include <utility>

namespace soa {
namespace {

using json = nlohmann::json;

/// Tolerances of the format (docs/scenes.md states them).
constexpr double kUnitTol = 1e-6;        // quaternions: | |q| - 1 | <= 1e-6
constexpr double kZeroAxis = 1e-9;       // an axis shorter than this is "zero"
constexpr double kParallel = 1e-6;       // universal hinge: |a1 x a2| below this is parallel
constexpr double kSymmetricTol = 1e-9;   // inertia: |J - J*| <= 1e-9 max|J|
constexpr double kTriangleTol = 1e-9;    // inertia: a + b >= c (1 - 1e-9)
constexpr double kMaxPlacement = 1e150;  // |position| of a placement (m): its square is finite

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

/// A string of the file in double quotes, as a message shows it (soa::printable()).
std::string in_quotes(const std::string& s) {
  return "\"" + printable(s) + "\"";
}

/// "bodies[3]".
std::string body_path(std::size_t i) {
  return "bodies[" + std::to_string(i) + "]";
}

/// A JSON path as messages show it ("bodies[3].hinge.axis"; the root is "top level"): a chain
/// of nodes on the stack, one per level the reader descends, spelled out only for a message.
/// A node refers to its parent: name each level (`const Path p = body.key("hinge");`) rather
/// than keeping a chain of temporaries.
class Path {
 public:
  Path() = default;  // the top level
  Path key(const char* k) const { return Path(this, k, 0); }
  Path index(std::size_t i) const { return Path(this, nullptr, i); }
  std::string str() const {
    if (!up_) return "top level";
    const std::string p = up_->up_ ? up_->str() : std::string();
    if (key_) return p.empty() ? std::string(key_) : p + "." + key_;
    return p + "[" + std::to_string(index_) + "]";
  }

 private:
  Path(const Path* up, const char* key, std::size_t index) : up_(up), key_(key), index_(index) {}
  const Path* up_ = nullptr;
  const char* key_ = nullptr;
  std::size_t index_ = 0;
};
const Path kTop;
const Path kBodies = kTop.key("bodies");

/// What a JSON value is, for "expected ..., got ..." messages.
std::string describe(const json& j) {
  switch (j.type()) {
    case json::value_t::string: {
      std::string s = j.get<std::string>();
      if (s.size() > 24) {
        std::size_t cut = 21;
        while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;
        s = s.substr(0, cut) + "...";
      }
      return "the string " + in_quotes(s);
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

/// Frees a document without nlohmann's destructor on it: that allocates (a stack, to flatten
/// deep documents), and std::bad_alloc in a destructor ends the program; here it is an
/// exception like any other. Each container is emptied before it is destroyed.
void dismantle(json& doc) {
  std::vector<json> stack;
  stack.push_back(std::move(doc));
  while (!stack.empty()) {
    json j = std::move(stack.back());
    stack.pop_back();
    if (j.is_array()) {
      for (json& x : j.get_ref<json::array_t&>())
        if (x.is_structured()) stack.push_back(std::move(x));
      j.get_ref<json::array_t&>().clear();
    } else if (j.is_object()) {
      for (auto& item : j.get_ref<json::object_t&>())
        if (item.second.is_structured()) stack.push_back(std::move(item.second));
      j.get_ref<json::object_t&>().clear();
    }
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

bool is_top_field(const std::string& k) {
  return k == "name" || k == "gravity" || k == "bodies" || k == "external_forces" || k == "compute";
}

/// The sum of squares is a normal double (neither overflows nor underflows).
bool plain_norm_is_safe(double squared_norm) {
  return squared_norm >= std::numeric_limits<double>::min() &&
         squared_norm <= std::numeric_limits<double>::max();
}

/// |x| without overflow or underflow: the plain formula where it is safe (the same bits as
/// always), Eigen's scaled one elsewhere (a component of 1e200 is fine).
template <class Derived>
double safe_norm(const Eigen::MatrixBase<Derived>& x) {
  const double n2 = x.squaredNorm();
  return plain_norm_is_safe(n2) ? std::sqrt(n2) : x.stableNorm();
}

/// x / |x| for x != 0, safe in the same way: x scaled by its largest component first (Eigen's
/// stableNormalized() still overflows for [1.7e308, 1.7e308, 1.7e308]).
Vec3<double> safe_normalized(const Vec3<double>& x) {
  const double n2 = x.squaredNorm();
  if (plain_norm_is_safe(n2)) return x / std::sqrt(n2);
  const Vec3<double> y = x / x.cwiseAbs().maxCoeff();
  return y / y.norm();
}

bool is_finite(const SpatialInertia& M) {
  return std::isfinite(M.mass()) && M.h().allFinite() && M.J().allFinite();
}

}  // namespace

namespace detail {

/// (scene_detail.hpp)
std::string inertia_problem(Mat3<double>& J) {
  const double scale = J.cwiseAbs().maxCoeff();
  for (int r = 0; r < 3; ++r)
    for (int c = r + 1; c < 3; ++c)
      if (std::abs(J(r, c) - J(c, r)) > kSymmetricTol * scale)
        return ("not symmetric ([" + std::to_string(r) + "][" + std::to_string(c) +
                "] = " + num(J(r, c)) + " but [" + std::to_string(c) + "][" + std::to_string(r) +
                "] = " + num(J(c, r)) + ")");
  J = (0.5 * J + 0.5 * J.transpose()).eval();  // J + J* would overflow near 1e308
  // The principal moments of J / 2^e, 2^e near the largest entry (exact scalings, so the
  // checks and the moments are those of J, without overflow); then of J for the messages.
  int e = 0;
  std::frexp(scale, &e);
  const double s = std::ldexp(1.0, e - 1);
  const Eigen::SelfAdjointEigenSolver<Mat3<double>> es(J / s, Eigen::EigenvaluesOnly);
  const Vec3<double> ls = es.eigenvalues();  // ascending
  const Vec3<double> l = ls * s;
  if (!l.allFinite())
    return ("overflows (entries up to " + num(scale) +
            "; the principal moments are out of the range of a double)");
  auto moments = [&] { return num(l[0]) + ", " + num(l[1]) + ", " + num(l[2]); };
  if (!(ls[0] > 0)) return ("not positive definite (principal moments " + moments() + ")");
  if (ls[0] + ls[1] < ls[2] * (1 - kTriangleTol))
    return ("principal moments " + moments() + " break the triangle inequality (" + num(l[0]) +
            " + " + num(l[1]) + " < " + num(l[2]) + ")");
  return "";
}

}  // namespace detail

namespace {

/// Reads values out of the document, failing with the file name and the JSON path.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}
  /// A reader of a URDF's document: "bodies[i]" is link names[i].first, "bodies[i].hinge"
  /// joint names[i].second.
  Reader(std::string file, const std::vector<std::pair<std::string, std::string>>& names)
      : file_(std::move(file)), names_(&names) {}
  const std::string& file() const { return file_; }

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw Error(file_ + ": " + named(path) + ": " + problem);
  }
  [[noreturn]] void fail(const Path& path, const std::string& problem) const {
    fail(path.str(), problem);
  }
  /// A problem of the file itself: "<file>: <problem>".
  [[noreturn]] void fail_file(const std::string& problem) const {
    throw Error(file_ + ": " + problem);
  }

  /// \p path, with a URDF's link or joint for "bodies[i]" ("joint 'j1' axis").
  std::string named(const std::string& path) const {
    const std::string prefix = "bodies[";
    if (!names_ || path.compare(0, prefix.size(), prefix) != 0) return path;
    const std::size_t close = path.find(']');
    const std::size_t i = std::stoul(path.substr(prefix.size(), close - prefix.size()));
    if (i >= names_->size()) return path;
    std::string rest = path.substr(close + 1);
    const bool hinge = rest.compare(0, 6, ".hinge") == 0;
    const std::string who = hinge ? "joint '" + printable((*names_)[i].second) + "'"
                                  : "link '" + printable((*names_)[i].first) + "'";
    if (hinge) rest = rest.substr(6);
    if (!rest.empty() && rest[0] == '.') rest = " " + rest.substr(1);
    return who + rest;
  }

  void expect_object(const json& j, const Path& path) const {
    if (!j.is_object()) fail(path, "expected an object, got " + describe(j));
  }

  /// Refuses a field that is not in \p allowed (a typo must not be silently ignored).
  void only_fields(const json& obj, const Path& path,
                   std::initializer_list<const char*> allowed) const {
    for (const auto& item : obj.items()) {
      bool ok = false;
      for (const char* a : allowed) ok = ok || item.key() == a;
      if (!ok) fail(path, "unknown field " + in_quotes(item.key()));
    }
  }

  const json& required(const json& obj, const Path& path, const char* key) const {
    const auto it = obj.find(key);
    if (it == obj.end()) fail(path, std::string("missing field \"") + key + "\"");
    return *it;
  }
  static const json* optional(const json& obj, const char* key) {
    const auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
  }

  double number(const json& j, const Path& path) const {
    if (!j.is_number()) fail(path, "expected a number, got " + describe(j));
    const double x = j.get<double>();
    if (!std::isfinite(x)) fail(path, "not a finite number");
    return x;
  }
  std::string string(const json& j, const Path& path) const {
    if (!j.is_string()) fail(path, "expected a string, got " + describe(j));
    return j.get<std::string>();
  }
  /// An array of numbers; \p n < 0 for any length, else exactly n (\p what explains n).
  std::vector<double> numbers(const json& j, const Path& path, int n = -1,
                              const std::string& what = "") const {
    if (!j.is_array())
      fail(path, "expected an array of " + (n < 0 ? std::string("numbers") : count(n, "number")) +
                     ", got " + describe(j));
    if (n >= 0 && int(j.size()) != n)
      fail(path, "expected " + count(n, "number") + what + ", got " + std::to_string(j.size()));
    std::vector<double> x;
    x.reserve(j.size());
    for (std::size_t i = 0; i < j.size(); ++i) x.push_back(number(j[i], path.index(i)));
    return x;
  }
  Vec3<double> vec3(const json& j, const Path& path) const {
    const std::vector<double> x = numbers(j, path, 3);
    return Vec3<double>(x[0], x[1], x[2]);
  }
  /// A direction: any non-zero 3-vector, normalized (without overflow: [2e154, 0, 0] is x).
  Vec3<double> axis(const json& j, const Path& path) const {
    const Vec3<double> a = vec3(j, path);
    if (!(safe_norm(a) > kZeroAxis)) fail(path, "zero axis; an axis needs a direction");
    return safe_normalized(a);
  }
  /// A unit quaternion [x, y, z, w], vector part first, norm 1 within 1e-6.
  UnitQuaternion quaternion(const json& j, const Path& path) const {
    const std::vector<double> c = numbers(j, path, 4, " [x, y, z, w]");
    check_unit(c.data(), path, "");
    return UnitQuaternion(Vec3<double>(c[0], c[1], c[2]), c[3]);
  }
  void check_unit(const double* c, const Path& path, const std::string& which) const {
    const double norm = safe_norm(Eigen::Map<const Eigen::Vector4d>(c));
    if (!(std::abs(norm - 1) <= kUnitTol))
      fail(path, "not a unit quaternion" + which + " (norm " + num(norm) +
                     "; the norm must be 1 within 1e-6)");
  }

  /// The inertia about the centre of mass: a 3x3 matrix (rows) or {Ixx, ..., Iyz}; symmetric,
  /// positive definite, principal moments obeying the triangle inequality, none overflowing.
  Mat3<double> inertia(const json& j, const Path& path) const {
    Mat3<double> J;
    if (j.is_array()) {
      if (j.size() != 3) fail(path, "expected 3 rows, got " + std::to_string(j.size()));
      for (int r = 0; r < 3; ++r) J.row(r) = vec3(j[r], path.index(r)).transpose();
    } else if (j.is_object()) {
      only_fields(j, path, {"Ixx", "Iyy", "Izz", "Ixy", "Ixz", "Iyz"});
      auto get = [&](const char* key) {
        const json* v = optional(j, key);
        return v ? number(*v, path.key(key)) : 0.0;
      };
      for (const char* key : {"Ixx", "Iyy", "Izz"}) required(j, path, key);
      // Every value is read before the matrix is filled: a throw inside Eigen's comma
      // initializer trips its assertion (an abort) in builds without NDEBUG.
      const double xx = get("Ixx"), xy = get("Ixy"), xz = get("Ixz"), yy = get("Iyy"),
                   yz = get("Iyz"), zz = get("Izz");
      J << xx, xy, xz, xy, yy, yz, xz, yz, zz;
    } else {
      fail(path, "expected a 3x3 matrix (3 rows) or an object {\"Ixx\", ..., \"Iyz\"}, got " +
                     describe(j));
    }
    const std::string problem = detail::inertia_problem(J);
    if (!problem.empty()) fail(path, problem);
    return J;
  }

 private:
  std::string file_;
  const std::vector<std::pair<std::string, std::string>>* names_ = nullptr;
};

/// What the reader keeps of the bodies while it streams them, in file order: the Body and
/// little else (a name -> index map, the parents as indices, the given state values).
struct FileBodies {
  static constexpr std::size_t kBase = std::size_t(-1);     // the parent is the base
  static constexpr std::size_t kLater = std::size_t(-2);    // a name not listed before (later)
  static constexpr std::size_t kUnknown = std::size_t(-3);  // a name no body has
  enum Flag : unsigned char { kQ = 1, kQd = 2, kQdd = 4, kLocked = 8, kMassless = 16 };

  std::size_t count = 0;
  std::vector<Body> body;
  std::vector<std::size_t> parent;  // the parent's index, or kBase, kLater, kUnknown
  std::vector<std::pair<std::size_t, std::string>> later;   // (body, parent name), by body
  std::unordered_map<std::string, std::size_t> index;       // name -> body
  std::vector<unsigned char> flags;                         // Flag bits
  std::vector<double> q, qd, qdd;                           // the values given, body by body
  std::vector<std::pair<std::size_t, HingeLimits>> limits;  // (body, its limits), by body

  /// The parents listed after their child (or not at all), now that every name is known.
  void resolve_later() {
    for (const auto& [i, name] : later) {
      const auto it = index.find(name);
      parent[i] = it == index.end() ? kUnknown : it->second;
    }
  }
  std::string parent_name(std::size_t i) const {
    const std::size_t p = parent[i];
    if (p == kBase) return "base";
    if (p < count) return body[p].name;
    const auto it = std::lower_bound(later.begin(), later.end(), i,
                                     [](const auto& l, std::size_t b) { return l.first < b; });
    return it->second;
  }
};

/// The hinge of a body: type, axes, pitch and placement; returns its "name" ("" when none).
std::string read_hinge(const Reader& r, const json& j, const Path& path, Body& b) {
  r.expect_object(j, path);
  const Path type_path = path.key("type");
  const std::string type = r.string(r.required(j, path, "type"), type_path);
  const auto it = hinge_types().find(type);
  if (it == hinge_types().end())
    r.fail(type_path, "unknown hinge type " + in_quotes(type) +
                          " (expected revolute, prismatic, helical, universal, spherical, "
                          "free or locked)");
  b.hinge.type = it->second;
  const HingeType t = b.hinge.type;
  const bool one_axis = t == HingeType::Revolute || t == HingeType::Prismatic ||
                        t == HingeType::Helical || t == HingeType::Universal;
  for (const auto& item : j.items()) {
    const std::string& k = item.key();
    const bool applies = k == "type" || k == "name" || k == "placement" ||
                         (k == "axis" && one_axis) || (k == "axis2" && t == HingeType::Universal) ||
                         (k == "pitch" && t == HingeType::Helical);
    if (applies) continue;
    if (k == "axis" || k == "axis2" || k == "pitch")
      r.fail(path, "field \"" + k + "\" does not apply to a " + type + " hinge");
    r.fail(path, "unknown field " + in_quotes(k));
  }
  if (one_axis) b.hinge.axis = r.axis(r.required(j, path, "axis"), path.key("axis"));
  if (t == HingeType::Universal) {
    const Path p2 = path.key("axis2");
    b.hinge.axis2 = r.axis(r.required(j, path, "axis2"), p2);
    if (b.hinge.axis.cross(b.hinge.axis2).norm() < kParallel)
      r.fail(p2, "parallel to axis; a universal hinge needs two different axes");
  }
  if (t == HingeType::Helical)
    b.hinge.pitch = r.number(r.required(j, path, "pitch"), path.key("pitch"));
  if (const json* p = Reader::optional(j, "placement")) {
    const Path pp = path.key("placement");
    r.expect_object(*p, pp);
    r.only_fields(*p, pp, {"position", "rotation"});
    Vec3<double> l = Vec3<double>::Zero();
    Mat3<double> R = Mat3<double>::Identity();
    if (const json* x = Reader::optional(*p, "position")) {
      l = r.vec3(*x, pp.key("position"));
      if (!(safe_norm(l) <= kMaxPlacement))
        r.fail(pp.key("position"), num(safe_norm(l)) +
                                       " m from the parent's frame, more than the 1e+150 m a "
                                       "placement may have (its products would overflow)");
    }
    if (const json* x = Reader::optional(*p, "rotation"))
      R = r.quaternion(*x, pp.key("rotation")).matrix();
    b.placement = Pose(R, l);
  }
  const json* name = Reader::optional(j, "name");
  return name ? r.string(*name, path.key("name")) : std::string();
}

/// The optional joint spring and damper.
void read_spring(const Reader& r, const json& j, const Path& path, Body& b) {
  r.expect_object(j, path);
  r.only_fields(j, path, {"stiffness", "damping", "rest"});
  const HingeType t = b.hinge.type;
  if (t == HingeType::Locked) r.fail(path, "a locked hinge has no spring");
  auto coefficient = [&](const char* key) {
    const json* v = Reader::optional(j, key);
    const double x = v ? r.number(*v, path.key(key)) : 0.0;
    if (x < 0) r.fail(path.key(key), "must not be negative (got " + num(x) + ")");
    return x;
  };
  b.stiffness = coefficient("stiffness");
  b.damping = coefficient("damping");
  if (const json* v = Reader::optional(j, "rest")) {
    const Path rest = path.key("rest");
    if (has_quaternion(t))
      r.fail(rest, std::string("a ") + hinge_type_name(t) +
                       " spring pulls toward the identity; \"rest\" applies to 1-dof and "
                       "universal hinges only");
    const int n = b.hinge.nq();
    const std::vector<double> x =
        r.numbers(*v, rest, n, std::string(" for a ") + hinge_type_name(t) + " hinge");
    b.rest = Eigen::Map<const VecX<double>>(x.data(), n);
  }
}

/// The optional "limits" {"lower", "upper", "effort", "velocity"} and "friction" of a 1-dof
/// hinge: kept for the record (HingeLimits), not used by the dynamics.
HingeLimits read_limits(const Reader& r, const json* limits, const json* friction, const Path& path,
                        const Body& b, const std::string& hinge_name) {
  const HingeType t = b.hinge.type;
  const bool one_dof =
      t == HingeType::Revolute || t == HingeType::Prismatic || t == HingeType::Helical;
  const Path lp = path.key(limits ? "limits" : "friction");
  if (!one_dof)
    r.fail(lp, std::string("applies to revolute, prismatic and helical hinges only, not to a ") +
                   hinge_type_name(t) + " hinge");
  HingeLimits l;
  l.hinge = hinge_name;
  if (limits) {
    r.expect_object(*limits, lp);
    r.only_fields(*limits, lp, {"lower", "upper", "effort", "velocity"});
    auto get = [&](const char* key, double& x) {
      if (const json* v = Reader::optional(*limits, key)) x = r.number(*v, lp.key(key));
    };
    get("lower", l.lower);
    get("upper", l.upper);
    get("effort", l.effort);
    get("velocity", l.velocity);
    if (!(l.lower <= l.upper))
      r.fail(lp, "lower " + num(l.lower) + " is above upper " + num(l.upper));
    if (!(l.effort >= 0))
      r.fail(lp.key("effort"), "must not be negative (got " + num(l.effort) + ")");
    if (!(l.velocity >= 0))
      r.fail(lp.key("velocity"), "must not be negative (got " + num(l.velocity) + ")");
  }
  if (friction) {
    const Path fp = path.key("friction");
    l.friction = r.number(*friction, fp);
    if (!(l.friction >= 0)) r.fail(fp, "must not be negative (got " + num(l.friction) + ")");
  }
  return l;
}

/// A per-body state vector ("q", "qd", "qdd") of the hinge's size, appended to \p out.
void read_state(const Reader& r, const json& j, const Path& path, const Hinge& h,
                bool configuration, std::vector<double>& out) {
  const int n = configuration ? h.nq() : h.nv();
  std::vector<double> x =
      r.numbers(j, path, n, std::string(" for a ") + hinge_type_name(h.type) + " hinge");
  if (configuration && has_quaternion(h.type)) {
    r.check_unit(x.data(), path, " in entries 0-3");
    const UnitQuaternion q(Vec3<double>(x[0], x[1], x[2]), x[3]);
    for (int i = 0; i < 4; ++i) x[i] = q.coeffs()[i];
  }
  out.insert(out.end(), x.begin(), x.end());
}

/// Body \p i of the file, checked and added to \p fb.
void read_body(const Reader& r, const json& j, std::size_t i, FileBodies& fb) {
  const Path path = kBodies.index(i);
  r.expect_object(j, path);
  r.only_fields(j, path,
                {"name", "parent", "mass", "com", "inertia", "hinge", "spring", "limits",
                 "friction", "q", "qd", "qdd"});
  Body b;
  const Path name_path = path.key("name");
  b.name = r.string(r.required(j, path, "name"), name_path);
  if (b.name.empty()) r.fail(name_path, "empty name");
  if (b.name == "base") r.fail(name_path, "\"base\" names the ground; pick another");
  const std::string parent = r.string(r.required(j, path, "parent"), path.key("parent"));
  // A massless body (a frame such as a URDF's tool0) has none of mass, com, inertia.
  const bool massless = !Reader::optional(j, "mass") && !Reader::optional(j, "com") &&
                        !Reader::optional(j, "inertia");
  if (!massless) {
    const double m = r.number(r.required(j, path, "mass"), path.key("mass"));
    if (!(m > 0)) r.fail(path.key("mass"), "must be positive (got " + num(m) + ")");
    const Vec3<double> com = r.vec3(r.required(j, path, "com"), path.key("com"));
    const Mat3<double> J = r.inertia(r.required(j, path, "inertia"), path.key("inertia"));
    b.M = SpatialInertia::from_cm(m, com, J);
    if (!is_finite(b.M))  // m p and m p p about O_k
      r.fail(path, "the inertia about the hinge frame overflows (mass " + num(m) + ", com at " +
                       num(safe_norm(com)) + " from it)");
  }
  const std::string hinge_name = read_hinge(r, r.required(j, path, "hinge"), path.key("hinge"), b);
  if (const json* s = Reader::optional(j, "spring")) read_spring(r, *s, path.key("spring"), b);
  const json* limits = Reader::optional(j, "limits");
  const json* friction = Reader::optional(j, "friction");
  if (limits || friction)
    fb.limits.emplace_back(i, read_limits(r, limits, friction, path, b, hinge_name));
  unsigned char flags = b.hinge.type == HingeType::Locked ? FileBodies::kLocked : 0;
  if (massless) flags |= FileBodies::kMassless;
  if (const json* v = Reader::optional(j, "q")) {
    read_state(r, *v, path.key("q"), b.hinge, true, fb.q);
    flags |= FileBodies::kQ;
  }
  if (const json* v = Reader::optional(j, "qd")) {
    read_state(r, *v, path.key("qd"), b.hinge, false, fb.qd);
    flags |= FileBodies::kQd;
  }
  if (const json* v = Reader::optional(j, "qdd")) {
    read_state(r, *v, path.key("qdd"), b.hinge, false, fb.qdd);
    flags |= FileBodies::kQdd;
  }
  // The parent by index when it is listed before (a valid file lists every parent before
  // its child); else by name, resolved once every name is known (resolve_later()).
  std::size_t p = FileBodies::kBase;
  if (parent != "base") {
    const auto it = fb.index.find(parent);
    p = it != fb.index.end() ? it->second : FileBodies::kLater;
    if (p == FileBodies::kLater) fb.later.emplace_back(i, parent);
  }
  const auto [it, fresh] = fb.index.try_emplace(b.name, i);
  if (!fresh)
    r.fail(name_path,
           "duplicate name " + in_quotes(b.name) + " (" + body_path(it->second) + " has it too)");
  fb.parent.push_back(p);
  fb.flags.push_back(flags);
  fb.body.push_back(std::move(b));
  ++fb.count;
}

/// Builds the document from nlohmann's SAX events in O(n), with the checks its DOM parser
/// lacks: a key given twice in one object (nlohmann would keep the last; found in O(log k) in
/// the object being built), the path of a number out of the range of a double (nlohmann does
/// not say where), nesting deeper than kMaxSceneDepth. The elements of the top-level "bodies"
/// array are not kept: each goes to read_body() as soon as it is complete, and is dropped.
class SceneSax {
 public:
  SceneSax(const Reader& r, FileBodies& bodies) : r_(r), bodies_(bodies) {}

  /// The top level, with null for "bodies" when they were streamed.
  const json& document() const { return root_; }
  void drop_document() { dismantle(root_); }
  /// "bodies" was an array (so its elements went to read_body()).
  bool bodies_streamed() const { return streamed_; }
  /// What was being read, for "out of memory while ...".
  std::string doing() const {
    if (body_ != kNone) return "reading " + body_path(body_);
    const std::string p = stack_.empty() ? "top level" : path(false);
    return p == "top level" ? "reading the top level" : "reading " + p;
  }

  // nlohmann's SAX interface.
  bool null() { return add(json(nullptr)); }
  bool boolean(bool v) { return add(json(v)); }
  bool number_integer(json::number_integer_t v) { return add(json(v)); }
  bool number_unsigned(json::number_unsigned_t v) { return add(json(v)); }
  bool number_float(json::number_float_t v, const json::string_t&) { return add(json(v)); }
  bool string(json::string_t& v) { return add(json(std::move(v))); }
  bool binary(json::binary_t& v) { return add(json::binary(std::move(v))); }  // not in JSON text
  bool start_object(std::size_t) { return open(json::value_t::object); }
  bool start_array(std::size_t) { return open(json::value_t::array); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool key(json::string_t& k) {
    Level& l = stack_.back();
    if (stack_.size() == 1) {
      if (!is_top_field(k)) r_.fail("top level", "unknown field " + in_quotes(k));
      stream_next_ = k == "bodies";
    }
    const auto [it, fresh] = l.node->get_ref<json::object_t&>().try_emplace(std::move(k));
    if (!fresh) r_.fail(path(false), "field " + in_quotes(it->first) + " given twice");
    l.key = &it->first;
    l.slot = &it->second;
    return true;
  }
  bool parse_error(std::size_t, const std::string& token, const json::exception& e) {
    if (e.id == 406)  // "number overflow parsing '1e999'", thrown without a path
      r_.fail(path(true), "not a finite number (" + token + " is out of the range of a double)");
    // "[json.exception.parse_error.101] parse error at line 3, column 5: <detail>"
    const std::string w = e.what();
    const std::size_t at = w.find(" at line ");
    const std::size_t colon = at == std::string::npos ? at : w.find(": ", at);
    if (colon == std::string::npos) r_.fail("top level", "invalid JSON: " + w);
    r_.fail(w.substr(at + 4, colon - at - 4), "invalid JSON: " + w.substr(colon + 2));
  }

 private:
  static constexpr std::size_t kNone = std::size_t(-1);
  /// An open array or object.
  struct Level {
    json* node = nullptr;              // the container being built; null for the streamed "bodies"
    std::size_t next = 0;              // arrays: the index of the next element
    const std::string* key = nullptr;  // objects: the last key (a key of node's map: stable)
    json* slot = nullptr;              // objects: its value
  };

  /// The elements of the streamed "bodies" come next.
  bool in_bodies() const { return !stack_.empty() && !stack_.back().node; }

  /// Where the next value goes (an element pointer stays valid while the element is open:
  /// nothing is added to its array until it closes).
  json* place() {
    if (stack_.empty()) return &root_;
    Level& l = stack_.back();
    if (!l.node) {
      ++l.next;
      return &element_;
    }
    if (l.node->is_object()) return l.slot;
    ++l.next;
    json::array_t& a = l.node->get_ref<json::array_t&>();
    a.emplace_back();
    return &a.back();
  }

  bool add(json&& v) {
    stream_next_ = false;
    if (stack_.empty()) r_.fail("top level", "expected an object, got " + describe(v));
    if (in_bodies()) r_.fail(path(true), "expected an object, got " + describe(v));
    *place() = std::move(v);
    return true;
  }

  bool open(json::value_t type) {
    const bool stream = stream_next_ && type == json::value_t::array;
    stream_next_ = false;
    if (stack_.size() >= std::size_t(kMaxSceneDepth))
      r_.fail(path(true), "nested more than " + std::to_string(kMaxSceneDepth) + " levels deep");
    // Refused at once, as assemble() and read_body() would: nothing to keep.
    if (type == json::value_t::array && (stack_.empty() || in_bodies()))
      r_.fail(stack_.empty() ? "top level" : path(true), "expected an object, got an array");
    if (stream) {  // "bodies": its slot in the top level stays null
      streamed_ = true;
      stack_.push_back(Level{});
      return true;
    }
    json* v = place();
    *v = json(type);
    Level l;
    l.node = v;
    stack_.push_back(l);
    return true;
  }

  bool close() {
    stack_.pop_back();
    if (in_bodies()) {  // a body is complete: read it, drop it
      body_ = stack_.back().next - 1;
      read_body(r_, element_, body_, bodies_);
      body_ = kNone;
      dismantle(element_);
    }
    return true;
  }

  /// The path of the innermost open container, or (\p pending) of the value about to be
  /// read in it. A path deeper than 12 levels shows its first 4 and last 4, so that a
  /// message is O(1) however deep the file.
  std::string path(bool pending) const {
    const std::size_t n = stack_.size() - (pending ? 0 : 1);  // levels that name a child
    if (n == 0) return "top level";
    constexpr std::size_t kEnds = 4;
    std::string p;
    if (n <= 3 * kEnds) {
      for (std::size_t i = 0; i < n; ++i) p += segment(i, i == 0);
      return p;
    }
    for (std::size_t i = 0; i < kEnds; ++i) p += segment(i, i == 0);
    p += " ... (" + std::to_string(n - 2 * kEnds) + " levels) ... ";
    for (std::size_t i = n - kEnds; i < n; ++i) p += segment(i, i == n - kEnds);
    return p;
  }
  /// Level i's part of a path: ".key" (no dot when \p first) or "[index]".
  std::string segment(std::size_t i, bool first) const {
    const Level& l = stack_[i];
    if (l.node && l.node->is_object()) {
      if (!l.key) return "";
      return first ? *l.key : "." + *l.key;
    }
    // An open child is the last element; a pending one is the next.
    const std::size_t index = i + 1 < stack_.size() ? l.next - 1 : l.next;
    return "[" + std::to_string(index) + "]";
  }

  const Reader& r_;
  FileBodies& bodies_;
  std::vector<Level> stack_;
  json root_;
  json element_;              // the body being built
  std::size_t body_ = kNone;  // the body being read
  bool stream_next_ = false;  // the value of the top-level "bodies" comes next
  bool streamed_ = false;
};

/// Checks the chain as a whole: unknown parents, branches, loops, and a file that does not
/// list the chain base first. When it returns, the file lists the chain from the base.
void check_chain(const Reader& r, const FileBodies& fb) {
  constexpr std::size_t kNone = std::size_t(-1);
  const std::size_t n = fb.count;
  std::vector<std::size_t> child(n, kNone);
  std::size_t first = kNone;  // the body hanging from the base
  for (std::size_t i = 0; i < n; ++i) {
    const Path body = kBodies.index(i);
    const std::size_t p = fb.parent[i];
    if (p == FileBodies::kUnknown)
      r.fail(body.key("parent"), "no body named " + in_quotes(fb.parent_name(i)) +
                                     " (a parent is \"base\" or a body's name)");
    std::size_t& c = p == FileBodies::kBase ? first : child[p];
    if (c != kNone)
      r.fail(body.key("parent"), in_quotes(fb.parent_name(i)) + " already has a child (" +
                                     body_path(c) + "); serial chains only, no branches");
    c = i;
  }
  std::vector<bool> reached(n, false);
  std::size_t length = 0, misplaced = kNone;
  for (std::size_t c = first; c != kNone; c = child[c], ++length) {
    reached[c] = true;
    if (c != length && misplaced == kNone) misplaced = length;
  }
  if (length == n) {
    // The chain is sound; the file must list it base first, so that "file order" (of --q,
    // of the output) is the order of the chain.
    if (misplaced != kNone)
      r.fail(kBodies.index(misplaced).key("parent"),
             in_quotes(fb.parent_name(misplaced)) + " is listed after this body (" +
                 body_path(fb.parent[misplaced]) +
                 "); list the bodies base first, each after its parent");
    return;
  }
  // Every parent exists and none has two children: the bodies not reached form loops. The
  // loop through the first of them, following parents (its middle left out when long).
  std::size_t u = 0;
  while (reached[u]) ++u;
  std::size_t loop = 1;
  for (std::size_t i = fb.parent[u]; i != u; i = fb.parent[i]) ++loop;
  std::string cycle = printable(fb.body[u].name);
  std::size_t at = 1;
  for (std::size_t i = fb.parent[u]; i != u; i = fb.parent[i], ++at) {
    if (loop <= 8 || at < 4 || at + 2 >= loop)
      cycle += " -> " + printable(fb.body[i].name);
    else if (at == 4)
      cycle += " -> ... (" + std::to_string(loop - 6) + " bodies) ...";
  }
  cycle += " -> " + printable(fb.body[u].name);
  r.fail(kBodies.index(u).key("parent"),
         "loop (" + cycle + ", following parents) never reaches \"base\"");
}

/// The scene from the parsed top level \p doc and the bodies read from it.
Scene assemble(const json& doc, bool streamed, FileBodies& fb, const Reader& r) {
  Scene s;
  s.name = r.file();
  r.expect_object(doc, kTop);  // SceneSax refused anything else, and unknown fields
  if (const json* v = Reader::optional(doc, "name")) {
    s.title = r.string(*v, kTop.key("name"));
  } else {
    const std::size_t slash = s.name.find_last_of("/\\");
    s.title = s.name.substr(slash == std::string::npos ? 0 : slash + 1);
    const std::size_t dot = s.title.rfind('.');
    if (dot != std::string::npos && dot > 0) s.title.resize(dot);
  }
  Vec3<double> gravity = Vec3<double>::Zero();
  if (const json* v = Reader::optional(doc, "gravity")) gravity = r.vec3(*v, kTop.key("gravity"));

  // The bodies, each checked on its own as it was read.
  const json& jb = r.required(doc, kTop, "bodies");
  if (!streamed) r.fail(kBodies, "expected an array of bodies, got " + describe(jb));
  if (fb.count == 0) r.fail(kBodies, "empty; a scene needs at least one body");

  // The chain, base first (the file's order); locked bodies merge into their inboard
  // neighbour, whose course number k their frames keep.
  fb.resolve_later();
  check_chain(r, fb);
  const std::size_t n = fb.count;
  if (fb.flags[0] & FileBodies::kLocked)
    r.fail(kBodies.index(0).key("hinge").key("type"),
           "a locked hinge next to the base fixes the body to the ground; remove the body or "
           "give it another hinge");
  // A massless body is a frame; its hinge must move something of mass.
  bool mass_outboard = false;
  for (std::size_t i = n; i-- > 0;) {
    mass_outboard = mass_outboard || !(fb.flags[i] & FileBodies::kMassless);
    if (!mass_outboard && !(fb.flags[i] & FileBodies::kLocked))
      r.fail(kBodies.index(i),
             "massless, and so is every body outboard of it: its " +
                 std::string(hinge_type_name(fb.body[i].hinge.type)) +
                 " hinge moves nothing of mass (give a body a mass, or lock the hinge)");
  }
  int n_kept = 0;
  for (unsigned char f : fb.flags) n_kept += !(f & FileBodies::kLocked);
  std::vector<int> k(n);
  std::vector<std::pair<std::size_t, Scene::Frame>> locked;  // by body
  {
    int kept = 0;
    std::size_t carrier = 0;
    SpatialInertia M;  // the carrier's inertia with the locked bodies merged so far
    for (std::size_t i = 0; i < n; ++i) {
      const Body& b = fb.body[i];
      if (!(fb.flags[i] & FileBodies::kLocked)) {
        k[i] = n_kept - kept++;
        carrier = i;
        M = b.M;
        continue;
      }
      Scene::Frame f;
      f.name = b.name;
      f.k = k[i] = k[i - 1];
      f.set_offset(
          (locked.empty() || locked.back().first + 1 != i ? Pose()
                                                          : locked.back().second.offset()) *
              b.placement,
          fb.flags[i] & FileBodies::kMassless ? Vec3<double>::Zero() : b.M.p());
      f.locked = true;
      M = M + transform(Phi(f.offset()), b.M);  // as ModelT::from_base_first() does
      if (!is_finite(M))
        r.fail(kBodies.index(i), "merged into " + body_path(carrier) +
                                     " through its locked hinge, its inertia about that body's "
                                     "frame overflows");
      locked.emplace_back(i, std::move(f));
    }
  }
  auto offset_of = [&](std::size_t i) {
    if (!(fb.flags[i] & FileBodies::kLocked)) return Pose();
    return std::lower_bound(locked.begin(), locked.end(), i,
                            [](const auto& l, std::size_t b) { return l.first < b; })
        ->second.offset();
  };

  // External forces, moved to O_k of the model body (a locked body's force by phi(O_k, F)).
  if (const json* v = Reader::optional(doc, "external_forces")) {
    const Path forces = kTop.key("external_forces");
    if (!v->is_array()) r.fail(forces, "expected an array of forces, got " + describe(*v));
    if (!v->empty()) s.f_ext.assign(n_kept, Force());
    for (std::size_t i = 0; i < v->size(); ++i) {
      const Path path = forces.index(i);
      const json& e = (*v)[i];
      r.expect_object(e, path);
      r.only_fields(e, path, {"body", "moment", "force"});
      const std::string name = r.string(r.required(e, path, "body"), path.key("body"));
      const auto it = fb.index.find(name);
      if (it == fb.index.end()) r.fail(path.key("body"), "no body named " + in_quotes(name));
      const std::size_t b = it->second;
      Vec3<double> N = Vec3<double>::Zero(), F = Vec3<double>::Zero();
      if (const json* x = Reader::optional(e, "moment")) N = r.vec3(*x, path.key("moment"));
      if (const json* x = Reader::optional(e, "force")) F = r.vec3(*x, path.key("force"));
      s.f_ext[k[b] - 1] += Phi(offset_of(b)).apply(Force(N, F));
    }
  }

  if (const json* v = Reader::optional(doc, "compute")) {
    const Path compute = kTop.key("compute");
    if (!v->is_array()) r.fail(compute, "expected an array of strings, got " + describe(*v));
    for (std::size_t i = 0; i < v->size(); ++i) {
      const std::string what = r.string((*v)[i], compute.index(i));
      if (what != "kinematics" && what != "jacobian" && what != "inverse-dynamics" &&
          what != "mass-matrix")
        r.fail(compute.index(i),
               "unknown computation " + in_quotes(what) +
                   " (expected kinematics, jacobian, inverse-dynamics or mass-matrix)");
      s.compute.push_back(what);
    }
  }

  // Every check passed. The model takes the bodies (moved, not copied; the name map and the
  // parents go first, to keep the peak of memory low), then the frames name them.
  decltype(fb.index)().swap(fb.index);
  decltype(fb.parent)().swap(fb.parent);
  decltype(fb.later)().swap(fb.later);
  s.model = Model::from_base_first(std::move(fb.body));
  s.model.gravity = gravity;
  s.frames.reserve(n);
  s.file_order.reserve(n_kept);
  auto next_locked = locked.begin();
  auto next_limits = fb.limits.begin();
  for (std::size_t i = 0; i < n; ++i) {
    if (next_locked != locked.end() && next_locked->first == i) {
      s.frames.push_back(std::move(next_locked++->second));
      continue;
    }
    Scene::Frame f;
    f.name = s.model.body(k[i]).name;
    f.k = k[i];
    if (next_limits != fb.limits.end() && next_limits->first == i)
      f.set_limits(next_limits++->second);
    s.frames.push_back(std::move(f));
    s.file_order.push_back(k[i]);
  }

  // The initial state, body by body (model order is tip first).
  s.state = State::rest(s.model);
  s.beta_dot = VecX<double>::Zero(s.model.nv());
  const double *q = fb.q.data(), *qd = fb.qd.data(), *qdd = fb.qdd.data();
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char f = fb.flags[i];
    if (f & FileBodies::kLocked) continue;  // no coordinates (nor values)
    const Body& B = s.model.body(k[i]);
    const int nq = B.hinge.nq(), nv = B.hinge.nv();
    if (f & FileBodies::kQ) {
      s.state.theta.segment(B.q_offset, nq) = Eigen::Map<const VecX<double>>(q, nq);
      q += nq;
    }
    if (f & FileBodies::kQd) {
      s.state.beta.segment(B.v_offset, nv) = Eigen::Map<const VecX<double>>(qd, nv);
      qd += nv;
    }
    if (f & FileBodies::kQdd) {
      s.beta_dot.segment(B.v_offset, nv) = Eigen::Map<const VecX<double>>(qdd, nv);
      qdd += nv;
    }
  }
  return s;
}

/// "larger than the 1 GiB limit of a scene file".
std::string too_large(std::uint64_t limit) {
  const char* units[] = {" GiB", " MiB", " KiB"};
  for (int u = 0; u < 3; ++u) {
    const std::uint64_t unit = std::uint64_t(1) << (30 - 10 * u);
    if (limit >= unit && limit % unit == 0)
      return "larger than the " + std::to_string(limit / unit) + units[u] +
             " limit of a scene file";
  }
  return "larger than the " + std::to_string(limit) + "-byte limit of a scene file";
}

/// The bytes of a scene, handed to nlohmann one by one: a file read through a small buffer,
/// or a text in memory. More than the limit is refused as soon as it is read.
class Bytes {
 public:
  Bytes(const std::string& text, const Reader& r) : r_(r), pos_(text.data()), end_(pos_) {
    end_ += text.size();
  }
  Bytes(std::FILE* file, const Reader& r, std::uint64_t max_bytes)
      : r_(r), file_(file), max_(max_bytes), buffer_(new char[kBuffer]) {}

  bool more() { return pos_ != end_ || fill(); }
  char peek() const { return *pos_; }
  void skip() { ++pos_; }

 private:
  static constexpr std::size_t kBuffer = 64 * 1024;
  bool fill() {
    if (!file_ || eof_) return false;
    // At most one byte past the limit: that byte says the file is larger.
    const std::size_t want = std::size_t(std::min<std::uint64_t>(kBuffer, max_ - total_ + 1));
    const std::size_t got = std::fread(buffer_.get(), 1, want, file_);
    if (got == 0) {
      if (std::ferror(file_)) {
        const int e = errno;
        if (e == EISDIR) r_.fail_file("is a directory, not a scene file");
        r_.fail_file(std::string("cannot read the file (") + std::strerror(e) + ")");
      }
      eof_ = true;
      return false;
    }
    total_ += got;
    if (total_ > max_) r_.fail_file(too_large(max_));
    pos_ = buffer_.get();
    end_ = pos_ + got;
    return true;
  }

  const Reader& r_;
  std::FILE* file_ = nullptr;
  std::uint64_t max_ = 0, total_ = 0;
  std::unique_ptr<char[]> buffer_;
  const char* pos_ = nullptr;
  const char* end_ = nullptr;
  bool eof_ = false;
};

/// An input iterator over Bytes, compared only with the end (a default one), as nlohmann's
/// iterator adapter does.
class ByteIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = char;

  ByteIterator() = default;
  explicit ByteIterator(Bytes* bytes) : bytes_(bytes) {}
  char operator*() const { return bytes_->peek(); }
  ByteIterator& operator++() {
    bytes_->skip();
    return *this;
  }
  bool operator!=(const ByteIterator&) const { return bytes_->more(); }
  bool operator==(const ByteIterator& end) const { return !(*this != end); }

 private:
  Bytes* bytes_ = nullptr;
};

/// Reads the scene from \p in; out of memory becomes one soa::Error saying where.
Scene read_scene(Bytes& in, const Reader& r) {
  FileBodies bodies;
  SceneSax sax(r, bodies);
  bool parsed = false;
  try {
    json::sax_parse(ByteIterator(&in), ByteIterator(), &sax, json::input_format_t::json,
                    /*strict=*/true, /*ignore_comments=*/true);
    parsed = true;
    Scene s = assemble(sax.document(), sax.bodies_streamed(), bodies, r);
    sax.drop_document();
    return s;
  } catch (const std::bad_alloc&) {
    r.fail_file("out of memory while " +
                (parsed ? "building the scene (" + std::to_string(bodies.count) + " bodies)"
                        : sax.doing()));
  } catch (const json::exception& e) {  // not expected: every value is checked before use
    r.fail("top level", e.what());
  }
}

/// load_scene(): the file's checks, then read_scene().
Scene load_file(const std::string& path, std::uint64_t max_bytes) {
  const Reader r(path);
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::is_directory(status)) r.fail_file("is a directory, not a scene file");
  if (fs::is_regular_file(status)) {  // refused before reading when its size says so
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!ec && size > max_bytes) r.fail_file(too_large(max_bytes));
  }
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) {
    const int e = errno;
    r.fail_file(std::string("cannot open the file (") + std::strerror(e) + ")");
  }
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> closer(file, &std::fclose);
  std::setvbuf(file, nullptr, _IONBF, 0);  // Bytes has the buffer
  Bytes in(file, r, max_bytes);
  return read_scene(in, r);
}

}  // namespace

namespace detail {

Scene scene_from_urdf(const UrdfScene& u, const std::string& file) {
  const Reader r(file, u.names);
  FileBodies fb;
  for (std::size_t i = 0; i < u.bodies.size(); ++i) read_body(r, u.bodies[i], i, fb);
  json top = u.top;
  top["bodies"] = nullptr;  // as SceneSax leaves it when the bodies were streamed
  return assemble(top, /*streamed=*/true, fb, r);
}

}  // namespace detail

Scene parse_scene(const std::string& json_text, const std::string& name) {
  try {
    const Reader r(name);
    if (json_text.size() > kMaxSceneBytes) r.fail_file(too_large(kMaxSceneBytes));
    Bytes in(json_text, r);
    return read_scene(in, r);
  } catch (const std::bad_alloc&) {  // before read_scene() (which says where)
    throw Error(name + ": out of memory before reading");
  }
}

Scene load_scene(const std::string& path) {
  return load_scene(path, kMaxSceneBytes);
}

Scene load_scene(const std::string& path, const UrdfOptions& urdf) {
  if (!is_urdf(path)) {
    if (!urdf.tip.empty() || !urdf.lock.empty())
      throw Error(path + ": " + (urdf.tip.empty() ? "--lock" : "--tip") +
                  " applies to URDF files, not to a JSON scene");
    return load_scene(path);
  }
  try {
    const detail::UrdfScene u = detail::convert_urdf(path, urdf);
    return detail::scene_from_urdf(u, path);
  } catch (const std::bad_alloc&) {
    throw Error(path + ": out of memory while reading the URDF");
  }
}

Scene load_scene(const std::string& path, std::uint64_t max_bytes) {
  try {
    if (is_urdf(path)) return load_scene(path, UrdfOptions{});
    return load_file(path, max_bytes);
  } catch (const std::bad_alloc&) {  // before read_scene() (which says where)
    throw Error(path + ": out of memory before reading");
  }
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
    const double norm = safe_norm(Eigen::Map<const Eigen::Vector4d>(c));
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
