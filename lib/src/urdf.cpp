// URDF scenes: a robot description read with urdfdom, mapped onto the course's serial chain
// as the JSON reader's document (docs/scenes.md, "URDF input"), a structure that the JSON
// reader checks and assembles; `soa convert` writes that same structure as JSON text, so
// loading a URDF and loading the JSON that `soa convert` prints give the same model bit for
// bit.
//
// Before urdfdom sees the file, a linear scan bounds its nesting and its element count (the
// XML parser recurses per level), and a pass over the elements urdfdom reads refuses what it
// would drop without a word or crash on (an unknown attribute or child, a second <origin>, a
// '%' in a value, an empty name); after, the model is checked as a tree (a joint cycle, a
// link that is its own parent) and its names as UTF-8 text, and it is freed link by link (its
// links own their children: freeing a long chain would recurse once per link).
//
// The mapping (the table of docs/scenes.md): a link is a body, the joint above it is its
// hinge; the root link and whatever is fixed to it is the ground; the chain is the path from
// the root to the tip link; links fixed to the chain off that path are merged into the body
// they hang on, as rigid mass; a link without <inertial> is a massless frame.
#include <tinyxml.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

#include <console_bridge/console.h>
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "scene_detail.hpp"
#include "soa/phi.hpp"
#include "soa/printable.hpp"
#include "soa/rotation.hpp"
#include "soa/scene.hpp"
#include "soa/spatial_inertia.hpp"

namespace soa {
namespace {

/// Everything urdfdom says goes here, not to the terminal. Its errors and warnings are kept:
/// urdfdom logs a value it cannot read and goes on without it (a link keeps a zero
/// <inertial>), so any of them makes the file an error. (console_bridge's handler is global:
/// one parse at a time, under urdfdom_mutex.)
class Capture : public console_bridge::OutputHandler {
 public:
  Capture() : level_(console_bridge::getLogLevel()) {
    console_bridge::useOutputHandler(this);
    console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_WARN);
  }
  ~Capture() override {
    console_bridge::restorePreviousOutputHandler();
    console_bridge::setLogLevel(level_);
  }
  Capture(const Capture&) = delete;
  Capture& operator=(const Capture&) = delete;
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level < console_bridge::CONSOLE_BRIDGE_LOG_WARN) return;
    if (++count_ <= 3) said_ += (said_.empty() ? "" : "; then: ") + printable(text);
  }
  /// urdfdom's first three errors and warnings, in its words ("" when it had none).
  std::string said() const {
    return count_ > 3 ? said_ + " (and " + std::to_string(count_ - 3) + " more)" : said_;
  }

 private:
  std::string said_;
  int count_ = 0;
  console_bridge::LogLevel level_;
};
std::mutex urdfdom_mutex;

/// A double as the shortest text that reads back to the same bits.
std::string num(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}
/// A short number for messages and comments.
std::string brief(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}
/// A name of the file in single quotes, as a message or a comment shows it.
std::string quote(const std::string& name) {
  return "'" + printable(name) + "'";
}
/// The first few of \p names, then how many more: a message stays short however large the
/// robot.
std::string first_few(const std::vector<std::string>& names, std::size_t few = 6) {
  std::string s;
  for (std::size_t i = 0; i < names.size() && i < few; ++i) s += (i ? ", " : "") + names[i];
  if (names.size() > few) s += ", and " + std::to_string(names.size() - few) + " more";
  return s;
}
using json = nlohmann::json;
json to_json(const Vec3<double>& v) {
  return json::array({v[0], v[1], v[2]});
}

Vec3<double> to_vec(const urdf::Vector3& v) {
  return Vec3<double>(v.x, v.y, v.z);
}
/// A URDF pose (the rotation a unit quaternion urdfdom made from rpy) as a Pose.
Pose to_pose(const urdf::Pose& p) {
  const UnitQuaternion q(Vec3<double>(p.rotation.x, p.rotation.y, p.rotation.z), p.rotation.w);
  return Pose(q.matrix(), to_vec(p.position));
}
bool is_identity(const urdf::Rotation& r) {
  return r.x == 0 && r.y == 0 && r.z == 0 && r.w == 1;
}

const char* type_name(int t) {
  switch (t) {
    case urdf::Joint::REVOLUTE:
      return "revolute";
    case urdf::Joint::CONTINUOUS:
      return "continuous";
    case urdf::Joint::PRISMATIC:
      return "prismatic";
    case urdf::Joint::FLOATING:
      return "floating";
    case urdf::Joint::PLANAR:
      return "planar";
    case urdf::Joint::FIXED:
      return "fixed";
    default:
      return "unknown";
  }
}

/// One body of the scene being built: a link of the chain and the joint above it.
struct Entry {
  std::string link, joint, joint_type;
  std::string hinge;  // the scene's hinge type
  Pose placement;
  const urdf::Pose* origin = nullptr;  // the joint's own origin, written as given when set
  Vec3<double> axis = Vec3<double>::UnitX();
  bool massless = true;
  double mass = 0;
  Vec3<double> com = Vec3<double>::Zero();
  Mat3<double> J = Mat3<double>::Zero();
  double damping = 0;
  const urdf::JointLimits* limits = nullptr;
  bool continuous = false;
  double friction = 0;
  std::vector<std::string> notes;  // comments above the body
};

/// The links of \p l's subtree, \p l first, depth first (without recursion: a chain of 10^5
/// links is 10^5 levels deep).
std::vector<const urdf::Link*> subtree(const urdf::Link& l) {
  std::vector<const urdf::Link*> out, stack{&l};
  while (!stack.empty()) {
    const urdf::Link* x = stack.back();
    stack.pop_back();
    out.push_back(x);
    for (auto c = x->child_links.rbegin(); c != x->child_links.rend(); ++c)
      stack.push_back(c->get());
  }
  return out;
}

