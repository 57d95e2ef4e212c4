/// # Lesson 4 — Serial-chain dynamics
///
/// Topic 4 of the course (slides 1 and 80; Jain 2011, chapter 4): the equations of motion of
/// a serial chain, first body by body with the single-body equations of lesson 2, then all at
/// once with the spatial operators of lesson 3, which give
/// \f[ T = \mathcal M(\theta)\,\dot\beta + \mathcal C(\theta, \beta), \qquad
///     \mathcal M = H\phi M\phi^* H^*, \qquad \mathcal C = H\phi\,(M\phi^* a + b), \f]
/// the Newton–Euler factorization of the mass matrix. Every identity is computed on concrete
/// numbers and checked; the program ends with the count of checks that passed.
///
/// Numbering (\ref conventions): **body 1 is the tip, body n is next to the base**, the
/// inertial frame is body n+1, hinge k joins body k+1 (inboard) to body k, and \f$\theta\f$,
/// \f$\beta\f$ and \f$T\f$ are stacked in the same order, tip first.
///
/// Learning goals. After this lesson you can
/// - write the equations of motion of body k of a chain, with the inter-body forces, and
///   compute the hinge forces \f$T\f$ by the O(N) Newton–Euler recursions (inverse
///   dynamics);
/// - stack them with the operators \f$\phi\f$, \f$H\f$, \f$M\f$ into
///   \f$T = \mathcal M\dot\beta + \mathcal C\f$ and read off the mass matrix and the bias;
/// - put gravity in as a base acceleration, external forces into \f$b\f$, and joint springs
///   and dampers into \f$T\f$;
/// - check a dynamics code with physics: a symmetric positive definite mass matrix, the
///   kinetic energy, the power balance and the momentum balance along a motion, and the
///   Lagrangian equations of the planar two-link arm;
/// - build the Coriolis matrix \f$\mathcal C_v\f$ and the rate \f$\dot{\mathcal M}\f$ in
///   operator form and show \f$\dot{\mathcal M} - 2\mathcal C_v\f$ skew-symmetric.
///
/// Run it as `lesson04 OUTDIR`: it prints each check and writes the joint torques of a
/// 7-joint arm along a motion (`l4_arm7_torques.csv`, `l4_arm7_terms.csv`), their figures
/// (`l4_arm7_torques.png`, `l4_arm7_terms.png`) and the 3D viewer of that motion with its
/// inter-body forces, `OUTDIR/l4_arm7_view/` (open its `index.html` in a browser), and the
/// Panda's torques holding a payload (`l4_panda_payload.md`, `l4_panda_payload.csv`).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "args.hpp"
#include "checklist.hpp"
#include "plot.hpp"
#include "scenes.hpp"
#include "soa/chain.hpp"
#include "soa/chain/energy_structure.hpp"
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
using soa::Operators;
using soa::Phi;
using soa::Pose;
using soa::SpatialInertia;
using soa::State;
using soa::Velocity;
using soa::Workspace;
using Vec3 = soa::Vec3<double>;
using Mat3 = soa::Mat3<double>;
using VecX = soa::VecX<double>;
using MatX = soa::MatX<double>;

const double kEps = soa::eps<double>();
const double kPi = std::acos(-1.0);

/// ## Helpers
///
/// A body of a chain: mass \f$m\f$, centre of mass \f$p = l(O_k, C_k)\f$ and the principal
/// moments of \f$J(C)\f$ (principal axes along those of \f$O_k\f$), placed on its inboard
/// body at \f${}^{O_{k+1}}T_{O_k^+}\f$, with its hinge.
Body make_body(const std::string& name, double m, const Vec3& p, const Vec3& J_principal,
               const Pose& placement, const soa::Hinge& hinge) {
  Body b;
  b.name = name;
  b.M = SpatialInertia::from_cm(m, p, J_principal.asDiagonal().toDenseMatrix());
  b.placement = placement;
  b.hinge = hinge;
  return b;
}

soa::Hinge hinge(HingeType type, const Vec3& axis, const Vec3& axis2 = Vec3::UnitY(),
                 double pitch = 0) {
  soa::Hinge h;
  h.type = type;
  h.axis = axis.normalized();
  h.axis2 = axis2.normalized();
  h.pitch = pitch;
  return h;
}

Pose at(const Vec3& rotation_vector, const Vec3& offset) {
  return Pose(soa::exp_so3<double>(rotation_vector), offset);
}

/// The small chain of sections 1-8: four bodies, from the base out a universal joint, a
/// helical joint (a screw), a prismatic joint and a revolute joint at the tip; 5 degrees of
/// freedom. All four hinge types have \f$\dot\theta = \beta\f$, which sections 5 and 8 use.
Model small_chain() {
  std::vector<Body> base_first = {
      make_body("shoulder", 3.0, Vec3(0.05, 0.02, 0.25), Vec3(0.05, 0.06, 0.02),
                at(Vec3(0.2, 0.0, 0.0), Vec3(0.0, 0.0, 0.3)),
                hinge(HingeType::Universal, Vec3::UnitZ(), Vec3::UnitY())),
      make_body("screw", 1.5, Vec3(0.0, 0.03, 0.2), Vec3(0.02, 0.02, 0.01),
                at(Vec3(0.0, 0.1, 0.3), Vec3(0.02, 0.0, 0.5)),
                hinge(HingeType::Helical, Vec3(0.0, 0.3, 1.0), Vec3::UnitY(), 0.05)),
      make_body("slider", 1.0, Vec3(0.15, 0.0, 0.02), Vec3(0.004, 0.01, 0.01),
                at(Vec3(-0.3, 0.0, 0.2), Vec3(0.0, 0.05, 0.4)),
                hinge(HingeType::Prismatic, Vec3(1.0, 0.0, 0.2))),
      make_body("tip", 0.8, Vec3(0.2, 0.0, -0.03), Vec3(0.002, 0.01, 0.01),
                at(Vec3(0.0, 0.0, 0.3), Vec3(0.4, 0.0, 0.1)),
                hinge(HingeType::Revolute, Vec3(0.0, 1.0, 0.1))),
  };
  Model m = Model::from_base_first(base_first);
  m.gravity = Vec3(0, 0, -9.81);
  return m;
}

/// The 7-joint arm of lesson 3 (`lib/scenes/arm7.json`) built
/// in code, should its scene file not load: seven revolute joints with axes z, y, z, y, z,
/// y, z (a common redundant-arm layout), 1.26 m from the base to the flange, masses from
/// 4 kg at the shoulder to 0.3 kg at the flange, and a 0.9 kg gripper on a locked hinge
/// (merged into the last link); gravity along −z.
Model arm7_in_code() {
  const Vec3 z = Vec3::UnitZ(), y = Vec3::UnitY();
  const auto rev = [](const Vec3& a) { return hinge(HingeType::Revolute, a); };
  const auto up = [](double d) { return Pose(Mat3::Identity(), Vec3(0, 0, d)); };
  std::vector<Body> base_first = {
      make_body("link1", 4.0, Vec3(0, -0.03, 0.12), Vec3(0.1, 0.09, 0.02), up(0.1575), rev(z)),
      make_body("link2", 4.0, Vec3(0, 0.03, 0.10), Vec3(0.05, 0.044, 0.018), up(0.2025), rev(y)),
      make_body("link3", 3.0, Vec3(0, 0.03, 0.13), Vec3(0.08, 0.075, 0.01), up(0.2045), rev(z)),
      make_body("link4", 2.7, Vec3(0, -0.034, 0.067), Vec3(0.03, 0.029, 0.01), up(0.2155), rev(y)),
      make_body("link5", 1.7, Vec3(0, 0.021, 0.076), Vec3(0.02, 0.018, 0.005), up(0.1845), rev(z)),
      make_body("link6", 1.8, Vec3(0, 0.002, 0.06), Vec3(0.005, 0.0047, 0.0036), up(0.2155),
                rev(y)),
      make_body("link7", 0.3, Vec3(0, 0, 0.02), Vec3(0.001, 0.001, 0.001), up(0.081), rev(z)),
      make_body("gripper", 0.9, Vec3(0, 0, 0.06), Vec3(0.0025, 0.0025, 0.0012), up(0.045),
                hinge(HingeType::Locked, z)),
  };
  Model m = Model::from_base_first(base_first);
  m.gravity = Vec3(0, 0, -9.81);
  return m;
}

/// The 7-joint arm from its scene file (lesson 3), or from arm7_in_code() when the file does
/// not load or has a hinge with \f$\dot\theta \ne \beta\f$ (section 10 needs
/// \f$\dot\theta = \beta\f$); as a scene, for the viewer.
soa::Scene arm7(std::string& source) {
  const std::string path = SOA_SCENE_DIR "/arm7.json";
  try {
    soa::Scene scene = soa::load_scene(path);
    bool plain = scene.model.n() > 0;
    for (const Body& b : scene.model.bodies()) plain = plain && b.hinge.nq() == b.hinge.nv();
    if (plain) {
      source = "scene file lib/scenes/arm7.json";
      return scene;
    }
    source = "built in code (the scene file has a hinge with theta_dot != beta)";
  } catch (const std::exception& e) {
    source = std::string("built in code (") + e.what() + ")";
  }
  return soa::lesson::scene_of(arm7_in_code(), "7-joint arm");
}

/// The hinge forces by the library's Newton–Euler inverse dynamics, soa::inverse_dynamics (the
/// fast form of soa::reference::inverse_dynamics(), lib/include/soa/reference/
/// inverse_dynamics.hpp, which is the one to read).
VecX inverse_dynamics(const Model& m, const State& x, const VecX& beta_dot,
                      const soa::ExternalForces<double>& f_ext = {}) {
  Workspace ws(m);
  VecX T(m.nv());
  soa::inverse_dynamics(m, x, beta_dot, f_ext, ws, T);
  return T;
}

