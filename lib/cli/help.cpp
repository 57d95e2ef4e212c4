// The help texts of `soa`: what each verb computes, the order of --q/--qd/--qdd, the exit
// codes. The README's "The soa command" section says the same, shorter.
#include "help.hpp"

#include <string>
#include <vector>

#include "verbs.hpp"

namespace soa::cli {
namespace {

constexpr const char* kUsage =
    R"(soa - serial-chain computations on a scene file (SOA course companion)

Usage:
  soa kinematics       SCENE.json [--q V,...] [--qd V,...] [--qdd V,...] [--body NAME]
  soa jacobian         SCENE.json [--q V,...] [--body NAME]
  soa inverse-dynamics SCENE.json [--q V,...] [--qd V,...] [--qdd V,...]
  soa forward-dynamics SCENE.json [--q V,...] [--qd V,...] [--tau V,...] [--check]
  soa mass-matrix      SCENE.json [--q V,...] [--inverse] [--operational BODY] [--check]
  soa simulate         SCENE.json --integrator NAME (--dt H | --tol E) [--t-end T]
                       [--max-steps N] [--out traj.csv [--every K | --out-dt H]]
                       [--q V,...] [--qd V,...]
                       [--view DIR [--frames N] [--no-velocity] [--no-force]]
  soa view             SCENE.json --out DIR [--q V,...] [--qd V,...]
                       [--integrator NAME (--dt H | --tol E) [--t-end T] | --trajectory F.csv]
                       [--frames N] [--no-velocity] [--no-force]
  soa convert          ROBOT.urdf [--tip LINK] [--lock JOINT,...] > scene.json
  soa --help
  soa VERB --help

The scene file gives the chain and its state; its format is on the notes' page "Scene
files" (docs/scenes.md); at most 1 GiB. Results are JSON on stdout, written once they
are complete (and every write checked).

A URDF robot description (ROBOT.urdf) is a scene too, for every verb: the chain from
its root link to --tip LINK (default: the one leaf below every moving joint), links
fixed to it merged, --lock JOINT,... taking joints as fixed at zero. convert prints the
equivalent JSON scene; the mapping is on the same page.

)";

constexpr const char* kUrdf = R"(URDF scenes:
  SCENE may be a URDF file (ROBOT.urdf): the chain from its root link to --tip LINK
  (default: the one leaf below every moving joint), --lock J1,J2 taking joints as fixed
  at zero (a gripper's fingers); its bodies are the links of the chain. URDF has no
  state: the neutral configuration at rest unless the options give one. Joint limits
  are kept, not enforced: a state outside them is reported on stderr.
)";

/// The "State:" block of a verb's help: only the options the verb takes (all of them in
/// soa --help).
std::string state_help(std::optional<Verb> verb) {
  auto has = [&](const char* option) { return !verb || takes(*verb, option); };
  std::vector<std::string> rates;  // the options that give one number per coordinate of qd
  for (const char* o : {"--qd", "--qdd", "--tau"})
    if (has(o)) rates.push_back(o);
  std::string given = "--q";
  for (std::size_t i = 0; i < rates.size(); ++i)
    given += (i + 1 == rates.size() ? " and " : ", ") + rates[i];
  std::string rate_head;
  for (std::size_t i = 0; i < rates.size(); ++i) rate_head += (i ? ", " : "") + rates[i];
  const bool tau = has("--tau");
  const std::string paragraph =
      "The state is the scene's (each body's \"q\"" + std::string(has("--qd") ? ", \"qd\"" : "") +
      (has("--qdd") ? ", \"qdd\"" : "") + "; the neutral configuration at rest where absent). " +
      given + (tau ? " (--tau zero when absent)" : "") +
      (rates.empty() ? " replaces" : " replace") +
      " it: comma-separated numbers, given as --q 0.1,0.2 or --q=0.1,0.2, listing the bodies "
      "in the order of the file (base first), each hinge's coordinates in turn:";
  std::string text = "State:\n", line;  // the paragraph wrapped at 88 columns
  std::size_t start = 0;
  while (start < paragraph.size()) {
    std::size_t end = paragraph.find(' ', start);
    if (end == std::string::npos) end = paragraph.size();
    const std::string word = paragraph.substr(start, end - start);
    if (!line.empty() && line.size() + 1 + word.size() > 86)
      text += "  " + line + "\n", line.clear();
    line += (line.empty() ? "" : " ") + word;
    start = end + 1;
  }
  text += "  " + line + "\n";
  struct Row {
    const char *hinge, *q, *rate;
  };
  const Row table[] = {
      {"hinge", "--q", ""},
      {"revolute", "angle (rad)", "rate"},
      {"prismatic", "offset (m)", "rate"},
      {"helical", "angle (rad)", "rate"},
      {"universal", "two angles", "two rates"},
      {"spherical", "quaternion x, y, z, w", "angular velocity (3)"},
      {"free", "quaternion x, y, z, w, position (3)", "angular, linear velocity (6)"},
      {"locked", "nothing", "nothing"}};
  for (const Row& r : table) {
    std::string l = "    " + std::string(r.hinge);
    l.resize(16, ' ');
    l += r.q;
    if (!rates.empty()) {
      l.resize(54, ' ');
      l += &r == table ? rate_head : std::string(r.rate);
    }
    while (!l.empty() && l.back() == ' ') l.pop_back();
    text += l + "\n";
  }
  return text + "  Quaternions must have norm 1 within 1e-6.\n\n" + kUrdf;
}

constexpr const char* kFrames = R"(Frames and vectors:
  Each body's frame is its hinge frame O_k. Spatial vectors are angular first, [w; v],
  in the coordinates of the frame they belong to. A body on a locked hinge rides on its
  inboard neighbour and has no coordinates of its own.

)";

