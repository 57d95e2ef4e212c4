/// \file
/// The exercise checker: feedback that names the mistake.
///
/// An exercise test draws many random cases and, for each, gives a Check the student's
/// result, the library's (the expected value), the scale rounding errors grow with, what the
/// case has (tags: moving, gravity, prismatic hinges, ...), the case's inputs as C++ a
/// student can paste into a program, and the classic wrong answers of the exercise computed
/// from the reference (its catalogue of mistakes). When the check fails, its message says,
/// in this order:
///   - which check failed, in words, how often, and the worst relative error;
///   - the mistake of the catalogue the student's result equals in every failing case
///     ("did you transpose?");
///   - otherwise the symptom: the tag that every failing case has and every passing case
///     may lack ("passes at rest, fails moving: a velocity term");
///   - where the error is in the simplest failing case (per body, angular / linear part, per
///     hinge), expected against got;
///   - that case's inputs as code, and the worst case's (inline when short, else written to
///     $SOA_EXERCISE_CASES as a small program).
/// A symptom says what was measured (which cases fail, a constant factor, a variant of the
/// computation the result equals); it does not guess a cause the evidence does not single out.
///
/// Level 3 exercises (derive, predict, find the bug) are worked out by the student: their
/// first messages give the symptom and the place (the check, the body, the case) but not the
/// catalogue's mistake. The mistake is named once the student has had the exercise fail in
/// as many runs as its statement says ("after 3 failed runs"; counted in $SOA_EXERCISE_CASES,
/// which `make exercises` sets) or has read all of its hints (`make exercises HINT=N.K`,
/// kept in $SOA_EXERCISE_HINTS, by default the folder `hints` beside $SOA_EXERCISE_CASES).
/// `make exercises` shows every failed check's message under the exercise's row.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "property.hpp"
#include "soa/chain.hpp"