/// What the XML pass found that the model does not keep: the joints whose <limit> leaves out
/// lower or upper (the URDF spec's default, 0, is taken), by name.
struct XmlFacts {
  std::unordered_map<std::string, std::string> limit_default;  // joint -> "lower" or "upper"
};

class Converter {
 public:
  Converter(std::string file, const urdf::ModelInterface& model, const XmlFacts& facts,
            const UrdfOptions& o)
      : file_(std::move(file)), model_(model), facts_(facts), options_(o) {}

  detail::UrdfScene run() {
    for (const std::string& j : options_.lock) {
      if (!model_.getJoint(j)) fail("--lock: no joint named " + quote(j) + names_of_joints());
      locked_.insert(j);
    }
    std::size_t n_moving = 0;
    for (const auto& [name, j] : model_.joints_) n_moving += moving(*j);
    if (n_moving == 0) fail("no moving joint: every joint is fixed (or locked), no chain");
    const urdf::LinkConstSharedPtr root = model_.getRoot();
    const urdf::Link* tip = tip_ = find_tip(*root);
    std::vector<const urdf::Link*> path;  // root ... tip
    for (const urdf::Link* l = tip; l; l = l->getParent().get()) path.push_back(l);
    std::reverse(path.begin(), path.end());
    std::size_t first = 1;  // the first moving joint on the path
    while (first < path.size() && !moving(*path[first]->parent_joint)) ++first;
    if (first == path.size())
      fail("link " + quote(tip->name) + ": fixed to the root " + quote(root->name) +
           " all the way: no moving joint between them, no chain (choose another tip with "
           "--tip LINK)");
    // The ground: the root and what is fixed to it, up to the first moving joint.
    Pose ground;  // root -> the first moving joint's parent link
    for (std::size_t i = 1; i < first; ++i)
      ground = ground * to_pose(path[i]->parent_joint->parent_to_joint_origin_transform);
    double ground_mass = 0;
    std::vector<std::string> ground_links;
    for (std::size_t i = 0; i < first; ++i) {
      ground_links.push_back(quote(path[i]->name));
      if (path[i]->inertial) ground_mass += path[i]->inertial->mass;
      for (const urdf::LinkSharedPtr& c : path[i]->child_links)
        if (c.get() != path[i + 1]) ground_mass += fixed_subtree(*c, *path[i], ground_links);
    }
    bool geometry = false;
    for (const auto& [name, l] : model_.links_)
      geometry = geometry || !l->visual_array.empty() || !l->collision_array.empty();
    if (geometry) header_.push_back("<visual> and <collision> geometry: not used");
    header_.push_back("the ground: " + first_few(ground_links) +
                      (ground_mass > 0 ? " (" + brief(ground_mass) +
                                             " kg fixed to the world: not part of the dynamics)"
                                       : ""));
    for (std::size_t i = first; i < path.size(); ++i) {
      const urdf::Link& link = *path[i];
      const urdf::Joint& joint = *link.parent_joint;
      Entry e = entry(link, joint);
      if (i == first && first > 1) {
        e.placement = ground * e.placement;
        e.origin = nullptr;
        e.notes.push_back("placement: the joint's origin composed with the fixed joints from " +
                          quote(root->name));
      }
      // Links fixed to this one off the chain: rigid mass.
      SpatialInertia M = inertia_of(e);
      bool merged_mass = false;
      for (const urdf::LinkSharedPtr& c : link.child_links) {
        if (i + 1 < path.size() && c.get() == path[i + 1]) continue;
        std::vector<std::string> merged;
        const SpatialInertia side = branch_inertia(*c, link, merged, e.notes);
        if (side.mass() > 0) M = M + side, merged_mass = true;
        e.notes.push_back("merged, fixed to it off the chain: " + first_few(merged) +
                          (side.mass() > 0 ? " (" + brief(side.mass()) + " kg)" : " (massless)"));
      }
      if (merged_mass) set_inertia(M, e);  // else the link's own numbers, as the file has them
      entries_.push_back(std::move(e));
    }
    check_moves_mass();
    return scene(tip->name);
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const { throw Error(file_ + ": " + problem); }

  bool moving(const urdf::Joint& j) const {
    return j.type != urdf::Joint::FIXED && !locked_.count(j.name);
  }
  /// A joint --lock fixed: said the same way wherever it is, on the chain or off it.
  std::string locked_note(const urdf::Joint& j) const {
    return "joint " + quote(j.name) + " (" + type_name(j.type) +
           ") locked at its zero position by --lock";
  }

  std::string names_of_joints() const {
    std::vector<std::string> names;
    for (const auto& [name, j] : model_.joints_) names.push_back(quote(name));
    return names.empty() ? " (the model has no joint)" : " (joints: " + first_few(names) + ")";
  }

  static std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
  }

  /// The moving joints between the root and \p l.
  std::size_t moving_above(const urdf::Link& l) const {
    std::size_t n = 0;
    for (const urdf::Link* x = &l; x->parent_joint; x = x->getParent().get())
      n += moving(*x->parent_joint);
    return n;
  }

