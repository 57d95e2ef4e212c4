/// \file
/// Scene files: a serial chain and what to do with it, read from JSON (lessons 3-4).
///
/// The format is documented, with a commented example, on the "Scene files" page of the
/// notes (docs/scenes.md). Reading is strict: any problem is one soa::Error whose message
/// names the file and the JSON path, e.g. `arm.json: bodies[3].inertia: not positive
/// definite`.
///
/// Reading takes time and memory in proportion to the file (10^5 bodies in about a second); a
/// file larger than kMaxSceneBytes or nested deeper than kMaxSceneDepth is refused.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "soa/chain/inverse_dynamics.hpp"
#include "soa/chain/model.hpp"
#include "soa/chain/workspace.hpp"

namespace soa {

/// What a scene keeps of a hinge but the course's dynamics do not use: the limits and the
/// Coulomb friction of a URDF joint (`<limit>`, `<dynamics friction>`), or a JSON body's
/// "limits" and "friction". They are kept to be reported (and written back by `soa
/// convert`), never applied: the recursions have no joint limits and no friction.
struct HingeLimits {
  double lower = -std::numeric_limits<double>::infinity();  ///< position (rad or m)
  double upper = std::numeric_limits<double>::infinity();
  double effort = std::numeric_limits<double>::infinity();    ///< |T| (N m or N)
  double velocity = std::numeric_limits<double>::infinity();  ///< |beta| (rad/s or m/s)
  double friction = 0;                                        ///< Coulomb friction (N m or N)
  /// The hinge's own name (the URDF joint's; a JSON hinge's "name"), "" when it has none.
  std::string hinge;
  /// The position has a bound (URDF's continuous joints have none).
  bool has_position() const { return std::isfinite(lower) || std::isfinite(upper); }
};

/// A scene: the chain, its initial state and the optional parts (gravity lives in the model,
/// springs and dampers on its bodies).
struct Scene {
  std::string name;  ///< the file name as given (used in messages)
  Model model;
  State state;  ///< initial state (the neutral configuration at rest when the file has none)
  VecX<double> beta_dot;             ///< \f$\dot\beta\f$ for inverse dynamics (zero when absent)
  ExternalForces<double> f_ext;      ///< empty when the scene applies none
  std::vector<std::string> compute;  ///< what the scene asks to compute (may be empty)
  /// The bodies in the order of the file (base first), as course numbers k: the order of
  /// `--q/--qd/--qdd` on the command line and of per-body output.
  std::vector<int> file_order;

  // Added with the reader:
  std::string title;  ///< the scene's own "name" in the file (the file's stem when absent)

  /// A body of the file seen by the model. A body on a locked hinge is merged into its
  /// inboard neighbour (ModelT::from_base_first) and rides on it: its frame is fixed on body
  /// k at `offset` \f$= {}^{O_k}T_{F}\f$ (the identity for a body that keeps its hinge).
  struct Frame {
    std::string name;
    int k = 0;            ///< the course number of the model body it is fixed on
    bool locked = false;  ///< merged through a locked hinge (no coordinates of its own)
    /// \f${}^{O_k}T_F\f$: the identity unless the body is locked.
    const Pose& offset() const { return locked_ ? locked_->offset : Locked::none().offset; }
    /// A locked body's own centre of mass, in its frame F (the model merged its mass into
    /// body k, whose \f$M(k)\f$ has the centre of the whole); zero for a body that keeps its
    /// hinge, whose own centre is \f$M(k)\f$'s unless locked bodies ride on it.
    const Vec3<double>& own_com() const { return locked_ ? locked_->com : Locked::none().com; }
    /// The limits and friction the file gives the body's hinge (unused by the dynamics:
    /// HingeLimits), or null.
    const HingeLimits* limits() const { return limits_.get(); }
    void set_limits(const HingeLimits& l) { limits_ = std::make_shared<const HingeLimits>(l); }
    /// Makes the frame a locked body's: fixed on body k at \p T, with its own centre of mass.
    void set_offset(const Pose& T, const Vec3<double>& own_com = Vec3<double>::Zero()) {
      locked_ = std::make_shared<const Locked>(Locked{T, own_com});
    }

