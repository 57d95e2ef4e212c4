/// \file
/// The 3D viewer's data: what a chain looks like and where its bodies are, frame by frame,
/// as the library computes it; written with the viewer page into a folder that opens from
/// `file://` with nothing loaded from the network (notes page "Viewing a chain in 3D",
/// docs/viewer.md, which also documents the data format).
///
/// The page only renders: every pose, velocity, force, energy and tip position it shows comes
/// from here (soa's kinematics, inverse and forward dynamics), never from JavaScript.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "soa/scene.hpp"

namespace soa::view {

/// How a body is drawn, in its own frame (the file's body frame, at its hinge: \f$O_k\f$ for a
/// body with a hinge, the locked body's own frame for a locked one).
struct Body {
  std::string name;
  std::string hinge;           ///< "revolute", "prismatic", ..., "locked" (the scene's names)
  Vec3<double> axis{0, 0, 0};  ///< the hinge axis for revolute/prismatic hinges, else zero
  /// The far end of the body's solid: the next body's hinge point (fixed in this body); for
  /// the last body, twice its own centre of mass (its far end when the centre is midway).
  Vec3<double> segment{0, 0, 0};
  /// Centre of mass of what rides on the frame: model body k's (locked bodies merged into it
  /// included) for a body with a hinge, the body's own for a locked one.
  Vec3<double> com{0, 0, 0};
  double mass = 0;  ///< model body k's; 0 for a locked body (merged: no ellipsoid of its own)
  /// The inertia ellipsoid about the centre of mass: the solid ellipsoid of uniform density
  /// with the same mass and inertia, semi-axes \f$a_i = \sqrt{5 (J_j + J_k - J_i)/(2m)}\f$ along
  /// the principal axes. \p axes_quaternion (x y z w) is \f${}^B R_P\f$, the orientation of the
  /// principal frame P in the body frame B: it turns principal-frame vectors into body-frame
  /// ones (its matrix's columns are the principal axes; radii[i] lies along column i).
  Vec3<double> radii{0, 0, 0};
  std::array<double, 4> axes_quaternion{0, 0, 0, 1};
};

/// One instant: per body (file order), the pose, and on request the spatial velocity and the
/// inter-body force, all in inertial (world) coordinates.
struct Frame {
  double t = 0;
  double energy = 0;
  /// 7 per body: position of the body frame's origin, then its orientation as a quaternion
  /// x y z w (inertial from body).
  std::vector<double> pose;
  /// 6 per body, or empty: \f$V\f$ at the body frame's origin, \f$[\omega; v]\f$, world axes.
  std::vector<double> V;
  /// 6 per body, or empty: the inter-body force \f$f(k)\f$ on body k at its hinge \f$O_k\f$,
  /// \f$[N; F]\f$, world axes (zeros for a locked body: its hinge transmits nothing apart).
  std::vector<double> f;
  Vec3<double> tip{0, 0, 0};  ///< world position of the tip point (for the tip path)
};

/// A vector fixed in space (lesson 2: the angular momentum of a torque-free body).
struct FixedVector {
  std::string label;
  Vec3<double> origin{0, 0, 0}, vector{0, 0, 0};
};

/// A run: the frames of one trajectory, with its label ("RK4, h = 0.02 s").
struct Run {
  std::string label;
  std::vector<Frame> frames;
};

/// Everything the page shows. Several runs of the same bodies are drawn side by side.
struct View {
  std::string title;
  std::string note;  ///< e.g. the decimation (Recorder::note()); "" for none
  Vec3<double> gravity{0, 0, 0};
  std::vector<Body> bodies;
  int tip_body = -1;                ///< index into bodies of the tip (-1: no tip path)
  Vec3<double> tip_point{0, 0, 0};  ///< the tip point in that body's frame
  std::vector<FixedVector> fixed;
  std::vector<Run> runs;
};

/// The bodies of a scene (file order, locked ones included), tip = the last body's far end.
View view_of(const Scene& scene);

/// The frame budget of a run the caller did not size: 400 frames.
inline constexpr std::size_t kDefaultFrames = 400;

/// What a recorder computes per frame beyond the poses.
struct Quantities {
  bool velocity = true;  ///< V per body
  bool force = true;     ///< f(k) per body (needs a forward and an inverse dynamics per frame)
};

/// Records frames of a scene's motion at most \p budget times over [0, t_end] (the first
/// state at or after each multiple of t_end / (budget - 1)), and the last state always.
/// Per frame, from the scene's model (lessons 3-4): the poses by update_poses(), \f$V(k)\f$ by
/// update_velocities(), \f$f(k)\f$ by inverse_dynamics() at the accelerations
/// \f$\dot\beta\f$ of the forward dynamics (ChainSystem, the scene's external forces and
/// springs, no hinge forces), or at the \f$\dot\beta\f$ given with the state (a prescribed
/// motion: lesson 4's inverse dynamics along it), the energy by ChainSystem::energy(). Keeps a
/// reference to \p scene, which must outlive it. Only the frames kept cost anything.
class Recorder {
 public:
  /// Throws soa::Error for a \p t_end that is negative or not finite, or a \p budget below 2.
  Recorder(const Scene& scene, double t_end, std::size_t budget = kDefaultFrames,
           Quantities q = {});
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;
  /// Offers the state at time \p t (every step may be offered; most are skipped).
  void offer(double t, const State& x);
  /// Records the state at \p t whatever the budget (the final state; at the budget it takes
  /// the last frame's place). The state of the last frame kept is not recorded twice.
  void record(double t, const State& x);
  /// offer() for a prescribed motion: \f$f(k)\f$ by inverse dynamics at its own
  /// \p beta_dot, not the forward dynamics'. Throws soa::Error when \p beta_dot does not have
  /// the chain's nv entries.
  void offer(double t, const State& x, const VecX<double>& beta_dot);
  /// record() for a prescribed motion, as offer(t, x, beta_dot).
  void record(double t, const State& x, const VecX<double>& beta_dot);
  /// The frames so far, as a run called \p label (they are moved out: a second take()
  /// returns only the frames recorded after the first).
  Run take(const std::string& label);
  long offered() const;      ///< how many states were offered or recorded
  std::size_t kept() const;  ///< how many frames were recorded (taken ones included)
  double interval() const;   ///< the time between frames: t_end / (budget - 1)
  /// The decimation, for View::note: decimation_note(offered(), kept(), interval()).
  std::string note() const;