  /// --tip, or the one leaf below every moving joint.
  const urdf::Link* find_tip(const urdf::Link& root) {
    if (!options_.tip.empty()) {
      const urdf::LinkConstSharedPtr l = model_.getLink(options_.tip);
      if (!l) {
        std::vector<std::string> names;
        for (const auto& [name, link] : model_.links_) names.push_back(quote(name));
        fail("--tip: no link named " + quote(options_.tip) + " (links: " + first_few(names) + ")");
      }
      return l.get();
    }
    std::size_t n_moving = 0;
    for (const auto& [name, j] : model_.joints_) n_moving += moving(*j);
    // Below every moving joint: the depth-first order meets a leaf's ancestors before it.
    std::unordered_map<const urdf::Link*, std::size_t> above;  // moving joints above a link
    std::vector<const urdf::Link*> leaves, full;
    for (const urdf::Link* l : subtree(root)) {
      const urdf::Link* p = l->getParent().get();
      const std::size_t n = p ? above[p] + moving(*l->parent_joint) : 0;
      above[l] = n;
      if (!l->child_links.empty()) continue;
      leaves.push_back(l);
      if (n == n_moving) full.push_back(l);
    }
    if (full.size() == 1) return full[0];
    std::vector<std::string> names;
    for (const urdf::Link* l : (full.empty() ? leaves : full)) names.push_back(quote(l->name));
    if (full.empty())
      fail("a tree, not a chain: no single path from " + quote(root.name) +
           " passes every moving joint (its ends: " + first_few(names) +
           "); choose the tip with --tip LINK, and lock the joints off its path with --lock JOINT");
    // Several ends, each below every moving joint: their paths part after the last moving
    // joint, and fixed joints only follow. The chain ends where they part.
    std::vector<const urdf::Link*> common;
    for (const urdf::Link* l = full[0]; l; l = l->getParent().get()) common.push_back(l);
    std::reverse(common.begin(), common.end());
    std::size_t n_common = common.size();
    for (const urdf::Link* leaf : full) {
      std::vector<const urdf::Link*> p;
      for (const urdf::Link* l = leaf; l; l = l->getParent().get()) p.push_back(l);
      std::reverse(p.begin(), p.end());
      std::size_t i = 0;
      while (i < n_common && i < p.size() && p[i] == common[i]) ++i;
      n_common = i;
    }
    header_.push_back(first_few(names) + " end the chain, fixed to " +
                      quote(common[n_common - 1]->name) +
                      ": merged into it (keep one's frame with --tip LINK)");
    return common[n_common - 1];
  }

  /// A side branch from \p on must be fixed all the way: the error names its moving joint.
  void require_fixed(const urdf::Joint& j, const urdf::Link& on) const {
    if (!moving(j)) return;
    const std::string where = &on == tip_ ? "beyond the tip " + quote(on.name)
                                          : "a branch off the chain at " + quote(on.name);
    fail("joint " + quote(j.name) + " (" + type_name(j.type) + ") moves " +
         quote(j.child_link_name) + ", " + where +
         ": the course's chains are serial; lock it with --lock " + printable(j.name) +
         ", or choose a tip beyond it with --tip LINK");
  }

  /// The mass of a branch fixed to the ground (checked fixed all the way); names its links.
  double fixed_subtree(const urdf::Link& l, const urdf::Link& on, std::vector<std::string>& names) {
    double m = 0;
    for (const urdf::Link* x : subtree(l)) {
      require_fixed(*x->parent_joint, on);
      if (locked_.count(x->parent_joint->name)) header_.push_back(locked_note(*x->parent_joint));
      names.push_back(quote(x->name));
      if (x->inertial) m += x->inertial->mass;
    }
    return m;
  }

  /// The inertia of the branch from \p l (fixed all the way) about the frame of \p on, the
  /// chain's link it hangs on; names its links, and notes the joints --lock fixed.
  SpatialInertia branch_inertia(const urdf::Link& l, const urdf::Link& on,
                                std::vector<std::string>& names,
                                std::vector<std::string>& notes) const {
    std::unordered_map<const urdf::Link*, Pose> T;  // on <- the link's frame
    SpatialInertia M;
    for (const urdf::Link* x : subtree(l)) {
      require_fixed(*x->parent_joint, on);
      if (locked_.count(x->parent_joint->name)) notes.push_back(locked_note(*x->parent_joint));
      names.push_back(quote(x->name));
      const Pose up = x == &l ? Pose() : T.at(x->getParent().get());
      const Pose Tx = T[x] = up * to_pose(x->parent_joint->parent_to_joint_origin_transform);
      Entry own;
      read_inertial(*x, own);
      M = M + transform(Phi(Tx), inertia_of(own));
    }
    return M;
  }

  /// The link's <inertial> into \p e: mass, com, and the inertia rotated into the link frame.
  void read_inertial(const urdf::Link& l, Entry& e) const {
    if (!l.inertial) return;
    const urdf::Inertial& I = *l.inertial;
    const std::string where = "link " + quote(l.name) + ": inertial: ";
    if (!std::isfinite(I.mass)) fail(where + "mass is not a finite number");
    Mat3<double> J;
    J << I.ixx, I.ixy, I.ixz, I.ixy, I.iyy, I.iyz, I.ixz, I.iyz, I.izz;
    if (!J.allFinite()) fail(where + "inertia has an entry that is not a finite number");
    if (I.mass < 0) fail(where + "mass " + brief(I.mass) + " is negative");
    if (I.mass == 0) {
      if (!J.isZero(0))
        fail(where +
             "mass 0 with a non-zero inertia (a massless link has neither: leave "
             "<inertial> out)");
      e.notes.push_back("link " + quote(l.name) + ": <inertial> of mass 0: a massless frame");
      return;
    }
    const std::string problem = detail::inertia_problem(J);
    if (!problem.empty()) fail(where + "inertia " + problem);
    if (!is_identity(I.origin.rotation)) {
      const Mat3<double> R = to_pose(I.origin).R();  // link frame <- inertial frame
      J = R * J * R.transpose();
      J = (0.5 * J + 0.5 * J.transpose()).eval();
      e.notes.push_back(
          "inertia: rotated from the <inertial> frame (origin rpy) into the link "
          "frame");
    }
    e.massless = false;
    e.mass = I.mass;
    e.com = to_vec(I.origin.position);
    e.J = J;
  }

