/// # Lesson 8 — Recursive forward dynamics
///
/// Topic 8 of the course (slides 1 and 80; Jain 2011): the forward dynamics of a
/// serial chain, the accelerations \f$\dot\beta\f$ that given hinge forces \f$T\f$ produce,
/// \f[ \dot\beta = \mathcal M^{-1}(\theta)\,\bigl(T - \mathcal C(\theta, \beta)\bigr), \f]
/// computed in O(N) without forming or factoring \f$\mathcal M\f$: the articulated body
/// algorithm. It is built from the articulated inertias \f$P\f$, \f$D\f$, \f$G\f$ of lesson 6
/// and is the innovations factorization of lesson 7 applied to a vector. Every identity is
/// computed on concrete numbers and checked; the program ends with the count of checks that
/// passed.
///
/// Numbering (\ref conventions): **body 1 is the tip, body n is next to the base**, hinge k
/// joins body k+1 to body k, and \f$\theta\f$, \f$\beta\f$, \f$T\f$ are stacked tip first.
///
/// Learning goals. After this lesson you can
/// - derive the three sweeps of the articulated body algorithm — base to tip \f$V\f$, \f$a\f$,
///   \f$b\f$; tip to base \f$z, \epsilon, \nu, z^+\f$; base to tip
///   \f$\alpha^+, \dot\beta, \alpha\f$ — from \f$f = P(\alpha - a) + z\f$ (the Riccati
///   sweep, derived in lesson 6), and again from the innovations factorization of
///   \f$\mathcal M\f$;
/// - put gravity in as the base acceleration, external forces into \f$b\f$ and joint springs
///   and dampers into \f$T\f$;
/// - recover the inter-body forces \f$f(k) = P^+(k)\alpha^+(k) + z^+(k)\f$;
/// - check a forward dynamics code against the mass matrix (composite bodies + LDLT), the
///   dense operator form and the round trip through inverse dynamics, and integrate it.
///
/// Run it as `lesson08 OUTDIR`: it prints each check and writes a 2 s simulation of the
/// double pendulum (`l8_double_pendulum.csv`, `l8_energy.csv`), its figures
/// (`l8_double_pendulum.png`, `l8_energy.png`), and the 3D viewers of the double pendulum and
/// of the 50-link chain falling, `OUTDIR/l8_double_pendulum_view/` and
/// `OUTDIR/l8_chain50_view/` (open their `index.html` in a browser), and the Panda falling
/// under gravity (`l8_panda_fall.csv`, `l8_panda_fall.png`, `l8_panda_fall.md`).
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "args.hpp"
#include "chain_builder.hpp"
#include "checklist.hpp"
#include "plot.hpp"
#include "scenes.hpp"
#include "soa/chain.hpp"
#include "soa/scene.hpp"
#include "soa/soa.hpp"
#include "soa/view.hpp"
#include "viewer.hpp"

namespace {

using soa::Acceleration;
using soa::Body;
using soa::Force;
using soa::HingeType;
using soa::Model;
using soa::Pose;
using soa::SpatialInertia;
using soa::State;
using soa::Workspace;
using Forces = soa::ExternalForces<double>;
using Vec3 = soa::Vec3<double>;
using Vec6 = soa::Vec6<double>;
using Mat3 = soa::Mat3<double>;
using Mat6 = soa::Mat6<double>;
using VecX = soa::VecX<double>;
using MatX = soa::MatX<double>;

const double kEps = soa::eps<double>();

/// ## Helpers
///
/// The chain-building helpers of `lessons/common/chain_builder.hpp`: make_body(), inertia()
/// (mass, centre of mass \f$p\f$, principal moments about it), hinge() and at() (a pose from a
/// rotation vector and an offset).
using soa::lesson::at;
using soa::lesson::hinge;
using soa::lesson::inertia;
using soa::lesson::make_body;

/// A chain with every hinge type of lesson 3, from the base out: a free hinge (a floating
/// base), a spherical joint, a universal joint, a helical joint, a locked hinge (its body is
/// merged into the helical one), a prismatic joint and a revolute joint at the tip: 6 bodies,
/// 14 degrees of freedom. Gravity along −z; a spring and a damper on the universal joint.
Model every_hinge_chain() {
  Model m = Model::from_base_first({
      make_body("base", inertia(5.0, Vec3(0.0, 0.0, 0.1), Vec3(0.2, 0.25, 0.3)), Pose(),
                hinge(HingeType::Free, Vec3::UnitZ())),
      make_body("ball", inertia(2.0, Vec3(0.02, 0.0, 0.2), Vec3(0.03, 0.04, 0.01)),
                at(Vec3(0.1, 0.0, 0.0), Vec3(0.0, 0.0, 0.25)),
                hinge(HingeType::Spherical, Vec3::UnitZ())),
      make_body("shoulder", inertia(3.0, Vec3(0.05, 0.02, 0.25), Vec3(0.05, 0.06, 0.02)),
                at(Vec3(0.2, 0.0, 0.0), Vec3(0.0, 0.0, 0.3)),
                hinge(HingeType::Universal, Vec3::UnitZ(), Vec3::UnitY())),
      make_body("screw", inertia(1.5, Vec3(0.0, 0.03, 0.2), Vec3(0.02, 0.02, 0.01)),
                at(Vec3(0.0, 0.1, 0.3), Vec3(0.02, 0.0, 0.5)),
                hinge(HingeType::Helical, Vec3(0.0, 0.3, 1.0), Vec3::UnitY(), 0.05)),
      make_body("clamp", inertia(0.5, Vec3(0.0, 0.05, 0.05), Vec3(0.002, 0.002, 0.001)),
                at(Vec3(0.0, 0.0, 0.4), Vec3(0.0, 0.0, 0.45)),
                hinge(HingeType::Locked, Vec3::UnitZ())),
      make_body("slider", inertia(1.0, Vec3(0.15, 0.0, 0.02), Vec3(0.004, 0.01, 0.01)),
                at(Vec3(-0.3, 0.0, 0.2), Vec3(0.0, 0.05, 0.1)),
                hinge(HingeType::Prismatic, Vec3(1.0, 0.0, 0.2))),
      make_body("tip", inertia(0.8, Vec3(0.2, 0.0, -0.03), Vec3(0.002, 0.01, 0.01)),
                at(Vec3(0.0, 0.0, 0.3), Vec3(0.4, 0.0, 0.1)),
                hinge(HingeType::Revolute, Vec3(0.0, 1.0, 0.1))),
  });
  m.gravity = Vec3(0, 0, -9.81);
  const int shoulder = m.find("shoulder");
  m.body(shoulder).stiffness = 4.0;
  m.body(shoulder).damping = 0.3;
  m.body(shoulder).rest << 0.1, -0.2;
  return m;
}

/// A state of \p m with every coordinate and rate drawn from \p rnd (quaternions normalized).
State random_state(const Model& m, std::mt19937_64& rnd) {
  std::normal_distribution<double> normal;
  State x = State::rest(m);
  for (int i = 0; i < m.nq(); ++i) x.theta[i] = normal(rnd);
  for (const Body& B : m.bodies())
    if (B.hinge.type == HingeType::Spherical || B.hinge.type == HingeType::Free)
      x.theta.segment(B.q_offset, 4).normalize();
  for (int i = 0; i < m.nv(); ++i) x.beta[i] = normal(rnd);
  return x;
}

VecX random_vector(int n, std::mt19937_64& rnd) {
  std::normal_distribution<double> normal;
  VecX v(n);
  for (int i = 0; i < n; ++i) v[i] = normal(rnd);
  return v;
}

Forces random_forces(const Model& m, std::mt19937_64& rnd) {
  Forces f;
  for (int k = 1; k <= m.n(); ++k) f.push_back(Force(random_vector(6, rnd)));
  return f;
}

/// A random chain of \p n bodies: masses 0.5-2 kg, principal moments that satisfy the
/// triangle inequality about randomly turned axes, placements up to about half a metre, hinge
/// i of type `types[i % types.size()]` (a locked first hinge becomes revolute).
Model random_chain(int n, const std::vector<HingeType>& types, std::mt19937_64& rnd) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> normal;
  const auto vec3 = [&] { return Vec3(normal(rnd), normal(rnd), normal(rnd)); };
  std::vector<Body> base_first;
  for (int i = 0; i < n; ++i) {
    const double m = 0.5 + 1.5 * u(rnd);
    const Vec3 s(0.01 + 0.1 * u(rnd), 0.01 + 0.1 * u(rnd), 0.01 + 0.1 * u(rnd));
    const Vec3 J(s[1] + s[2], s[0] + s[2], s[0] + s[1]);  // a box-like body: triangle inequality
    const Mat3 Q = soa::exp_so3<double>(vec3());
    HingeType type = types[std::size_t(i) % types.size()];
    if (i == 0 && type == HingeType::Locked) type = HingeType::Revolute;
    Body b = make_body("body" + std::to_string(i),
                       SpatialInertia::from_cm(m, 0.3 * vec3(), Q * J.asDiagonal() * Q.transpose()),
                       Pose(soa::exp_so3<double>(vec3()), 0.3 * vec3()),
                       hinge(type, vec3(), vec3(), 0.5 * (u(rnd) - 0.5)));
    base_first.push_back(b);
  }
  return Model::from_base_first(base_first);
}