/// The "Exit codes:" block; the output files and the signals only where simulate and view
/// are.
std::string exit_help(std::optional<Verb> verb) {
  const bool sim = !verb || *verb == Verb::Simulate;
  const bool view = !verb || *verb == Verb::View;
  return std::string(R"(Exit codes:
  0  the result is on stdout
  1  bad scene file or bad input: one line on stderr, "FILE: WHERE: PROBLEM"; out of
     memory: "FILE: out of memory while building ..."; an output that cannot be written:
     )") +
         (sim    ? "\"--out traj.csv: No space left on device\" or \"stdout: ...\""
          : view ? "\"--out my_view: holds \"notes.txt\", which is not a file of the viewer; "
                   "...\" or\n     \"stdout: ...\"; a bad trajectory: \"traj.csv: line 17, column "
                   "\"qd:link3\": ...\""
                 : "\"stdout: No space left on device\"") +
         R"(
  2  usage error (unknown verb or option, missing scene file, options that do not go
     together): one line on stderr
)" +
         (sim || view ? std::string("  130, 143, 129  ") + (sim ? "simulate" : "a simulation") +
                            " stopped by SIGINT (Ctrl-C), SIGTERM or SIGHUP:\n" +
                            (sim ? "     the rows and the viewer so far are kept\n"
                                 : "     the viewer so far is kept\n")
                      : "");
}

const std::string& full_help() {
  static const std::string text = std::string(kUsage) + R"(Verbs:
  kinematics        pose, spatial velocity and acceleration of every body
  jacobian          the Jacobian of a body's frame (default: the tip)
  inverse-dynamics  the hinge forces T that give the accelerations qdd
  forward-dynamics  the accelerations qdd under the hinge forces tau
  mass-matrix       the mass matrix at q, with symmetry and definiteness checks, and
                    with --inverse its inverse, with --operational BODY the 6x6
                    operational-space inverse inertia J M^-1 J* of a body
  simulate          integrate the motion over time, trajectory as CSV, and with
                    --view DIR the run's 3D viewer
  view              the 3D viewer of the chain (its state, a simulation or a trajectory
                    file) as a folder DIR: open DIR/index.html in a browser
  convert           the JSON scene of a URDF file, commented where the URDF was folded

)" + state_help(std::nullopt) + kFrames +
                                  exit_help(std::nullopt);
  return text;
}

const std::string& kinematics_help() {
  static const std::string text =
      std::string(
          R"(Usage: soa kinematics SCENE.json [--q V,...] [--qd V,...] [--qdd V,...] [--body NAME]

The scatter recursions base to tip (lesson 3). For every body in file order (or only
--body NAME), in JSON:
  "position"      the origin of its frame, inertial coordinates
  "quaternion"    its attitude ^I R_O, vector part first [x, y, z, w]
  "velocity"      V = [w; v], the frame's spatial velocity, frame coordinates
  "acceleration"  alpha, the inertial time derivative of V at qdd, frame coordinates
                  (gravity not included: the true acceleration)

)") + state_help(Verb::Kinematics) +
      exit_help(Verb::Kinematics);
  return text;
}