  static SpatialInertia inertia_of(const Entry& e) {
    return e.massless ? SpatialInertia() : SpatialInertia::from_cm(e.mass, e.com, e.J);
  }
  /// The entry's mass, com and J(C) from \p M about its frame (of positive mass).
  static void set_inertia(const SpatialInertia& M, Entry& e) {
    e.massless = false;
    e.mass = M.mass();
    e.com = M.p();
    Mat3<double> J = M.J_cm();
    e.J = (0.5 * J + 0.5 * J.transpose()).eval();
  }

  /// The body of \p link on its joint.
  Entry entry(const urdf::Link& link, const urdf::Joint& joint) {
    Entry e;
    e.link = link.name;
    e.joint = joint.name;
    e.joint_type = type_name(joint.type);
    const std::string where = "joint " + quote(joint.name) + ": ";
    e.origin = &joint.parent_to_joint_origin_transform;
    e.placement = to_pose(*e.origin);
    if (!e.placement.l().allFinite() || !e.placement.R().allFinite())
      fail(where + "origin is not finite");
    if (joint.mimic)
      fail(where + "mimics " + quote(joint.mimic->joint_name) +
           ": the course's hinges have coordinates of their own; lock it with --lock " +
           printable(joint.name));
    const bool locked = locked_.count(joint.name) > 0;
    switch (locked ? int(urdf::Joint::FIXED) : joint.type) {
      case urdf::Joint::REVOLUTE:
      case urdf::Joint::CONTINUOUS:
        e.hinge = "revolute";
        break;
      case urdf::Joint::PRISMATIC:
        e.hinge = "prismatic";
        break;
      case urdf::Joint::FLOATING:
        e.hinge = "free";
        break;
      case urdf::Joint::FIXED:
        e.hinge = "locked";
        if (locked) e.notes.push_back(locked_note(joint));
        break;
      case urdf::Joint::PLANAR:
        fail(where +
             "a planar joint (3 dofs in a plane) has no hinge in the course (revolute, "
             "prismatic, helical, universal, spherical, free); lock it with --lock " +
             printable(joint.name));
      default:
        fail(where + "unknown joint type");
    }
    if (e.hinge == "revolute" || e.hinge == "prismatic") {
      e.axis = to_vec(joint.axis);
      if (!e.axis.allFinite()) fail(where + "axis is not finite");
      if (!(e.axis.norm() > 1e-9)) fail(where + "axis is zero");
    }
    read_inertial(link, e);
    if (e.hinge != "locked") {
      if (joint.dynamics) {
        e.damping = joint.dynamics->damping;
        e.friction = joint.dynamics->friction;
        if (!std::isfinite(e.damping) || e.damping < 0)
          fail(where + "dynamics damping " + brief(e.damping) + " is not a finite number >= 0");
        if (!std::isfinite(e.friction) || e.friction < 0)
          fail(where + "dynamics friction " + brief(e.friction) + " is not a finite number >= 0");
      }
      if (joint.limits && e.hinge != "free") e.limits = joint.limits.get();
      e.continuous = joint.type == urdf::Joint::CONTINUOUS;
      if (e.limits && !e.continuous && !(e.limits->lower <= e.limits->upper))
        fail(where + "limit lower " + brief(e.limits->lower) + " is above upper " +
             brief(e.limits->upper));
      // The URDF spec's effort and velocity bound magnitudes, |effort| and |velocity|.
      if (e.limits && e.limits->effort < 0)
        fail(where + "limit effort " + brief(e.limits->effort) +
             " is negative: it bounds |effort|");
      if (e.limits && e.limits->velocity < 0)
        fail(where + "limit velocity " + brief(e.limits->velocity) +
             " is negative: it bounds |velocity|");
      const auto taken = facts_.limit_default.find(joint.name);
      if (e.limits && !e.continuous && taken != facts_.limit_default.end())
        e.notes.push_back("limit " + taken->second + ": not given, 0 (the URDF spec's default)");
    }
    if (joint.safety) e.notes.push_back("<safety_controller> not used");
    if (joint.calibration) e.notes.push_back("<calibration> not used");
    return e;
  }

  /// A moving joint must move something of mass: the error names it and its massless links.
  void check_moves_mass() const {
    bool mass = false;
    std::vector<std::string> massless;
    for (auto e = entries_.rbegin(); e != entries_.rend(); ++e) {
      mass = mass || !e->massless;
      if (!mass) massless.push_back(quote(e->link));
      if (!mass && e->hinge != "locked") {
        std::reverse(massless.begin(), massless.end());
        fail("joint " + quote(e->joint) + " (" + e->joint_type + ") moves only massless links (" +
             first_few(massless) + "): nothing of mass outboard of it, its motion is undefined");
      }
    }
  }