   private:
    struct Locked {
      Pose offset;
      Vec3<double> com = Vec3<double>::Zero();
      static const Locked& none() {
        static const Locked identity{};
        return identity;
      }
    };
    std::shared_ptr<const Locked> locked_;       // only locked bodies have one (a frame each)
    std::shared_ptr<const HingeLimits> limits_;  // only hinges given limits or friction
  };
  /// Every body of the file, in the order of the file, locked ones included.
  std::vector<Frame> frames;
};

/// The largest scene file read, 1 GiB: a larger one is refused ("<file>: larger than the 1 GiB
/// limit of a scene file") after reading at most this much (so an endless input such as
/// /dev/zero stops too).
constexpr std::uint64_t kMaxSceneBytes = std::uint64_t(1) << 30;
/// The deepest nesting of JSON arrays and objects in a scene file (a scene needs 6 levels:
/// top level, "bodies", a body, its "hinge", "placement", "rotation").
constexpr int kMaxSceneDepth = 100;
/// The deepest nesting of XML elements in a URDF file (a URDF needs 5: robot, link, visual,
/// geometry, mesh). Checked, with the element count, in one pass before the XML parser,
/// which recurses once per level.
constexpr int kMaxUrdfDepth = 100;
/// The most XML elements in a URDF file: about 11 a link with its joint, so a robot of
/// 180,000 links.
constexpr std::uint64_t kMaxUrdfElements = 2000000;

/// Reads and checks a scene file, JSON or URDF (is_urdf(); the URDF's only chain). Throws soa::Error("<file>: <json path>: <problem>"), or
/// "<file>: <problem>" for the file itself (cannot open it, a directory, a read error, larger
/// than kMaxSceneBytes, out of memory while reading it).
Scene load_scene(const std::string& path);
/// The same with another size limit: a file larger than \p max_bytes bytes is refused.
Scene load_scene(const std::string& path, std::uint64_t max_bytes);

/// What a URDF file's chain is (docs/scenes.md, URDF input).
struct UrdfOptions {
  std::string tip;                ///< the tip link ("": the one leaf below every moving joint)
  std::vector<std::string> lock;  ///< joints taken as fixed at their zero position
};

/// A URDF file, read with urdfdom, as a scene: the serial chain from the root link to the tip
/// (UrdfOptions). Throws soa::Error("<file>: joint 'j': <problem>", "<file>: link 'l': ...").
/// The same as load_scene() of the JSON text urdf_to_scene_json() gives, bit for bit.
Scene load_scene(const std::string& path, const UrdfOptions& urdf);
/// The JSON scene equivalent to a URDF file (what `soa convert` prints), with comments where
/// the URDF was folded (ground, merged links, rotated inertias) or something dropped.
std::string urdf_to_scene_json(const std::string& path, const UrdfOptions& urdf = {});
/// A URDF file: named *.urdf, or its first character that is not white space is '<'.
bool is_urdf(const std::string& path);

/// The same from JSON text (at most kMaxSceneBytes); \p name stands for the file in messages.
Scene parse_scene(const std::string& json_text, const std::string& name);

/// File order of the coordinates: entry i is where the i-th value of `--q` (bodies in file
/// order, base first, each hinge's coordinates in turn) sits in the model's \f$\theta\f$
/// (tip first).
std::vector<int> file_q_index(const Scene& scene);
/// The same for \f$\beta\f$, \f$\dot\beta\f$ and \f$T\f$ (`--qd`, `--qdd`).
std::vector<int> file_v_index(const Scene& scene);

/// \f$\theta\f$ from values in file order. Throws soa::Error("<problem>") for a wrong count,
/// a value that is not finite, or a quaternion (spherical, free hinges) whose norm is not 1
/// within 1e-6 (the norm computed without overflow: "norm 1.73205e+200"); quaternions are then
/// normalized.
VecX<double> theta_from_file_order(const Scene& scene, const std::vector<double>& q);
/// \f$\beta\f$ (or \f$\dot\beta\f$) from values in file order; the same checks.
VecX<double> beta_from_file_order(const Scene& scene, const std::vector<double>& v);

}  // namespace soa