const std::string& jacobian_help() {
  static const std::string text = std::string(
                                      R"(Usage: soa jacobian SCENE.json [--q V,...] [--body NAME]

The Jacobian J of the frame of body NAME (default: the tip, the last body of the file):
V = J qd with V = [w; v] the frame's spatial velocity in its own coordinates (lesson 3,
J = B* phi* H*). In JSON: "J" as 6 rows (wx, wy, wz, vx, vy, vz), one column per
coordinate of qd in file order ("columns" names them).

)") + state_help(Verb::Jacobian) + exit_help(Verb::Jacobian);
  return text;
}

const std::string& inverse_dynamics_help() {
  static const std::string text =
      std::string(R"(Usage: soa inverse-dynamics SCENE.json [--q V,...] [--qd V,...] [--qdd V,...]

Newton-Euler inverse dynamics (lesson 4): the hinge forces T that give the chain the
accelerations qdd at the state (q, qd), with the scene's gravity, external forces, springs
and dampers. In JSON: "hinge_forces", T per body (the torque of a revolute hinge, the force
of a prismatic one, ...), and "T", the whole vector in file order ("columns" names its
entries).

)") + state_help(Verb::InverseDynamics) +
      exit_help(Verb::InverseDynamics);
  return text;
}

const std::string& forward_dynamics_help() {
  static const std::string text =
      std::string(
          R"(Usage: soa forward-dynamics SCENE.json [--q V,...] [--qd V,...] [--tau V,...] [--check]

The articulated body forward dynamics (lesson 8, O(N)): the accelerations qdd of the chain
at the state (q, qd) under the hinge forces tau (zero when absent), with the scene's
gravity, external forces, springs and dampers. In JSON: "accelerations" per body, "qdd" in
file order ("columns" names its entries), and "check", two checks that are not the answer:
  "round_trip_residual"  |ID(q, qd, qdd) - tau| / (|tau| + |C(q, qd)|), the inverse
                         dynamics of the result (O(N)): how well qdd satisfies the
                         equations of motion
  "dense_difference"     |qdd - qdd_dense| / |qdd|, qdd_dense from M qdd = tau - C with the
                         mass matrix of lesson 5 and Eigen's LDLT, whose own error is about
                         eps cond(M) ("dense_cond_estimate"): a 200-link chain shows 1e-10
                         here while the O(N) answer is right to 1e-15. O(n_v^3): run up to
                         n_v = 2000, beyond only with --check ("dense_skipped" says so).
A hinge whose articulated inertia D(k) is singular (a massless tip, say) is an error
naming the body.

)") + state_help(Verb::ForwardDynamics) +
      exit_help(Verb::ForwardDynamics);
  return text;
}