namespace soa::test {

// --- What a case has: tags, for the symptom of a mistake no catalogue entry matches ----------

/// Features of a random case. A test sets those its case has; the checker looks for a tag
/// that separates the failing cases from the passing ones.
enum Tag : unsigned {
  kMoving = 1u << 0,          ///< \f$\beta \ne 0\f$ (velocities)
  kAccelerating = 1u << 1,    ///< \f$\dot\beta \ne 0\f$
  kGravity = 1u << 2,         ///< gravity is on
  kPrismatic = 1u << 3,       ///< some hinge is prismatic
  kHelical = 1u << 4,         ///< some hinge is helical
  kMultiDof = 1u << 5,        ///< some hinge has several degrees of freedom
  kSeveralBodies = 1u << 6,   ///< more than one body
  kExternalForces = 1u << 7,  ///< external forces act on the bodies
  kSprings = 1u << 8,         ///< hinge springs or dampers
  kOffsetCom = 1u << 9,       ///< a centre of mass away from the frame's origin
  kRotated = 1u << 10,        ///< a frame rotated relative to the other
  kTranslated = 1u << 11,     ///< a frame offset from the other
  kOwn1 = 1u << 16,           ///< a feature of the exercise's own: Check::tag_meaning() says which
  kOwn2 = 1u << 17,           ///< another of the exercise's own
};

/// What a tag means for a student: the cases it marks ("where ..."). A symptom built on a tag
/// says which cases fail and which pass, nothing more: the same split has many causes.
struct TagMeaning {
  Tag tag;
  const char* cases;  ///< "it moves (the velocities are not zero)"
};

inline const std::vector<TagMeaning>& tag_meanings() {
  static const std::vector<TagMeaning> t = {
      {kMoving, "it moves (the velocities are not zero)"},
      {kAccelerating, "the accelerations are not zero"},
      {kGravity, "gravity is on"},
      {kPrismatic, "a hinge is prismatic"},
      {kHelical, "a hinge is helical"},
      {kMultiDof, "a hinge has several degrees of freedom"},
      {kSeveralBodies, "there is more than one body"},
      {kExternalForces, "external forces act"},
      {kSprings, "the hinges have springs or dampers"},
      {kOffsetCom, "the centre of mass is off the frame's origin"},
      {kRotated, "the frames are rotated"},
      {kTranslated, "the frames are offset"},
  };
  return t;
}

// --- The exercise being checked: its level and what its student has seen -------------------

/// The exercise of the running test, read from its statement: the test suite is named
/// `ExerciseL_K_Name` and its file is tests/exercises/NN-topic.cpp, whose statements are in
/// exercises/NN-topic/exercises.hpp and hints in exercises/NN-topic/hints.md.
struct ExerciseInfo {
  std::string id;          ///< "7.12"; empty outside an exercise test
  int level = 0;           ///< 1 to 3; 0 when the statement was not found
  int explicit_after = 0;  ///< level 3: failed runs after which the mistake is named
  int hints = 0;           ///< the number of hints of its ladder in hints.md
};

inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline int read_int(const std::string& path) {
  std::ifstream in(path);
  int n = 0;
  return in >> n ? n : 0;
}

/// Reads the statement of exercise \p id from \p hpp and its hint ladder from \p hints.
inline ExerciseInfo parse_exercise(const std::string& id, const std::string& hpp,
                                   const std::string& hints) {
  ExerciseInfo e;
  e.id = id;
  std::istringstream in(read_text(hpp));
  std::string line;
  bool on = false;
  const std::regex level(R"(\*Level ([1-3]) of 3)"), after(R"(after ([0-9]+) failed runs)");
  while (std::getline(in, line)) {
    if (line.find("**Exercise ") != std::string::npos) {
      if (on) break;
      on = line.find("**Exercise " + id + ":") != std::string::npos ||
           line.find("**Exercise " + id + " ") != std::string::npos;
    }
    std::smatch m;
    if (on && e.level == 0 && std::regex_search(line, m, level)) e.level = std::stoi(m[1]);
    if (on && e.explicit_after == 0 && std::regex_search(line, m, after))
      e.explicit_after = std::stoi(m[1]);
  }
  // The ladder: the numbered items of the section "## <id> ..." (tests/exercises/hint.sh).
  std::istringstream h(read_text(hints));
  on = false;
  const std::regex item(R"(^[0-9]+\. )");
  while (std::getline(h, line)) {
    if (line.rfind("## ", 0) == 0) on = line.rfind("## " + id + " ", 0) == 0;
    if (on && std::regex_search(line, item)) ++e.hints;
  }
  return e;
}

/// The exercise of the running test (see ExerciseInfo); id empty outside a test.
inline ExerciseInfo current_exercise() {
  const auto* info = testing::UnitTest::GetInstance()->current_test_info();
  if (!info) return {};
  const std::string suite = info->test_suite_name();
  static const std::regex name(R"(^Exercise([0-9]+)_([0-9]+)_)");
  std::smatch m;
  if (!std::regex_search(suite, m, name)) return {};
  const std::string id = m[1].str() + "." + m[2].str();
  static std::map<std::string, ExerciseInfo> seen;
  const auto it = seen.find(id);
  if (it != seen.end()) return it->second;
  const std::string file = info->file() ? info->file() : "";
  const auto at = file.rfind("tests/exercises/");
  ExerciseInfo e;
  e.id = id;
  if (at != std::string::npos && file.size() > 4 && file.substr(file.size() - 4) == ".cpp") {
    const std::string topic = file.substr(at + 16, file.size() - 4 - at - 16);
    const std::string dir = file.substr(0, at) + "exercises/" + topic + "/";
    e = parse_exercise(id, dir + "exercises.hpp", dir + "hints.md");
  }
  return seen[id] = e;
}

/// Where the failed runs are counted ($SOA_EXERCISE_CASES) and the hints seen are kept
/// ($SOA_EXERCISE_HINTS, else `hints` beside the cases: build/exercises/hints for make
/// exercises); empty when not set.
inline std::string cases_dir() {
  const char* d = std::getenv("SOA_EXERCISE_CASES");
  return d && *d ? d : "";
}
inline std::string hints_dir() {
  const char* d = std::getenv("SOA_EXERCISE_HINTS");
  if (d && *d) return d;
  const std::string c = cases_dir();
  return c.empty() ? "" : c + "/../hints";
}

/// How far the student of a level 3 exercise is: failed runs before this one, hints seen.
struct Progress {
  int failed_runs = 0;  ///< before this run
  int hints_seen = 0;
  bool named = false;  ///< the catalogue's mistake may be named
};

/// Counts this run as a failed run of exercise \p e (once per process) and says whether the
/// mistake may be named: always below level 3; at level 3 after e.explicit_after failed
/// runs, or once every hint of the ladder has been shown.
inline Progress progress(const ExerciseInfo& e) {
  static std::map<std::string, Progress> done;  // one count per run of the exercise
  const auto it = done.find(e.id);
  if (it != done.end()) return it->second;
  Progress p;
  const std::string cases = cases_dir(), hints = hints_dir();
  if (e.level == 3 && !cases.empty()) {
    const std::string path = cases + "/" + e.id + ".failed-runs";
    p.failed_runs = read_int(path);
    std::ofstream(path) << p.failed_runs + 1 << "\n";
  }
  if (!hints.empty()) p.hints_seen = read_int(hints + "/" + e.id);
  p.named = e.level != 3 || (e.explicit_after > 0 && p.failed_runs >= e.explicit_after) ||
            (e.hints > 0 && p.hints_seen >= e.hints);
  return done[e.id] = p;
}

// --- Inputs as code ----------------------------------------------------------------------------

/// A double with every digit (round-trips exactly).
inline std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

/// Eigen initializer list text of \p a, row by row: `{{a00, a01}, {a10, a11}}`, or
/// `{a0, a1, a2}` for a vector.
template <class D>
std::string list(const Eigen::MatrixBase<D>& a) {
  std::string s = "{";
  if (a.cols() == 1) {
    for (Eigen::Index i = 0; i < a.rows(); ++i) s += (i ? ", " : "") + num(double(a(i, 0)));
    return s + "}";
  }
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    s += i ? ", {" : "{";
    for (Eigen::Index j = 0; j < a.cols(); ++j) s += (j ? ", " : "") + num(double(a(i, j)));
    s += "}";
  }
  return s + "}";
}