/// The mass matrix by the composite bodies of lesson 5 (soa::mass_matrix_crb) and the bias
/// \f$\mathcal C(\theta,\beta)\f$ by Newton–Euler inverse dynamics at \f$\dot\beta = 0\f$
/// (lesson 4; gravity, external forces, springs and dampers included), and the condition
/// number of \f$\mathcal M\f$.
struct MassAndBias {
  MatX M;
  VecX C;
  double cond = 0;
  MassAndBias(const Model& m, const State& x, const Forces& f_ext) {
    Workspace ws(m);
    C.resize(m.nv());
    soa::inverse_dynamics(m, x, VecX::Zero(m.nv()).eval(), f_ext, ws, C);
    std::vector<SpatialInertia> R(std::size_t(m.n()));
    soa::mass_matrix_crb(m, x, ws, R, M);
    const VecX ev = Eigen::SelfAdjointEigenSolver<MatX>(M, Eigen::EigenvaluesOnly).eigenvalues();
    cond = ev.maxCoeff() / ev.minCoeff();
  }
  // The reference forward dynamics: solve M beta_dot = T - C by
  // Eigen's LDLT (Cholesky with pivoting), O(N^3).
  VecX solve(const VecX& T) const { return M.ldlt().solve(T - C); }
};

/// The library's forward dynamics, soa::forward_dynamics (the fast form of
/// soa::reference::forward_dynamics(), lib/include/soa/reference/forward_dynamics.hpp, which
/// is the one to read), returning \f$\dot\beta\f$ (and, when asked, its per-body results and
/// workspace).
VecX forward(const Model& m, const State& x, const VecX& T, const Forces& f_ext,
             soa::ForwardDynamics* fd_out = nullptr, Workspace* ws_out = nullptr) {
  Workspace ws(m);
  soa::ForwardDynamics fd(m);
  VecX beta_dot(m.nv());
  soa::forward_dynamics(m, x, T, f_ext, ws, fd, beta_dot);
  if (fd_out) *fd_out = fd;
  if (ws_out) *ws_out = ws;
  return beta_dot;
}

/// The hinge forces by Newton–Euler inverse dynamics (lesson 4), and its workspace (with the
/// inter-body forces \f$f(k)\f$ in `ws.f`).
VecX inverse(const Model& m, const State& x, const VecX& beta_dot, const Forces& f_ext,
             Workspace* ws_out = nullptr) {
  Workspace ws(m);
  VecX T(m.nv());
  soa::inverse_dynamics(m, x, beta_dot, f_ext, ws, T);
  if (ws_out) *ws_out = ws;
  return T;
}

/// The hinge forces of the springs and dampers, \f$\tau_s = -k\,\delta(\theta) - c\,\beta\f$.
VecX spring_forces(const Model& m, const State& x) {
  VecX tau = VecX::Zero(m.nv());
  for (const Body& B : m.bodies())
    soa::add_spring_force(B, x.theta.data() + B.q_offset, x.beta.data() + B.v_offset,
                          tau.data() + B.v_offset);
  return tau;
}

/// Stacks per-body 6-vectors (entry k−1 for body k) into one 6n-vector, tip first.
template <class V>
VecX stack(const std::vector<V>& v) {
  VecX s(6 * int(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) s.segment<6>(6 * Eigen::Index(i)) = v[i].vector();
  return s;
}

/// The block diagonal \f$6n \times 6n\f$ operator of per-body 6x6 blocks, tip first.
MatX block_diagonal(const std::vector<Mat6>& b) {
  const int n = int(b.size());
  MatX out = MatX::Zero(6 * n, 6 * n);
  for (int k = 0; k < n; ++k) out.block<6, 6>(6 * k, 6 * k) = b[std::size_t(k)];
  return out;
}

/// \f$|a - b| / \max(|b|, \text{floor})\f$.
double rel(const VecX& a, const VecX& b, double floor = 1e-300) {
  return (a - b).norm() / std::max(b.norm(), floor);
}

/// A default scene of lesson 3, `lib/scenes/NAME.json`.
soa::Scene scene(const std::string& name) {
  return soa::load_scene(SOA_SCENE_DIR "/" + name + ".json");
}

/// The three sweeps of the articulated body algorithm written out as in section 2, with
/// dense 6x6 matrices (\f$\phi\f$ by `phi.matrix()`, \f$H^*(k)\f$ by `H_star`) so that the
/// code reads like the formulas; \f$P\f$, \f$D\f$, \f$G\f$ from soa::articulated_inertias()
/// (lesson 6). soa::reference::forward_dynamics() (lib/include/soa/reference/
/// forward_dynamics.hpp) is the same with spatial types; its fast form soa::forward_dynamics,
/// which the command line runs, does it without any 6x6 \f$\phi\f$, fused into fewer loops.
struct Sweeps {
  std::vector<Vec6> z, z_plus, alpha_plus, alpha;
  std::vector<VecX> eps, nu;
  VecX beta_dot;
};

Sweeps articulated_body_sweeps(const Model& m, const State& x, const VecX& T, const Forces& f_ext) {
  const int n = m.n();
  const std::size_t N = std::size_t(n);
  Workspace ws(m);
  soa::update_phi(m, x.theta, ws);
  soa::update_velocities(m, x, ws);  // V(k), a(k)
  soa::Articulated art(m);
  soa::articulated_inertias(m, x, ws, art);  // P(k), D(k), G(k), P+(k)
  const VecX tau_s = spring_forces(m, x);
  Sweeps s{std::vector<Vec6>(N), std::vector<Vec6>(N), std::vector<Vec6>(N), std::vector<Vec6>(N),
           std::vector<VecX>(N), std::vector<VecX>(N), VecX(m.nv())};
  // Tip to base: z, epsilon, nu, z+.
  for (int k = 1; k <= n; ++k) {
    const std::size_t j = std::size_t(k - 1);
    const Body& B = m.body(k);
    const MatX Hs = B.hinge.H_star(x.theta.data() + B.q_offset);  // H*(k), 6 x n_k
    Vec6 b = soa::gyroscopic_force(B.M, ws.V[j]).vector();        // b(k)
    if (!f_ext.empty()) b -= f_ext[j].vector();
    s.z[j] = art.P[j] * ws.a[j].vector() + b;
    if (k > 1) s.z[j] += ws.phi[j - 1].matrix() * s.z_plus[j - 1];  // phi(k,k-1) z+(k-1)
    const VecX T_k = T.segment(B.v_offset, B.hinge.nv()) + tau_s.segment(B.v_offset, B.hinge.nv());
    s.eps[j] = T_k - Hs.transpose() * s.z[j];
    s.nu[j] = MatX(art.D[j]).inverse() * s.eps[j];
    s.z_plus[j] = s.z[j] + art.G[j] * s.eps[j];
  }
  // Base to tip: alpha+, beta_dot, alpha, from alpha(n+1) = [0; -g].
  Vec6 alpha_next = soa::gravity_base_acceleration(m).vector();
  for (int k = n; k >= 1; --k) {
    const std::size_t j = std::size_t(k - 1);
    const Body& B = m.body(k);
    const MatX Hs = B.hinge.H_star(x.theta.data() + B.q_offset);
    s.alpha_plus[j] = ws.phi[j].matrix().transpose() * alpha_next;  // phi*(k+1,k) alpha(k+1)
    const VecX bd = s.nu[j] - art.G[j].transpose() * s.alpha_plus[j];
    s.beta_dot.segment(B.v_offset, B.hinge.nv()) = bd;
    s.alpha[j] = s.alpha_plus[j] + Hs * bd + ws.a[j].vector();
    alpha_next = s.alpha[j];
  }
  return s;
}

/// A per-body vector (a spatial vector or an n_k-vector) as a VecX.
template <class Derived>
VecX as_vec(const Eigen::MatrixBase<Derived>& v) {
  return v;
}
template <class S, class Kind>
VecX as_vec(const soa::SpatialVector<S, Kind>& v) {
  return v.vector();
}

/// Worst difference of two lists of per-body vectors, relative to the largest of \p b.
template <class A, class B>
double worst_rel(const std::vector<A>& a, const std::vector<B>& b) {
  double scale = 1e-300, err = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    scale = std::max(scale, as_vec(b[i]).norm());
    err = std::max(err, (as_vec(a[i]) - as_vec(b[i])).norm());
  }
  return err / scale;
}