/// Stacks per-body spatial vectors (entry k−1 for body k) into one 6n-vector, tip first, as
/// the operators of soa::OperatorsT lay them out.
template <class SV>
VecX stack(const std::vector<SV>& v) {
  VecX s(6 * int(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) s.segment<6>(6 * Eigen::Index(i)) = v[i].vector();
  return s;
}

/// The kinetic energy body by body, \f$\sum_k \tfrac12 V^*(k)\,M(k)\,V(k)\f$ (slide 72), with
/// the velocities of the scatter recursion of lesson 3.
double kinetic_energy(const Model& m, const State& x) {
  Workspace ws(m);
  soa::update_phi(m, x.theta, ws);
  soa::update_velocities(m, x, ws);
  double K = 0;
  for (int k = 1; k <= m.n(); ++k) K += m.body(k).M.kinetic_energy(ws.V[k - 1]);
  return K;
}

/// The centre of mass of every body in inertial coordinates,
/// \f${}^I l(I, C_k) = {}^I T_{O_k}\, p(k)\f$.
std::vector<Vec3> mass_centres(const Model& m, const VecX& theta) {
  Workspace ws(m);
  soa::update_phi(m, theta, ws);
  soa::update_poses(m, ws);
  std::vector<Vec3> c;
  for (int k = 1; k <= m.n(); ++k) c.push_back(ws.pose[k - 1].apply(m.body(k).M.p()));
  return c;
}

/// The potential energy: of gravity, \f$-\sum_k m_k\, g^* l(I, C_k)\f$, and of the joint
/// springs, \f$\sum_k \tfrac12 k_k\,|\theta(k) - \theta_0(k)|^2\f$ (1-dof and universal
/// hinges).
double potential_energy(const Model& m, const VecX& theta) {
  const std::vector<Vec3> c = mass_centres(m, theta);
  double U = 0;
  for (int k = 1; k <= m.n(); ++k) {
    const Body& B = m.body(k);
    U -= B.M.mass() * m.gravity.dot(c[std::size_t(k - 1)]);
    for (int i = 0; i < B.hinge.nq(); ++i) {
      const double d = theta[B.q_offset + i] - B.rest[i];
      U += 0.5 * B.stiffness * d * d;
    }
  }
  return U;
}

/// The power the dampers take out, \f$\sum_k c_k\,|\beta(k)|^2\f$.
double damper_power(const Model& m, const VecX& beta) {
  double P = 0;
  for (const Body& B : m.bodies())
    P += B.damping * beta.segment(B.v_offset, B.hinge.nv()).squaredNorm();
  return P;
}

/// A motion of every degree of freedom (for hinges with \f$\dot\theta = \beta\f$):
/// \f$\theta_i(t) = \theta_{0,i} + A_i \sin(\omega_i t)\f$, with its rates.
struct Motion {
  VecX theta0, A, w;
  VecX theta(double t) const { return theta0 + A.cwiseProduct((w * t).array().sin().matrix()); }
  VecX beta(double t) const {
    return A.cwiseProduct(w).cwiseProduct((w * t).array().cos().matrix());
  }
  VecX beta_dot(double t) const {
    return -A.cwiseProduct(w).cwiseProduct(w).cwiseProduct((w * t).array().sin().matrix());
  }
  State state(double t) const { return State{theta(t), beta(t)}; }
};

/// Time derivatives along a motion are taken numerically with the five-point central
/// difference \f$\dot x(t) \approx (x(t-2h) - 8x(t-h) + 8x(t+h) - x(t+2h))/(12h)\f$. Its
/// truncation error \f$O(h^4\omega^5)\f$ and rounding error \f$O(\varepsilon/h)\f$ (for a
/// motion of frequency \f$\omega\f$) balance at \f$h = \varepsilon^{1/5}/\omega\f$, where both
/// are of order \f$\varepsilon^{4/5}\omega\f$ times the magnitude: `fd_tol` is a hundred times
/// that.
template <class F>
auto derivative(const F& x, double t, double w_max) {
  const double h = std::pow(kEps, 0.2) / w_max;
  using T = decltype(x(t));
  const T d = (x(t - 2 * h) - 8.0 * x(t - h) + 8.0 * x(t + h) - x(t + 2 * h)) / (12.0 * h);
  return d;
}
double fd_tol(double w_max, double scale) {
  return 100 * std::pow(kEps, 0.8) * w_max * scale;
}

/// A vector as a row, `[a, b, ...]`, 6 significant digits.
std::string row(const VecX& v) {
  std::string s = "[";
  char cell[32];
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    std::snprintf(cell, sizeof cell, "%s%.6g", i ? ", " : "", v[i]);
    s += cell;
  }
  return s + "]";
}