const std::string& mass_matrix_help() {
  static const std::string text =
      std::string(
          R"(Usage: soa mass-matrix SCENE.json [--q V,...] [--inverse] [--operational BODY] [--check]

The mass matrix M = H phi M phi* H* at q, computed in O(N^2) from the composite rigid body
inertias (lesson 5: M(i,i) = H(i) R(i) H*(i), M(i,j) = H(i) phi(i,j) R(j) H*(j)). In JSON:
"M" as rows, rows and columns in file order ("columns" names them), "symmetric"
(|M - M*| <= 1e-12 max|M|) and "positive_definite" (a Cholesky factorization succeeds).
With --inverse, also "Minv", the inverse computed in O(N^2) without forming M (lesson 7:
M^-1 = [I - H psi K]* D^-1 [I - H psi K]), "probe_residual", the largest
|M (Minv x) - x| / |x| over three random x (O(n_v^2)), and "identity_residual",
max|M Minv - I|. With --operational BODY (the name of a body of the file), also
"operational": the operational-space inverse inertia J M^-1 J* of that body's frame
("Lambda_inv", 6 rows [wx, wy, wz, vx, vy, vz], the frame's own coordinates), computed in
O(N) as phi*(O_k,F) Upsilon(k) phi(O_k,F) (lesson 7), and "dense_residual",
max|Lambda_inv - J M^-1 J*| / max|J M^-1 J*| against the dense form (J of the jacobian verb,
M^-1 J* by an LDL* solve). The Cholesky factorization, M Minv and the dense J M^-1 J* cost
O(n_v^3): they run up to n_v = 2000, beyond only with --check ("skipped" says so). Chains
of more than 20000 coordinates are refused (the matrix alone would be 3.2 GB).

)") + state_help(Verb::MassMatrix) +
      exit_help(Verb::MassMatrix);
  return text;
}

const std::string& simulate_help() {
  static const std::string text =
      std::string(
          R"(Usage: soa simulate SCENE.json --integrator NAME (--dt H | --tol E) [--t-end T] [--max-steps N]
                    [--stiffness stop|warn|off] [--out traj.csv [--every K | --out-dt H]] [--q V,...] [--qd V,...]
                    [--view DIR [--frames N] [--no-velocity] [--no-force]]

Integrates the scene's forward dynamics (lesson 8) from its state (or --q, --qd) over
[0, T] (T = 1 s when --t-end is absent), with gravity, external forces, springs and
dampers. Integrators (--integrator, rk4 when absent):
  euler              explicit Euler, order 1, --dt
  symplectic-euler   semi-implicit Euler (velocity, then position), order 1, --dt
  rk4                classical Runge-Kutta, order 4, --dt
  dopri5             Dormand-Prince 5(4), adaptive, --tol (local error, rel. and abs.)
  implicit-midpoint  implicit midpoint, order 2, A-stable (stiff springs), --dt
  esdirk4            ESDIRK4(3)6L[2]SA, order 4, L-stable, adaptive, --tol (stiff springs;
                     Newton failures shrink the step)
  radau5             Radau IIA, 3 stages, order 5, L-stable, adaptive, --tol (stiff springs
                     at tight tolerances: global error near --tol; Newton failures shrink
                     the step)
  variational        implicit midpoint in (theta, p = M beta), order 2, symplectic, --dt
                     (revolute, prismatic, helical and universal hinges only)
Fixed steps divide [0, T] evenly. Spherical and free hinges move on the unit quaternions
(q <- q exp(u), Runge-Kutta-Munthe-Kaas); at most 2^53 fixed steps. --tol below 1 and at
least 2.2e-14 (100 eps: the rounding of a step's own arithmetic). --max-steps N: the step
budget (10000000 when absent, as CVODE's mxstep): a run that has taken N steps before T
stops (exit code 1) with one line giving t, the rows so far kept as for a blow-up.
dopri5's first step comes from the problem (Hairer, Norsett, Wanner, II.4); a trial step
that overflows is taken again smaller.
--out writes one CSV line per step: t, q and qd in file order, the energy and the largest
|norm(quaternion) - 1| (fields holding a comma, a quote or a line break are quoted as RFC
4180 says). --every K writes every K-th step instead, --out-dt H the first step at or
after each multiple of H; the last state is always written. The file appears when the
run ends, complete (it is written beside the target and renamed), never the scene file.
On stdout, JSON: steps, rejected steps, forward-dynamics evaluations, wall time, energy
at start and end and its largest drift, the final q, qd, and the rows written. A progress
bar goes to stderr for long runs when it is a terminal.
The explicit fixed-step methods (euler, symplectic-euler, rk4) are watched by a stiffness
monitor: h lambda, lambda the dominant eigenvalue of the dynamics' Jacobian by power
iteration, at the start, every 100 steps (rk4: 25) and at the end, about 5 % more
evaluations; beyond the method's stability bound the run stops (exit code 1) with h lambda
(--stiffness stop, the default), or goes on with a line on stderr and "warning" in the
JSON's "stiffness" (warn); off spends nothing on it.
A run that blows up stops (exit code 1) with the time, the step and the estimated
stiffness x step; the rows before the blow-up are kept in the --out file and the message
says so. Ctrl-C (SIGINT), SIGTERM or SIGHUP stops the run at the end of a step: the rows
so far are kept, the summary on stdout has "interrupted" with the time, a line on stderr
says so, exit code 130, 143 or 129 (a second one ends the program at once, without the
file or its temporary). Past the file size limit (ulimit -f): "--out F: File too large".
--view DIR also writes the run's 3D viewer into the folder DIR (soa view --help): at most
N frames (--frames N, 400 when absent), with each body's V and f unless --no-velocity,
--no-force. The folder is checked before the first step (a folder that cannot be used
stops the command before the run) and written when the run ends: blown up or interrupted
included, the messages say so. On stdout, "view": the folder, its
"open" (index.html), the frames and the "note". --view may go with --out.

)") + state_help(Verb::Simulate) +
      exit_help(Verb::Simulate);
  return text;
}

const std::string& view_help() {
  static const std::string text =
      std::string(
          R"(Usage: soa view SCENE.json --out DIR [--q V,...] [--qd V,...]
                [--integrator NAME (--dt H | --tol E) [--t-end T] [--max-steps N] [--stiffness P]
                 | --trajectory F.csv] [--frames N] [--no-velocity] [--no-force]

Writes the 3D viewer of the chain into the folder DIR: open DIR/index.html in a browser
(from file://: nothing is loaded from the network). What it shows:
  the state      the scene's, or --q, --qd: one frame
  a simulation   --integrator, --dt or --tol, --t-end, --max-steps, --stiffness, as soa simulate takes
                 them (soa simulate --help), recorded as it runs
  a trajectory   --trajectory F.csv, written by soa simulate --out for this scene
A run is shown as at most N frames (--frames N, 400 when absent, 2 to 100000): the first
state at or after each multiple of T / (N - 1), and the last state always; the page's
note says how many states became how many frames. Every number the page shows comes from
the library: per frame each body's pose, its spatial velocity V (--no-velocity leaves it
out) and the inter-body force f(k) at its hinge (--no-force), the energy, the tip.
The folder is created; an existing one is used only when it holds nothing but a viewer's
files (nothing of yours is replaced); the files appear when all are complete; two
writers of one folder take turns (a lock on the folder), leaving one's viewer. A
simulation checks the folder before the first step (a folder that cannot be used stops
the command before the run) and writes it when the run ends, blown up or interrupted
included (the messages say so).
A trajectory is read and checked whole before anything is written: the header must be
the one soa simulate --out writes for this scene (t, q: and qd: of every coordinate in
file order, energy, quaternion_norm_error), then rows of finite numbers, times >= 0 that
increase, quaternions of unit norm (within 1e-6; then normalized). Each problem is one
line naming the file, the line and the column:
  traj.csv: line 17, column "qd:link3": "x" is not a number
On stdout, JSON: the scene, the "source" (state, simulation, trajectory), the "folder"
and its index.html ("open"), the "run" label, the "frames" written, the "states"
offered and the "note".

)") + state_help(Verb::View) +
      exit_help(Verb::View);
  return text;
}

const std::string& convert_help() {
  static const std::string text =
      std::string(R"(Usage: soa convert ROBOT.urdf [--tip LINK] [--lock JOINT,...] > scene.json

Writes the JSON scene of a URDF file: the serial chain from the root link to the tip
link, as every verb reads the URDF. Comments say where the URDF was folded: the links
fixed to the root (the ground), links fixed to the chain off its path (merged into the
body they hang on), massless links (frames), inertias rotated from their <inertial>
frame, joint limits and friction (kept, not used by the dynamics). Loading the JSON
gives the same model, bit for bit.

  --tip LINK        the chain's last link (default: the leaf below every moving joint)
  --lock J1,J2,...  joints taken as fixed at their zero position (a gripper's fingers)

)") + exit_help(Verb::Convert);
  return text;
}

}  // namespace

const char* help_text(std::optional<Verb> verb) {
  if (!verb) return full_help().c_str();
  switch (*verb) {
    case Verb::Kinematics:
      return kinematics_help().c_str();
    case Verb::Jacobian:
      return jacobian_help().c_str();
    case Verb::InverseDynamics:
      return inverse_dynamics_help().c_str();
    case Verb::ForwardDynamics:
      return forward_dynamics_help().c_str();
    case Verb::MassMatrix:
      return mass_matrix_help().c_str();
    case Verb::Simulate:
      return simulate_help().c_str();
    case Verb::View:
      return view_help().c_str();
    case Verb::Convert:
      return convert_help().c_str();
  }
  return full_help().c_str();
}

}  // namespace soa::cli