/// The energy of a chain without springs: kinetic \f$\sum_k \tfrac12 V^*(k)M(k)V(k)\f$ and
/// potential \f$-\sum_k m_k\, g^*\, l(I, C_k)\f$ (lesson 4).
double energy(const Model& m, const State& x) {
  Workspace ws(m);
  soa::update_phi(m, x.theta, ws);
  soa::update_poses(m, ws);
  soa::update_velocities(m, x, ws);
  double E = 0;
  for (int k = 1; k <= m.n(); ++k) {
    const SpatialInertia& M = m.body(k).M;
    E += M.kinetic_energy(ws.V[k - 1]) - M.mass() * m.gravity.dot(ws.pose[k - 1].apply(M.p()));
  }
  return E;
}

/// One step of the classical Runge–Kutta method (RK4) for \f$\dot\theta = \beta\f$,
/// \f$\dot\beta = \text{FD}(\theta, \beta, T)\f$ (hinges with \f$\dot\theta = \beta\f$),
/// with the library's forward dynamics and a workspace reused from step to step.
struct Integrator {
  const Model& m;
  Workspace ws;
  soa::ForwardDynamics fd;
  VecX T;
  explicit Integrator(const Model& model)
      : m(model), ws(model), fd(model), T(VecX::Zero(model.nv())) {}
  VecX accel(const VecX& theta, const VecX& beta) {
    VecX bd(m.nv());
    soa::forward_dynamics(m, State{theta, beta}, T, {}, ws, fd, bd);
    return bd;
  }
  void step(State& x, double h) {
    const VecX k1q = x.beta, k1v = accel(x.theta, x.beta);
    const VecX k2q = x.beta + 0.5 * h * k1v, k2v = accel(x.theta + 0.5 * h * k1q, k2q);
    const VecX k3q = x.beta + 0.5 * h * k2v, k3v = accel(x.theta + 0.5 * h * k2q, k3q);
    const VecX k4q = x.beta + h * k3v, k4v = accel(x.theta + h * k3q, k4q);
    x.theta += h / 6 * (k1q + 2 * k2q + 2 * k3q + k4q);
    x.beta += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  }
};

/// The largest hinge force that the inter-body forces of a run's frames carry,
/// \f$|T(k)| = |H(k) f(k)|\f$, relative to the largest \f$|f(k)|\f$: zero (to rounding) for
/// a chain released with \f$T = 0\f$.
double largest_hinge_force(const soa::Scene& scene, const soa::view::Run& run) {
  double T = 0, f = 1e-300;
  for (const soa::view::Frame& fr : run.frames) {
    T = std::max(T, soa::lesson::hinge_forces(scene, fr).lpNorm<Eigen::Infinity>());
    for (double fi : fr.f) f = std::max(f, std::abs(fi));
  }
  return T / f;
}