  /// The JSON reader's document, with the comments where the URDF was folded or something
  /// was dropped.
  detail::UrdfScene scene(const std::string& tip) const {
    detail::UrdfScene u;
    u.header = {"Converted by `soa convert` from " + printable(file_) + " (robot " +
                    quote(model_.getName()) + "):",
                "the chain from its root to link " + quote(tip) + " (docs/scenes.md, URDF input).",
                "URDF has no gravity: the scene takes 9.81 m/s^2 along -z, as ROS does.",
                "Joint limits and friction are kept (\"limits\", \"friction\") but not used: the",
                "course's dynamics have neither."};
    u.header.insert(u.header.end(), header_.begin(), header_.end());
    u.top = json::object();
    u.top["name"] = model_.getName();  // not empty: XmlCheck refuses an empty name
    u.top["gravity"] = json::array({0.0, 0.0, -9.81});
    std::string parent = "base";
    for (const Entry& e : entries_) {
      json b = json::object();
      b["name"] = e.link;
      b["parent"] = parent;
      if (!e.massless) {
        b["mass"] = e.mass;
        b["com"] = to_json(e.com);
        b["inertia"] = {{"Ixx", e.J(0, 0)}, {"Iyy", e.J(1, 1)}, {"Izz", e.J(2, 2)},
                        {"Ixy", e.J(0, 1)}, {"Ixz", e.J(0, 2)}, {"Iyz", e.J(1, 2)}};
      }
      json h = {{"type", e.hinge}, {"name", e.joint}};
      if (e.hinge == "revolute" || e.hinge == "prismatic") h["axis"] = to_json(e.axis);
      json placement = {{"position", to_json(e.placement.l())}};
      if (e.origin) {
        const urdf::Rotation& r = e.origin->rotation;
        if (!is_identity(r)) placement["rotation"] = json::array({r.x, r.y, r.z, r.w});
      } else if (!e.placement.R().isIdentity(0)) {
        const Eigen::Vector4d q = UnitQuaternion::from_matrix(e.placement.R()).coeffs();
        placement["rotation"] = json::array({q[0], q[1], q[2], q[3]});
      }
      h["placement"] = std::move(placement);
      b["hinge"] = std::move(h);
      if (e.damping > 0) b["spring"] = {{"damping", e.damping}};
      if (e.limits) {
        const urdf::JointLimits& l = *e.limits;
        json limits = {{"effort", l.effort}, {"velocity", l.velocity}};
        if (!e.continuous) limits["lower"] = l.lower, limits["upper"] = l.upper;
        b["limits"] = std::move(limits);
      }
      if (e.friction > 0) b["friction"] = e.friction;
      std::vector<std::string> notes{"link " + quote(e.link) + " on joint " + quote(e.joint) +
                                     " (" + e.joint_type +
                                     (e.joint_type == e.hinge ? ")" : "): " + e.hinge)};
      notes.insert(notes.end(), e.notes.begin(), e.notes.end());
      u.bodies.push_back(std::move(b));
      u.notes.push_back(std::move(notes));
      u.names.emplace_back(e.link, e.joint);
      parent = e.link;
    }
    return u;
  }

  std::string file_;
  const urdf::ModelInterface& model_;
  const XmlFacts& facts_;
  const UrdfOptions& options_;
  std::set<std::string> locked_;
  std::vector<Entry> entries_;
  std::vector<std::string> header_;
  const urdf::Link* tip_ = nullptr;
};

/// The file's bytes (at most kMaxSceneBytes), its problems named.
std::string read_text(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw Error(path + ": is a directory, not a scene file");
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw Error(path + ": cannot open the file (" + std::strerror(errno) + ")");
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> closer(f, &std::fclose);
  std::string text;
  char buf[65536];
  std::size_t got = 0;
  while ((got = std::fread(buf, 1, sizeof buf, f)) > 0) {
    text.append(buf, got);
    if (text.size() > kMaxSceneBytes)
      throw Error(path + ": larger than the 1 GiB limit of a scene file");
  }
  if (std::ferror(f)) throw Error(path + ": cannot read the file (" + std::strerror(errno) + ")");
  return text;
}

/// The XML's nesting and element count, in one pass over the text, before urdfdom (whose XML
/// parser recurses once per level) sees it: a refusal names the line. Comments, CDATA,
/// processing instructions and the DOCTYPE are skipped; quotes inside a tag are respected.
void check_xml_shape(const std::string& path, const std::string& xml) {
  std::size_t depth = 0, elements = 0, line = 1;
  const std::size_t n = xml.size();
  // Moves i past the first \p end at or after i (counting lines); false when there is none.
  auto skip_to = [&](std::size_t& i, const char* end) {
    const std::size_t at = xml.find(end, i);
    const std::size_t stop = at == std::string::npos ? n : at + std::strlen(end);
    line += std::count(xml.begin() + i, xml.begin() + stop, '\n');
    i = stop;
    return at != std::string::npos;
  };
  for (std::size_t i = 0; i < n;) {
    if (xml[i] != '<') {
      line += xml[i] == '\n';
      ++i;
      continue;
    }
    if (xml.compare(i, 4, "<!--") == 0) {
      skip_to(i, "-->");
    } else if (xml.compare(i, 9, "<![CDATA[") == 0) {
      skip_to(i, "]]>");
    } else if (xml.compare(i, 2, "<?") == 0) {
      skip_to(i, "?>");
    } else if (xml.compare(i, 2, "<!") == 0) {  // DOCTYPE, with an internal subset in [ ]
      int brackets = 0;
      for (++i; i < n && (xml[i] != '>' || brackets > 0); ++i) {
        brackets += xml[i] == '[' ? 1 : xml[i] == ']' ? -1 : 0;
        line += xml[i] == '\n';
      }
      ++i;
    } else if (xml.compare(i, 2, "</") == 0) {
      if (depth > 0) --depth;
      skip_to(i, ">");
    } else {
      char quote_char = 0;  // inside an attribute value
      std::size_t j = i + 1;
      for (; j < n && (quote_char || xml[j] != '>'); ++j) {
        if (quote_char ? xml[j] == quote_char : (xml[j] == '"' || xml[j] == '\''))
          quote_char = quote_char ? 0 : xml[j];
        line += xml[j] == '\n';
      }
      const bool empty = j < n && xml[j - 1] == '/';
      if (++elements > kMaxUrdfElements)
        throw Error(path + ": line " + std::to_string(line) + ": more than " +
                    std::to_string(kMaxUrdfElements) +
                    " XML elements, the most a URDF file may have");
      if (!empty && ++depth > std::size_t(kMaxUrdfDepth))
        throw Error(path + ": line " + std::to_string(line) + ": XML nested more than " +
                    std::to_string(kMaxUrdfDepth) + " levels deep, the most a URDF file may be");
      i = j + 1;
    }
  }
}

