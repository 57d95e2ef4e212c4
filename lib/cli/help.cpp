// The help texts of `soa`: what each verb computes, the order of --q/--qd/--qdd, the exit
// codes. The README's "The soa command" section says the same, shorter.
#include "help.hpp"

namespace soa::cli {
namespace {

constexpr const char* kUsage =
    R"(soa - serial-chain computations on a scene file (SOA course companion)

Usage:
  soa kinematics       SCENE.json [--q V,...] [--qd V,...] [--qdd V,...] [--body NAME]
  soa jacobian         SCENE.json [--q V,...] [--body NAME]
  soa inverse-dynamics SCENE.json [--q V,...] [--qd V,...] [--qdd V,...]
  soa forward-dynamics SCENE.json [--q V,...] [--qd V,...] [--tau V,...]
  soa mass-matrix      SCENE.json [--q V,...] [--inverse]
  soa simulate         SCENE.json --integrator NAME (--dt H | --tol E) [--t-end T]
                       [--out traj.csv] [--q V,...] [--qd V,...]
  soa --help
  soa VERB --help

The scene file gives the chain and its state; its format is on the notes' page "Scene
files" (docs/scenes.md). Results are JSON on stdout.

)";

constexpr const char* kState = R"(State:
  The state is the scene's (each body's "q", "qd", "qdd"; the neutral configuration at
  rest where absent). --q, --qd, --qdd (and --tau, zero when absent) replace it: comma-separated numbers, given as
  --q 0.1,0.2 or --q=0.1,0.2, listing the bodies in the order of the file (base first),
  each hinge's coordinates in turn:
    hinge       --q                                   --qd, --qdd, --tau
    revolute    angle (rad)                           rate
    prismatic   offset (m)                            rate
    helical     angle (rad)                           rate
    universal   two angles                            two rates
    spherical   quaternion x, y, z, w                 angular velocity (3)
    free        quaternion x, y, z, w, position (3)   angular, linear velocity (6)
    locked      nothing                               nothing
  Quaternions must have norm 1 within 1e-6.

)";

constexpr const char* kFrames = R"(Frames and vectors:
  Each body's frame is its hinge frame O_k. Spatial vectors are angular first, [w; v],
  in the coordinates of the frame they belong to. A body on a locked hinge rides on its
  inboard neighbour and has no coordinates of its own.

)";

constexpr const char* kExit = R"(Exit codes:
  0  the result is on stdout
  1  bad scene file or bad input: one line on stderr, "FILE: WHERE: PROBLEM"
  2  usage error (unknown verb or option, missing scene file): one line on stderr
)";

const std::string& full_help() {
  static const std::string text = std::string(kUsage) + R"(Verbs:
  kinematics        pose, spatial velocity and acceleration of every body
  jacobian          the Jacobian of a body's frame (default: the tip)
  inverse-dynamics  the hinge forces T that give the accelerations qdd
  forward-dynamics  the accelerations qdd under the hinge forces tau
  mass-matrix       the mass matrix at q, with symmetry and definiteness checks, and
                    with --inverse its inverse
  simulate          integrate the motion over time, trajectory as CSV

)" + kState + kFrames + kExit;
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

)") + kState +
      kExit;
  return text;
}

const std::string& jacobian_help() {
  static const std::string text = std::string(
                                      R"(Usage: soa jacobian SCENE.json [--q V,...] [--body NAME]

The Jacobian J of the frame of body NAME (default: the tip, the last body of the file):
V = J qd with V = [w; v] the frame's spatial velocity in its own coordinates (lesson 3,
J = B* phi* H*). In JSON: "J" as 6 rows (wx, wy, wz, vx, vy, vz), one column per
coordinate of qd in file order ("columns" names them).

)") + kState + kExit;
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

)") + kState +
      kExit;
  return text;
}

const std::string& forward_dynamics_help() {
  static const std::string text =
      std::string(R"(Usage: soa forward-dynamics SCENE.json [--q V,...] [--qd V,...] [--tau V,...]

The articulated body forward dynamics (lesson 8, O(N)): the accelerations qdd of the chain
at the state (q, qd) under the hinge forces tau (zero when absent), with the scene's
gravity, external forces, springs and dampers. In JSON: "accelerations" per body, "qdd" in
file order ("columns" names its entries), and "check": the relative difference from a
second method, M qdd = tau - C solved with the mass matrix of lesson 5 and Eigen's LDLT.
A hinge whose articulated inertia D(k) is singular (a massless tip, say) is an error
naming the body.

)") + kState +
      kExit;
  return text;
}

const std::string& mass_matrix_help() {
  static const std::string text = std::string(
                                      R"(Usage: soa mass-matrix SCENE.json [--q V,...] [--inverse]

The mass matrix M = H phi M phi* H* at q, computed in O(N^2) from the composite rigid body
inertias (lesson 5: M(i,i) = H(i) R(i) H*(i), M(i,j) = H(i) phi(i,j) R(j) H*(j)). In JSON:
"M" as rows, rows and columns in file order ("columns" names them), "symmetric"
(|M - M*| <= 1e-12 max|M|) and "positive_definite" (a Cholesky factorization succeeds).
With --inverse, also "Minv", the inverse computed in O(N^2) without forming M (lesson 7:
M^-1 = [I - H psi K]* D^-1 [I - H psi K]), and "identity_residual", max|M Minv - I|.

)") + kState + kExit;
  return text;
}

const std::string& simulate_help() {
  static const std::string text =
      std::string(
          R"(Usage: soa simulate SCENE.json --integrator NAME (--dt H | --tol E) [--t-end T]
                    [--out traj.csv] [--q V,...] [--qd V,...]

Integrates the scene's forward dynamics (lesson 8) from its state (or --q, --qd) over
[0, T] (T = 1 s when --t-end is absent), with gravity, external forces, springs and
dampers. Integrators (--integrator, rk4 when absent):
  euler              explicit Euler, order 1, --dt
  symplectic-euler   semi-implicit Euler (velocity, then position), order 1, --dt
  rk4                classical Runge-Kutta, order 4, --dt
  dopri5             Dormand-Prince 5(4), adaptive, --tol (local error, rel. and abs.)
  implicit-midpoint  implicit midpoint, order 2, A-stable (stiff springs), --dt
Fixed steps divide [0, T] evenly. Spherical and free hinges move on the unit quaternions
(q <- q exp(u), Runge-Kutta-Munthe-Kaas). --out writes one CSV line per step: t, q and qd
in file order, the energy and the largest |norm(quaternion) - 1|. On stdout, JSON: steps,
rejected steps, forward-dynamics evaluations, wall time, energy at start and end and its
largest drift, and the final q, qd. A progress bar goes to stderr for long runs when it is
a terminal. A run that blows up stops (exit code 1) with the time, the step and the
estimated stiffness x step.

)") + kState +
      kExit;
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
  }
  return full_help().c_str();
}

}  // namespace soa::cli