 private:
  struct Impl;
  Impl* impl_;
};

/// "10001 states shown as 400 frames (one every 25.1 ms)", or "all 51 states shown" ("1
/// state shown") when \p frames == \p states.
std::string decimation_note(long states, std::size_t frames, double interval);

/// Where three.min.js and OrbitControls.js are taken from: the environment variable
/// SOA_THREE_DIR when set and not empty, else the folder configured at build time (CMake's
/// SOA_THREE_DIR, /usr/share/javascript/three by default: Debian's libjs-three). The files
/// are build/three.min.js and examples/js/controls/OrbitControls.js in it.
std::filesystem::path three_dir();

/// Throws the soa::Error write() would throw for the folder \p dir or for three.js, touching
/// nothing: a long run checks where its viewer goes before it starts.
void check_destination(const std::filesystem::path& dir);

/// Writes the page into the folder \p dir: index.html, viewer.js, viewer.css, data.js,
/// three.min.js and OrbitControls.js (from Debian's libjs-three). The folder is created; an
/// existing folder is refused unless it holds nothing but a viewer's files (so nothing of the
/// user's is lost); the files are written beside and renamed into place only when all are
/// complete. Throws soa::Error naming the folder or the file; before anything is created or
/// written, for a number that is not finite ("view: run 0 \"RK4\", frame 12 (t = 0.3): V of
/// body \"link3\" is not finite"), a frame of the wrong size, or three.js not found ("three.js
/// not found: <path> (Debian package libjs-three)").
void write(const View& view, const std::filesystem::path& dir);

}  // namespace soa::view
