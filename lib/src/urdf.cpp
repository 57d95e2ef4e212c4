// URDF scenes: a robot description read with urdfdom, mapped onto the course's serial chain
// and written as a JSON scene (docs/scenes.md, "URDF input"), which the JSON reader then
// reads. Loading a URDF and loading the JSON that `soa convert` prints are the same reading
// of the same text: the two give the same model bit for bit.
//
// The mapping (the table of docs/scenes.md): a link is a body, the joint above it is its
// hinge; the root link and whatever is fixed to it is the ground; the chain is the path from
// the root to the tip link; links fixed to the chain off that path are merged into the body
// they hang on, as rigid mass; a link without <inertial> is a massless frame.
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
#include <vector>

#include "scene_detail.hpp"
#include "soa/phi.hpp"
#include "soa/rotation.hpp"
#include "soa/scene.hpp"
#include "soa/spatial_inertia.hpp"

namespace soa {
namespace {

/// Everything urdfdom says goes here, not to the terminal; its first error explains a failed
/// parse. (console_bridge's handler is global: one parse at a time, under urdfdom_mutex.)
class Capture : public console_bridge::OutputHandler {
 public:
  Capture() : level_(console_bridge::getLogLevel()) {
    console_bridge::useOutputHandler(this);
    console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_ERROR);
  }
  ~Capture() override {
    console_bridge::restorePreviousOutputHandler();
    console_bridge::setLogLevel(level_);
  }
  Capture(const Capture&) = delete;
  Capture& operator=(const Capture&) = delete;
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && error_.empty()) error_ = text;
  }
  const std::string& error() const { return error_; }

 private:
  std::string error_;
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
std::string vec(const Vec3<double>& v) {
  return "[" + num(v[0]) + ", " + num(v[1]) + ", " + num(v[2]) + "]";
}
std::string json_string(const std::string& s) {
  return nlohmann::json(s).dump();
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

/// One body of the scene being written: a link of the chain and the joint above it.
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

class Converter {
 public:
  Converter(std::string file, const urdf::ModelInterface& model, const UrdfOptions& o)
      : file_(std::move(file)), model_(model), options_(o) {}

  /// (link, joint) of each body of the scene, in its order (after run()).
  std::vector<std::pair<std::string, std::string>> bodies() const {
    std::vector<std::pair<std::string, std::string>> b;
    for (const Entry& e : entries_) b.emplace_back(e.link, e.joint);
    return b;
  }

  std::string run() {
    for (const std::string& j : options_.lock) {
      if (!model_.getJoint(j)) fail("--lock: no joint named '" + j + "'" + names_of_joints());
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
      fail("link '" + tip->name + "': fixed to the root '" + root->name +
           "' all the way: no moving joint between them, no chain (choose another tip with "
           "--tip LINK)");
    // The ground: the root and what is fixed to it, up to the first moving joint.
    Pose ground;  // root -> the first moving joint's parent link
    for (std::size_t i = 1; i < first; ++i)
      ground = ground * to_pose(path[i]->parent_joint->parent_to_joint_origin_transform);
    double ground_mass = 0;
    std::vector<std::string> ground_links;
    for (std::size_t i = 0; i < first; ++i) {
      ground_links.push_back("'" + path[i]->name + "'");
      if (path[i]->inertial) ground_mass += path[i]->inertial->mass;
      for (const urdf::LinkSharedPtr& c : path[i]->child_links)
        if (c.get() != path[i + 1]) ground_mass += fixed_subtree(*c, *path[i], ground_links);
    }
    bool geometry = false;
    for (const auto& [name, l] : model_.links_)
      geometry = geometry || !l->visual_array.empty() || !l->collision_array.empty();
    if (geometry) header_.push_back("<visual> and <collision> geometry: not used");
    header_.push_back("the ground: " + join(ground_links) +
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
        e.notes.push_back("placement: the joint's origin composed with the fixed joints from '" +
                          root->name + "'");
      }
      // Links fixed to this one off the chain: rigid mass.
      SpatialInertia M = inertia_of(e);
      bool merged_mass = false;
      for (const urdf::LinkSharedPtr& c : link.child_links) {
        if (i + 1 < path.size() && c.get() == path[i + 1]) continue;
        std::vector<std::string> merged;
        const SpatialInertia side = branch_inertia(*c, Pose(), link, merged);
        if (side.mass() > 0) M = M + side, merged_mass = true;
        e.notes.push_back("merged, fixed to it off the chain: " + join(merged) +
                          (side.mass() > 0 ? " (" + brief(side.mass()) + " kg)" : " (massless)"));
      }
      if (merged_mass) set_inertia(M, e);  // else the link's own numbers, as the file has them
      entries_.push_back(std::move(e));
    }
    check_moves_mass();
    return text(tip->name);
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const { throw Error(file_ + ": " + problem); }

  bool moving(const urdf::Joint& j) const {
    return j.type != urdf::Joint::FIXED && !locked_.count(j.name);
  }

  std::string names_of_joints() const {
    std::string s;
    int n = 0;
    for (const auto& [name, j] : model_.joints_) {
      if (n++ == 12) return s + ", ...)";
      s += (s.empty() ? " (joints: '" : ", '") + name + "'";
    }
    return s.empty() ? " (the model has no joint)" : s + ")";
  }

  static std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
  }

  /// The moving joints between the root and \p l.
  std::vector<const urdf::Joint*> moving_above(const urdf::Link& l) const {
    std::vector<const urdf::Joint*> js;
    for (const urdf::Link* x = &l; x->parent_joint; x = x->getParent().get())
      if (moving(*x->parent_joint)) js.push_back(x->parent_joint.get());
    return js;
  }

  /// --tip, or the one leaf below every moving joint.
  const urdf::Link* find_tip(const urdf::Link& root) {
    if (!options_.tip.empty()) {
      const urdf::LinkConstSharedPtr l = model_.getLink(options_.tip);
      if (!l) {
        std::string names;
        int n = 0;
        for (const auto& [name, link] : model_.links_)
          if (n++ < 12) names += (names.empty() ? "'" : ", '") + name + "'";
        fail("--tip: no link named '" + options_.tip + "' (links: " + names +
             (model_.links_.size() > 12 ? ", ...)" : ")"));
      }
      return l.get();
    }
    std::size_t n_moving = 0;
    for (const auto& [name, j] : model_.joints_) n_moving += moving(*j);
    std::vector<const urdf::Link*> leaves, full;
    collect_leaves(root, leaves);
    for (const urdf::Link* l : leaves)
      if (moving_above(*l).size() == n_moving) full.push_back(l);
    if (full.size() == 1) return full[0];
    std::vector<std::string> names;
    for (const urdf::Link* l : (full.empty() ? leaves : full)) names.push_back("'" + l->name + "'");
    if (full.empty())
      fail("a tree, not a chain: no single path from '" + root.name +
           "' passes every moving joint (its ends: " + join(names) +
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
    header_.push_back(join(names) + " end the chain, fixed to '" + common[n_common - 1]->name +
                      "': merged into it (keep one's frame with --tip LINK)");
    return common[n_common - 1];
  }
  void collect_leaves(const urdf::Link& l, std::vector<const urdf::Link*>& out) const {
    if (l.child_links.empty()) out.push_back(&l);
    for (const urdf::LinkSharedPtr& c : l.child_links) collect_leaves(*c, out);
  }

  /// A side branch from \p on must be fixed all the way: the error names its moving joint.
  void require_fixed(const urdf::Joint& j, const urdf::Link& on) const {
    if (!moving(j)) return;
    const std::string where = &on == tip_ ? "beyond the tip '" + on.name + "'"
                                          : "a branch off the chain at '" + on.name + "'";
    fail("joint '" + j.name + "' (" + type_name(j.type) + ") moves '" + j.child_link_name + "', " +
         where + ": the course's chains are serial; lock it with --lock " + j.name +
         ", or choose a tip beyond it with --tip LINK");
  }

  /// The mass of a branch fixed to the ground (checked fixed all the way); names its links.
  double fixed_subtree(const urdf::Link& l, const urdf::Link& on,
                       std::vector<std::string>& names) const {
    require_fixed(*l.parent_joint, on);
    names.push_back("'" + l.name + "'");
    double m = l.inertial ? l.inertial->mass : 0;
    for (const urdf::LinkSharedPtr& c : l.child_links) m += fixed_subtree(*c, on, names);
    return m;
  }

  /// The inertia of the branch from \p l (fixed all the way) about the frame of \p on, the
  /// chain's link it hangs on; \p T_on_parent is the pose of l's parent in on's frame.
  SpatialInertia branch_inertia(const urdf::Link& l, const Pose& T_on_parent, const urdf::Link& on,
                                std::vector<std::string>& names) const {
    require_fixed(*l.parent_joint, on);
    names.push_back("'" + l.name + "'");
    const Pose T = T_on_parent * to_pose(l.parent_joint->parent_to_joint_origin_transform);
    Entry own;
    read_inertial(l, own);
    SpatialInertia M = transform(Phi(T), inertia_of(own));
    for (const urdf::LinkSharedPtr& c : l.child_links) M = M + branch_inertia(*c, T, on, names);
    return M;
  }

  /// The link's <inertial> into \p e: mass, com, and the inertia rotated into the link frame.
  void read_inertial(const urdf::Link& l, Entry& e) const {
    if (!l.inertial) return;
    const urdf::Inertial& I = *l.inertial;
    const std::string where = "link '" + l.name + "': inertial: ";
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
      e.notes.push_back("link '" + l.name + "': <inertial> of mass 0: a massless frame");
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
    const std::string where = "joint '" + joint.name + "': ";
    e.origin = &joint.parent_to_joint_origin_transform;
    e.placement = to_pose(*e.origin);
    if (!e.placement.l().allFinite() || !e.placement.R().allFinite())
      fail(where + "origin is not finite");
    if (joint.mimic)
      fail(where + "mimics '" + joint.mimic->joint_name +
           "': the course's hinges have coordinates of their own; lock it with --lock " +
           joint.name);
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
        if (locked)
          e.notes.push_back("joint '" + joint.name + "' (" + e.joint_type +
                            ") locked at its zero position by --lock");
        break;
      case urdf::Joint::PLANAR:
        fail(where +
             "a planar joint (3 dofs in a plane) has no hinge in the course (revolute, "
             "prismatic, helical, universal, spherical, free); lock it with --lock " +
             joint.name);
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
      if (!mass) massless.insert(massless.begin(), "'" + e->link + "'");
      if (!mass && e->hinge != "locked")
        fail("joint '" + e->joint + "' (" + e->joint_type + ") moves only massless links (" +
             join(massless) + "): nothing of mass outboard of it, its motion is undefined");
    }
  }

  /// The JSON scene, with comments where the URDF was folded or something was dropped.
  std::string text(const std::string& tip) const {
    std::string s;
    s += "// Converted by `soa convert` from " + file_ + " (robot '" + model_.getName() + "'):\n";
    s += "// the chain from its root to link '" + tip + "' (docs/scenes.md, URDF input).\n";
    s += "// URDF has no gravity: the scene takes 9.81 m/s^2 along -z, as ROS does.\n";
    s += "// Joint limits and friction are kept (\"limits\", \"friction\") but not used: the\n";
    s += "// course's dynamics have neither.\n";
    for (const std::string& h : header_) s += "// " + h + "\n";
    s += "{\n  \"name\": " + json_string(model_.getName().empty() ? tip : model_.getName()) + ",\n";
    s += "  \"gravity\": [0, 0, -9.81],\n  \"bodies\": [\n";
    std::string parent = "base";
    for (std::size_t i = 0; i < entries_.size(); ++i) {
      const Entry& e = entries_[i];
      s += "    // link '" + e.link + "' on joint '" + e.joint + "' (" + e.joint_type + ")";
      s += e.joint_type == e.hinge ? "\n" : ": " + e.hinge + "\n";
      for (const std::string& n : e.notes) s += "    // " + n + "\n";
      s += "    {\n      \"name\": " + json_string(e.link) +
           ", \"parent\": " + json_string(parent) + ",\n";
      if (!e.massless) {
        s += "      \"mass\": " + num(e.mass) + ", \"com\": " + vec(e.com) + ",\n";
        s += "      \"inertia\": {\"Ixx\": " + num(e.J(0, 0)) + ", \"Iyy\": " + num(e.J(1, 1)) +
             ", \"Izz\": " + num(e.J(2, 2)) + ", \"Ixy\": " + num(e.J(0, 1)) +
             ", \"Ixz\": " + num(e.J(0, 2)) + ", \"Iyz\": " + num(e.J(1, 2)) + "},\n";
      }
      s += "      \"hinge\": {\"type\": \"" + e.hinge + "\"";
      if (e.hinge == "revolute" || e.hinge == "prismatic") s += ", \"axis\": " + vec(e.axis);
      s += ", \"placement\": {\"position\": " + vec(e.placement.l());
      if (e.origin) {
        if (!is_identity(e.origin->rotation))
          s += ", \"rotation\": [" + num(e.origin->rotation.x) + ", " + num(e.origin->rotation.y) +
               ", " + num(e.origin->rotation.z) + ", " + num(e.origin->rotation.w) + "]";
      } else if (!e.placement.R().isIdentity(0)) {
        const Eigen::Vector4d q = UnitQuaternion::from_matrix(e.placement.R()).coeffs();
        s += ", \"rotation\": [" + num(q[0]) + ", " + num(q[1]) + ", " + num(q[2]) + ", " +
             num(q[3]) + "]";
      }
      s += "}}";
      if (e.damping > 0) s += ",\n      \"spring\": {\"damping\": " + num(e.damping) + "}";
      if (e.limits) {
        const urdf::JointLimits& l = *e.limits;
        s += ",\n      \"limits\": {";
        if (!e.continuous)
          s += "\"lower\": " + num(l.lower) + ", \"upper\": " + num(l.upper) + ", ";
        s += "\"effort\": " + num(l.effort) + ", \"velocity\": " + num(l.velocity) + "}";
      }
      if (e.friction > 0) s += ",\n      \"friction\": " + num(e.friction);
      s += "\n    }";
      s += i + 1 < entries_.size() ? ",\n" : "\n";
      parent = e.link;
    }
    s += "  ]\n}\n";
    return s;
  }

  std::string file_;
  const urdf::ModelInterface& model_;
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

}  // namespace

namespace detail {

UrdfText convert_urdf(const std::string& path, const UrdfOptions& options) {
  const std::string xml = read_text(path);
  urdf::ModelInterfaceSharedPtr model;
  std::string error;
  {
    const std::lock_guard<std::mutex> lock(urdfdom_mutex);
    const Capture capture;
    model = urdf::parseURDF(xml);
    error = capture.error();
  }
  if (!model)
    throw Error(path + ": not a valid URDF (urdfdom: " +
                (error.empty() ? std::string("no reason given") : error) + ")");
  Converter c(path, *model, options);
  UrdfText t;
  t.json = c.run();
  t.bodies = c.bodies();
  return t;
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
  return detail::convert_urdf(path, options).json;
}

}  // namespace soa
