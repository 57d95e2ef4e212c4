// The computations of `soa`, each from a scene and a state to a result that writes
// itself as JSON (json_out.hpp). Everything is computed before the result is returned; the
// result only formats it, in O(n) time and O(1) memory.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "json_out.hpp"
#include "soa/scene.hpp"
#include "soa/sim.hpp"
#include "soa/view.hpp"

namespace soa::cli {

/// The dense cross-checks (forward-dynamics, mass-matrix) run up to this many coordinates,
/// beyond it only with --check: they cost O(n_v^3), the answers O(n_v) and O(n_v^2).
inline constexpr int kDenseCheckMax = 2000;
/// mass-matrix refuses chains with more coordinates: the n_v x n_v matrix (3.2 GB at the
/// limit) and its text (about 9 GB) are no longer a result anyone reads.
inline constexpr int kMassMatrixMax = 20000;

/// The most frames a viewer may hold (--frames): each holds every body's pose, V and f, 19
/// numbers a body (at the limit, data.js passes a gigabyte: its size a frame is in
/// docs/scenes.md).
inline constexpr std::size_t kMaxFrames = 100000;

/// A viewer to write (view --out DIR, simulate --view DIR).
struct ViewOptions {
  std::string dir;     ///< the folder
  std::string option;  ///< the option that named it, for messages: "--out" or "--view"
  std::size_t frames = soa::view::kDefaultFrames;  ///< the budget of a run's frames
  soa::view::Quantities quantities;                ///< V, f per frame
};

/// A viewer that was written.
struct ViewWritten {
  std::string folder, label, note;
  std::size_t frames = 0;  ///< frames in data.js
  long states = 0;         ///< states offered to the recorder (steps + 1, rows, 1)
};

/// What the verb wants printed, and how the program ends.
struct Result {
  Emit emit;          ///< the JSON on stdout
  int exit_code = 0;  ///< 0, or 128 + the signal that interrupted a simulation
  std::string note;   ///< a line for stderr (an interrupted simulation), empty when none
  /// The viewer written by simulate --view, view (null when none).
  std::shared_ptr<const ViewWritten> view;
  /// simulate: what the run did.
  std::shared_ptr<const SimulationSummary> summary;
};

/// The frame of the body called \p name in \p scene; throws soa::Error("--body: ...").
const Scene::Frame& find_frame(const Scene& scene, const std::string& name,
                               const std::string& option = "--body");

/// Poses, velocities and accelerations (gravity not included) of every body in file order,
/// or of \p only when it is not null.
Emit kinematics(const Scene& scene, const State& x, const VecX<double>& beta_dot,
                const Scene::Frame* only);

/// The Jacobian of \p frame: 6 rows, one column per coordinate of beta in file order.
Emit jacobian(const Scene& scene, const State& x, const Scene::Frame& frame);

/// The hinge forces T per body and as one vector in file order.
Emit inverse_dynamics(const Scene& scene, const State& x, const VecX<double>& beta_dot);

/// The accelerations at the state \p x under the hinge forces \p tau (articulated body
/// algorithm), per body and in file order, with the round-trip residual through inverse
/// dynamics (O(N)) and, up to kDenseCheckMax coordinates or with \p check, the difference
/// from CRB + LDLT.
Emit forward_dynamics(const Scene& scene, const State& x, const VecX<double>& tau, bool check);

/// The options of simulate beyond the integrator's.
struct OutputOptions {
  std::string csv_path;  ///< the trajectory (none when empty)
  long every = 1;        ///< write every this many steps (and the last)
  double out_dt = 0;     ///< or: the first step at or after each multiple of this (> 0)
};

/// Integrates the scene's motion from \p x (simulate): the trajectory as CSV into
/// out.csv_path, the summary as JSON; with \p view, the run recorded into that viewer
/// (its folder checked once the run's options are, so that one that cannot be written stops
/// the command before the run; written with the run's frames at the end). SIGINT, SIGTERM
/// and SIGHUP stop the run at a step boundary: the rows and the viewer so far are kept, the
/// summary says so, exit code 130, 143 or 129. A run that blows up, or spends its step
/// budget (opt.max_steps) before opt.t_end, keeps the rows and the viewer before that and
/// its message says where they are. \p verb begins the note of an interruption.
Result simulate(const Scene& scene, const State& x, const SimulationOptions& opt,
                const OutputOptions& out, const ViewOptions* view = nullptr,
                const char* verb = "simulate");

/// Writes the frames of \p rec, taken as the run \p label, into the viewer of \p scene in
/// opt.dir (soa::view::write()), with \p note; its errors as FileError beginning with the
/// option: "--view my_view: holds \"notes.txt\", which is not a file of the viewer; ...".
ViewWritten write_view(const Scene& scene, const ViewOptions& opt, soa::view::Recorder& rec,
                       const std::string& label, const std::string& note);

/// Throws the FileError write_view() would throw for opt.dir (a folder that is not a viewer's,
/// three.js missing) without writing anything: checked before a run starts.
void check_view_destination(const ViewOptions& opt);

/// view: the viewer of \p scene into view.dir, from one of three sources: the state \p x
/// (one frame; \p given_state says it came from --q, --qd), a run simulated from \p x with
/// \p sim (as simulate does), or the trajectory file \p trajectory (read_trajectory(),
/// decimated to the budget, its last row always kept). Nothing is written unless all is
/// right (but for a simulation that blows up or is interrupted: see simulate()).
Result view(const Scene& scene, const State& x, bool given_state, const ViewOptions& view,
            const std::optional<SimulationOptions>& sim,
            const std::optional<std::string>& trajectory);

/// The members of a written viewer in a verb's JSON: folder, open (its index.html), run,
/// frames, states, note.
void emit_view(JsonWriter& w, const ViewWritten& v);

/// The mass matrix in file order, with its symmetry and (up to kDenseCheckMax coordinates
/// or with \p check) definiteness; with \p inverse, also its inverse by the O(N^2) algorithm
/// of lesson 7, with its residual; with \p operational, the operational-space inverse inertia
/// \f$J\mathcal M^{-1}J^* = \phi^*(O_k,F)\Upsilon(k)\phi(O_k,F)\f$ of that body's frame in O(N)
/// (lesson 7, section 8), with (as for the checks above) its difference from the dense form.
Emit mass_matrix(const Scene& scene, const State& x, bool inverse, bool check,
                 const Scene::Frame* operational = nullptr);

/// "SIGINT", "SIGTERM" or "SIGHUP": the signals that stop a simulation.
const char* signal_name(int sig);

/// The default of simulate --max-steps: the most steps a run takes.
inline constexpr long kDefaultMaxSteps = 10000000;

/// What the program is building, for an out-of-memory message ("the mass matrix (n_v =
/// 100000)").
const std::string& stage();
void set_stage(std::string what);

}  // namespace soa::cli