/// The elements urdfdom reads, with their attributes and child elements, as the URDF spec
/// lists them (wiki.ros.org/urdf/XML: robot, link, joint; urdfdom reads <robot version> too).
/// A child marked '*' may repeat; any other comes at most once, since urdfdom reads the
/// first and drops the others without a word. In a closed element the spec lists every
/// child, so another one is a typo; in an open one (the document, robot, link, visual,
/// collision, material) extensions are common (<gazebo>, <transmission>, <ros2_control>), so
/// only a near miss of a known child is refused. urdfdom ignores what it does not know, but
/// for <geometry>'s shape: it reads the first child, whatever its name, and refuses an
/// unknown one itself.
struct UrdfElement {
  std::string_view name, attributes, children;  // separated by spaces
  bool closed;
};
constexpr UrdfElement kUrdfElements[] = {
    {"", "", "robot", false},  // the document
    {"robot", "name version", "link* joint* material*", false},
    {"link", "name", "inertial visual* collision*", false},
    {"inertial", "", "origin mass inertia", true},
    {"origin", "xyz rpy", "", true},
    {"mass", "value", "", true},
    {"inertia", "ixx ixy ixz iyy iyz izz", "", true},
    {"visual", "name", "origin geometry material", false},
    {"collision", "name", "origin geometry", false},
    {"geometry", "", "box cylinder sphere mesh", false},
    {"box", "size", "", true},
    {"cylinder", "radius length", "", true},
    {"sphere", "radius", "", true},
    {"mesh", "filename scale", "", true},
    {"material", "name", "color texture", false},
    {"color", "rgba", "", true},
    {"texture", "filename", "", true},
    {"joint", "name type",
     "origin parent child axis calibration dynamics limit mimic safety_controller", true},
    {"parent", "link", "", true},
    {"child", "link", "", true},
    {"axis", "xyz", "", true},
    {"calibration", "rising falling", "", true},
    {"dynamics", "damping friction", "", true},
    {"limit", "lower upper effort velocity", "", true},
    {"mimic", "joint multiplier offset", "", true},
    {"safety_controller", "soft_lower_limit soft_upper_limit k_position k_velocity", "", true},
};

std::vector<std::string_view> words(std::string_view s) {
  std::vector<std::string_view> out;
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t end = std::min(s.find(' ', i), s.size());
    out.push_back(s.substr(i, end - i));
    i = end + 1;
  }
  return out;
}
const UrdfElement* urdf_element(std::string_view name) {
  for (const UrdfElement& e : kUrdfElements)
    if (e.name == name) return &e;
  return nullptr;
}
/// The Levenshtein distance of \p a and \p b, or 3 when it is more than 2.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  if ((a.size() > b.size() ? a.size() - b.size() : b.size() - a.size()) > 2) return 3;
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = up;
    }
  }
  return std::min<std::size_t>(row[b.size()], 3);
}
/// "; did you mean X?" for the name of \p known within 2 edits of \p name, else "".
std::string near_miss(std::string_view name, const std::vector<std::string_view>& known,
                      const char* open, const char* close) {
  for (std::string_view k : known) {
    const std::string_view bare = k.substr(0, k.find('*'));
    if (edit_distance(name, bare) <= 2)
      return "; did you mean " + std::string(open) + std::string(bare) + close + "?";
  }
  return "";
}
std::string listed(const std::vector<std::string_view>& names) {
  std::string s;
  for (std::string_view n : names)
    s += (s.empty() ? "" : ", ") + std::string(n.substr(0, n.find('*')));
  return s.empty() ? "none" : s;
}
/// An attribute value as a message shows it: escaped, and cut after 40 bytes.
std::string shown(const std::string& value) {
  return value.size() > 40 ? printable(value.substr(0, 40)) + "..." : printable(value);
}

/// The elements urdfdom reads, checked before it reads them, in TinyXML's reading (urdfdom's
/// own XML parser, so the two see the same document; check_xml_shape() has bounded its
/// depth): each attribute known (kUrdfElements), no '%' in a value but a file name (urdfdom
/// passes some values to printf as the format: it would crash), no empty name, each child known or, in
/// an open element, not a near miss, a child that comes once not repeated, and a revolute or
/// prismatic joint's <limit> with lower or upper. A refusal names the line.
class XmlCheck {
 public:
  explicit XmlCheck(const std::string& path) : path_(path) {}

  XmlFacts run(const std::string& xml) {
    TiXmlDocument doc;
    doc.Parse(xml.c_str());
    if (doc.Error()) return {};  // urdfdom says why
    element(doc, *urdf_element(""), "");
    return std::move(facts_);
  }

 private:
  [[noreturn]] void fail(const TiXmlNode& at, const std::string& owner,
                         const std::string& problem) const {
    throw Error(path_ + ": line " + std::to_string(at.Row()) + ": " +
                (owner.empty() ? "" : owner + ": ") + problem);
  }