/// `soa::Vec3<double> name{...};` and friends: one declaration per line.
inline std::string code(const std::string& name, const Vec3<double>& v) {
  return "soa::Vec3<double> " + name + " = soa::Vec3<double>" + list(v) + ";\n";
}
inline std::string code(const std::string& name, const Mat3<double>& R) {
  return "soa::Mat3<double> " + name + " = soa::Mat3<double>" + list(R) + ";\n";
}
inline std::string code(const std::string& name, const VecX<double>& v) {
  std::string s = "soa::VecX<double> " + name + "(" + std::to_string(v.size()) + ");";
  if (v.size() > 0) s += " " + name + " << " + list(v).substr(1, list(v).size() - 2) + ";";
  return s + "\n";
}
inline std::string code(const std::string& name, const Phi& p) {
  return "soa::Phi " + name + "(soa::Mat3<double>" + list(p.R()) + ", soa::Vec3<double>" +
         list(p.l()) + ");\n";
}
inline std::string code(const std::string& name, const Pose& p) {
  return "soa::Pose " + name + "(soa::Mat3<double>" + list(p.R()) + ", soa::Vec3<double>" +
         list(p.l()) + ");\n";
}
template <class Kind>
std::string code(const std::string& name, const SpatialVector<double, Kind>& v) {
  // The type's name as the student writes it.
  const char* type = std::is_same_v<SpatialVector<double, Kind>, Velocity> ? "soa::Velocity"
                     : std::is_same_v<SpatialVector<double, Kind>, Acceleration>
                         ? "soa::Acceleration"
                     : std::is_same_v<SpatialVector<double, Kind>, Force> ? "soa::Force"
                                                                          : "soa::Momentum";
  return std::string(type) + " " + name + "(soa::Vec3<double>" + list(Vec3<double>(v.angular())) +
         ", soa::Vec3<double>" + list(Vec3<double>(v.linear())) + ");\n";
}
inline std::string code(const std::string& name, const SpatialInertia& M) {
  return "soa::SpatialInertia " + name + "(" + num(M.mass()) + ", soa::Vec3<double>" + list(M.h()) +
         ", soa::Mat3<double>" + list(M.J()) + ");\n";
}

inline const char* hinge_enum(HingeType t) {
  switch (t) {
    case HingeType::Revolute:
      return "Revolute";
    case HingeType::Prismatic:
      return "Prismatic";
    case HingeType::Helical:
      return "Helical";
    case HingeType::Universal:
      return "Universal";
    case HingeType::Spherical:
      return "Spherical";
    case HingeType::Free:
      return "Free";
    case HingeType::Locked:
      return "Locked";
  }
  return "Revolute";
}

/// The chain \p m as code that rebuilds it (`soa::Model name = ...`), base first as
/// soa::ModelT::from_base_first takes it.
inline std::string code(const std::string& name, const Model& m) {
  std::ostringstream s;
  s << "std::vector<soa::Body> " << name << "_bodies(" << m.n() << ");  // base first\n";
  for (int k = m.n(); k >= 1; --k) {
    const Body& B = m.body(k);
    const std::string b = name + "_bodies[" + std::to_string(m.n() - k) + "]";
    s << "// body " << k << " (" << hinge_type_name(B.hinge.type) << " hinge)\n";
    s << b << ".M = soa::SpatialInertia(" << num(B.M.mass()) << ", soa::Vec3<double>"
      << list(B.M.h()) << ", soa::Mat3<double>" << list(B.M.J()) << ");\n";
    s << b << ".placement = soa::Pose(soa::Mat3<double>" << list(B.placement.R())
      << ", soa::Vec3<double>" << list(B.placement.l()) << ");\n";
    s << b << ".hinge.type = soa::HingeType::" << hinge_enum(B.hinge.type) << ";\n";
    s << b << ".hinge.axis = soa::Vec3<double>" << list(B.hinge.axis) << ";\n";
    if (B.hinge.type == HingeType::Universal)
      s << b << ".hinge.axis2 = soa::Vec3<double>" << list(B.hinge.axis2) << ";\n";
    if (B.hinge.type == HingeType::Helical)
      s << b << ".hinge.pitch = " << num(B.hinge.pitch) << ";\n";
    if (B.stiffness != 0) s << b << ".stiffness = " << num(B.stiffness) << ";\n";
    if (B.damping != 0) s << b << ".damping = " << num(B.damping) << ";\n";
  }
  s << "soa::Model " << name << " = soa::Model::from_base_first(" << name << "_bodies);\n";
  if (m.has_gravity()) s << name << ".gravity = soa::Vec3<double>" << list(m.gravity) << ";\n";
  return s.str();
}
inline std::string code(const std::string& name, const State& x) {
  return code(name + "_theta", x.theta) + code(name + "_beta", x.beta) + "soa::State " + name +
         "{" + name + "_theta, " + name + "_beta};\n";
}