/// The smallest and largest eigenvalues of a symmetric matrix.
std::pair<double, double> eigen_range(const MatX& A) {
  const Eigen::SelfAdjointEigenSolver<MatX> eig(A);
  return {eig.eigenvalues().minCoeff(), eig.eigenvalues().maxCoeff()};
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path out = soa::lesson::output_dir(argc, argv);
  soa::lesson::Checklist checks;

  /// ## 1. One body of the chain: the Newton–Euler recursions
  ///
  /// Body k is pushed by its inboard hinge with the spatial force \f$f(k)\f$, at \f$O_k\f$,
  /// and by its outboard neighbour with \f$-f(k-1)\f$, at \f$O_{k-1}\f$; moved to
  /// \f$O_k\f$ with \f$\phi(k,k-1)\f$ (slides 49-51). The equations of motion of one body
  /// about \f$O_k\f$ (lesson 2) with \f$V(k)\f$ and its inertial derivative \f$\alpha(k)\f$
  /// give the balance of the forces on body k,
  /// \f[ f(k) = \phi(k,k-1)\, f(k-1) + M(k)\,\alpha(k) + b(k), \qquad
  ///     b(k) = \begin{pmatrix} \tilde\omega_k\, J(k)\,\omega_k \\ m_k\,\tilde\omega_k
  ///     \tilde\omega_k\, p(k) \end{pmatrix}, \f]
  /// with \f$f(0) = 0\f$ (nothing is outboard of the tip). Only the part of \f$f(k)\f$ along
  /// the hinge's free directions is done by the hinge's actuator; the rest is carried by its
  /// structure. That part is the hinge force \f$T(k) = H(k)\, f(k)\f$, the dual of
  /// \f$\Delta_V(k) = H^*(k)\beta(k)\f$: its power is
  /// \f$T^*(k)\beta(k) = f^*(k)\,\Delta_V(k)\f$.
  ///
  /// Inverse dynamics, the hinge forces that give the chain the accelerations
  /// \f$\dot\beta\f$, is then two O(N) sweeps: base to tip the velocities and accelerations
  /// of lesson 3,
  /// \f$V(k) = \phi^*(k+1,k)V(k+1) + H^*(k)\beta(k)\f$,
  /// \f$\alpha(k) = \phi^*(k+1,k)\alpha(k+1) + H^*(k)\dot\beta(k) + a(k)\f$ (with
  /// \f$V(n+1) = 0\f$ and, section 5, \f$\alpha(n+1) = [0; -g]\f$); tip to base the
  /// forces above. We write the tip-to-base sweep here and compare it with the library's
  /// soa::inverse_dynamics, the fast form of soa::reference::inverse_dynamics()
  /// (lib/include/soa/reference/inverse_dynamics.hpp).
  ///
  /// Now do exercise 4.1 (the gather sweep) and 4.2 (both sweeps of a revolute chain, with
  /// gravity as in section 5); exercise 4.8 derives the Coriolis term \f$a(k)\f$ of a helical
  /// hinge.
  checks.section("1. One body of the chain: the Newton-Euler recursions");
  const Model chain = small_chain();
  const int n = chain.n(), nv = chain.nv();
  std::printf("  the chain: n = %d bodies, %d degrees of freedom, tip first:", n, nv);
  for (int k = 1; k <= n; ++k)
    std::printf(" %d:%s(%s)", k, chain.body(k).name.c_str(),
                soa::hinge_type_name(chain.body(k).hinge.type));
  std::printf("\n");
  State x = State::rest(chain);
  x.theta << 0.4, 0.15, -0.7, 0.5, -0.3;  // tip: revolute, prismatic, helical, universal (2)
  x.beta << 1.1, -0.6, 0.8, -0.9, 1.3;
  VecX beta_dot(nv);
  beta_dot << -0.5, 2.0, 0.7, 1.5, -1.2;

  Workspace ws(chain);
  soa::update_phi(chain, x.theta, ws);
  soa::update_velocities(chain, x, ws);
  soa::update_accelerations(chain, x, beta_dot.data(), soa::gravity_base_acceleration(chain), ws);
  std::vector<Force> f(std::size_t(n), Force::Zero());
  VecX T_gather(nv);
  for (int k = 1; k <= n; ++k) {
    const Body& B = chain.body(k);
    Force fk = B.M * ws.alpha[k - 1] + soa::gyroscopic_force(B.M, ws.V[k - 1]);
    if (k > 1) fk += ws.phi[k - 2].apply(f[std::size_t(k - 2)]);  // phi(k,k-1) f(k-1)
    f[std::size_t(k - 1)] = fk;
    B.hinge.H_times(x.theta.data() + B.q_offset, fk, T_gather.data() + B.v_offset);
  }
  Workspace ws_id(chain);
  VecX T(nv);
  soa::inverse_dynamics(chain, x, beta_dot, {}, ws_id, T);
  const double f_scale = stack(f).norm();
  std::printf("  T = %s\n", row(T).c_str());
  checks.check("the gather sweep: f(k) = soa::inverse_dynamics's f(k)",
               (stack(f) - stack(ws_id.f)).norm(), 8 * kEps * f_scale);
  checks.check("the gather sweep: T(k) = H(k) f(k) = soa::inverse_dynamics's T",
               (T_gather - T).norm(), 8 * kEps * f_scale);
  double power_gap = 0, power_scale = 0;
  for (int k = 1; k <= n; ++k) {
    const Body& B = chain.body(k);
    const Velocity dV =
        B.hinge.H_star_times(x.theta.data() + B.q_offset, x.beta.data() + B.v_offset);
    const double p_hinge =
        T.segment(B.v_offset, B.hinge.nv()).dot(x.beta.segment(B.v_offset, B.hinge.nv()));
    power_gap = std::max(power_gap, std::abs(p_hinge - soa::dot(f[std::size_t(k - 1)], dV)));
    power_scale = std::max(power_scale, f[std::size_t(k - 1)].vector().norm() * dV.vector().norm());
  }
  checks.check("hinge power T*(k) beta(k) = f*(k) Delta_V(k), every hinge", power_gap,
               8 * kEps * power_scale);

  /// ## 2. The stacked equations: spatial operators
  ///
  /// Stack the per-body quantities into 6n-vectors, tip first, and the hinge forces into
  /// \f$T\f$. With the shift operator \f$\mathcal E_\phi\f$, whose only non-zero blocks are
  /// \f$\phi(k+1,k)\f$ at block row k+1, column k, the gather recursion reads
  /// \f$f = \mathcal E_\phi f + M\alpha + b\f$, so
  /// \f[ f = \phi\,(M\alpha + b), \qquad T = H f, \qquad
  ///     \phi = (I - \mathcal E_\phi)^{-1}, \f]
  /// with \f$M = \mathrm{diag}(M(k))\f$, \f$H = \mathrm{diag}(H(k))\f$ and \f$\phi\f$ the
  /// block lower triangular matrix of the \f$\phi(i,j)\f$, \f$i \ge j\f$ (lesson 3). The
  /// scatter recursions read \f$V = \phi^* H^*\beta\f$ and
  /// \f$\alpha = \phi^*(H^*\dot\beta + a)\f$: the same \f$\phi\f$, transposed, because
  /// velocities move with \f$\phi^*\f$ where forces move with \f$\phi\f$ (slide 50).
  /// soa::OperatorsT builds all of them as dense matrices at one state (for teaching and
  /// tests only: the recursions never form them). It folds the base acceleration into the
  /// last block of \f$a\f$: \f$a(n) \mathrel{+}= \phi^*(n+1,n)\,\alpha(n+1)\f$.
  checks.section("2. The stacked equations: spatial operators");
  const Operators op = Operators::build(chain, x);
  const int N = 6 * n;
  checks.check("(I - E_phi) phi = I",
               ((MatX::Identity(N, N) - op.E_phi) * op.phi - MatX::Identity(N, N)).norm(),
               4 * kEps * op.phi.norm());
  checks.check("V = phi* H* beta = the scatter recursion", (op.V(x.beta) - stack(ws.V)).norm(),
               8 * kEps * op.phi.norm() * x.beta.norm());
  const VecX alpha_op = op.phi.transpose() * (op.H.transpose() * beta_dot + op.a);
  checks.check("alpha = phi* (H* beta_dot + a) = the scatter recursion",
               (alpha_op - stack(ws.alpha)).norm(), 8 * kEps * alpha_op.norm() * n);
  const VecX f_op = op.phi * (op.M * alpha_op + op.b);
  checks.check("f = phi (M alpha + b) = the gather recursion", (f_op - stack(f)).norm(),
               8 * kEps * f_scale * n);
  checks.check("T = H f = soa::inverse_dynamics", (op.H * f_op - T).norm(), 8 * kEps * f_scale * n);

  /// ## 3. T = M β̇ + C: the Newton–Euler factorization of the mass matrix
  ///
  /// Insert \f$\alpha\f$ into \f$f\f$ and \f$f\f$ into \f$T\f$:
  /// \f[ T = H\phi M\phi^* H^*\,\dot\beta + H\phi\,(M\phi^* a + b)
  ///       = \mathcal M(\theta)\,\dot\beta + \mathcal C(\theta, \beta), \f]
  /// \f[ \mathcal M = H\phi\, M\, \phi^* H^*, \qquad
  ///     \mathcal C = H\phi\,(M\phi^* a + b). \f]
  /// The mass matrix comes out factored, \f$\mathcal M = B^* M B\f$ with
  /// \f$B = \phi^* H^*\f$ (the Newton–Euler factorization; lessons 5-7 find two more). The bias
  /// \f$\mathcal C\f$ holds everything that does not depend on \f$\dot\beta\f$: Coriolis and
  /// centrifugal terms (in \f$a\f$ and \f$b\f$), gravity (in \f$a\f$, section 5), external
  /// forces (in \f$b\f$, section 6). Two consequences give the O(N) route to both: the bias is
  /// inverse dynamics at \f$\dot\beta = 0\f$, and column j of \f$\mathcal M\f$ is
  /// \f$T(\dot\beta = e_j) - T(\dot\beta = 0)\f$.
  ///
  /// Now do exercises 4.3 (the mass matrix from the operators), 4.4 (the mass matrix column by
  /// column from inverse dynamics) and 4.5 (the bias from the operators).
  checks.section("3. T = M beta_dot + C: the Newton-Euler factorization");
  const MatX M_ne = op.H * op.phi * op.M * op.phi.transpose() * op.H.transpose();
  const VecX C_ne = op.H * op.phi * (op.M * op.phi.transpose() * op.a + op.b);
  const double M_scale = M_ne.norm();
  checks.check("H phi M phi* H* = soa::OperatorsT::mass_matrix()", (M_ne - op.mass_matrix()).norm(),
               8 * kEps * M_scale);
  checks.check("H phi (M phi* a + b) = soa::OperatorsT::bias()", (C_ne - op.bias()).norm(),
               8 * kEps * f_scale * n);
  checks.check("C = inverse dynamics at beta_dot = 0",
               (C_ne - inverse_dynamics(chain, x, VecX::Zero(nv))).norm(), 8 * kEps * f_scale * n);
  checks.check("T = M beta_dot + C", (M_ne * beta_dot + C_ne - T).norm(), 8 * kEps * f_scale * n);
  MatX M_columns(nv, nv);
  const VecX T0 = inverse_dynamics(chain, x, VecX::Zero(nv));
  for (int j = 0; j < nv; ++j)
    M_columns.col(j) = inverse_dynamics(chain, x, VecX::Unit(nv, j)) - T0;
  checks.check("column j of M = T(e_j) - T(0)", (M_columns - M_ne).norm(),
               8 * kEps * (M_scale + T0.norm()) * n);

  /// ## 4. The mass matrix is symmetric positive definite; the kinetic energy
  ///
  /// The kinetic energy of the chain is the sum of the bodies' (slide 72), and with
  /// \f$V = \phi^* H^*\beta\f$
  /// \f[ \mathcal K = \sum_k \tfrac12 V^*(k)\, M(k)\, V(k) = \tfrac12 V^* M V
  ///     = \tfrac12\,\beta^*\, H\phi M\phi^* H^*\,\beta = \tfrac12\,\beta^*\mathcal M\beta . \f]
  /// \f$\mathcal M = B^* M B\f$ is symmetric because each \f$M(k)\f$ is (slide 69); it is
  /// positive definite because each \f$M(k)\f$ of a body with mass is, and
  /// \f$B = \phi^* H^*\f$ has full column rank (\f$\phi^*\f$ is invertible and the columns of
  /// each \f$H^*(k)\f$ are independent): \f$\beta^*\mathcal M\beta = V^* M V > 0\f$ for every
  /// \f$\beta \ne 0\f$. A mass matrix with a negative eigenvalue is a bug.
  checks.section("4. The mass matrix is symmetric positive definite; the kinetic energy");
  checks.check("M = M*", (M_ne - M_ne.transpose()).norm(), 4 * kEps * M_scale);
  const auto [lo, hi] = eigen_range(M_ne);
  std::printf("  eigenvalues of M in [%.4g, %.4g], condition number %.1f\n", lo, hi, hi / lo);
  checks.check("smallest eigenvalue of M > 0", lo > 64 * kEps * hi);
  const double K_bodies = kinetic_energy(chain, x);
  const double K_beta = 0.5 * x.beta.dot(M_ne * x.beta);
  std::printf("  kinetic energy K = %.6f J\n", K_bodies);
  checks.check("1/2 beta* M beta = sum_k 1/2 V*(k) M(k) V(k)", std::abs(K_beta - K_bodies),
               16 * kEps * K_bodies * n);

  /// ## 5. Gravity as a base acceleration
  ///
  /// Gravity pulls body k with \f$m_k g\f$ at its centre of mass \f$C_k\f$. Instead of adding
  /// these n forces, accelerate the base upwards: with \f$\alpha(n+1) = [0; -g]\f$ the scatter
  /// recursion adds to every \f$\alpha(k)\f$ the uniform acceleration \f$[0; -g]\f$ (moved to
  /// \f$O_k\f$, \f$\phi^*\f$ does not change a pure linear acceleration but for its
  /// coordinates), and \f$M(k)\,[0; -g] = -[\tilde p(k)\, m_k g;\ m_k g] =
  /// -\phi(O_k, C_k)\,[0; m_k g]\f$ is exactly minus the gravity force moved to \f$O_k\f$.
  /// So both ways give the same \f$T\f$, and the same inter-body forces \f$f(k)\f$: those of
  /// the real chain in the real gravity field. (The equivalence principle: nothing inside
  /// the chain tells gravity from an upward acceleration of the base.)
  ///
  /// Gravity is a potential force, \f$\mathcal U_g = -\sum_k m_k\, g^* l(I, C_k)\f$, so the
  /// hinge forces that hold the chain still at \f$\theta\f$ are its gradient:
  /// \f$\mathcal G(\theta) = \mathcal C(\theta, 0) = \partial\,\mathcal U_g/\partial\theta\f$
  /// (for hinges with \f$\dot\theta = \beta\f$; checked by finite differences).
  ///
  /// Now do exercise 4.9: predict which way each hinge holds a chain up against gravity.
  checks.section("5. Gravity as a base acceleration");
  Model chain_no_g = chain;
  chain_no_g.gravity = Vec3::Zero();
  soa::ExternalForces<double> f_gravity;
  {
    Workspace wp(chain);
    soa::update_phi(chain, x.theta, wp);
    soa::update_poses(chain, wp);
    for (int k = 1; k <= n; ++k) {
      const SpatialInertia& Mk = chain.body(k).M;
      const Vec3 F = Mk.mass() * (wp.pose[k - 1].R().transpose() * chain.gravity);  // O_k coords
      f_gravity.push_back(Force(Mk.p().cross(F), F));  // phi(O_k, C_k) [0; m_k g]
    }
  }
  Workspace ws_g(chain_no_g);
  VecX T_forces(nv);
  soa::inverse_dynamics(chain_no_g, x, beta_dot, f_gravity, ws_g, T_forces);
  checks.check("T with alpha(n+1) = [0; -g] = T with m_k g at each C_k", (T_forces - T).norm(),
               8 * kEps * f_scale * n);
  checks.check("f(k) with alpha(n+1) = [0; -g] = f(k) with m_k g at each C_k",
               (stack(ws_g.f) - stack(ws_id.f)).norm(), 8 * kEps * f_scale * n);
  const VecX G = inverse_dynamics(chain, State{x.theta, VecX::Zero(nv)}, VecX::Zero(nv));
  VecX grad_U(nv);
  for (int j = 0; j < nv; ++j) {
    const auto U_along = [&](double s) {
      return potential_energy(chain, x.theta + s * VecX::Unit(nv, j));
    };
    grad_U[j] = derivative(U_along, 0.0, 1.0);
  }
  std::printf("  G(theta) = C(theta, 0) = %s\n", row(G).c_str());
  checks.check("G(theta) = dU_g/dtheta (finite differences)", (G - grad_U).norm(),
               fd_tol(1.0, G.norm()));

  /// ## 6. External forces enter b
  ///
  /// An external spatial force \f$f_{ext}(k)\f$ on body k, at \f$O_k\f$, joins the balance
  /// of body k on the side of the hinge forces:
  /// \f$f(k) + f_{ext}(k) = \phi(k,k-1) f(k-1) + M(k)\alpha(k) + b(k)\f$, so it enters as
  /// \f$b(k) \to b(k) - f_{ext}(k)\f$ and changes the hinge forces by
  /// \f$\Delta T = -H\phi\, f_{ext}\f$. For a force \f$f_F\f$ at a frame F on body k,
  /// \f$f_{ext}(k) = \phi(O_k, F)\, f_F\f$, and \f$H\phi\,\phi(O_k,F)\f$ picks the transpose of
  /// the Jacobian of F, \f$J = B^*\phi^* H^*\f$ (lesson 3):
  /// \f[ \Delta T = -J^*(F)\, f_F , \f]
  /// the hinge forces that a static force at a tool point costs, the dual of
  /// \f$V(F) = J\beta\f$.
  ///
  /// Now do exercise 4.6: the gravity torques as \f$-\sum_k J^*(C_k)\,[0; m_k g]\f$.
  checks.section("6. External forces enter b");
  const Pose tool = at(Vec3(0.1, -0.2, 0.3), Vec3(0.25, 0.05, -0.04));  // ^{O_1}T_F on the tip
  const Force f_tool(Vec3(0.3, -0.5, 0.2), Vec3(4.0, -2.0, 6.0));       // at F, F coordinates
  soa::ExternalForces<double> f_ext(std::size_t(n), Force::Zero());
  f_ext[0] = Phi(tool).apply(f_tool);  // phi(O_1, F) f_F
  const VecX T_ext = inverse_dynamics(chain, x, beta_dot, f_ext);
  Eigen::Matrix<double, 6, Eigen::Dynamic> J_tool(6, nv);
  {
    Workspace wj(chain);
    soa::update_phi(chain, x.theta, wj);
    soa::update_poses(chain, wj);
    soa::jacobian(chain, x.theta, wj, 1, tool, J_tool);
  }
  const VecX dT_J = -J_tool.transpose() * f_tool.vector();
  checks.check("T(f_ext) - T = -J*(F) f_F", (T_ext - T - dT_J).norm(),
               8 * kEps * (f_scale + T_ext.norm()) * n);
  const Operators op_ext = Operators::build(chain, x, f_ext);
  checks.check("b with f_ext = b - f_ext (stacked)", (op_ext.b - op.b + stack(f_ext)).norm(),
               4 * kEps * stack(f_ext).norm());

  /// ## 7. Joint springs and dampers
  ///
  /// A spring of stiffness \f$k_k\f$ and rest position \f$\theta_0(k)\f$ and a damper
  /// \f$c_k\f$ in hinge k push the hinge with \f$\tau_s(k) = -k_k(\theta(k) - \theta_0(k)) -
  /// c_k\,\beta(k)\f$ (soa::BodyT). The hinge force \f$H(k)f(k)\f$ is now the actuator's plus
  /// the spring's, so the actuator supplies
  /// \f[ T = \mathcal M\dot\beta + \mathcal C - \tau_s . \f]
  /// The spring is a potential force, \f$\mathcal U_s = \sum_k \tfrac12 k_k|\theta(k) -
  /// \theta_0(k)|^2\f$; the damper takes the power \f$\sum_k c_k|\beta(k)|^2\f$ out of the
  /// chain (section 8).
  checks.section("7. Joint springs and dampers");
  Model sprung = chain;
  const double stiffness[] = {8.0, 20.0, 5.0, 12.0}, damping[] = {0.3, 1.5, 0.2, 0.6};
  for (int k = 1; k <= n; ++k) {
    sprung.body(k).stiffness = stiffness[k - 1];
    sprung.body(k).damping = damping[k - 1];
    for (int i = 0; i < sprung.body(k).rest.size(); ++i) sprung.body(k).rest[i] = 0.1 * (k + i);
  }
  VecX tau_s = VecX::Zero(nv);
  for (int k = 1; k <= n; ++k) {
    const Body& B = sprung.body(k);
    for (int i = 0; i < B.hinge.nv(); ++i) {
      const int j = B.v_offset + i;
      tau_s[j] = -B.stiffness * (x.theta[B.q_offset + i] - B.rest[i]) - B.damping * x.beta[j];
    }
  }
  const VecX T_sprung = inverse_dynamics(sprung, x, beta_dot);
  checks.check("T with springs and dampers = M beta_dot + C - tau_s",
               (T_sprung - (M_ne * beta_dot + C_ne - tau_s)).norm(),
               8 * kEps * (f_scale + tau_s.norm()) * n);

  /// ## 8. Energy and momentum along a motion
  ///
  /// The power of the hinge forces is the power delivered to the bodies. With
  /// \f$T + \tau_s = Hf\f$ and \f$f = \phi(M\alpha + b)\f$, \f$V = \phi^*H^*\beta\f$:
  /// \f[ \beta^*(T + \tau_s) = \beta^* H\phi\,(M\alpha + b) = V^*(M\alpha + b)
  ///     = \sum_k V^*(k)\,\bigl(M(k)\alpha(k) + b(k)\bigr) , \f]
  /// and \f$V^*(k)(M(k)\alpha(k) + b(k))\f$ is the rate of the kinetic energy of body k
  /// (at its centre of mass, \f$m\,v^*\dot v + \omega^*(J\dot\omega + \tilde\omega J\omega)\f$,
  /// the gyroscopic term doing no work; power is the same at every point, slide 50) plus, as
  /// gravity hides in \f$\alpha\f$, the rate of \f$\mathcal U_g\f$. With
  /// \f$\beta^*\tau_s = -\dot{\mathcal U}_s - \sum c_k|\beta(k)|^2\f$ (for
  /// \f$\dot\theta = \beta\f$):
  /// \f[ \frac{d}{dt}\bigl(\mathcal K + \mathcal U_g + \mathcal U_s\bigr) = \beta^* T
  ///     - \sum_k c_k\,|\beta(k)|^2 . \f]
  /// Newton's law for the whole chain: the spatial momentum of the chain about the inertial
  /// origin O, \f$h(O) = \sum_k \phi(O, O_k)\, M(k)V(k)\f$ (slides 76-77), changes at the rate
  /// of the external forces on it, the base's \f$\phi(O, O_n) f(n)\f$ and gravity's:
  /// \f[ \dot h(O) = \phi(O, O_n)\, f(n) + \sum_k \begin{pmatrix} \tilde l(O, C_k)\, m_k g
  ///     \\ m_k g \end{pmatrix} . \f]
  /// Both are checked along the motion \f$\theta_i(t) = \theta_{0,i} + A_i\sin(\omega_i t)\f$,
  /// with \f$T(t)\f$ from inverse dynamics at each t and the time derivatives by finite
  /// differences.
  checks.section("8. Energy and momentum along a motion");
  Motion motion;
  motion.theta0 = x.theta;
  motion.A.resize(nv);
  motion.A << 0.6, 0.1, 0.8, 0.5, 0.7;
  motion.w.resize(nv);
  motion.w << 2.0, 3.0, 1.5, 2.5, 1.0;
  const double w_max = motion.w.maxCoeff();
  const auto energy = [&](double t) {
    const State s = motion.state(t);
    return kinetic_energy(sprung, s) + potential_energy(sprung, s.theta);
  };
  const auto momentum = [&](double t) {
    const State s = motion.state(t);
    Workspace wm(sprung);
    soa::update_phi(sprung, s.theta, wm);
    soa::update_poses(sprung, wm);
    soa::update_velocities(sprung, s, wm);
    soa::Vec6<double> h = soa::Vec6<double>::Zero();
    for (int k = 1; k <= n; ++k)
      h += Phi(wm.pose[k - 1]).apply(sprung.body(k).M * wm.V[k - 1]).vector();
    return h;
  };
  double power_err = 0, power_ref = 0, momentum_err = 0, momentum_ref = 0;
  for (const double t : {0.3, 0.9, 1.7, 2.4, 3.1}) {
    const State s = motion.state(t);
    const VecX beta_dot_t = motion.beta_dot(t);
    Workspace wt(sprung);
    VecX Tt(nv);
    soa::inverse_dynamics(sprung, s, beta_dot_t, {}, wt, Tt);
    const double P = s.beta.dot(Tt) - damper_power(sprung, s.beta);
    const double dE = derivative(energy, t, w_max);
    std::printf("  t = %.1f s: dE/dt = %+.9f W, beta* T - sum c|beta|^2 = %+.9f W\n", t, dE, P);
    power_err = std::max(power_err, std::abs(dE - P));
    power_ref = std::max(power_ref, std::abs(energy(t)) + kinetic_energy(sprung, s));
    soa::update_poses(sprung, wt);
    soa::Vec6<double> rate = Phi(wt.pose[n - 1]).apply(wt.f[n - 1]).vector();
    const std::vector<Vec3> c = mass_centres(sprung, s.theta);
    for (int k = 1; k <= n; ++k) {
      const Vec3 F = sprung.body(k).M.mass() * sprung.gravity;
      rate.head<3>() += c[std::size_t(k - 1)].cross(F);
      rate.tail<3>() += F;
    }
    const soa::Vec6<double> dh = derivative(momentum, t, w_max);
    momentum_err = std::max(momentum_err, (dh - rate).norm());
    momentum_ref = std::max(momentum_ref, momentum(t).norm() + rate.norm() / w_max);
  }
  checks.check("d/dt (K + U_g + U_s) = beta* T - sum c |beta|^2 (finite differences)", power_err,
               fd_tol(w_max, power_ref));
  checks.check("d/dt h(O) = phi(O, O_n) f(n) + gravity (finite differences)", momentum_err,
               fd_tol(w_max, momentum_ref));

  /// ## 9. A closed-form check: the planar two-link arm
  ///
  /// Two links in the vertical x-y plane, gravity \f$g\f$ along −y, joined by revolute joints
  /// about z: the shoulder angle \f$q_1\f$ of link 1 from the x axis, the elbow angle
  /// \f$q_2\f$ of link 2 from link 1. Link i has mass \f$m_i\f$, length \f$l_i\f$, its centre
  /// of mass at \f$l_{c,i}\f$ along it and the moment of inertia \f$I_i\f$ about z there.
  /// With \f$c_1 = \cos q_1\f$, \f$c_{12} = \cos(q_1 + q_2)\f$, ... the centres of mass are at
  /// \f$r_1 = l_{c1}(c_1, s_1)\f$ and \f$r_2 = l_1(c_1, s_1) + l_{c2}(c_{12}, s_{12})\f$, so
  /// \f$|\dot r_1|^2 = l_{c1}^2\dot q_1^2\f$ and \f$|\dot r_2|^2 = l_1^2\dot q_1^2 +
  /// l_{c2}^2(\dot q_1 + \dot q_2)^2 + 2 l_1 l_{c2} c_2\,\dot q_1(\dot q_1 + \dot q_2)\f$. The
  /// kinetic energy \f$\tfrac12 m_1|\dot r_1|^2 + \tfrac12 I_1\dot q_1^2 +
  /// \tfrac12 m_2|\dot r_2|^2 + \tfrac12 I_2(\dot q_1 + \dot q_2)^2 = \tfrac12\dot q^*
  /// M(q)\dot q\f$ gives
  /// \f[ M(q) = \begin{pmatrix} I_1 + I_2 + m_1 l_{c1}^2 + m_2(l_1^2 + l_{c2}^2 + 2l_1 l_{c2}c_2)
  ///     & I_2 + m_2(l_{c2}^2 + l_1 l_{c2}c_2) \\ I_2 + m_2(l_{c2}^2 + l_1 l_{c2}c_2)
  ///     & I_2 + m_2 l_{c2}^2 \end{pmatrix} , \f]
  /// and the potential energy is \f$\mathcal U = m_1 g\, l_{c1}s_1 + m_2 g\,(l_1 s_1 +
  /// l_{c2}s_{12})\f$. Lagrange's equations
  /// \f$\frac{d}{dt}\frac{\partial\mathcal L}{\partial\dot q} - \frac{\partial\mathcal L}
  /// {\partial q} = \tau\f$, \f$\mathcal L = \mathcal K - \mathcal U\f$, give
  /// \f$\tau = M(q)\ddot q + C(q,\dot q) + G(q)\f$ with, for \f$h = m_2 l_1 l_{c2} s_2\f$
  /// (only \f$M_{11}\f$ and \f$M_{12}\f$ depend on \f$q\f$, through \f$c_2\f$),
  /// \f[ C = \begin{pmatrix} -h\,(2\dot q_1\dot q_2 + \dot q_2^2) \\ h\,\dot q_1^2
  ///     \end{pmatrix}, \qquad
  ///     G = \begin{pmatrix} (m_1 l_{c1} + m_2 l_1)\, g\, c_1 + m_2 l_{c2}\, g\, c_{12}
  ///     \\ m_2 l_{c2}\, g\, c_{12} \end{pmatrix} . \f]
  /// In the course's numbering the elbow link is body 1 (the tip) and the shoulder link body
  /// 2, so \f$\theta = (q_2, q_1)\f$: the library's \f$\mathcal M\f$ and \f$\mathcal C\f$ are
  /// these with both rows and columns swapped.
  checks.section("9. A closed-form check: the planar two-link arm");
  const double m1 = 2.0, m2 = 1.2, l1 = 0.8, l2 = 0.65, lc1 = 0.35, lc2 = 0.3, g = 9.81;
  const double I1 = m1 * l1 * l1 / 12, I2 = m2 * l2 * l2 / 12;
  Model planar = Model::from_base_first({
      make_body("upper", m1, Vec3(lc1, 0, 0), Vec3(1e-3, I1, I1), Pose(),
                hinge(HingeType::Revolute, Vec3::UnitZ())),
      make_body("fore", m2, Vec3(lc2, 0, 0), Vec3(1e-3, I2, I2),
                Pose(Mat3::Identity(), Vec3(l1, 0, 0)), hinge(HingeType::Revolute, Vec3::UnitZ())),
  });
  planar.gravity = Vec3(0, -g, 0);
  const double q1 = 0.7, q2 = -1.1, qd1 = 1.3, qd2 = -0.8, qdd1 = 0.5, qdd2 = 2.0;
  const double c1 = std::cos(q1), s2 = std::sin(q2), c2 = std::cos(q2), c12 = std::cos(q1 + q2);
  Eigen::Matrix2d M_lag;
  M_lag(0, 0) = I1 + I2 + m1 * lc1 * lc1 + m2 * (l1 * l1 + lc2 * lc2 + 2 * l1 * lc2 * c2);
  M_lag(0, 1) = M_lag(1, 0) = I2 + m2 * (lc2 * lc2 + l1 * lc2 * c2);
  M_lag(1, 1) = I2 + m2 * lc2 * lc2;
  const double hq = m2 * l1 * lc2 * s2;
  const Eigen::Vector2d C_lag(-hq * (2 * qd1 * qd2 + qd2 * qd2), hq * qd1 * qd1);
  const Eigen::Vector2d G_lag((m1 * lc1 + m2 * l1) * g * c1 + m2 * lc2 * g * c12,
                              m2 * lc2 * g * c12);
  const Eigen::Matrix2d swap =
      (Eigen::Matrix2d() << 0, 1, 1, 0).finished();  // (q1,q2) <-> tip first
  const State xp{swap * Eigen::Vector2d(q1, q2), swap * Eigen::Vector2d(qd1, qd2)};
  const VecX qdd = swap * Eigen::Vector2d(qdd1, qdd2);
  Model planar_no_g = planar;
  planar_no_g.gravity = Vec3::Zero();
  const MatX M_planar = Operators::build(planar, xp).mass_matrix();
  const VecX C_planar = inverse_dynamics(planar_no_g, xp, VecX::Zero(2));
  const VecX G_planar = inverse_dynamics(planar, State{xp.theta, VecX::Zero(2)}, VecX::Zero(2));
  const VecX T_planar = inverse_dynamics(planar, xp, qdd);
  const VecX T_lag = swap * (M_lag * Eigen::Vector2d(qdd1, qdd2) + C_lag + G_lag);
  std::printf("  Lagrange: tau = (%.6f, %.6f) N m (shoulder, elbow)\n", T_lag[1], T_lag[0]);
  checks.check("mass matrix = Lagrange's M(q) (rows and columns swapped)",
               (M_planar - swap * M_lag * swap).norm(), 8 * kEps * M_lag.norm());
  checks.check("Coriolis and centrifugal: C(theta, beta) without gravity = Lagrange's C",
               (C_planar - swap * C_lag).norm(), 16 * kEps * M_lag.norm() * xp.beta.squaredNorm());
  checks.check("gravity: C(theta, 0) = Lagrange's G", (G_planar - swap * G_lag).norm(),
               16 * kEps * G_lag.norm());
  checks.check("inverse dynamics = M(q) q_dd + C + G", (T_planar - T_lag).norm(),
               16 * kEps * (M_lag.norm() * qdd.norm() + C_lag.norm() + G_lag.norm()));

  /// ## 10. A 7-joint arm along a motion
  ///
  /// The 7-joint arm of lesson 3 (read from its scene file; built in code, the same arm, when
  /// the file does not load) moves every joint as \f$\theta_i(t) = \theta_{0,i} +
  /// A_i\sin(\omega_i t)\f$ for 4 s from a bent configuration (periods of 4, 2, 2, 4/3, 4/3,
  /// 1 and 1 s, base to flange). At each of 401 instants inverse dynamics gives the joint
  /// torques, split into the inertial part \f$\mathcal M\dot\beta\f$, the velocity part
  /// \f$\mathcal C(\theta,\beta) - \mathcal C(\theta,0)\f$ (Coriolis and centrifugal) and the
  /// static part \f$\mathcal C(\theta,0)\f$ (gravity, and springs if the arm has any). Along
  /// the way we check \f$T = \mathcal M\dot\beta + \mathcal C\f$ with the dense
  /// \f$\mathcal M = H\phi M\phi^*H^*\f$, that \f$\mathcal M\f$ stays positive definite, and
  /// the power balance of section 8.
  ///
  /// `l4_arm7_torques.csv` and `l4_arm7_torques.png`: the seven joint torques (or forces).
  ///
  /// \image html l4_arm7_torques.png "Joint torques of the 7-joint arm along the motion" width=600px
  ///
  /// `l4_arm7_terms.csv` and `l4_arm7_terms.png`: the three parts of the torque of joint 2,
  /// the shoulder that lifts the arm: the static (gravity) and the inertial parts are of one
  /// size at these speeds, the Coriolis and centrifugal part is smaller (it grows with the
  /// square of the speed).
  ///
  /// \image html l4_arm7_terms.png "Joint 2 of the 7-joint arm: the parts of its torque" width=600px
  checks.section("10. A 7-joint arm along a motion");
  std::string arm_source;
  const soa::Scene arm_scene = arm7(arm_source);
  const Model& arm = arm_scene.model;
  const int na = arm.nv();
  std::printf("  the arm: %s; %d bodies, %d degrees of freedom, gravity %.2f m/s^2\n",
              arm_source.c_str(), arm.n(), na, arm.gravity.norm());
  // Joint j (base first, j = 0 ... na-1) is degree of freedom dof[j] (tip first).
  std::vector<int> dof;
  std::vector<std::string> joint_name;
  for (int k = arm.n(); k >= 1; --k)
    for (int i = 0; i < arm.body(k).hinge.nv(); ++i) {
      dof.push_back(arm.body(k).v_offset + i);
      joint_name.push_back(arm.body(k).name);
    }
  const double theta0_bf[] = {0.0, 0.6, 0.0, -1.2, 0.0, 0.8, 0.0};
  const double A_bf[] = {0.8, 0.5, 0.6, 0.6, 0.9, 0.6, 1.0};
  const double period_bf[] = {4.0, 2.0, 2.0, 4.0 / 3, 4.0 / 3, 1.0, 1.0};
  Motion arm_motion{VecX::Zero(na), VecX::Zero(na), VecX::Zero(na)};
  for (int j = 0; j < na; ++j) {
    arm_motion.theta0[dof[std::size_t(j)]] = theta0_bf[j % 7];
    arm_motion.A[dof[std::size_t(j)]] = A_bf[j % 7];
    arm_motion.w[dof[std::size_t(j)]] = 2 * kPi / period_bf[j % 7];
  }
  const double arm_w_max = arm_motion.w.maxCoeff();
  const int joint2 = na > 1 ? 1 : 0;
  std::ofstream csv_T(out / "l4_arm7_torques.csv"), csv_terms(out / "l4_arm7_terms.csv");
  csv_T << "t";
  for (int j = 0; j < na; ++j)
    csv_T << ",joint " << j + 1 << " (" << joint_name[std::size_t(j)] << ")";
  csv_T << "\n";
  // Column titles of the figure (no commas: they are the CSV separator).
  const std::string static_label =
      arm.has_springs() ? "static: gravity and springs" : "static: gravity";
  csv_terms << "t,inertial: M dβ/dt,velocity: Coriolis and centrifugal," << static_label
            << ",total T\n";
  double split_err = 0, split_scale = 0, lowest = INFINITY, worst_cond = 0;
  double arm_power_err = 0, arm_power_ref = 0;
  const auto arm_energy = [&](double t) {
    const State s = arm_motion.state(t);
    return kinetic_energy(arm, s) + potential_energy(arm, s.theta);
  };
  // The viewer's frames: every instant, with f(k) of this motion (its own beta_dot).
  soa::view::Recorder rec(arm_scene, 4.0, 401);
  std::vector<VecX> torques;
  for (int i = 0; i <= 400; ++i) {
    const double t = 0.01 * i;
    const State s = arm_motion.state(t);
    const VecX bd = arm_motion.beta_dot(t);
    const VecX Tt = inverse_dynamics(arm, s, bd);
    rec.offer(t, s, bd);
    torques.push_back(Tt);
    const VecX T_rest = inverse_dynamics(arm, State{s.theta, VecX::Zero(na)}, VecX::Zero(na));
    const VecX T_vel = inverse_dynamics(arm, s, VecX::Zero(na));
    const Operators op_t = Operators::build(arm, s);
    const MatX M_t = op_t.mass_matrix();
    split_err = std::max(split_err, (M_t * bd + T_vel - Tt).norm());
    split_scale = std::max(split_scale, (M_t * bd).norm() + T_vel.norm());
    const auto [l, h] = eigen_range(M_t);
    lowest = std::min(lowest, l / h);
    worst_cond = std::max(worst_cond, h / l);
    if (i % 40 == 20) {  // the power balance at 10 instants
      const double P = s.beta.dot(Tt) - damper_power(arm, s.beta);
      arm_power_err = std::max(arm_power_err, std::abs(derivative(arm_energy, t, arm_w_max) - P));
      arm_power_ref = std::max(arm_power_ref, std::abs(arm_energy(t)) + kinetic_energy(arm, s));
    }
    char cell[64];
    std::snprintf(cell, sizeof cell, "%.2f", t);
    csv_T << cell;
    for (int j = 0; j < na; ++j) {
      std::snprintf(cell, sizeof cell, ",%.6f", Tt[dof[std::size_t(j)]]);
      csv_T << cell;
    }
    csv_T << "\n";
    const int d = dof[std::size_t(joint2)];
    std::snprintf(cell, sizeof cell, "%.2f,%.6f,%.6f,%.6f,%.6f\n", t, Tt[d] - T_vel[d],
                  T_vel[d] - T_rest[d], T_rest[d], Tt[d]);
    csv_terms << cell;
  }
  std::printf("  condition number of M along the motion: at most %.0f\n", worst_cond);
  checks.check("T = M beta_dot + C at all 401 instants (dense M)", split_err,
               64 * kEps * split_scale);
  checks.check("M positive definite all along (min eigenvalue / max > 64 eps)", lowest > 64 * kEps);
  checks.check("d/dt (K + U) = beta* T - sum c |beta|^2 at 10 instants", arm_power_err,
               fd_tol(arm_w_max, arm_power_ref));
  checks.check("l4_arm7_torques.csv written", bool(csv_T));
  checks.check("l4_arm7_terms.csv written", bool(csv_terms));
  csv_T.close();
  csv_terms.close();
  checks.check("figure written: l4_arm7_torques.png",
               soa::lesson::plot("l4_arm7_torques.gp", out, "l4_arm7_torques.png"));
  checks.check("figure written: l4_arm7_terms.png",
               soa::lesson::plot("l4_arm7_terms.gp", out, "l4_arm7_terms.png"));

  /// The motion in 3D: the viewer `l4_arm7_view` (\ref viewer) draws the arm at the 401 instants,
  /// with \f$V(k)\f$ and the inter-body forces \f$f(k)\f$ of the Newton-Euler inverse dynamics
  /// along this motion (at its own \f$\dot\beta\f$; moment N and force F at each hinge \f$O_k\f$,
  /// in inertial axes). They carry the joint torques: for a revolute hinge \f$T(k) = H(k) f(k) =
  /// h_k^* N(k)\f$, checked on every frame against the torques above. The force on the first link
  /// holds up the whole arm, of weight \f$g \sum_k m_k\f$, and accelerates it; each hinge further
  /// out carries less of the arm: the largest \f$|F(k)|\f$ along the motion falls from the base to
  /// the flange (printed, and checked).
  {
    soa::view::View view = soa::view::view_of(arm_scene);
    view.title = "7-joint arm (lesson 4): the inter-body forces along a joint motion";
    view.note = rec.note();
    view.runs.push_back(rec.take("inverse dynamics along the motion of section 10"));
    double T_gap = 0, T_scale = 0;
    const std::vector<soa::view::Frame>& frames = view.runs.front().frames;
    for (std::size_t i = 0; i < frames.size(); ++i) {
      T_gap = std::max(
          T_gap,
          (soa::lesson::hinge_forces(arm_scene, frames[i]) - torques[i]).lpNorm<Eigen::Infinity>());
      for (double fi : frames[i].f) T_scale = std::max(T_scale, std::abs(fi));
    }
    checks.check("viewer: T(k) = H(k) f(k) from its forces, every frame and hinge", T_gap,
                 64 * kEps * T_scale);
    double weight = 0;
    for (const Body& B : arm.bodies()) weight += B.M.mass() * arm.gravity.norm();
    std::printf("  weight of the arm %.1f N; largest |F(k)| along the motion, base first:", weight);
    bool falls = true;
    double previous = INFINITY;
    for (std::size_t b = 0; b < arm_scene.frames.size(); ++b) {
      if (arm_scene.frames[b].locked) continue;
      double largest = 0;
      for (const soa::view::Frame& f : frames)
        largest = std::max(largest, Vec3(f.f[6 * b + 3], f.f[6 * b + 4], f.f[6 * b + 5]).norm());
      std::printf(" %.1f", largest);
      falls = falls && largest < previous;
      previous = largest;
    }
    std::printf(" N\n");
    checks.check("viewer: the largest |F(k)| falls from the base to the flange", falls);
    soa::lesson::check_viewer(checks, out, "l4_arm7_view", view, "paused=1&t=1.5&show=axes,f,tip");
  }

  /// ## 11. The energy structure: the Coriolis matrix and the rate of the mass matrix
  ///
  /// With \f$B = \phi^* H^*\f$, \f$V = B\beta\f$ and \f$\mathcal M = B^* M B\f$ (section 3),
  /// in body coordinates, where every \f$M(k)\f$ is constant. **The rate of \f$\phi\f$.**
  /// \f$\phi(k+1,k) = [R, \tilde l R; 0, R]\f$ moves with the hinge,
  /// \f$\dot R = R\tilde\Delta_\omega\f$ and \f$\dot l = R\Delta_v\f$ for
  /// \f$\Delta_V(k) = H^*(k)\beta(k)\f$ in \f$O_k\f$ coordinates, so (with \f$R^*\widetilde{R
  /// \Delta_v}R = \tilde\Delta_v\f$ and \f$\bar X\f$ of slide 55)
  /// \f[ \dot\phi(k+1,k) = \phi(k+1,k)\begin{pmatrix} \tilde\Delta_\omega & \tilde\Delta_v \\ 0
  ///     & \tilde\Delta_\omega \end{pmatrix} = \phi(k+1,k)\,\bar\Delta_V(k), \qquad
  ///     \dot{\mathcal E}_\phi = \mathcal E_\phi\bar\Delta_V, \f]
  /// \f$\bar\Delta_V = \mathrm{diag}(\bar\Delta_V(k))\f$; from \f$\phi = (I -
  /// \mathcal E_\phi)^{-1}\f$, \f$\dot\phi = \phi\dot{\mathcal E}_\phi\phi = \tilde\phi\,
  /// \bar\Delta_V\phi\f$ with \f$\tilde\phi = \phi\,\mathcal E_\phi = \phi - I\f$. **The rate of
  /// \f$H^*\f$** seen from \f$O_k\f$ is zero but for the universal hinge, whose first column
  /// \f$c_1 = e^{-\theta_2\tilde a_2}a_1\f$ turns with \f$\dot c_1 = \beta_2\,c_1\times a_2\f$.
  /// So, with \f$\bar\Delta_V^* = -\tilde\Delta_V\f$ (slide 55),
  /// \f[ \dot B = \dot\phi^* H^* + \phi^*\dot H^* = \phi^*\bigl(\dot H^* - \tilde\Delta_V
  ///     \tilde\phi^* H^*\bigr), \qquad \dot{\mathcal M} = \dot B^* M B + B^* M\dot B . \f]
  /// **The bias in these terms.** \f$\tilde\phi^* H^*\beta = V - \Delta_V = V^+\f$, stacked
  /// \f$V^+(k) = \phi^*(k+1,k)V(k+1)\f$, so \f$\dot B\beta = \phi^*\mathring a\f$ with
  /// \f$\mathring a(k) = \tilde V^+(k)\Delta_V(k) + \dot H^*(k)\beta(k)\f$. The Coriolis term of
  /// lesson 3 is \f$a(k) = \mathring a(k) + w(k) - \phi^*(k+1,k)\,w(k+1)\f$ with \f$w(k) =
  /// [0; \omega_k\times v_k]\f$ (as \f$\tilde V\Delta_V = \tilde V^+\Delta_V\f$), i.e.
  /// \f$\phi^* a = \phi^*\mathring a + w\f$, and for each body (Jacobi's identity)
  /// \f$M(k)w(k) + b(k) = \bar V(k)M(k)V(k)\f$. Without gravity and external forces:
  /// \f[ \mathcal C(\theta,\beta) = H\phi\,(M\phi^*\mathring a + Mw + b)
  ///     = B^*\bigl(M\dot B\beta + \bar V M V\bigr) . \f]
  /// **The Coriolis matrix.** For a force or momentum \f$h = [N; F]\f$ let
  /// \f$\breve h = -[\tilde N, \tilde F; \tilde F, 0]\f$, so \f$\breve h V = \bar V h\f$ for
  /// every motion vector V and \f$\breve h^* = -\breve h\f$. With \f$\breve h =
  /// \mathrm{diag}(\breve h(k))\f$, \f$h(k) = M(k)V(k)\f$:
  /// \f[ \mathcal C_v(\theta,\beta) = B^*\bigl(M\dot B + \breve h B\bigr), \qquad
  ///     \mathcal C_v\beta = \mathcal C(\theta,\beta) - \mathcal C(\theta,0), \qquad
  ///     \mathcal C_v + \mathcal C_v^* = \dot B^* M B + B^* M\dot B + B^*(\breve h +
  ///     \breve h^*)B = \dot{\mathcal M} . \f]
  /// So \f$\dot{\mathcal M} - 2\,\mathcal C_v = \dot B^* M B - B^* M\dot B - 2B^*\breve h B\f$
  /// is skew-symmetric, \f$\beta^*(\dot{\mathcal M} - 2\mathcal C_v)\beta = 0\f$ (the
  /// passivity property). (Only \f$\mathcal C_v\beta\f$ is fixed by the dynamics; the
  /// book, Jain 2011, has its own spatial-operator expression for such a matrix; this one is
  /// derived here from the factorization and checked, not taken from there.)
  /// **The power balance.** With \f$T = \mathcal M\dot\beta + \mathcal C_v\beta + \mathcal
  /// G\f$, \f$\mathcal G = \mathcal C(\theta, 0)\f$, and \f$\mathcal K = \tfrac12\beta^*
  /// \mathcal M\beta\f$:
  /// \f[ \dot{\mathcal K} = \beta^*\mathcal M\dot\beta + \tfrac12\beta^*\dot{\mathcal M}\beta
  ///     = \beta^*(T - \mathcal G) + \tfrac12\beta^*(\dot{\mathcal M} - 2\mathcal C_v)\beta
  ///     = \beta^*(T - \mathcal G), \f]
  /// and \f$\beta^*\mathcal G = \dot{\mathcal U}_g\f$ (section 5) gives section 8's balance.
  /// soa::EnergyStructureT holds the dense operators (teaching and tests only). Checked on
  /// the chain of section 1 and on a floating chain (free, spherical and revolute hinges),
  /// whose quaternions are moved by the library's soa::retract() for the differences.
  ///
  /// Now do exercise 4.7: the Coriolis matrix from the operators.
  checks.section("11. The energy structure: Coriolis matrix and mass matrix rate");
  {
    const auto energy_checks = [&](const Model& mc, const State& xs, const char* name) {
      const int nvc = mc.nv(), Nc = 6 * mc.n();
      const soa::EnergyStructure es = soa::EnergyStructure::build(mc, xs);
      // The direction u of theta(t) = retract(theta, t u) along theta_dot = beta (the free
      // hinge's position moves as l_dot = R v in O_k^+ coordinates).
      VecX u = xs.beta;
      for (const Body& B : mc.bodies())
        if (B.hinge.type == HingeType::Free)
          u.segment<3>(B.v_offset + 3) = soa::Hinge::quaternion(xs.theta.data() + B.q_offset)
                                             .rotate(Vec3(xs.beta.segment<3>(B.v_offset + 3)));
      const double w_rate = std::max(1.0, xs.beta.lpNorm<Eigen::Infinity>());
      const auto moved = [&](double t) {
        VecX q;
        soa::retract(mc, xs.theta, VecX(t * u), q);
        return q;
      };
      double phi_err = 0, phi_ref = 0;
      for (int k = 1; k <= mc.n(); ++k) {
        const Body& B = mc.body(k);
        const double* th = xs.theta.data() + B.q_offset;
        const MatX rate = soa::joint_phi_rate(
            soa::joint_phi(B, th), B.hinge.H_star_times(th, xs.beta.data() + B.v_offset));
        const MatX fd = derivative(
            [&](double t) {
              return MatX(soa::joint_phi(B, moved(t).data() + B.q_offset).matrix());
            },
            0.0, w_rate);
        phi_err = std::max(phi_err, (rate - fd).norm());
        phi_ref = std::max(phi_ref, soa::joint_phi(B, th).matrix().norm());
      }
      checks.check(
          std::string(name) + ": phi_dot(k+1,k) = phi(k+1,k) bar(Delta_V(k)) (finite differences)",
          phi_err, fd_tol(w_rate, phi_ref));
      const MatX phi_fd = derivative(
          [&](double t) {
            return Operators::build(mc, State{moved(t), xs.beta}).phi;
          },
          0.0, w_rate);
      checks.check(std::string(name) + ": phi_dot = phi~ bar(Delta_V) phi (finite differences)",
                   (es.phi_dot() - phi_fd).norm(), fd_tol(w_rate, es.op.phi.norm()));
      const MatX Md = es.mass_matrix_rate();
      const MatX M_fd = derivative(
          [&](double t) {
            return Operators::build(mc, State{moved(t), xs.beta}).mass_matrix();
          },
          0.0, w_rate);
      checks.check(std::string(name) + ": M_dot = B_dot* M B + B* M B_dot (finite differences)",
                   (Md - M_fd).norm(), fd_tol(w_rate, es.op.mass_matrix().norm()));
      const MatX Cv = es.coriolis_matrix();
      Model m0 = mc;
      m0.gravity = Vec3::Zero();
      const VecX zero = VecX::Zero(nvc);
      const VecX C_id = inverse_dynamics(m0, xs, zero);
      const VecX G_id = inverse_dynamics(mc, State{xs.theta, zero}, zero);
      const double c_scale = 16 * kEps * mc.n() *
                             (es.B().squaredNorm() * (es.op.M.norm() + es.h_breve.norm()) *
                                  (1 + xs.beta.squaredNorm()) +
                              G_id.norm());
      checks.check(std::string(name) + ": C_v beta = inverse dynamics at beta_dot = 0, no gravity",
                   (Cv * xs.beta - C_id).norm(), c_scale);
      checks.check(std::string(name) + ": C_v beta = C(theta, beta) - C(theta, 0) with gravity",
                   (Cv * xs.beta - (inverse_dynamics(mc, xs, zero) - G_id)).norm(), c_scale);
      const MatX Nm = Md - 2 * Cv;
      const double n_scale = 16 * kEps * mc.n() * (Md.norm() + Cv.norm()) * es.op.phi.norm() *
                             (MatX::Identity(Nc, Nc) - es.op.E_phi).norm();
      std::printf(
          "  %s: |M_dot| = %.4g, |C_v| = %.4g, |(M_dot - 2 C_v) + (M_dot - 2 C_v)*| = %.3g\n", name,
          Md.norm(), Cv.norm(), (Nm + Nm.transpose()).norm());
      checks.check(std::string(name) + ": M_dot - 2 C_v is skew-symmetric",
                   (Nm + Nm.transpose()).norm(), n_scale);
      checks.check(std::string(name) + ": beta* (M_dot - 2 C_v) beta = 0",
                   std::abs(xs.beta.dot(Nm * xs.beta)), n_scale * xs.beta.squaredNorm());
      return es;
    };
    const soa::EnergyStructure es = energy_checks(chain, x, "chain of section 1");
    // The universal hinge (body 4) is the one with H*_dot != 0.
    const Body& U = chain.body(4);
    const double* thU = x.theta.data() + U.q_offset;
    const MatX H_fd = derivative(
        [&](double t) {
          const VecX q = x.theta + t * x.beta;  // theta_dot = beta on this chain
          return MatX(U.hinge.H_star(q.data() + U.q_offset));
        },
        0.0, std::max(1.0, x.beta.lpNorm<Eigen::Infinity>()));
    checks.check("universal hinge: H*_dot = [beta_2 c_1 x a_2, 0; 0, 0] (finite differences)",
                 (soa::hinge_map_rate(U.hinge, thU, x.beta.data() + U.v_offset) - H_fd).norm(),
                 fd_tol(std::max(1.0, x.beta.lpNorm<Eigen::Infinity>()), 1.0));
    VecX a_ring(N);
    {
      const VecX V_plus = es.phi_tilde().transpose() * (op.H.transpose() * x.beta);
      const VecX w_stack = [&] {
        VecX ws6 = VecX::Zero(N);
        for (int k = 1; k <= n; ++k)
          ws6.segment<3>(6 * (k - 1) + 3) = ws.V[k - 1].angular().cross(Vec3(ws.V[k - 1].linear()));
        return ws6;
      }();
      for (int k = 1; k <= n; ++k) {
        const Velocity Vp(soa::Vec6<double>(V_plus.segment<6>(6 * (k - 1))));
        const Body& B = chain.body(k);
        const double* th = x.theta.data() + B.q_offset;
        const double* be = x.beta.data() + B.v_offset;
        a_ring.segment<6>(6 * (k - 1)) = soa::cross(Vp, B.hinge.H_star_times(th, be)).vector() +
                                         B.hinge.H_star_dot_times(th, be).vector();
      }
      checks.check("B_dot beta = phi* a_ring",
                   (es.B_dot() * x.beta - op.phi.transpose() * a_ring).norm(),
                   16 * kEps * es.B_dot().norm() * x.beta.norm() * n);
      Model chain0 = chain;
      chain0.gravity = Vec3::Zero();
      const Operators op0 = Operators::build(chain0, x);
      checks.check("phi* a = phi* a_ring + w (a without gravity)",
                   (op0.phi.transpose() * op0.a - op.phi.transpose() * a_ring - w_stack).norm(),
                   16 * kEps * op0.phi.norm() * op0.a.norm() * n);
      checks.check("M w + b = bar(V) M V, every body",
                   (op.M * w_stack + op.b - es.h_breve * es.V).norm(),
                   16 * kEps * op.M.norm() * es.V.squaredNorm());
    }
    // The floating chain: a free base body, a spherical joint, a revolute tip.
    Model floating = Model::from_base_first({
        make_body("hull", 5.0, Vec3(0.1, 0.0, 0.05), Vec3(0.2, 0.3, 0.25), Pose(),
                  hinge(HingeType::Free, Vec3::UnitZ())),
        make_body("ball", 1.2, Vec3(0.0, 0.05, 0.25), Vec3(0.03, 0.03, 0.01),
                  at(Vec3(0.0, 0.2, 0.0), Vec3(0.3, 0.0, 0.2)),
                  hinge(HingeType::Spherical, Vec3::UnitZ())),
        make_body("fin", 0.6, Vec3(0.15, 0.0, 0.0), Vec3(0.002, 0.01, 0.01),
                  at(Vec3(0.1, 0.0, 0.3), Vec3(0.0, 0.0, 0.5)),
                  hinge(HingeType::Revolute, Vec3(0.0, 1.0, 0.2))),
    });
    floating.gravity = Vec3(0, 0, -9.81);
    State xf = State::rest(floating);
    // tip first: revolute (1), spherical quaternion (4), free quaternion and position (7)
    xf.theta << 0.7, 0.2, -0.3, 0.1, 0.0, 0.1, 0.3, -0.2, 0.0, 0.4, -0.1, 1.5;
    xf.theta.segment<4>(1).normalize();
    xf.theta.segment<4>(5).normalize();
    xf.beta << 1.2, 0.5, -0.8, 0.6, 0.3, -0.4, 0.9, 0.2, -0.5, 0.7;
    energy_checks(floating, xf, "floating chain");
    // The power balance along the motion of section 8, without springs: dK/dt = beta* (T - G).
    double kin_err = 0, kin_ref = 0;
    const auto K_of = [&](double t) { return kinetic_energy(chain, motion.state(t)); };
    for (const double t : {0.3, 0.9, 1.7, 2.4, 3.1}) {
      const State s = motion.state(t);
      const VecX bd = motion.beta_dot(t);
      const VecX Tt = inverse_dynamics(chain, s, bd);
      const VecX Gt = inverse_dynamics(chain, State{s.theta, VecX::Zero(nv)}, VecX::Zero(nv));
      const soa::EnergyStructure est = soa::EnergyStructure::build(chain, s);
      const MatX Mt = est.op.mass_matrix();
      const double K_dot = s.beta.dot(Mt * bd) + 0.5 * s.beta.dot(est.mass_matrix_rate() * s.beta);
      kin_err = std::max(kin_err, std::abs(derivative(K_of, t, w_max) - s.beta.dot(Tt - Gt)));
      kin_err = std::max(kin_err, std::abs(K_dot - s.beta.dot(Tt - Gt)));
      kin_ref = std::max(kin_ref, K_of(t) + std::abs(s.beta.dot(Tt)));
    }
    checks.check("dK/dt = beta* M beta_dot + 1/2 beta* M_dot beta = beta* (T - G) along the motion",
                 kin_err, fd_tol(w_max, kin_ref));
  }

  /// ## 12. A real arm holding a payload: the Franka Emika Panda
  ///
  /// The Panda of lesson 3 (`lib/scenes/panda.urdf`: Franka's
  /// kinematics, the inertial parameters identified by Gaz et al. 2019, Franka's joint limits
  /// and rated torques; the header of the file cites them) holds a payload still,
  /// \f$\beta = 0\f$, \f$\dot\beta = 0\f$, at the pose \f$q = (0, -0.3, 0, -2.2, 0, 2.0,
  /// 0.8)\f$ rad (Franka's joints 1 to 7, from the base; inside every joint's limits, checked).
  /// The payload, of mass \f$m_p\f$ from 0 to Franka's rated 3 kg, is a point mass at the
  /// origin of the flange frame F (`panda_link8`, a massless frame fixed on link 7: in the
  /// scene a locked body, fixed on body k at \f${}^{O_k}T_F\f$, Scene::Frame::offset()). Its
  /// weight is the external force \f$f_F = [0;\ m_p\,{}^F g]\f$ at F, which enters body k as
  /// \f$f_{ext}(k) = \phi(O_k, F)\, f_F\f$ (section 6). The torques the motors must supply are
  /// computed three ways:
  /// - the O(N) Newton–Euler recursions of section 1 with \f$f_{ext}\f$ (soa::inverse_dynamics);
  /// - the operator form of section 3 at \f$\dot\beta = 0\f$, \f$T = H\phi\,(M\phi^* a + b)\f$
  ///   with \f$b(k) = -f_{ext}(k)\f$ (dense, soa::OperatorsT);
  /// - the arm's own gravity torques plus the payload's through the flange Jacobian of
  ///   lesson 3, \f$T = \mathcal G(\theta) - J^*(F)\, f_F\f$ (section 6); and, as a fourth
  ///   check, the arm with the payload welded to link 7 (its point-mass inertia moved to
  ///   \f$O_k\f$ by the parallel axis theorem and added to \f$M(k)\f$), without \f$f_{ext}\f$.
  ///
  /// The table `l4_panda_payload.md` of the lesson 4 page gives \f$|T_k|\f$ over the rated torque
  /// of joint k (87 N m for joints 1 to 4, 12 N m for joints 5 to 7, read from the file's
  /// `<limit effort>`) for each payload, and the sentence under it the largest ratio: both are
  /// written by the program from the torques it computes. The torques grow linearly with
  /// \f$m_p\f$ (the Jacobian route), by \f$-J^*(F)\,[0;\ {}^F g]\f$ per kilogram. Joint limits
  /// and rated torques are only read here: the recursions never apply them.
  checks.section("12. A real arm holding a payload: the Franka Emika Panda");
  {
    const std::optional<soa::Scene> loaded =
        soa::lesson::load_lesson3_scene(checks, "panda.urdf", 7);
    if (loaded) {
      const soa::Scene& panda = *loaded;
      const Model& pm = panda.model;
      const int pn = pm.n(), pv = pm.nv();
      // Its joints base first, with their limits, and the flange frame.
      std::vector<const soa::Scene::Frame*> joints;
      const soa::Scene::Frame* flange = nullptr;
      for (const soa::Scene::Frame& F : panda.frames) {
        if (F.name == "panda_link8") flange = &F;
        if (!F.locked && pm.body(F.k).hinge.nv() == 1) joints.push_back(&F);
      }
      bool rated = joints.size() == 7 && flange && flange->locked;
      for (const soa::Scene::Frame* F : joints)
        rated = rated && F->limits() && std::isfinite(F->limits()->effort) &&
                F->limits()->effort > 0 && F->limits()->has_position();
      checks.check("7 joints with limits and rated torques; flange panda_link8 fixed on link 7",
                   rated);
      if (rated) {
        const std::vector<double> q_franka = {0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8};
        const State xp{soa::theta_from_file_order(panda, q_franka), VecX::Zero(pv)};
        bool inside = true;
        for (std::size_t j = 0; j < joints.size(); ++j) {
          const soa::HingeLimits& L = *joints[j]->limits();
          const double qj = xp.theta[pm.body(joints[j]->k).q_offset];
          inside = inside && qj >= L.lower && qj <= L.upper;
        }
        checks.check("the pose lies inside every joint's limits", inside);
        const int kf = flange->k;
        const Pose& offset = flange->offset();  // ^{O_k}T_F
        Workspace wp(pm);
        soa::update_phi(pm, xp.theta, wp);
        soa::update_poses(pm, wp);
        Eigen::Matrix<double, 6, Eigen::Dynamic> J_F(6, pv);
        soa::jacobian(pm, xp.theta, wp, kf, offset, J_F);
        const Vec3 g_F = (wp.pose[kf - 1] * offset).R().transpose() * pm.gravity;  // F coords
        const VecX zero = VecX::Zero(pv);
        const VecX G_arm = inverse_dynamics(pm, xp, zero);
        std::vector<double> payloads;
        for (int i = 0; i <= 6; ++i) payloads.push_back(0.5 * i);
        std::vector<VecX> ratios;
        double op_err = 0, jac_err = 0, weld_err = 0, scale = 0;
        for (const double mp : payloads) {
          const Force f_F(Vec3::Zero(), mp * g_F);
          soa::ExternalForces<double> fe(std::size_t(pn), Force::Zero());
          fe[std::size_t(kf - 1)] = Phi(offset).apply(f_F);  // phi(O_k, F) f_F
          Workspace wt(pm);
          VecX Tp(pv);
          soa::inverse_dynamics(pm, xp, zero, fe, wt, Tp);
          const double s = stack(wt.f).norm();
          scale = std::max(scale, s);
          const Operators opp = Operators::build(pm, xp, fe);
          const VecX T_op = opp.H * opp.phi * (opp.M * opp.phi.transpose() * opp.a + opp.b);
          op_err = std::max(op_err, (T_op - Tp).norm() / s);
          const VecX T_jac = G_arm - J_F.transpose() * f_F.vector();
          jac_err = std::max(jac_err, (T_jac - Tp).norm() / s);
          if (mp > 0) {
            Model welded = pm;
            welded.body(kf).M = welded.body(kf).M +
                                soa::transform(Phi(offset), SpatialInertia::from_cm(
                                                                mp, Vec3::Zero(), Mat3::Zero()));
            weld_err = std::max(weld_err, (inverse_dynamics(welded, xp, zero) - Tp).norm() / s);
          }
          VecX r(7);
          for (std::size_t j = 0; j < joints.size(); ++j)
            r[Eigen::Index(j)] =
                std::abs(Tp[pm.body(joints[j]->k).v_offset]) / joints[j]->limits()->effort;
          ratios.push_back(r);
          std::printf("  payload %.1f kg: |T_k| / rated, joints 1-7 = %s\n", mp, row(r).c_str());
        }
        checks.check("Panda: Newton-Euler T = H phi (M phi* a + b), f_ext at the flange (/ |f|)",
                     op_err, 8 * kEps * pn);
        checks.check("Panda: T = G(theta) - J*(F) f_F, flange Jacobian (/ |f|)", jac_err,
                     8 * kEps * pn);
        checks.check("Panda: T = the arm with the payload welded to link 7 (/ |f|)", weld_err,
                     8 * kEps * pn);
        // The largest ratio, and where.
        std::size_t worst_m = 0;
        Eigen::Index worst_j = 0;
        for (std::size_t i = 0; i < ratios.size(); ++i) {
          Eigen::Index j;
          if (ratios[i].maxCoeff(&j) > ratios[worst_m][worst_j]) worst_m = i, worst_j = j;
        }
        const double worst = ratios[worst_m][worst_j];
        std::printf("  largest |T_k| / rated: %.3f, joint %d, payload %.1f kg\n", worst,
                    int(worst_j) + 1, payloads[worst_m]);
        std::ofstream md(out / "l4_panda_payload.md");
        md << "| payload [kg] |";
        for (std::size_t j = 0; j < joints.size(); ++j)
          md << " joint " << j + 1 << " (" << joints[j]->limits()->effort << " N m) |";
        md << "\n|--:|";
        for (std::size_t j = 0; j < joints.size(); ++j) md << "--:|";
        md << "\n";
        std::ofstream csv(out / "l4_panda_payload.csv");
        csv << "payload [kg]";
        for (std::size_t j = 0; j < joints.size(); ++j) csv << ",joint " << j + 1 << " |T|/rated";
        csv << "\n";
        char cell[160];
        for (std::size_t i = 0; i < ratios.size(); ++i) {
          std::snprintf(cell, sizeof cell, "%.1f", payloads[i]);
          md << "| " << cell << " |";
          csv << cell;
          for (Eigen::Index j = 0; j < 7; ++j) {
            std::snprintf(cell, sizeof cell, "%.3f", ratios[i][j]);
            md << " " << cell << " |";
            csv << "," << cell;
          }
          md << "\n";
          csv << "\n";
        }
        std::snprintf(cell, sizeof cell,
                      "\nThe largest ratio is %.3f, at joint %d (rated %g N m) with %.1f kg: "
                      "%s.\n",
                      worst, int(worst_j) + 1, joints[std::size_t(worst_j)]->limits()->effort,
                      payloads[worst_m],
                      worst <= 1 ? "every joint holds the payloads within its rated torque"
                                 : "that joint's rated torque is exceeded");
        md << cell;
        md.close();
        csv.close();
        checks.check("l4_panda_payload.md and l4_panda_payload.csv written", bool(md) && bool(csv));
      }
    }
  }

  return checks.finish();
}