  /// \p x, the element \p e describes, and what is below it; \p owner names the link or joint
  /// it is in ("" above them).
  void element(const TiXmlNode& x, const UrdfElement& e, std::string owner) {
    if (const TiXmlElement* el = x.ToElement()) {
      attributes(*el, e, owner);
      if (e.name == "link" || e.name == "joint")
        owner =
            std::string(e.name) + " " + quote(el->Attribute("name") ? el->Attribute("name") : "");
    }
    const std::vector<std::string_view> known = words(e.children);
    std::unordered_map<std::string_view, const TiXmlElement*> first;  // a child that comes once
    for (const TiXmlElement* c = x.FirstChildElement(); c; c = c->NextSiblingElement()) {
      const std::string_view name = c->ValueStr();
      const auto k = std::find_if(known.begin(), known.end(), [&](std::string_view n) {
        return n.substr(0, n.find('*')) == name;
      });
      if (k != known.end()) {
        if (k->back() != '*') {
          const auto [it, fresh] = first.emplace(*k, c);
          if (!fresh)
            fail(*c, owner,
                 "a second <" + std::string(name) + "> (the first on line " +
                     std::to_string(it->second->Row()) + "), which urdfdom would ignore: give one");
        }
        element(*c, *urdf_element(name), owner);
        continue;
      }
      if (name.find(':') != std::string_view::npos) continue;  // a namespace's extension
      const std::string hint = near_miss(name, known, "<", ">");
      if (e.closed || !hint.empty())
        fail(*c, owner,
             "<" + printable(std::string(name)) + ">: not an element of " +
                 (e.name.empty() ? "the document" : "<" + std::string(e.name) + ">") +
                 " (URDF: " + listed(known) + "), which urdfdom would ignore" + hint);
    }
    if (e.name == "joint") limit(*x.ToElement(), owner);
  }

  void attributes(const TiXmlElement& x, const UrdfElement& e, const std::string& owner) const {
    const std::vector<std::string_view> known = words(e.attributes);
    const std::string tag = "<" + std::string(e.name);
    for (const TiXmlAttribute* a = x.FirstAttribute(); a; a = a->Next()) {
      const std::string name = a->Name(), value = a->Value();
      const bool extension = name.find(':') != std::string::npos || name == "xmlns";
      if (!extension && std::find(known.begin(), known.end(), name) == known.end())
        fail(x, owner,
             tag + " " + printable(name) + ">: not an attribute of " + tag + "> (URDF: " +
                 listed(known) + "), which urdfdom would ignore" + near_miss(name, known, "", ""));
      // A file name (<mesh>, <texture>) is never part of urdfdom's messages, and may be a
      // URL with escapes (%20).
      if (name != "filename" && value.find('%') != std::string::npos)
        fail(x, owner,
             tag + " " + printable(name) + "=\"" + shown(value) +
                 "\">: a '%' in a value, which urdfdom would use as a printf format (and "
                 "crash): leave it out");
      const bool names_something =
          (name == "name" && (e.name == "robot" || e.name == "link" || e.name == "joint")) ||
          (name == "link" && (e.name == "parent" || e.name == "child"));
      if (names_something && value.empty())
        fail(x, owner, tag + " " + name + "=\"\">: an empty name");
    }
  }

  /// A revolute or prismatic joint's <limit> with neither lower nor upper: the URDF spec then
  /// means 0 and 0, a joint that cannot move. With one of them, the other is the spec's 0.
  void limit(const TiXmlElement& joint, const std::string& owner) {
    const char *type = joint.Attribute("type"), *name = joint.Attribute("name");
    const TiXmlElement* l = joint.FirstChildElement("limit");
    if (!type || !name || !l ||
        (std::strcmp(type, "revolute") != 0 && std::strcmp(type, "prismatic") != 0))
      return;
    const bool lower = l->Attribute("lower"), upper = l->Attribute("upper");
    if (!lower && !upper)
      fail(*l, owner + " (" + type + ")",
           "<limit> without lower and upper: the URDF spec then means 0 and 0, a joint that "
           "cannot move; give them, or make the joint continuous");
    if (!lower || !upper) facts_.limit_default[name] = lower ? "upper" : "lower";
  }

  const std::string& path_;
  XmlFacts facts_;
};

/// The model checked as a tree, and its names as text: a link that is its own parent, a link
/// with two parent joints, a cycle of joints (which urdfdom does not refuse in every shape),
/// a name that is not UTF-8.
void check_tree(const std::string& path, const urdf::ModelInterface& m) {
  auto fail = [&](const std::string& problem) { throw Error(path + ": " + problem); };
  if (!is_utf8(m.getName())) fail("robot " + quote(m.getName()) + ": its name is not UTF-8 text");
  std::unordered_map<std::string, const urdf::Joint*> parent_joint;  // by child link
  for (const auto& [name, j] : m.joints_) {
    if (!is_utf8(name)) fail("joint " + quote(name) + ": its name is not UTF-8 text");
    if (j->parent_link_name == j->child_link_name)
      fail("joint " + quote(name) + " makes link " + quote(j->child_link_name) +
           " its own parent: the links of a URDF form a tree");
    const auto [it, fresh] = parent_joint.emplace(j->child_link_name, j.get());
    if (!fresh)
      fail("link " + quote(j->child_link_name) + " is the child of two joints, " +
           quote(it->second->name) + " and " + quote(name) +
           ": the links of a URDF form a tree, each below one joint");
  }
  for (const auto& [name, l] : m.links_)
    if (!is_utf8(name)) fail("link " + quote(name) + ": its name is not UTF-8 text");
  // Every link is reached from the root; the ones that are not hang on a cycle of joints.
  std::unordered_set<const urdf::Link*> reached;
  std::vector<const urdf::Link*> stack{m.getRoot().get()};
  while (!stack.empty()) {
    const urdf::Link* l = stack.back();
    stack.pop_back();
    if (!reached.insert(l).second) continue;
    for (const urdf::LinkSharedPtr& c : l->child_links) stack.push_back(c.get());
  }
  if (reached.size() == m.links_.size()) return;
  for (const auto& [name, l] : m.links_) {
    if (reached.count(l.get())) continue;
    std::unordered_map<const urdf::Link*, std::size_t> at;  // the walk up from l, in order
    std::vector<const urdf::Link*> walk;
    const urdf::Link* x = l.get();
    while (x && !at.count(x)) {
      at.emplace(x, walk.size());
      walk.push_back(x);
      const auto it = parent_joint.find(x->name);
      x = it == parent_joint.end() ? nullptr : m.getLink(it->second->parent_link_name).get();
    }
    if (!x)
      fail("link " + quote(name) + " is not connected to the root " + quote(m.getRoot()->name));
    std::vector<std::string> joints;  // the cycle, following parents
    for (std::size_t i = at[x]; i < walk.size(); ++i)
      joints.push_back(quote(parent_joint.at(walk[i]->name)->name));
    fail("joints " + first_few(joints) + " form a cycle through link " + quote(x->name) +
         ": the links of a URDF form a tree");
  }
}