/// The tags of a chain case: moving, gravity, the hinge types, several bodies, springs.
inline unsigned chain_tags(const Model& m, const State& x) {
  unsigned t = 0;
  if (x.beta.size() && x.beta.cwiseAbs().maxCoeff() > 0) t |= kMoving;
  if (m.has_gravity()) t |= kGravity;
  if (m.has_springs()) t |= kSprings;
  if (m.n() > 1) t |= kSeveralBodies;
  for (int k = 1; k <= m.n(); ++k) {
    const HingeType h = m.body(k).hinge.type;
    if (h == HingeType::Prismatic) t |= kPrismatic;
    if (h == HingeType::Helical) t |= kHelical;
    if (h == HingeType::Universal || h == HingeType::Spherical || h == HingeType::Free)
      t |= kMultiDof;
  }
  return t;
}

// --- Stacked per-body quantities -----------------------------------------------------------------

inline Vec6<double> as_vec6(const Vec6<double>& v) {
  return v;
}
template <class Kind>
Vec6<double> as_vec6(const SpatialVector<double, Kind>& v) {
  return v.vector();
}

/// Per-body spatial vectors (or 6-vectors) stacked tip first, as the operators lay them out:
/// body k at rows 6(k-1) ... 6k-1.
template <class V>
VecX<double> stack(const std::vector<V>& v) {
  VecX<double> s(6 * Eigen::Index(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) s.segment<6>(6 * Eigen::Index(i)) = as_vec6(v[i]);
  return s;
}

// --- Names of the entries of a result, for "where the error is" ---------------------------------

/// Names entry (i, j) of a result and the part it belongs to (the error is summed per part).
struct EntryName {
  std::string entry;  ///< "T[3] (body 2, revolute)"
  std::string part;   ///< "T of body 2"
};
using Naming = std::function<EntryName(Eigen::Index i, Eigen::Index j)>;

/// Which body each dof of \p m belongs to (tip first), and the bodies' hinge names: a copy,
/// so that a Naming outlives the model of its case.
struct DofMap {
  std::vector<int> body;           ///< body of dof i
  std::vector<std::string> hinge;  ///< hinge type name of body k at k-1
  explicit DofMap(const Model& m) {
    for (int k = 1; k <= m.n(); ++k) {
      hinge.push_back(hinge_type_name(m.body(k).hinge.type));
      for (int d = 0; d < m.body(k).hinge.nv(); ++d) body.push_back(k);
    }
  }
};

/// A vector of hinge quantities (size nv, tip first): entry i is a dof of body k.
inline Naming per_dof(const Model& m, const std::string& sym) {
  return [map = DofMap(m), sym](Eigen::Index i, Eigen::Index) {
    const int k = i < Eigen::Index(map.body.size()) ? map.body[std::size_t(i)] : 0;
    const std::string h = k > 0 ? map.hinge[std::size_t(k - 1)] : "?";
    return EntryName{
        sym + "[" + std::to_string(i) + "] (body " + std::to_string(k) + ", " + h + ")",
        sym + " of body " + std::to_string(k) + " (" + h + ")"};
  };
}

/// A stack of spatial vectors (6 per body, body 1 first): angular and linear part per body.
inline Naming per_body_spatial(const std::string& sym) {
  return [sym](Eigen::Index i, Eigen::Index) {
    const std::string k = std::to_string(i / 6 + 1);
    const bool ang = i % 6 < 3;
    const std::string part = sym + "(" + k + ") " + (ang ? "angular" : "linear") + " part";
    return EntryName{
        sym + "(" + k + ")[" + std::to_string(i % 6) + "] (" + (ang ? "angular" : "linear") + ")",
        part};
  };
}

/// One spatial vector: angular (rows 0-2) and linear (rows 3-5) part.
inline Naming spatial(const std::string& sym) {
  return [sym](Eigen::Index i, Eigen::Index) {
    const bool ang = i < 3;
    return EntryName{sym + "[" + std::to_string(i) + "] (" + (ang ? "angular" : "linear") + ")",
                     std::string("the ") + (ang ? "angular" : "linear") + " part of " + sym};
  };
}

/// A 6x6 matrix: its four 3x3 blocks.
inline Naming blocks6(const std::string& sym) {
  return [sym](Eigen::Index i, Eigen::Index j) {
    static const char* rc[2] = {"angular", "linear"};
    return EntryName{sym + "(" + std::to_string(i) + "," + std::to_string(j) + ")",
                     std::string("the ") + rc[i / 3] + "-" + rc[j / 3] + " block of " + sym};
  };
}

/// A matrix over bodies (6 rows/cols per body): block (k, l) of 6x6.
inline Naming body_blocks(const std::string& sym) {
  return [sym](Eigen::Index i, Eigen::Index j) {
    const std::string b = std::to_string(i / 6 + 1) + "," + std::to_string(j / 6 + 1);
    return EntryName{sym + "(" + std::to_string(i) + "," + std::to_string(j) + ")",
                     "block (" + b + ") of " + sym};
  };
}

/// A matrix over dofs (nv x nv): block (k, l) of the bodies the dofs belong to.
inline Naming dof_blocks(const Model& m, const std::string& sym) {
  return [map = DofMap(m), sym](Eigen::Index i, Eigen::Index j) {
    auto body = [&map](Eigen::Index d) {
      return d < Eigen::Index(map.body.size()) ? map.body[std::size_t(d)] : 0;
    };
    return EntryName{sym + "(" + std::to_string(i) + "," + std::to_string(j) + ")",
                     sym + "(" + std::to_string(body(i)) + "," + std::to_string(body(j)) +
                         ") (bodies " + std::to_string(body(i)) + " and " +
                         std::to_string(body(j)) + ")"};
  };
}

// --- The catalogue of mistakes ------------------------------------------------------------------

/// A classic wrong answer of an exercise, computed from the reference for one case. Of kind
/// kMeasured it is not a diagnosis but a variant of the computation whose equality with the
/// result is reported as what it is, a measurement: \p says completes "your result matches"
/// ("the expected value with D in place of D^-1").
struct Mistake {
  const char* kind;  ///< "transpose", "sign", "neighbour index", "dropped term", "wrong frame",
                     ///< "degrees", ..., or kMeasured
  std::string says;  ///< "your result equals phi(k+1,k) V: did you transpose?"
  MatX<double> value;
};
using Mistakes = std::vector<Mistake>;

/// The kind of a Mistake that is a measured variant, not a named mistake.
inline constexpr const char* kMeasured = "measured";

/// The sign-flipped answer: a mistake every exercise has.
template <class D>
Mistake negated(const Eigen::MatrixBase<D>& expected, std::string says) {
  return Mistake{"sign", std::move(says), MatX<double>(-expected)};
}

// --- The check ----------------------------------------------------------------------------------

/// One named check of an exercise over many random cases (see the file's comment).
class Check {
 public:
  /// \p what names the checked quantity in words ("T, the hinge forces"); a case passes when
  /// \f$\|got - expected\| \le tol \cdot scale\f$.
  Check(std::string what, double tol)
      : what_(std::move(what)), tol_(tol), worst_(what_ + " / scale"), id_(next_id()++) {
    ++live();
  }
  Check(const Check&) = delete;
  Check& operator=(const Check&) = delete;

  /// Case \p i. \p inputs and \p mistakes are called only for failing cases (the first few).
  /// Returns true when the case passes.
  template <class G, class E>
  bool add(int i, const Eigen::MatrixBase<G>& got, const Eigen::MatrixBase<E>& expected,
           double scale, unsigned tags, const std::function<std::string()>& inputs,
           const std::function<Mistakes()>& mistakes = {}, const Naming& naming = {}) {
    ++cases_;
    for (const auto& t : meanings()) (tags & t.tag ? with_ : without_)[t.tag].cases++;
    const MatX<double> g = got.template cast<double>(), e = expected.template cast<double>();
    if (g.rows() != e.rows() || g.cols() != e.cols()) {
      if (shape_.empty())
        shape_ = what_ + ": your result is " + std::to_string(g.rows()) + " x " +
                 std::to_string(g.cols()) + ", expected " + std::to_string(e.rows()) + " x " +
                 std::to_string(e.cols()) + " (case " + std::to_string(i) + ")\n" +
                 indent(inputs ? inputs() : "");
      fail(tags);
      worst_.add(INFINITY, i);
      return false;
    }
    double r = (g - e).norm() / std::max(scale, 1e-300);
    if (!g.allFinite()) r = INFINITY;
    worst_.add(r, i);
    if (r <= tol_) return true;
    fail(tags);
    track_factor(g, e);
    if (r >= worst_r_) {
      worst_r_ = r;
      worst_i_ = i;
      worst_exp_ = e;
      worst_inputs_ = inputs ? inputs() : "";
      worst_abs_ = (g - e).norm();
      worst_norm_ = e.norm();
      worst_nan_ = !g.allFinite();
    }
    // The case shown in full is the simplest that fails: the smallest result, then the
    // shortest inputs as code (fewer bodies, zeros, short readable numbers), then the worst
    // of those: easier to follow by hand than the worst of all.
    if (shown_i_ < 0 || g.size() <= shown_got_.size()) {
      std::string in = inputs ? inputs() : "";
      if (shown_i_ < 0 || g.size() < shown_got_.size() || in.size() < shown_inputs_.size() ||
          (in.size() == shown_inputs_.size() && r > shown_r_)) {
        shown_i_ = i;
        shown_r_ = r;
        shown_got_ = g;
        shown_exp_ = e;
        shown_inputs_ = std::move(in);
        naming_ = naming;
      }
    }
    if (mistakes && examined_ < kExamine) {
      ++examined_;
      for (Mistake& mk : mistakes()) {
        Tally& t = tally(mk);
        if (mk.value.rows() != e.rows() || mk.value.cols() != e.cols()) continue;
        // In a failing case every variant is evidence: one equal to the right answer here
        // is not what the student computed.
        ++t.informative;
        if ((g - mk.value).norm() / std::max(scale, 1e-300) <= 1e3 * tol_) ++t.matched;
      }
    }
    return false;
  }

  /// Reports in the order the checks were declared (the table's row shows the first): the
  /// last check of a test to go reports them all.
  ~Check() {
    auto& p = pending();
    // An exception (the stub's NotDone) stops the test: nothing to say about the numbers.
    if (std::uncaught_exceptions() == 0 && cases_ > 0 && failed_ > 0)
      p.emplace_back(id_, message());
    if (--live() > 0) return;
    std::sort(p.begin(), p.end());
    for (const auto& [id, msg] : p) ADD_FAILURE() << msg;
    p.clear();
  }

  /// What one call of add() is, in the message's counts: "case" (a random case), or "body",
  /// "step" when a test gives each body or step of a case separately.
  void count_as(std::string unit) { unit_ = std::move(unit); }

  /// Says what \p tag means for this check (the cases it marks, "where ..."), in place of
  /// the general wording of tag_meanings().
  void tag_meaning(Tag tag, const char* cases) { overrides_.push_back(TagMeaning{tag, cases}); }

  int failed() const { return failed_; }
  double worst() const { return worst_.value(); }

  /// The feedback: first line for the table's row, the rest under it. For a level 3
  /// exercise whose student has not yet earned it (see progress()), the catalogue's mistake
  /// is not named: the message gives the symptom and the place, and says when it will.
  std::string message() const {
    if (!shape_.empty()) return shape_;
    const ExerciseInfo ex = current_exercise();
    const Progress pr = ex.level == 3 ? progress(ex) : Progress{0, 0, true};
    std::ostringstream s;
    s << what_ << ": wrong in " << failed_ << " of " << cases_ << " " << unit_ << "s (worst "
      << error_words() << ", " << unit_ << " " << worst_i_ << ")\n";
    bool named = false, known = false;
    for (const Tally& t : tallies_)
      if (t.kind != std::string(kMeasured) && t.informative > 0 && t.matched == t.informative) {
        known = true;
        if (pr.named) s << "  likely mistake (" << t.kind << "): " << t.says << "\n";
        named = pr.named;
      }
    if (!named) {
      if (pr.named)
        for (const Tally& t : tallies_)
          if (t.kind != std::string(kMeasured) && t.informative > 0 &&
              t.matched * 2 >= t.informative && t.matched > 0)
            s << "  perhaps (" << t.kind << ", " << t.matched << " of " << t.informative
              << " failing " << unit_ << "s): " << t.says << "\n";
      for (const std::string& sym : symptoms(pr.named)) s << "  symptom: " << sym << "\n";
    }
    if (!pr.named) s << withheld(ex, pr, known);
    s << where();
    s << case_code();
    return s.str();
  }

 private:
  static constexpr int kExamine = 64;  // failing cases whose mistakes are computed
  static int& next_id() {
    static int n = 0;
    return n;
  }
  static int& live() {
    static int n = 0;
    return n;
  }
  static std::vector<std::pair<int, std::string>>& pending() {
    static std::vector<std::pair<int, std::string>> p;
    return p;
  }
  std::vector<TagMeaning> meanings() const {
    std::vector<TagMeaning> m = tag_meanings();
    for (const TagMeaning& o : overrides_) {
      bool known = false;
      for (TagMeaning& t : m)
        if (t.tag == o.tag) t = o, known = true;
      if (!known) m.push_back(o);  // kOwn1, kOwn2
    }
    return m;
  }
  struct Count {
    int cases = 0, failed = 0;
  };
  struct Tally {
    const char* kind;
    std::string says;
    int informative = 0, matched = 0;
  };

  Tally& tally(const Mistake& mk) {
    for (Tally& t : tallies_)
      if (t.says == mk.says) return t;
    tallies_.push_back(Tally{mk.kind, mk.says});
    return tallies_.back();
  }
  void fail(unsigned tags) {
    ++failed_;
    for (const auto& t : meanings()) (tags & t.tag ? with_ : without_)[t.tag].failed++;
  }

  // What was measured: a variant of the computation the result equals (kMeasured, shown
  // only when \p measured_variants), a constant factor, then a tag that all failing cases
  // have while the cases without it all pass (or the reverse).
  std::vector<std::string> symptoms(bool measured_variants) const {
    const std::string every = failed_ == cases_ ? "in every " + unit_ : "in every failing " + unit_;
    std::vector<std::string> out;
    if (measured_variants)
      for (const Tally& t : tallies_)
        if (t.kind == std::string(kMeasured) && t.informative > 0 && t.matched == t.informative)
          out.push_back(every + ", your result matches " + t.says);
    if (factor_ok_ && factor_cases_ > 0 && std::abs(factor_ - 1) > 1e-3) {
      char b[96];
      std::snprintf(b, sizeof b, "your result is %.3f times the expected value ", factor_);
      out.push_back(b + every);
    }
    // "Fails only where X" says more than "passes wherever Y": those first.
    std::vector<std::string> only, never;
    for (const auto& t : meanings()) {
      const Count w = at(with_, t.tag), wo = at(without_, t.tag);
      if (wo.cases > 0 && wo.failed == 0 && w.failed > 0)
        only.push_back("it fails only where " + std::string(t.cases) + ": " +
                       std::to_string(w.failed) + " of those " + std::to_string(w.cases) + " " +
                       unit_ + "s fail, and every other " + unit_ + " passes");
      else if (w.cases > 0 && w.failed == 0 && wo.failed > 0)
        never.push_back("it passes wherever " + std::string(t.cases) + "; " +
                        std::to_string(wo.failed) + " of the " + std::to_string(wo.cases) +
                        " other " + unit_ + "s fail");
    }
    only.insert(only.end(), never.begin(), never.end());
    if (only.size() > 2) only.resize(2);
    out.insert(out.end(), only.begin(), only.end());
    if (out.empty() && failed_ == cases_)
      out.push_back("every " + unit_ + " fails, whatever it has (no kind of case passes)");
    return out;
  }

  // Level 3, the mistake not yet named: when it will be.
  std::string withheld(const ExerciseInfo& ex, const Progress& pr, bool known) const {
    std::ostringstream s;
    s << "  "
      << (known ? "the checker knows this mistake: it names it" : "known mistakes are named");
    if (ex.explicit_after > 0) {
      s << " after " << ex.explicit_after << " failed runs of make exercises";
      if (!cases_dir().empty()) s << " (this is failed run " << pr.failed_runs + 1 << ")";
    }
    if (ex.hints > 0)
      s << (ex.explicit_after > 0 ? ", or " : " ") << "once you have read all " << ex.hints
        << " hints (make exercises HINT=" << ex.id << ", " << pr.hints_seen << " read so far)";
    s << "\n";
    return s.str();
  }

  // A constant factor between the result and the expected value, over the failing cases.
  template <class G, class E>
  void track_factor(const G& g, const E& e) {
    const double ee = e.squaredNorm();
    if (!factor_ok_ || ee == 0 || !g.allFinite()) {
      factor_ok_ = false;
      return;
    }
    const double c = (g.array() * e.array()).sum() / ee;
    if ((g - c * e).norm() > 1e-6 * std::max(g.norm(), 1e-300) ||
        (factor_cases_ > 0 && std::abs(c - factor_) > 1e-6 * std::abs(factor_))) {
      factor_ok_ = false;
      return;
    }
    if (factor_cases_++ == 0) factor_ = c;
  }
  static Count at(const std::map<unsigned, Count>& v, unsigned tag) {
    const auto it = v.find(tag);
    return it == v.end() ? Count{} : it->second;
  }

  // Where the error of the worst case sits: parts ranked by their share, then the entries.
  std::string where() const {
    if (shown_got_.size() == 0) return "";
    std::ostringstream s;
    const MatX<double> d = shown_got_ - shown_exp_;
    const double total = d.squaredNorm();
    std::vector<std::pair<std::string, double>> parts;
    std::vector<std::tuple<double, std::string, double, double>> entries;
    for (Eigen::Index j = 0; j < d.cols(); ++j)
      for (Eigen::Index i = 0; i < d.rows(); ++i) {
        const EntryName n =
            naming_
                ? naming_(i, j)
                : EntryName{d.cols() == 1 ? "[" + std::to_string(i) + "]"
                                          : "(" + std::to_string(i) + "," + std::to_string(j) + ")",
                            ""};
        if (!n.part.empty()) {
          auto it = std::find_if(parts.begin(), parts.end(),
                                 [&](const auto& p) { return p.first == n.part; });
          if (it == parts.end()) parts.emplace_back(n.part, 0.0), it = parts.end() - 1;
          it->second += d(i, j) * d(i, j);
        }
        entries.emplace_back(std::abs(d(i, j)), n.entry, shown_exp_(i, j), shown_got_(i, j));
      }
    if (!parts.empty() && total > 0) {
      std::sort(parts.begin(), parts.end(),
                [](const auto& a, const auto& b) { return a.second > b.second; });
      s << "  where, in case " << shown_i_ << " (the simplest that fails):";
      int shown = 0;
      for (const auto& [name, e2] : parts) {
        if (shown == 4 || e2 < 1e-6 * total) break;
        s << (shown++ ? "," : "") << " " << name << " " << int(std::lround(100 * e2 / total))
          << "%";
      }
      s << " of the error\n";
    }
    std::stable_sort(entries.begin(), entries.end(),
                     [](const auto& a, const auto& b) { return std::get<0>(a) > std::get<0>(b); });
    const std::size_t n_show = std::min<std::size_t>(entries.size(), 6);
    char line[200];
    std::snprintf(line, sizeof line, "    %-34s %22s %22s\n", "entry", "expected", "got");
    s << line;
    for (std::size_t k = 0; k < n_show; ++k) {
      std::snprintf(line, sizeof line, "    %-34s %22.15g %22.15g\n",
                    std::get<1>(entries[k]).c_str(), std::get<2>(entries[k]),
                    std::get<3>(entries[k]));
      s << line;
    }
    if (entries.size() > n_show)
      s << "    (" << entries.size() - n_show << " more entries, with smaller errors)\n";
    return s.str();
  }

  // The shown case's inputs as code: inline when short; else written as a file under
  // $SOA_EXERCISE_CASES (make exercises sets it to build/exercises/cases), named for the
  // exercise and the check.
  std::string case_code() const {
    std::string out = one_case(shown_i_, shown_inputs_, shown_exp_, "the simplest that fails", "");
    if (worst_i_ != shown_i_ && !worst_inputs_.empty())
      out += one_case(worst_i_, worst_inputs_, worst_exp_, "the worst", "-worst");
    return out;
  }
  std::string one_case(int i, const std::string& inputs, const MatX<double>& expected,
                       const char* which, const char* suffix) const {
    if (inputs.empty()) return "";
    const std::string head = "  case " + std::to_string(i) + " (" + which + ") as code";
    if (std::count(inputs.begin(), inputs.end(), '\n') <= 12)
      return head + " (paste into a program):\n" + indent(inputs);
    const char* dir = std::getenv("SOA_EXERCISE_CASES");
    if (!dir || !*dir) return head + ": set SOA_EXERCISE_CASES=<dir> to have it written out\n";
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info ? info->test_suite_name() : "case";
    if (name.rfind("Exercise", 0) == 0) name = name.substr(8);
    std::string what;
    for (char ch : what_) what += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
    const std::string path =
        std::string(dir) + "/" + name + "-" + what.substr(0, 24) + suffix + ".cpp";
    std::FILE* out = std::fopen(path.c_str(), "w");
    if (!out) return head + ": could not write " + path + "\n";
    std::fprintf(out,
                 "// %s, case %d (%s): a random case where your result is wrong.\n"
                 "// Paste it into a program of your own (it includes exercises.hpp).\n"
                 "#include <iostream>\n\n#include \"exercises.hpp\"\n\nint main() {\n",
                 what_.c_str(), i, which);
    std::istringstream in(inputs);
    std::string line;
    while (std::getline(in, line)) std::fprintf(out, "  %s\n", line.c_str());
    std::fprintf(out, "  // expected (row by row): %s\n}\n", list(expected).c_str());
    std::fclose(out);
    return head + " (paste into a program): " + path + "\n";
  }

  // The worst error in plain words: relative to the expected value, or absolute when that is
  // zero, or "not a number".
  std::string error_words() const {
    if (worst_nan_) return "result not finite (NaN or inf)";
    if (worst_norm_ > 0) return "relative error " + short_num(worst_abs_ / worst_norm_);
    return "error " + short_num(worst_abs_) + " where the answer is zero";
  }

  static std::string short_num(double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%.2g", x);
    return b;
  }
  static std::string indent(const std::string& text) {
    std::string out, line;
    std::istringstream in(text);
    while (std::getline(in, line)) out += "      " + line + "\n";
    return out;
  }

  std::string what_;
  double tol_;
  Worst worst_;
  int id_;
  std::vector<TagMeaning> overrides_;
  int cases_ = 0, failed_ = 0, examined_ = 0;
  std::map<unsigned, Count> with_, without_;
  std::vector<Tally> tallies_;
  bool factor_ok_ = true;  // every failing case so far is factor_ times the expected value
  double factor_ = 1;
  int factor_cases_ = 0;
  std::string shape_;
  double worst_r_ = -1, worst_abs_ = 0, worst_norm_ = 0;
  bool worst_nan_ = false;
  std::string unit_ = "case";
  int worst_i_ = -1;
  double shown_r_ = 0;
  int shown_i_ = -1;
  MatX<double> shown_got_, shown_exp_, worst_exp_;
  std::string worst_inputs_;
  std::string shown_inputs_;
  Naming naming_;
};

}  // namespace soa::test