/// The largest \f$|E - E_0|/|E_0|\f$ over a run's frames.
double energy_drift(const soa::view::Run& run) {
  const double E0 = run.frames.front().energy;
  double d = 0;
  for (const soa::view::Frame& fr : run.frames) d = std::max(d, std::abs(fr.energy - E0));
  return d / std::abs(E0);
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path out = soa::lesson::output_dir(argc, argv);
  soa::lesson::Checklist checks;

  /// ## 1. The problem
  ///
  /// Lesson 4 gave the equations of motion \f$T = \mathcal M\dot\beta + \mathcal C\f$ with
  /// \f$\mathcal M = H\phi M\phi^*H^*\f$ and \f$\mathcal C = H\phi(M\phi^*a + b)\f$;
  /// inverse dynamics evaluates the right side in O(N). Forward dynamics goes the other way:
  /// given the state \f$(\theta, \beta)\f$ and the hinge forces \f$T\f$, find \f$\dot\beta\f$.
  /// The direct route forms \f$\mathcal M\f$ (lesson 5, O(N²)), \f$\mathcal C\f$ (inverse
  /// dynamics at \f$\dot\beta = 0\f$, O(N)) and solves \f$\mathcal M\dot\beta = T - \mathcal
  /// C\f$ by Cholesky (O(N³)). This lesson derives an O(N) algorithm instead.
  ///
  /// The example: a chain with every hinge type of lesson 3 (free, spherical, universal,
  /// helical, locked — merged into its inboard body —, prismatic, revolute), under gravity,
  /// with a spring and a damper on the universal joint and an external force on every body,
  /// moving, with random hinge forces.
  checks.section("1. The problem");
  const Model m = every_hinge_chain();
  const int n = m.n(), nv = m.nv(), N6 = 6 * n;
  std::printf("  the chain: n = %d bodies, %d degrees of freedom, tip first:", n, nv);
  for (int k = 1; k <= n; ++k)
    std::printf(" %d:%s(%s)", k, m.body(k).name.c_str(),
                soa::hinge_type_name(m.body(k).hinge.type));
  std::printf("\n");
  std::mt19937_64 rnd(8);
  const State x = random_state(m, rnd);
  const VecX T = random_vector(nv, rnd);
  const Forces f_ext = random_forces(m, rnd);
  const MassAndBias mb(m, x, f_ext);
  const VecX bd_ref = mb.solve(T);
  std::printf("  cond(M) = %.1f\n", mb.cond);
  checks.check("reference M^-1 (T - C) (CRB + LDLT) passes inverse dynamics: ID(bd) = T",
               (inverse(m, x, bd_ref, f_ext) - T).norm(),
               16 * nv * kEps * (T.norm() + mb.C.norm() + mb.M.norm() * bd_ref.norm()));

  /// ## 2. The Riccati sweep
  ///
  /// Lesson 6 (\ref lesson06_riccati, section 2 of \ref lesson06_program) derived the
  /// Riccati recursion from the equations of lesson 4 in any state, with velocities, hinge
  /// forces, gravity and external forces: by induction from the tip, the force across hinge k
  /// is
  /// \f[ f(k) = P(k)\,\bigl(\alpha(k) - a(k)\bigr) + z(k) = P^+(k)\,\alpha^+(k) + z^+(k),
  ///     \qquad \alpha^+(k) = \phi^*(k+1,k)\,\alpha(k+1), \f]
  /// where \f$T(k) = H(k)f(k)\f$ gives the hinge acceleration
  /// \f$\dot\beta(k) = \nu(k) - G^*(k)\,\alpha^+(k)\f$ with the *innovation*
  /// \f$\epsilon(k) = T(k) - H(k)z(k)\f$ and \f$\nu(k) = D^{-1}(k)\epsilon(k)\f$, and
  /// \f$z^+(k) = z(k) + G(k)\epsilon(k)\f$, \f$z(k+1) = \phi(k+1,k)z^+(k) + P(k+1)a(k+1) +
  /// b(k+1)\f$ carry the bias inboard while \f$P(k+1) = \phi P^+(k)\phi^* + M(k+1)\f$ carries
  /// the inertia. The second form is the **inter-body forces identity** (section 3).
  ///
  /// So the forward dynamics is three O(N) sweeps:
  /// 1. base to tip, the velocities: \f$\phi(k+1,k)\f$, \f$V(k)\f$, \f$a(k)\f$, \f$b(k)\f$
  ///    (lesson 3);
  /// 2. tip to base, with the Riccati recursion for \f$P, D, G, P^+\f$:
  ///    \f$z(k) = \phi(k,k-1)z^+(k-1) + P(k)a(k) + b(k)\f$, \f$\epsilon(k) = T(k) -
  ///    H(k)z(k)\f$, \f$\nu(k) = D^{-1}(k)\epsilon(k)\f$, \f$z^+(k) = z(k) + G(k)\epsilon(k)\f$;
  /// 3. base to tip, from the base acceleration \f$\alpha(n+1)\f$:
  ///    \f$\alpha^+(k) = \phi^*(k+1,k)\alpha(k+1)\f$, \f$\dot\beta(k) = \nu(k) -
  ///    G^*(k)\alpha^+(k)\f$, \f$\alpha(k) = \alpha^+(k) + H^*(k)\dot\beta(k) + a(k)\f$.
  ///
  /// Gravity is the base acceleration \f$\alpha(n+1) = [0; -g]\f$ (lesson 4), external forces
  /// enter \f$b(k) = b_{\rm gyro}(k) - f_{\rm ext}(k)\f$, and joint springs and dampers add
  /// their force \f$\tau_s\f$ to \f$T\f$ (so \f$\epsilon = T + \tau_s - Hz\f$). Nothing is
  /// singular as long as every \f$D(k)\f$ is invertible (lesson 6, section 5).
  ///
  /// The sweeps are written out in `articulated_body_sweeps()` above with dense 6x6
  /// matrices, as soa::reference::forward_dynamics() writes them with spatial types; its fast
  /// form soa::forward_dynamics fuses the Riccati recursion into sweep 2, works on the
  /// 3-vector parts and never forms a 6x6 \f$\phi\f$. Both against the reference of
  /// section 1:
  ///
  /// Now do exercises 8.1 (sweep 2 of a revolute chain), 8.2 (sweep 3) and 8.3 (the whole
  /// algorithm, the Riccati recursion included); then 8.6, a forward dynamics with one bug to
  /// find, and 8.7, which derives the sweeps when some hinges have prescribed accelerations.
  checks.section("2. The Riccati sweep");
  const Sweeps sw = articulated_body_sweeps(m, x, T, f_ext);
  soa::ForwardDynamics fd(m);
  Workspace ws_fd(m);
  const VecX bd = forward(m, x, T, f_ext, &fd, &ws_fd);
  std::printf("  beta_dot (tip first):");
  for (int i = 0; i < nv; ++i) std::printf(" %.6f", bd[i]);
  std::printf("\n");
  // Two roundings of one algorithm: the rounding grows with |P(k)| |D^-1(k)| (lesson 6).
  double kappa = 1;
  for (int k = 1; k <= n; ++k)
    kappa = std::max(
        kappa, fd.art.P[std::size_t(k - 1)].norm() * MatX(fd.art.D_inv[std::size_t(k - 1)]).norm());
  const double tol_same = 64 * nv * kEps * kappa;
  checks.check("sweeps written out == soa::forward_dynamics: beta_dot", rel(sw.beta_dot, bd),
               tol_same);
  checks.check("... z(k) and z+(k)",
               std::max(worst_rel(sw.z, fd.z), worst_rel(sw.z_plus, fd.z_plus)), tol_same);
  checks.check("... nu(k), alpha+(k), alpha(k)",
               std::max({worst_rel(sw.nu, fd.nu), worst_rel(sw.alpha_plus, fd.alpha_plus),
                         worst_rel(sw.alpha, ws_fd.alpha)}),
               tol_same);
  checks.check("soa::forward_dynamics == M^-1 (T - C) by CRB + LDLT (/ |bd|)", rel(bd, bd_ref),
               16 * nv * kEps * mb.cond);

  /// ## 3. The inter-body forces
  ///
  /// Section 2 (from lesson 6) has \f$f(k) = P^+(k)\alpha^+(k) + z^+(k)\f$ along the way:
  /// the forward dynamics gives the forces in the hinges for free. Newton–Euler inverse dynamics (lesson
  /// 4) at the computed \f$\dot\beta\f$ computes the same \f$f(k)\f$ from
  /// \f$f(k) = \phi(k,k-1)f(k-1) + M(k)\alpha(k) + b(k)\f$, and its hinge forces
  /// \f$T(k) = H(k)f(k) - \tau_s(k)\f$ must give back the \f$T\f$ we started from.
  ///
  /// Now do exercise 8.4: the inter-body forces from the sweeps' results.
  checks.section("3. The inter-body forces");
  Workspace ws_ne(m);
  const VecX T_back = inverse(m, x, bd, f_ext, &ws_ne);
  std::vector<Vec6> f_aba;
  double f_scale = 1e-300;
  for (int k = 1; k <= n; ++k) {
    const std::size_t j = std::size_t(k - 1);
    f_aba.push_back(fd.art.P_plus[j] * fd.alpha_plus[j].vector() + fd.z_plus[j].vector());
    f_scale = std::max({f_scale, ws_ne.f[j].vector().norm(),
                        fd.art.P_plus[j].norm() * fd.alpha_plus[j].vector().norm(),
                        fd.z_plus[j].vector().norm()});
    std::printf("  k = %d  f(k) = P+ alpha+ + z+ = [%9.4f %9.4f %9.4f | %9.4f %9.4f %9.4f]\n", k,
                f_aba.back()[0], f_aba.back()[1], f_aba.back()[2], f_aba.back()[3], f_aba.back()[4],
                f_aba.back()[5]);
  }
  double f_err = 0;
  for (std::size_t j = 0; j < f_aba.size(); ++j)
    f_err = std::max(f_err, (f_aba[j] - ws_ne.f[j].vector()).norm());
  checks.check("f(k) = P+(k) alpha+(k) + z+(k) == Newton-Euler f(k) at beta_dot", f_err / f_scale,
               16 * nv * kEps * mb.cond);
  checks.check("round trip: ID(FD(T)) = T (/ |T| + |C| + |M||bd|)", (T_back - T).norm(),
               16 * nv * kEps * (T.norm() + mb.C.norm() + mb.M.norm() * bd.norm()));

  /// ## 4. The same from the innovations factorization
  ///
  /// Lesson 7 factored the mass matrix, \f$\mathcal M = [I + H\phi K]\,D\,[I + H\phi K]^*\f$,
  /// and inverted the factor, \f$[I + H\phi K]^{-1} = I - H\psi K\f$, so
  /// \f[ \mathcal M^{-1} = [I - H\psi K]^*\,D^{-1}\,[I - H\psi K], \qquad
  ///     K = \mathcal E_\phi G, \quad \psi = (I - \mathcal E_\phi\bar\tau)^{-1}. \f]
  /// Apply it to \f$T - \mathcal C = T - H\phi(M\phi^*a + b)\f$. Two identities do the work:
  /// - \f$[I - H\psi K]\,H\phi = H\psi\f$, from \f$\psi K H\phi = \phi - \psi\f$ (lesson 7);
  /// - \f$\psi M\phi^* = \psi P + P\tilde\phi^*\f$ with \f$\tilde\phi = \phi - I\f$: multiply
  ///   by \f$\psi^{-1}\f$ and \f$\phi^{-*}\f$ to get \f$M = P - \mathcal E_\psi P\,
  ///   \mathcal E_\phi^*\f$, which is the Riccati equation \f$P = \mathcal E_\phi P^+\mathcal
  ///   E_\phi^* + M\f$ since \f$\mathcal E_\psi P = \mathcal E_\phi\bar\tau P =
  ///   \mathcal E_\phi P^+\f$. (Lesson 5 had \f$\phi M\phi^* = R + \tilde\phi R + R\tilde\phi^*\f$.)
  ///
  /// With them, \f$[I - H\psi K](T - \mathcal C) = T - H\psi K T - H\psi(Pa + b) -
  /// HP\tilde\phi^* a = \epsilon - HP\tilde\phi^*a\f$, where
  /// \f[ z = \psi\,(K T + P a + b), \qquad \epsilon = T - H z, \qquad \nu = D^{-1}\epsilon \f]
  /// are sweep 2 in operator form (\f$z = \mathcal E_\psi z + KT + Pa + b\f$ is
  /// \f$z(k) = \phi(k,k-1)[\bar\tau z + GT](k-1) + P(k)a(k) + b(k)\f$, and \f$\bar\tau z + GT =
  /// z + G\epsilon = z^+\f$). Then \f$D^{-1}HP = G^*\f$ and \f$G^*\tilde\phi^* = K^*\phi^*\f$ give
  /// \f$\dot\beta = [I - K^*\psi^*H^*](\nu - K^*\phi^* a)\f$, and
  /// \f$K^*\psi^*H^*K^*\phi^* = K^*(\phi^* - \psi^*)\f$ leaves
  /// \f[ \dot\beta = \nu - K^*\alpha, \qquad \alpha = \psi^*(H^*\nu + a), \f]
  /// sweep 3 in operator form: \f$K^*\alpha = G^*(k)\,\phi^*(k+1,k)\,\alpha(k+1) =
  /// G^*\alpha^+\f$, and \f$\alpha = \mathcal E_\psi^*\alpha + H^*\nu + a\f$ is \f$\alpha(k) =
  /// \bar\tau^*\alpha^+ + H^*\nu + a = \alpha^+ + H^*\dot\beta + a\f$.
  ///
  /// The dense operators of lessons 4 and 6 check every step. Here the chain moves and
  /// carries the external forces, but without gravity and springs: the operator form of
  /// lesson 4 folds gravity into \f$a(n)\f$, which would shift \f$z(n)\f$ by
  /// \f$P(n)\phi^*(n+1,n)\alpha(n+1)\f$ against the library's sweep (\f$\dot\beta\f$ and
  /// \f$\alpha\f$ are the same either way), and has no springs.
  checks.section("4. The same from the innovations factorization");
  Model m0 = m;
  m0.gravity = Vec3::Zero();
  for (int k = 1; k <= n; ++k) m0.body(k).stiffness = m0.body(k).damping = 0;
  const soa::Operators op = soa::Operators::build(m0, x, f_ext);
  soa::ForwardDynamics fd0(m0);
  Workspace ws0(m0);
  const VecX bd0 = forward(m0, x, T, f_ext, &fd0, &ws0);
  const soa::Articulated& art = fd0.art;
  std::vector<Mat6> P_blocks, tau_blocks;
  MatX G = MatX::Zero(N6, nv), D = MatX::Zero(nv, nv);
  for (int k = 1; k <= n; ++k) {
    const Body& B = m0.body(k);
    const std::size_t j = std::size_t(k - 1);
    P_blocks.push_back(art.P[j]);
    tau_blocks.push_back(art.tau_bar(m0, x.theta, k));
    G.block(6 * (k - 1), B.v_offset, 6, B.hinge.nv()) = art.G[j];
    D.block(B.v_offset, B.v_offset, B.hinge.nv(), B.hinge.nv()) = art.D[j];
  }
  const MatX P = block_diagonal(P_blocks), I6 = MatX::Identity(N6, N6);
  const MatX K = op.E_phi * G;
  const MatX psi = (I6 - op.E_phi * block_diagonal(tau_blocks)).inverse();
  const MatX I_HpsiK = MatX::Identity(nv, nv) - op.H * psi * K;
  const MatX Mass = op.mass_matrix();
  const VecX C0 = op.bias();
  const double cond0 = Mass.norm() * Mass.inverse().norm();
  const double H_norm = op.H.norm(), phi_norm = op.phi.norm(), psi_norm = psi.norm();
  checks.check("[I - H psi K] H phi = H psi", (I_HpsiK * op.H * op.phi - op.H * psi).norm(),
               64 * N6 * kEps * H_norm * (I_HpsiK.norm() * phi_norm + psi_norm));
  checks.check(
      "psi M phi* = psi P + P (phi - I)*",
      (psi * op.M * op.phi.transpose() - psi * P - P * (op.phi - I6).transpose()).norm(),
      64 * N6 * kEps * (psi_norm * op.M.norm() * phi_norm + P.norm() * (psi_norm + phi_norm)));
  checks.check("M^-1 = [I - H psi K]* D^-1 [I - H psi K]",
               (I_HpsiK.transpose() * D.inverse() * I_HpsiK * Mass - MatX::Identity(nv, nv)).norm(),
               64 * nv * kEps * cond0);
  const VecX z_op = psi * (K * T + P * op.a + op.b);
  const VecX eps_op = T - op.H * z_op;
  const VecX nu_op = D.inverse() * eps_op;
  const VecX alpha_op = psi.transpose() * (op.H.transpose() * nu_op + op.a);
  const VecX bd_op = nu_op - K.transpose() * alpha_op;
  VecX nu_lib(nv);
  for (int k = 1; k <= n; ++k)
    nu_lib.segment(m0.body(k).v_offset, m0.body(k).hinge.nv()) = fd0.nu[std::size_t(k - 1)];
  const double tol_op = 64 * nv * kEps * cond0;
  checks.check("[I - H psi K](T - C) = epsilon - H P (phi - I)* a",
               rel(I_HpsiK * (T - C0), eps_op - op.H * P * (op.phi - I6).transpose() * op.a),
               tol_op);
  checks.check("z = psi (K T + P a + b) == the sweep's z(k)", rel(z_op, stack(fd0.z)), tol_op);
  checks.check("nu = D^-1 (T - H z) == the sweep's nu(k)", rel(nu_op, nu_lib), tol_op);
  checks.check("alpha = psi* (H* nu + a) == the sweep's alpha(k)", rel(alpha_op, stack(ws0.alpha)),
               tol_op);
  checks.check("beta_dot = nu - K* alpha == soa::forward_dynamics", rel(bd_op, bd0), tol_op);
  checks.check("soa::forward_dynamics == M^-1 (T - C), dense operator form",
               rel(bd0, Mass.inverse() * (T - C0)), 16 * nv * kEps * cond0);

  /// ## 5. Gravity, external forces, springs, and the parts left out
  ///
  /// Gravity as the base acceleration \f$\alpha(n+1) = [0; -g]\f$ is the same as the weight of
  /// every body applied as an external force: at \f$O_k\f$ in \f$O_k\f$ coordinates,
  /// \f$F = m_k\,{}^kR_I\,g\f$ and \f$N = p(k) \times F\f$ (the weight acts at the centre of
  /// mass). A spring and damper is a hinge force: forward dynamics with them equals forward
  /// dynamics without them and \f$T + \tau_s\f$, bit for bit (the library adds \f$\tau_s\f$
  /// to \f$T\f$ in the same order).
  ///
  /// The library skips what a case does not use: the velocity terms at rest
  /// (\f$V = a = b_{\rm gyro} = 0\f$), the external forces when the list is empty, the gravity
  /// pass when \f$g = 0\f$, the springs when none has a stiffness or damping. Leaving them out
  /// must change nothing: an empty force list gives bit for bit the result of explicit zero
  /// forces; springs at their rest position in a chain at rest give bit for bit the result
  /// without springs (\f$T - 0 = T\f$ exactly); at rest the workspace's \f$V\f$, \f$a\f$ and
  /// \f$b\f$ are exact zeros and \f$\dot\beta = \mathcal M^{-1}(T - \mathcal C(\theta, 0))\f$,
  /// the static bias alone.
  checks.section("5. Gravity, external forces, springs, and the parts left out");
  Model m_ng = m;
  m_ng.gravity = Vec3::Zero();
  Workspace ws_pose(m);
  soa::update_phi(m, x.theta, ws_pose);
  soa::update_poses(m, ws_pose);
  Forces weight_and_ext = f_ext;
  for (int k = 1; k <= n; ++k) {
    const SpatialInertia& Mk = m.body(k).M;
    const Vec3 F = Mk.mass() * (ws_pose.pose[k - 1].R().transpose() * m.gravity);
    weight_and_ext[std::size_t(k - 1)] += Force(Mk.p().cross(F), F);
  }
  checks.check("gravity as base acceleration == weights as external forces",
               rel(forward(m_ng, x, T, weight_and_ext), bd), 16 * nv * kEps * mb.cond);
  Model m_ns = m;
  for (int k = 1; k <= n; ++k) m_ns.body(k).stiffness = m_ns.body(k).damping = 0;
  const VecX T_s = T + spring_forces(m, x);
  checks.check("springs and dampers == no springs with T + tau_s (bitwise)",
               (forward(m, x, T, f_ext).array() == forward(m_ns, x, T_s, f_ext).array()).all());
  const Forces zeros(std::size_t(n), Force::Zero());
  checks.check("no external forces == explicit zero forces (bitwise)",
               (forward(m, x, T, {}).array() == forward(m, x, T, zeros).array()).all());
  State x_rest{x.theta, VecX::Zero(nv)};
  Model m_rest = m;
  for (int k = 1; k <= n; ++k) {  // springs relaxed at this configuration (1-dof, universal)
    Body& B = m_rest.body(k);
    if (B.hinge.nq() <= 2)
      B.rest = x.theta.segment(B.q_offset, B.hinge.nq());
    else
      B.stiffness = 0;
  }
  const VecX bd_rest_springs = forward(m_rest, x_rest, T, {});
  for (int k = 1; k <= n; ++k) m_rest.body(k).stiffness = m_rest.body(k).damping = 0;
  checks.check("springs at rest position, chain at rest == no springs (bitwise)",
               (bd_rest_springs.array() == forward(m_rest, x_rest, T, {}).array()).all());
  soa::ForwardDynamics fd_rest(m);
  Workspace ws_rest(m);
  const VecX bd_rest = forward(m, x_rest, T, {}, &fd_rest, &ws_rest);
  bool exact_zero = true;
  for (int k = 1; k <= n; ++k) {
    const std::size_t j = std::size_t(k - 1);
    exact_zero = exact_zero && (ws_rest.V[j].vector().array() == 0).all() &&
                 (ws_rest.a[j].vector().array() == 0).all() &&
                 (ws_rest.b[j].vector().array() == 0).all();
  }
  checks.check("at rest: V(k), a(k), b(k) exactly zero", exact_zero);
  const MassAndBias mb_rest(m, x_rest, {});
  checks.check("at rest: beta_dot == M^-1 (T - C(theta, 0))", rel(bd_rest, mb_rest.solve(T)),
               16 * nv * kEps * mb_rest.cond);
  const MassAndBias mb_free(m_ng, x, {});
  checks.check("no gravity, no external forces: == M^-1 (T - C) of that case",
               rel(forward(m_ng, x, T, {}), mb_free.solve(T)), 16 * nv * kEps * mb_free.cond);

  /// ## 6. The default scenes and random chains
  ///
  /// The scenes of lesson 3 (the double pendulum, the 7-joint arm, the 50-link chain) at the
  /// state the file gives, with the hinge forces \f$T\f$ that inverse dynamics finds for the
  /// file's \f$\dot\beta\f$ (`qdd`): forward dynamics must give that \f$\dot\beta\f$ back
  /// (\f$\text{FD}(\text{ID}(\dot\beta)) = \dot\beta\f$), agree with CRB + LDLT, and pass the
  /// round trip \f$\text{ID}(\text{FD}(T)) = T\f$ for random \f$T\f$. The forward error of a
  /// backward-stable solve is bounded by \f$\varepsilon\,\mathrm{cond}(\mathcal M)\f$ times a
  /// modest factor; the tolerance is \f$16\,n\,\varepsilon\,\mathrm{cond}(\mathcal M)\f$, and
  /// the `soa forward-dynamics` command must agree with CRB + LDLT to \f$10^{-10}\f$.
  /// Then 700 random chains of 1 to 12 bodies, every hinge type, with gravity, springs,
  /// external forces and rest states mixed in, and 70 chains of 20 bodies of a single hinge
  /// type each.
  checks.section("6. The default scenes and random chains");
  for (const char* name : {"double_pendulum", "arm7", "chain50"}) {
    soa::Scene sc;
    try {
      sc = scene(name);
    } catch (const std::exception& e) {
      checks.check(std::string(name) + ".json loads (" + e.what() + ")", false);
      continue;
    }
    const Model& ms = sc.model;
    const MassAndBias mbs(ms, sc.state, sc.f_ext);
    const VecX T_file = inverse(ms, sc.state, sc.beta_dot, sc.f_ext);
    const VecX bd_file = forward(ms, sc.state, T_file, sc.f_ext);
    const VecX T_rand = random_vector(ms.nv(), rnd);
    const VecX bd_rand = forward(ms, sc.state, T_rand, sc.f_ext);
    const double crb =
        std::max(rel(bd_file, mbs.solve(T_file), 1), rel(bd_rand, mbs.solve(T_rand)));
    const double tol = 16 * ms.nv() * kEps * mbs.cond;
    std::printf("  %-16s n = %2d, cond(M) = %.3g: |FD - CRB+LDLT|/|bd| = %.2e\n", name, ms.n(),
                mbs.cond, crb);
    checks.check(std::string(name) + ": FD == CRB + LDLT (and < 1e-10)", crb, std::min(tol, 1e-10));
    checks.check(std::string(name) + ": FD(ID(qdd)) = qdd", rel(bd_file, sc.beta_dot, 1), tol);
    const VecX T_rt = inverse(ms, sc.state, bd_rand, sc.f_ext);
    checks.check(
        std::string(name) + ": ID(FD(T)) = T (/ |T| + |C| + |M||bd|)",
        (T_rt - T_rand).norm() / (T_rand.norm() + mbs.C.norm() + mbs.M.norm() * bd_rand.norm()),
        16 * ms.nv() * kEps);
  }
  const std::vector<HingeType> all_types = {
      HingeType::Revolute,  HingeType::Prismatic, HingeType::Helical, HingeType::Universal,
      HingeType::Spherical, HingeType::Free,      HingeType::Locked};
  double worst_crb = 0, worst_rt = 0, worst_f = 0, worst_cond = 0;
  int cases = 0;
  const auto random_case = [&](const Model& mr, int i) {
    State xr = random_state(mr, rnd);
    if (i % 5 == 0) xr.beta.setZero();
    const VecX Tr = random_vector(mr.nv(), rnd);
    const Forces fr = i % 4 == 0 ? random_forces(mr, rnd) : Forces{};
    const MassAndBias mbr(mr, xr, fr);
    soa::ForwardDynamics fdr(mr);
    Workspace wsr(mr);
    const VecX bdr = forward(mr, xr, Tr, fr, &fdr, &wsr);
    const double unit = mr.nv() * kEps * mbr.cond;
    worst_crb = std::max(worst_crb, rel(bdr, mbr.solve(Tr)) / unit);
    Workspace wne(mr);
    const VecX Tb = inverse(mr, xr, bdr, fr, &wne);
    worst_rt = std::max(
        worst_rt, (Tb - Tr).norm() /
                      (mr.nv() * kEps * (Tr.norm() + mbr.C.norm() + mbr.M.norm() * bdr.norm())));
    for (int k = 1; k <= mr.n(); ++k) {
      const std::size_t j = std::size_t(k - 1);
      const Vec6 f = fdr.art.P_plus[j] * fdr.alpha_plus[j].vector() + fdr.z_plus[j].vector();
      const double s = 1 + wne.f[j].vector().norm() + fdr.z_plus[j].vector().norm() +
                       fdr.art.P_plus[j].norm() * fdr.alpha_plus[j].vector().norm();
      worst_f = std::max(worst_f, (f - wne.f[j].vector()).norm() / (s * unit));
    }
    worst_cond = std::max(worst_cond, mbr.cond);
    ++cases;
  };
  for (int i = 0; i < 700; ++i) {
    Model mr = random_chain(1 + i % 12, all_types, rnd);
    if (i % 2 == 1) mr.gravity = Vec3(0, 0, -9.81);
    if (i % 3 == 0)
      for (int k = 1; k <= mr.n(); ++k) mr.body(k).stiffness = 2, mr.body(k).damping = 0.5;
    random_case(mr, i);
  }
  for (int i = 0; i < 70; ++i) {
    Model mr = random_chain(20, {all_types[std::size_t(i % 6)]}, rnd);
    mr.gravity = Vec3(0, 0, -9.81);
    random_case(mr, i);
  }
  std::printf(
      "  %d random chains, cond(M) up to %.2g; worst, in units of n eps cond(M): "
      "FD vs CRB+LDLT %.3f, f = P+ alpha+ + z+ vs NE %.3f; round trip %.3f n eps\n",
      cases, worst_cond, worst_crb, worst_f, worst_rt);
  checks.check("random chains: FD == CRB + LDLT (/ n eps cond(M))", worst_crb, 16.0);
  checks.check("random chains: f = P+ alpha+ + z+ == Newton-Euler (/ n eps cond(M))", worst_f,
               16.0);
  checks.check("random chains: ID(FD(T)) = T (/ n eps (|T| + |C| + |M||bd|))", worst_rt, 16.0);

  /// ## 7. A short simulation
  ///
  /// Forward dynamics is what a simulation integrates: the state \f$(\theta, \beta)\f$
  /// moves by \f$\dot\theta = \beta\f$ (revolute hinges) and \f$\dot\beta = \text{FD}(\theta,
  /// \beta, T)\f$. The double pendulum of lesson 3 is released at rest from the angles its
  /// scene file gives and falls for 2 s under gravity, \f$T = 0\f$, with the classical
  /// Runge–Kutta method (RK4, 4 forward dynamics per step). No force does work, so the
  /// energy \f$\mathcal K + \mathcal U_g\f$ (lesson 4) must stay constant; RK4's error in it
  /// is \f$O(h^4)\f$, so halving the step divides it by about 16.
  ///
  /// \image html l8_double_pendulum.png "The double pendulum released at rest: its two hinge angles over 2 s (RK4, h = 1 ms)" width=600px
  ///
  /// \image html l8_energy.png "Relative energy error of RK4 on the double pendulum for four step sizes: each halving of h divides it by about 16" width=600px
  ///
  /// Now do exercise 8.5: one RK4 step.
  checks.section("7. A short simulation");
  soa::Scene pend;
  bool have_pendulum = true;
  try {
    pend = scene("double_pendulum");
  } catch (const std::exception& e) {
    have_pendulum = false;
    checks.check(std::string("double_pendulum.json loads (") + e.what() + ")", false);
  }
  if (have_pendulum) {
    const Model& mp = pend.model;
    const State x0{pend.state.theta, VecX::Zero(mp.nv())};
    const double E0 = energy(mp, x0);
    const double t_end = 2.0;
    const std::vector<double> steps = {0.008, 0.004, 0.002, 0.001};
    std::vector<std::vector<double>> err(steps.size());
    std::vector<double> worst_E(steps.size(), 0.0);
    std::ofstream csv_q(out / "l8_double_pendulum.csv");
    csv_q << "t,upper (hinge 2),lower (hinge 1)\n";
    soa::view::Recorder rec(pend, t_end, 401);  // the h = 1 ms run, every 5 ms
    for (std::size_t s = 0; s < steps.size(); ++s) {
      Integrator rk4(mp);
      State xs = x0;
      const int n_steps = int(std::lround(t_end / steps[s]));
      const int every = int(std::lround(0.008 / steps[s]));  // sample every 8 ms
      for (int i = 0; i <= n_steps; ++i) {
        if (i % every == 0) {
          const double e = std::abs(energy(mp, xs) - E0) / std::abs(E0);
          err[s].push_back(e);
          worst_E[s] = std::max(worst_E[s], e);
          if (s + 1 == steps.size()) {
            char line[96];
            std::snprintf(line, sizeof line, "%.3f,%.8f,%.8f\n", i * steps[s], xs.theta[1],
                          xs.theta[0]);
            csv_q << line;
          }
        }
        if (s + 1 == steps.size()) rec.offer(i * steps[s], xs);
        if (i < n_steps) rk4.step(xs, steps[s]);
      }
      std::printf("  h = %.3f s: %4d steps, max |E - E0|/|E0| = %.3e\n", steps[s], n_steps,
                  worst_E[s]);
    }
    csv_q.close();
    std::ofstream csv_e(out / "l8_energy.csv");
    csv_e << "t";
    for (const double h : steps) csv_e << ",h = " << h * 1000 << " ms";
    csv_e << "\n";
    for (std::size_t i = 0; i < err[0].size(); ++i) {
      char cell[48];
      std::snprintf(cell, sizeof cell, "%.3f", 0.008 * double(i));
      csv_e << cell;
      for (std::size_t s = 0; s < steps.size(); ++s) {
        std::snprintf(cell, sizeof cell, ",%.6e", std::max(err[s][i], 1e-17));
        csv_e << cell;
      }
      csv_e << "\n";
    }
    csv_e.close();
    double worst_ratio = 1e300;
    for (std::size_t s = 1; s < steps.size(); ++s)
      worst_ratio = std::min(worst_ratio, worst_E[s - 1] / worst_E[s]);
    checks.check("energy error of RK4 falls like h^4: each halving of h divides it by > 10",
                 worst_ratio > 10);
    checks.check("energy conserved to 1e-8 (relative) at h = 1 ms", worst_E.back(), 1e-8);
    checks.check("l8_double_pendulum.csv and l8_energy.csv written", bool(csv_q) && bool(csv_e));
    checks.check("figure written: l8_double_pendulum.png",
                 soa::lesson::plot("l8_double_pendulum.gp", out, "l8_double_pendulum.png"));
    checks.check("figure written: l8_energy.png",
                 soa::lesson::plot("l8_energy.gp", out, "l8_energy.png"));

    /// The h = 1 ms run in 3D: the viewer `l8_double_pendulum_view` (\ref viewer) draws it every 5
    /// ms, with \f$V(k)\f$ and the inter-body forces \f$f(k)\f$ of section 3 (inverse dynamics at
    /// the forward dynamics' \f$\dot\beta\f$), and the path of the lower link's end. The hinges are
    /// free (\f$T = 0\f$): the moment N(k) that each hinge passes on has no component along its
    /// axis, \f$H(k) f(k) = T(k) = 0\f$ on every frame (checked). The motion is planar, normal to
    /// the hinge axes, so N(k) has no other component either: the hinges pass on forces F(k) only,
    /// N(k) = 0 to rounding (checked; the page would draw that rounding at full scale, so the still
    /// image leaves f out). The energy of the frames stays within the bound above.
    soa::view::View view = soa::view::view_of(pend);
    view.title = "Double pendulum released at rest (lesson 8)";
    view.note = rec.note();
    view.runs.push_back(rec.take("RK4, h = 1 ms"));
    const soa::view::Run& run = view.runs.front();
    checks.check("viewer: H(k) f(k) = T(k) = 0 at the free hinges (/ max |f|)",
                 largest_hinge_force(pend, run), 64 * kEps);
    double N = 0, F = 0;
    for (const soa::view::Frame& fr : run.frames)
      for (std::size_t i = 0; i < fr.f.size(); ++i)
        (i % 6 < 3 ? N : F) = std::max(i % 6 < 3 ? N : F, std::abs(fr.f[i]));
    checks.check("viewer: planar motion, N(k) = 0 (/ max |F| x 1 m)", N / F, 64 * kEps);
    checks.check("viewer: energy of its frames conserved to 1e-8 (relative)", energy_drift(run),
                 1e-8);
    soa::lesson::check_viewer(checks, out, "l8_double_pendulum_view", view,
                              "paused=1&t=0.8&show=frames,axes,V,tip");
  }

  /// The 50-link chain of lesson 3 falls from the state its scene file gives (\f$T = 0\f$,
  /// RK4 with h = 1 ms, as above) for 3 s: the viewer `l8_chain50_view` keeps 201 of its 3001
  /// states, with \f$V(k)\f$, \f$f(k)\f$ and the path of its free end. Here too
  /// \f$H(k) f(k) = 0\f$ at every hinge (checked), and the energy is kept to the error of RK4
  /// at this step, larger than the double pendulum's: the light links at the end whip round
  /// fast (checked below \f$10^{-4}\f$, relative).
  try {
    const soa::Scene chain = scene("chain50");
    const double t_end = 3.0, h = 1e-3;
    const int n_steps = int(std::lround(t_end / h));
    soa::view::Recorder rec(chain, t_end, 201);
    Integrator rk4(chain.model);
    State xs = chain.state;
    for (int i = 0; i <= n_steps; ++i) {
      rec.offer(i * h, xs);
      if (i < n_steps) rk4.step(xs, h);
    }
    soa::view::View view = soa::view::view_of(chain);
    view.title = "50-link chain falling from its scene state (lesson 8)";
    view.note = rec.note();
    view.runs.push_back(rec.take("RK4, h = 1 ms"));
    const soa::view::Run& run = view.runs.front();
    std::printf("  chain50: %zu frames of %d states\n", run.frames.size(), n_steps + 1);
    checks.check("chain50 viewer: H(k) f(k) = T(k) = 0 at the free hinges (/ max |f|)",
                 largest_hinge_force(chain, run), 64 * kEps);
    checks.check("chain50 viewer: energy of its frames conserved to 1e-4 (relative)",
                 energy_drift(run), 1e-4);
    soa::lesson::check_viewer(checks, out, "l8_chain50_view", view, "paused=1&t=1&show=V,f,tip");
  } catch (const std::exception& e) {
    checks.check(std::string("chain50.json loads (") + e.what() + ")", false);
  }

  /// What the numbers say. The three sweeps cost a fixed number of 6x6 and 6-vector
  /// operations per body, so forward dynamics is O(N) like inverse dynamics, against the
  /// O(N²) of forming \f$\mathcal M\f$ and the O(N³) of factoring it. Its accuracy is that of
  /// a stable solve with \f$\mathcal M\f$: the difference from CRB + LDLT stays within a few
  /// \f$n\,\varepsilon\,\mathrm{cond}(\mathcal M)\f$. How the error and the run time of the
  /// three methods compare as N grows, in float and double, is the subject of the
  /// work-precision report of this lesson.

  /// ## 8. A real arm falling: the Franka Emika Panda
  ///
  /// The Panda of lesson 3 (`lib/scenes/panda.urdf`: Franka's
  /// kinematics and the inertial parameters identified by Gaz et al. 2019; the header of the
  /// file cites them) is released at rest from the pose \f$q = (0, -0.3, 0, -2.2, 0, 2.0,
  /// 0.8)\f$ rad (Franka's joints 1 to 7, from the base) with its motors off, \f$T = 0\f$, and
  /// falls under gravity for 1 s, integrated by RK4 as in section 7 with h = 1 ms (and again
  /// with h = 2 ms). The scene's joint limits are not applied (the recursions have none), nor
  /// are collisions: the arm folds through its limits and its own links as a limp chain would.
  ///
  /// At every step the articulated body algorithm's \f$\dot\beta\f$ (O(N),
  /// soa::forward_dynamics) is compared with the dense route of section 1,
  /// \f$\dot\beta = \mathcal M^{-1}(T - \mathcal C)\f$, \f$\mathcal M\f$ by composite bodies
  /// (lesson 5) and solved by Cholesky (LDLT); the difference, relative to \f$|\dot\beta|\f$,
  /// must stay within \f$16\,n\,\varepsilon\,\mathrm{cond}(\mathcal M)\f$ as in section 6. No
  /// force does work, so the energy \f$\mathcal K + \mathcal U_g\f$ must stay constant but for
  /// RK4's \f$O(h^4)\f$ error: halving h must divide its largest drift by more than 10.
  ///
  /// `l8_panda_fall.csv` and `l8_panda_fall.png`: the seven joint angles over the second (h =
  /// 1 ms). The table `l8_panda_fall.md` of the lesson 8 page gives the worst difference of
  /// the two routes and the energy drift of both runs, as the program computes them.
  checks.section("8. A real arm falling: the Franka Emika Panda");
  try {
    const soa::Scene panda = soa::load_scene(soa::lesson::lesson3_scene("panda.urdf"));
    const Model& pm = panda.model;
    checks.check("panda.urdf: 7 revolute joints", pm.nv() == 7);
    std::vector<int> dof;  // Franka's joint j (base first) is theta[dof[j]]
    for (const soa::Scene::Frame& F : panda.frames)
      if (!F.locked && pm.body(F.k).hinge.nv() == 1) dof.push_back(pm.body(F.k).q_offset);
    const State x0{soa::theta_from_file_order(panda, {0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8}),
                   VecX::Zero(pm.nv())};
    const double E0 = energy(pm, x0), t_end = 1.0;
    const VecX T0 = VecX::Zero(pm.nv());
    const std::vector<double> steps = {0.002, 0.001};
    std::vector<double> drift(steps.size(), 0.0);
    double worst_rel = 0, worst_unit = 0, cond_lo = INFINITY, cond_hi = 0, speed = 0;
    std::ofstream csv(out / "l8_panda_fall.csv");
    csv << "t";
    for (std::size_t j = 0; j < dof.size(); ++j) csv << ",joint " << j + 1;
    csv << "\n";
    for (std::size_t s = 0; s < steps.size(); ++s) {
      const bool last = s + 1 == steps.size();
      Integrator rk4(pm);
      State xs = x0;
      const int n_steps = int(std::lround(t_end / steps[s]));
      for (int i = 0; i <= n_steps; ++i) {
        drift[s] = std::max(drift[s], std::abs(energy(pm, xs) - E0) / std::abs(E0));
        if (last) {
          const MassAndBias mbp(pm, xs, {});
          const VecX bd = forward(pm, xs, T0, {});
          const double r = rel(bd, mbp.solve(T0));
          worst_rel = std::max(worst_rel, r);
          worst_unit = std::max(worst_unit, r / (pm.nv() * kEps * mbp.cond));
          cond_lo = std::min(cond_lo, mbp.cond);
          cond_hi = std::max(cond_hi, mbp.cond);
          speed = std::max(speed, xs.beta.lpNorm<Eigen::Infinity>());
          if (i % 5 == 0) {
            char cell[48];
            std::snprintf(cell, sizeof cell, "%.3f", i * steps[s]);
            csv << cell;
            for (const int d : dof) {
              std::snprintf(cell, sizeof cell, ",%.8f", xs.theta[d]);
              csv << cell;
            }
            csv << "\n";
          }
        }
        if (i < n_steps) rk4.step(xs, steps[s]);
      }
      std::printf("  Panda, h = %.3f s: %d steps, max |E - E0|/|E0| = %.3e\n", steps[s], n_steps,
                  drift[s]);
    }
    csv.close();
    std::printf(
        "  Panda, h = 1 ms: cond(M) in [%.3g, %.3g], fastest joint %.3g rad/s; worst "
        "|FD - CRB+LDLT|/|bd| = %.2e = %.3f n eps cond(M)\n",
        cond_lo, cond_hi, speed, worst_rel, worst_unit);
    checks.check("Panda falling: FD == CRB + LDLT at every step (/ n eps cond(M))", worst_unit,
                 16.0);
    const double ratio = drift[0] / drift[1];
    checks.check("Panda falling: halving h divides the energy drift by > 10 (RK4, h^4)",
                 ratio > 10);
    std::ofstream md(out / "l8_panda_fall.md");
    char text[900];
    std::snprintf(
        text, sizeof text,
        "| step h | steps | largest relative energy drift |\n|--:|--:|--:|\n"
        "| %g ms | %d | %.3e |\n| %g ms | %d | %.3e |\n\n"
        "Halving the step divides the energy drift by %.1f. At the %d states of the h = %g ms "
        "run, the articulated body algorithm and the mass matrix route (composite bodies, LDLT) "
        "give accelerations that differ by at most %.2e relative, %.3f times n ε cond(M), with "
        "cond(M) between %.3g and %.3g and joint rates up to %.3g rad/s.\n",
        steps[0] * 1e3, int(std::lround(t_end / steps[0])), drift[0], steps[1] * 1e3,
        int(std::lround(t_end / steps[1])), drift[1], ratio, int(std::lround(t_end / steps[1])) + 1,
        steps[1] * 1e3, worst_rel, worst_unit, cond_lo, cond_hi, speed);
    md << text;
    md.close();
    checks.check("l8_panda_fall.csv and l8_panda_fall.md written", bool(csv) && bool(md));
    checks.check("figure written: l8_panda_fall.png",
                 soa::lesson::plot("l8_panda_fall.gp", out, "l8_panda_fall.png"));
  } catch (const std::exception& e) {
    checks.check(std::string("panda.urdf loads (") + e.what() + ")", false);
  }

  return checks.finish();
}