/// Frees urdfdom's model link by link: each link owns its children, so that the last
/// reference to a long chain's root would free it recursively, one level per link.
struct FlatRelease {
  urdf::ModelInterfaceSharedPtr& model;
  ~FlatRelease() {
    if (!model) return;
    for (auto& [name, l] : model->links_) {
      l->child_links.clear();
      l->child_joints.clear();
      l->parent_joint.reset();
    }
    model->root_link_.reset();
  }
};

/// `soa convert`'s text of \p u: the comments, and the document through nlohmann's writer,
/// which escapes every string; numbers as the shortest text that reads back to the same bits.
class Writer {
 public:
  std::string text(const detail::UrdfScene& u) {
    for (const std::string& h : u.header) s_ += "// " + h + "\n";
    s_ += "{\n  \"name\": " + u.top.at("name").dump() + ",\n";
    s_ += "  \"gravity\": ";
    value(u.top.at("gravity"));
    s_ += ",\n  \"bodies\": [\n";
    for (std::size_t i = 0; i < u.bodies.size(); ++i) {
      for (const std::string& n : u.notes[i]) s_ += "    // " + n + "\n";
      s_ += "    {\n";
      bool first = true;
      for (const char* key :
           {"name", "parent", "mass", "com", "inertia", "hinge", "spring", "limits", "friction"}) {
        const auto it = u.bodies[i].find(key);
        if (it == u.bodies[i].end()) continue;
        // name and parent on one line, mass and com on one line, then a line each
        const bool same_line = std::strcmp(key, "parent") == 0 || std::strcmp(key, "com") == 0;
        s_ += first ? "      " : same_line ? ", " : ",\n      ";
        first = false;
        s_ += json(key).dump() + ": ";
        value(*it);
      }
      s_ += i + 1 < u.bodies.size() ? "\n    },\n" : "\n    }\n";
    }
    s_ += "  ]\n}\n";
    return std::move(s_);
  }

 private:
  void value(const json& v) {
    if (v.is_number()) {
      s_ += num(v.get<double>());
    } else if (v.is_array()) {
      s_ += "[";
      for (std::size_t i = 0; i < v.size(); ++i) {
        s_ += i ? ", " : "";
        value(v[i]);
      }
      s_ += "]";
    } else if (v.is_object()) {
      s_ += "{";
      bool first = true;
      auto field = [&](const std::string& k, const json& x) {
        s_ += (first ? "" : ", ") + json(k).dump() + ": ";
        first = false;
        value(x);
      };
      static const char* const order[] = {
          "type", "name", "axis", "placement", "position", "rotation", "Ixx",      "Iyy",    "Izz",
          "Ixy",  "Ixz",  "Iyz",  "lower",     "upper",    "effort",   "velocity", "damping"};
      for (const char* k : order)
        if (v.contains(k)) field(k, v.at(k));
      for (const auto& item : v.items()) {
        const std::string& k = item.key();
        if (std::find_if(std::begin(order), std::end(order),
                         [&](const char* o) { return k == o; }) == std::end(order))
          field(k, item.value());
      }
      s_ += "}";
    } else {
      s_ += v.dump();  // a string, escaped
    }
  }
  std::string s_;
};

}  // namespace

namespace detail {

UrdfScene convert_urdf(const std::string& path, const UrdfOptions& options) {
  const std::string xml = read_text(path);
  check_xml_shape(path, xml);
  const XmlFacts facts = XmlCheck(path).run(xml);
  urdf::ModelInterfaceSharedPtr model;
  const FlatRelease release{model};
  std::string said;
  {
    const std::lock_guard<std::mutex> lock(urdfdom_mutex);
    const Capture capture;
    model = urdf::parseURDF(xml);
    said = capture.said();
  }
  if (!model)
    throw Error(path + ": not a valid URDF (urdfdom: " +
                (said.empty() ? std::string("no reason given") : said) + ")");
  if (!said.empty())
    throw Error(path + ": urdfdom could not read all of it: " + said +
                " (it would go on without what it could not read)");
  check_tree(path, *model);
  return Converter(path, *model, facts, options).run();
}

}  // namespace detail

bool is_urdf(const std::string& path) {
  const std::size_t dot = path.rfind('.');
  if (dot != std::string::npos && path.substr(dot) == ".urdf") return true;
  std::error_code ec;  // only a regular file is looked into (a pipe's bytes would be lost)
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return false;
  int c = 0;
  while ((c = std::fgetc(f)) != EOF && std::isspace(c)) {
  }
  std::fclose(f);
  return c == '<';
}

std::string urdf_to_scene_json(const std::string& path, const UrdfOptions& options) {
  const detail::UrdfScene u = detail::convert_urdf(path, options);
  detail::scene_from_urdf(u, path);  // the JSON reader's checks: what is written reads back
  return Writer().text(u);
}

}  // namespace soa
