/// # Lesson 6 — Articulated body inertia
///
/// Topic 6 of the course (slide 1; Jain 2011, chapter 6): the articulated body inertia
/// \f$P(k)\f$, the inertia that the part of the chain outboard of hinge k presents at
/// \f$O_k\f$ when every hinge outboard of body k is free; its Riccati recursion, derived
/// from the equations of motion, the gain \f$G(k)\f$ and the projection \f$\bar\tau(k)\f$;
/// the operators \f$K = \mathcal E_\phi G\f$, \f$\mathcal E_\psi = \mathcal E_\phi\bar\tau\f$
/// and \f$\psi = (I - \mathcal E_\psi)^{-1}\f$ that lessons 7 and 8 build on; and the
/// alternative decompositions of the inter-body forces, through the composite and the
/// articulated inertias (section 8). Every identity is
/// computed on concrete numbers and checked; the program ends with the count of checks that
/// passed.
///
/// Numbering (\ref conventions): **body 1 is the tip, body n is next to the base**, hinge k
/// joins body k+1 to body k, and \f$\theta\f$, \f$\beta\f$ are stacked tip first.
///
/// Learning goals. After this lesson you can
/// - say what \f$P(k)\f$ is (a Schur complement of the composite inertia \f$R(k)\f$ of
///   lesson 5) and why \f$0 \le P(k) \le R(k)\f$;
/// - derive the Riccati recursion for \f$P\f$, \f$D\f$, \f$G\f$, \f$\bar\tau\f$, \f$P^+\f$ tip
///   to base from \f$f = P(\alpha - a) + z\f$, run it, and check its properties;
/// - write it with the operators \f$\mathcal E_\phi\f$, \f$\mathcal E_\psi\f$, \f$\psi\f$;
/// - recognise a singular \f$D(k)\f$ (a massless tip, a mass on its own hinge axis) and read
///   the library's diagnostic.
/// - split the inter-body forces as \f$f = R\alpha^+ + y\f$ (hinges locked) and
///   \f$f = P^+\alpha^+ + z^+ = P(\alpha - a) + z\f$ (hinges free), and derive the operator
///   identities behind them.
///
/// Run it as `lesson06 OUTDIR`: it prints each check and writes \f$D(k)\f$ and the sizes of
/// \f$P(k)\f$ and \f$R(k)\f$ along a 50-link chain (`l6_chain50.csv`) and their figures
/// (`l6_chain50_D.png`, `l6_chain50_P_vs_R.png`), and the results of the extreme chains of
/// section 7 (`l6_extreme.csv`, and the table `l6_extreme.md` of the lesson 6 page).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "args.hpp"
#include "chain_builder.hpp"
#include "checklist.hpp"
#include "extreme_cases.hpp"
#include "plot.hpp"
#include "soa/chain.hpp"
#include "soa/chain/force_decompositions.hpp"
#include "soa/scene.hpp"
#include "soa/soa.hpp"

namespace {

using soa::Body;
using soa::HingeType;
using soa::Model;
using soa::Pose;
using soa::SpatialInertia;
using soa::State;
using soa::Workspace;
using Vec3 = soa::Vec3<double>;
using Mat3 = soa::Mat3<double>;
using Mat6 = soa::Mat6<double>;
using Vec6 = soa::Vec6<double>;
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

/// The small chain of lesson 4: from the base out a universal joint, a helical joint, a
/// prismatic joint and a revolute joint at the tip (4 bodies, 5 degrees of freedom).
Model small_chain() {
  return Model::from_base_first({
      make_body("shoulder", inertia(3.0, Vec3(0.05, 0.02, 0.25), Vec3(0.05, 0.06, 0.02)),
                at(Vec3(0.2, 0.0, 0.0), Vec3(0.0, 0.0, 0.3)),
                hinge(HingeType::Universal, Vec3::UnitZ(), Vec3::UnitY())),
      make_body("screw", inertia(1.5, Vec3(0.0, 0.03, 0.2), Vec3(0.02, 0.02, 0.01)),
                at(Vec3(0.0, 0.1, 0.3), Vec3(0.02, 0.0, 0.5)),
                hinge(HingeType::Helical, Vec3(0.0, 0.3, 1.0), Vec3::UnitY(), 0.05)),
      make_body("slider", inertia(1.0, Vec3(0.15, 0.0, 0.02), Vec3(0.004, 0.01, 0.01)),
                at(Vec3(-0.3, 0.0, 0.2), Vec3(0.0, 0.05, 0.4)),
                hinge(HingeType::Prismatic, Vec3(1.0, 0.0, 0.2))),
      make_body("tip", inertia(0.8, Vec3(0.2, 0.0, -0.03), Vec3(0.002, 0.01, 0.01)),
                at(Vec3(0.0, 0.0, 0.3), Vec3(0.4, 0.0, 0.1)),
                hinge(HingeType::Revolute, Vec3(0.0, 1.0, 0.1))),
  });
}

/// The 50-link chain of lesson 3 (`lib/scenes/chain50.json`),
/// or the same chain built in code should the file not load: 50 links of 0.1 m and 0.2 kg,
/// revolute hinges about x and y in turn.
Model chain50(std::string& source, VecX& theta) {
  const std::string path = SOA_SCENE_DIR "/chain50.json";
  try {
    soa::Scene scene = soa::load_scene(path);
    source = "scene file lib/scenes/chain50.json";
    theta = scene.state.theta;
    return scene.model;
  } catch (const std::exception& e) {
    source = std::string("built in code (") + e.what() + ")";
  }
  std::vector<Body> base_first;
  for (int i = 0; i < 50; ++i)
    base_first.push_back(make_body(
        "link" + std::to_string(i + 1), inertia(0.2, Vec3(0, 0, -0.05), Vec3(1.7e-4, 1.7e-4, 1e-5)),
        Pose(Mat3::Identity(), Vec3(0, 0, i == 0 ? 0.0 : -0.1)),
        hinge(HingeType::Revolute, i % 2 == 0 ? Vec3::UnitX() : Vec3::UnitY())));
  Model m = Model::from_base_first(base_first);
  theta = VecX::Constant(m.nq(), 0.2);
  return m;
}

/// The smallest eigenvalue of a symmetric matrix.
double lambda_min(const MatX& A) {
  return Eigen::SelfAdjointEigenSolver<MatX>(A, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
}
double lambda_max(const MatX& A) {
  return Eigen::SelfAdjointEigenSolver<MatX>(A, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
}

/// The block diagonal \f$6n \times 6n\f$ operator of per-body 6x6 blocks, tip first.
MatX block_diagonal(const std::vector<Mat6>& b) {
  const int n = int(b.size());
  MatX out = MatX::Zero(6 * n, 6 * n);
  for (int k = 0; k < n; ++k) out.block<6, 6>(6 * k, 6 * k) = b[std::size_t(k)];
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path out = soa::lesson::output_dir(argc, argv);
  soa::lesson::Checklist checks;

  const Model m = small_chain();
  const int n = m.n(), N = 6 * n;
  State x = State::rest(m);
  for (int i = 0; i < m.nq(); ++i) x.theta[i] = 0.3 + 0.2 * i;
  Workspace ws(m);
  soa::update_phi(m, x.theta, ws);
  const soa::Operators op = soa::Operators::build(m, x, {});

  /// ## 1. Concept and definition
  ///
  /// Cut the chain at hinge k and hold body k: the bodies k, k−1, ..., 1 form the
  /// *outboard chain* of hinge k. At rest (\f$\beta = 0\f$), push body k with a spatial
  /// acceleration \f$\alpha(k)\f$ while the hinges k−1, ..., 1 stay free (no hinge force,
  /// \f$T(j) = 0\f$ for \f$j < k\f$). The outboard bodies accelerate as they please; the force
  /// needed at \f$O_k\f$ is linear in \f$\alpha(k)\f$,
  /// \f[ f(k) = P(k)\,\alpha(k), \f]
  /// and \f$P(k)\f$ is the **articulated body inertia** of body k. Were the hinges locked,
  /// the outboard chain would move as one rigid body with the composite inertia \f$R(k)\f$
  /// of lesson 5. With the operators of lesson 4 restricted to bodies 1..k,
  /// \f$A = \phi M \phi^*\f$, \f$E_k\f$ the 6k x 6 injection at body k and \f$H'\f$ the
  /// hinges k−1..1: \f$\alpha = \phi^*(H'^*\dot\beta' + E_k\alpha(k))\f$, \f$f = \phi M\alpha\f$,
  /// and \f$H' f = 0\f$ gives \f$\dot\beta'\f$; eliminating it,
  /// \f[ P(k) = R(k) - X(k)\,\mathcal M'^{-1}(k)\, X^*(k), \qquad R(k) = E_k^* A E_k, \quad
  ///     X(k) = E_k^* A H'^*, \quad \mathcal M'(k) = H' A H'^* , \f]
  /// a Schur complement: the composite inertia less what the free hinges let go. Since
  /// \f$\mathcal M' > 0\f$, \f$P(k) \le R(k)\f$ in the Loewner order, with equality at the tip.
  std::vector<Mat6> P_def(static_cast<std::size_t>(n));
  for (int k = 1; k <= n; ++k) {
    const int nv_out = m.body(k).v_offset;  // the dofs of bodies 1..k-1 (tip first)
    const MatX phi = op.phi.topLeftCorner(6 * k, 6 * k);
    const MatX A = phi * op.M.topLeftCorner(6 * k, 6 * k) * phi.transpose();
    const Mat6 R = A.bottomRightCorner<6, 6>();
    if (nv_out == 0) {
      P_def[std::size_t(k - 1)] = R;
      continue;
    }
    const MatX Hp = op.H.topLeftCorner(nv_out, 6 * k);
    const MatX X = A.bottomRows<6>() * Hp.transpose();
    const MatX M_out = Hp * A * Hp.transpose();
    P_def[std::size_t(k - 1)] = R - X * M_out.ldlt().solve(X.transpose());
  }

  /// ## 2. The Riccati recursion
  ///
  /// The Schur complement costs O(k^3) per body. Going tip to base instead gives P(k) for all
  /// k in O(n), and the derivation (Jain 2011, chapter 6) holds in any state: velocities,
  /// hinge forces \f$T\f$ on every hinge, gravity and external forces. The equations of
  /// lesson 4, with \f$f(0) = 0\f$ and \f$\alpha(n+1) = [0; -g]\f$:
  /// \f[ f(k) = \phi(k,k-1)\,f(k-1) + M(k)\,\alpha(k) + b(k), \qquad
  ///     \alpha(k) = \alpha^+(k) + H^*(k)\,\dot\beta(k) + a(k), \qquad T(k) = H(k)\,f(k), \f]
  /// with \f$\alpha^+(k) = \phi^*(k+1,k)\,\alpha(k+1)\f$, the acceleration body k would have
  /// were hinge k locked, and \f$b(k)\f$ the gyroscopic force less the external one. Claim,
  /// by induction from the tip:
  /// \f[ f(k) = P(k)\,\bigl(\alpha(k) - a(k)\bigr) + z(k), \f]
  /// with \f$P(k)\f$ depending on \f$\theta\f$ only and \f$z(k)\f$ not on \f$\dot\beta\f$.
  ///
  /// *At the tip*, \f$f(1) = M(1)\alpha(1) + b(1)\f$: \f$P(1) = M(1)\f$,
  /// \f$z(1) = P(1)a(1) + b(1)\f$.
  ///
  /// *Across hinge k*: \f$\alpha(k) - a(k) = \alpha^+(k) + H^*\dot\beta(k)\f$, so
  /// \f$T(k) = Hf(k) = HP\alpha^+ + D\dot\beta(k) + Hz(k)\f$ with \f$D = HPH^*\f$, and
  /// \f[ \dot\beta(k) = D^{-1}(k)\bigl(T(k) - H(k)z(k)\bigr) - D^{-1}(k)H(k)P(k)\,\alpha^+(k)
  ///     = \nu(k) - G^*(k)\,\alpha^+(k), \f]
  /// with the *innovation* \f$\epsilon(k) = T(k) - H(k)z(k)\f$, \f$\nu(k) = D^{-1}(k)
  /// \epsilon(k)\f$ and the gain \f$G(k) = P(k)H^*(k)D^{-1}(k)\f$ (\f$G^* = D^{-1}HP\f$, \f$P\f$
  /// symmetric). Putting \f$\dot\beta(k)\f$ back, \f$f = P\alpha^+ + PH^*(\nu - G^*\alpha^+) + z
  /// = (P - GDG^*)\alpha^+ + z + G\epsilon\f$ (\f$PH^* = GD\f$): the **inter-body forces
  /// identity**
  /// \f[ f(k) = P^+(k)\,\alpha^+(k) + z^+(k), \qquad P^+(k) = P(k) - G(k)D(k)G^*(k), \qquad
  ///     z^+(k) = z(k) + G(k)\,\epsilon(k). \f]
  ///
  /// *From body k to body k+1*: \f$f(k+1) = \phi(k+1,k)\bigl(P^+(k)\phi^*(k+1,k)\alpha(k+1) +
  /// z^+(k)\bigr) + M(k+1)\alpha(k+1) + b(k+1)\f$; writing \f$\alpha(k+1) = (\alpha(k+1) -
  /// a(k+1)) + a(k+1)\f$ this is the claim at k+1 with
  /// \f[ P(k+1) = \phi(k+1,k)\,P^+(k)\,\phi^*(k+1,k) + M(k+1), \qquad
  ///     z(k+1) = \phi(k+1,k)\,z^+(k) + P(k+1)\,a(k+1) + b(k+1). \f]
  ///
  /// The recursion for \f$P\f$ involves neither \f$\beta\f$ nor \f$T\f$ nor \f$g\f$. At rest,
  /// without gravity or external forces and with \f$T(j) = 0\f$ for \f$j < k\f$, every
  /// \f$z(j)\f$, \f$\epsilon(j)\f$, \f$z^+(j)\f$ for \f$j < k\f$ vanishes and \f$z(k) = 0\f$, so
  /// \f$f(k) = P(k)\alpha(k)\f$: the \f$P(k)\f$ of section 1. Collected, tip to base from
  /// \f$P^+(0) = 0\f$:
  /// \f[ P(k) = \phi(k,k-1)\,P^+(k-1)\,\phi^*(k,k-1) + M(k), \f]
  /// \f[ D(k) = H(k)P(k)H^*(k), \quad G(k) = P(k)H^*(k)D^{-1}(k), \quad
  ///     \bar\tau(k) = I - G(k)H(k), \quad P^+(k) = \bar\tau(k)P(k) = P(k) - G(k)D(k)G^*(k). \f]
  /// This is a discrete Riccati equation; with \f$\bar\tau = I\f$ (no free hinges) it is the
  /// Lyapunov recursion of \f$R\f$ (lesson 5). \f$D(k)\f$ is the inertia hinge k feels
  /// along its own free directions. \f$\phi P\phi^*\f$ for a symmetric \f$P\f$ is computed
  /// from \f$R\f$ and \f$\tilde\ell\f$ without the 6x6 \f$\phi\f$ (soa::transform_symmetric).
  /// To read: soa::reference::articulated_inertias() (lib/include/soa/reference/articulated.hpp),
  /// these equations line by line; soa::articulated_inertias(), which this program and the
  /// command line run, is its fast form. The \f$z\f$, \f$\epsilon\f$, \f$\nu\f$, \f$z^+\f$,
  /// \f$\alpha^+\f$ sweeps are the forward dynamics of lesson 8,
  /// soa::reference::forward_dynamics().
  ///
  /// *Now do* exercises 6.1 (one Riccati step), 6.4 (\f$\phi P\phi^*\f$ by blocks, without the
  /// 6x6 \f$\phi\f$) and 6.3 (the recursion down a revolute chain):
  /// `exercises/06-articulated-body-inertia/exercises.hpp`, then `make exercises LESSON=6`.
  soa::Articulated art(m);
  soa::articulated_inertias(m, x, ws, art);
  double def_err = 0, def_scale = 1;
  for (int k = 1; k <= n; ++k) {
    def_err = std::max(def_err, (art.P[std::size_t(k - 1)] - P_def[std::size_t(k - 1)]).norm());
    def_scale = std::max(def_scale, art.R[std::size_t(k - 1)].matrix().norm());
  }
  std::printf("  k  body      n_k  eig(D(k))                      tr P(k)   tr R(k)\n");
  for (int k = 1; k <= n; ++k) {
    const soa::HingeMatrix<double>& D = art.D[std::size_t(k - 1)];
    const VecX d = Eigen::SelfAdjointEigenSolver<MatX>(MatX(D)).eigenvalues();
    std::string eig;
    for (int i = 0; i < d.size(); ++i) {
      char c[32];
      std::snprintf(c, sizeof c, "%s%.5f", i ? " " : "", d[i]);
      eig += c;
    }
    std::printf("  %d  %-9s %d    %-30s %8.4f  %8.4f\n", k, m.body(k).name.c_str(), int(D.rows()),
                eig.c_str(), art.P[std::size_t(k - 1)].trace(),
                art.R[std::size_t(k - 1)].matrix().trace());
  }
  checks.check("Riccati P(k) == Schur complement R - X M'^-1 X* (the definition)", def_err,
               64 * kEps * def_scale);

  // The derivation at a moving state: the same chain and theta under gravity, with rates,
  // hinge forces and external forces; beta_dot, z, z+, alpha+ from the sweeps
  // (soa::forward_dynamics), f(k), alpha(k), a(k) from Newton-Euler (lesson 4) at beta_dot.
  Model mg = small_chain();
  mg.gravity = Vec3(0, 0, -9.81);
  State xm = x;
  VecX T(m.nv());
  for (int i = 0; i < m.nv(); ++i) {
    xm.beta[i] = 0.5 - 0.3 * i;
    T[i] = 1.0 - 0.4 * i;
  }
  soa::ExternalForces<double> f_ext;
  for (int k = 1; k <= n; ++k)
    f_ext.push_back(soa::Force(Vec3(0.1 * k, -0.2, 0.05), Vec3(0.3, 0.1 * k, -0.2)));
  Workspace ws_fd(mg), ws_ne(mg);
  soa::ForwardDynamics fd(mg);
  VecX bd(m.nv()), T_back(m.nv());
  soa::forward_dynamics(mg, xm, T, f_ext, ws_fd, fd, bd);
  soa::inverse_dynamics(mg, xm, bd, f_ext, ws_ne, T_back);
  double ansatz = 0, identity = 0, z_rec = 0, f_scale = 1e-300, kappa = 1;
  for (int k = 1; k <= n; ++k) {
    const std::size_t j = std::size_t(k - 1);
    const Mat6& Pk = fd.art.P[j];
    const Vec6 f = ws_ne.f[j].vector();
    const Vec6 alpha_less_a = ws_ne.alpha[j].vector() - ws_ne.a[j].vector();
    const Vec6 alpha_p = fd.alpha_plus[j].vector();
    Vec6 z = Pk * ws_fd.a[j].vector() + ws_fd.b[j].vector();
    if (k > 1) z += ws_fd.phi[j - 1].apply(fd.z_plus[j - 1]).vector();
    ansatz = std::max(ansatz, (Pk * alpha_less_a + fd.z[j].vector() - f).norm());
    identity = std::max(identity, (fd.art.P_plus[j] * alpha_p + fd.z_plus[j].vector() - f).norm());
    z_rec = std::max(z_rec, (z - fd.z[j].vector()).norm());
    f_scale = std::max({f_scale, f.norm(), Pk.norm() * alpha_less_a.norm(), z.norm(),
                        fd.art.P_plus[j].norm() * alpha_p.norm(), fd.z_plus[j].vector().norm()});
    kappa = std::max(kappa, Pk.norm() * MatX(fd.art.D_inv[j]).norm());
  }
  std::printf("  moving, under gravity: beta_dot = nu - G* alpha+ =");
  for (int i = 0; i < m.nv(); ++i) std::printf(" %.5f", bd[i]);
  std::printf("\n");
  const double tol_f = 16 * m.nv() * kEps * kappa * f_scale;
  checks.check("z(k) = phi(k,k-1) z+(k-1) + P(k) a(k) + b(k), z(1) = M(1) a(1) + b(1)", z_rec,
               tol_f);
  checks.check("the claim: f(k) = P(k) (alpha(k) - a(k)) + z(k) == Newton-Euler f(k)", ansatz,
               tol_f);
  checks.check("inter-body forces identity: f(k) = P+(k) alpha+(k) + z+(k) == Newton-Euler",
               identity, tol_f);
  checks.check("beta_dot = nu - G* alpha+ solves T = H f: ID(beta_dot) = T", (T_back - T).norm(),
               tol_f);

  /// *Now do* exercises 6.5 (the inter-body forces identity from the forward dynamics' sweeps)
  /// and 6.9 (the derivation above once more, at rest with every hinge free when the base is
  /// shaken: derive \f$\dot\beta\f$).

  /// ## 3. Properties
  ///
  /// \f$P(k)\f$ and \f$P^+(k)\f$ are symmetric positive semidefinite, \f$D(k)\f$ is positive
  /// definite (when every body has mass where its hinge can move it, section 5),
  /// \f$\bar\tau(k)\f$ is a projection, \f$\bar\tau^2 = \bar\tau\f$ (since
  /// \f$HG = I\f$), along \f$G\f$ onto the null space of \f$H\f$:
  /// \f[ H(k)P^+(k) = 0, \qquad P^+(k) = \bar\tau(k)P(k) = \bar\tau(k)P(k)\bar\tau^*(k), \f]
  /// so \f$P^+(k)\f$ has no stiffness along hinge k's free directions: what hinge k transmits
  /// inboard carries none of them. And \f$0 \le P^+(k) \le P(k) \le R(k)\f$.
  double sym = 0, psd = 0, d_min = 1e300, proj = 0, hp = 0, tp = 0, ttp = 0, loewner = 0, scale = 1;
  for (int k = 1; k <= n; ++k) {
    const std::size_t j = std::size_t(k - 1);
    const Mat6& P = art.P[j];
    const Mat6& Pp = art.P_plus[j];
    const Mat6 R = art.R[j].matrix();
    const Mat6 T = art.tau_bar(m, x.theta, k);
    const soa::JointMap<double> Hs = m.body(k).hinge.H_star(x.theta.data() + m.body(k).q_offset);
    scale = std::max(scale, R.norm());
    sym = std::max({sym, (P - P.transpose()).norm(), (Pp - Pp.transpose()).norm()});
    psd = std::max({psd, -lambda_min(P), -lambda_min(Pp), -lambda_min(P - Pp)});
    d_min = std::min(d_min, lambda_min(MatX(art.D[j])));
    proj = std::max(proj, (T * T - T).norm());
    hp = std::max(hp, (Hs.transpose() * Pp).norm());
    tp = std::max(tp, (T * P - Pp).norm());
    ttp = std::max(ttp, (T * P * T.transpose() - Pp).norm());
    loewner = std::max(loewner, -lambda_min(R - P));
  }
  checks.check("P(k), P+(k) symmetric", sym, 16 * kEps * scale);
  checks.check("P(k) >= P+(k) >= 0 (smallest eigenvalues >= -tol)", std::max(0.0, psd),
               64 * kEps * scale);
  checks.check("D(k) positive definite", d_min > 0);
  checks.check("tau_bar(k)^2 = tau_bar(k)", proj, 64 * kEps * scale);
  checks.check("H(k) P+(k) = 0", hp, 64 * kEps * scale);
  checks.check("tau_bar(k) P(k) = P+(k) = tau_bar(k) P(k) tau_bar*(k)", std::max(tp, ttp),
               64 * kEps * scale);
  checks.check("P(k) <= R(k): lambda_min(R - P) >= -tol", std::max(0.0, loewner),
               64 * kEps * scale);
  checks.check("tip: P(1) = R(1) = M(1)",
               std::max((art.P[0] - m.body(1).M.matrix()).norm(),
                        (art.R[0].matrix() - m.body(1).M.matrix()).norm()),
               16 * kEps * scale);

  /// *Now do* exercises 6.2 (\f$\bar\tau\f$ and its two properties), 6.8 (predict the null
  /// space of \f$P^+(k)\f$ from the hinge alone) and 6.7 (a Riccati sweep with one bug, which
  /// these properties find).

  /// ## 4. The operators \f$K\f$, \f$\mathcal E_\psi\f$ and \f$\psi\f$
  ///
  /// Stacked tip first like \f$\mathcal E_\phi\f$ (lesson 3): \f$P\f$, \f$P^+\f$, \f$D\f$,
  /// \f$G\f$, \f$\bar\tau\f$ block diagonal, and
  /// \f[ K = \mathcal E_\phi G, \qquad \mathcal E_\psi = \mathcal E_\phi\bar\tau, \qquad
  ///     \psi = (I - \mathcal E_\psi)^{-1}, \f]
  /// \f$\mathcal E_\psi\f$ with \f$\psi(k+1,k) = \phi(k+1,k)\bar\tau(k)\f$ on its block
  /// subdiagonal; \f$\psi\f$ is block lower triangular with identity diagonal and
  /// \f$\psi(i,j) = \psi(i,i-1)\cdots\psi(j+1,j)\f$, the articulated analogue of \f$\phi\f$.
  /// The Riccati recursion in operator form,
  /// \f[ P = \mathcal E_\phi P^+ \mathcal E_\phi^* + M = \mathcal E_\psi P\,\mathcal E_\psi^* + M,
  ///     \qquad P(k) = \sum_{j \le k} \psi(k,j)\,M(j)\,\psi^*(k,j), \f]
  /// the last the diagonal of \f$\psi M\psi^*\f$ as \f$R\f$ is that of \f$\phi M\phi^*\f$.
  /// A preview of lesson 7: the innovations factorization of the mass matrix,
  /// \f$\mathcal M = [I + H\phi K]\, D\, [I + H\phi K]^*\f$.
  const MatX P = block_diagonal(art.P), Pp = block_diagonal(art.P_plus);
  std::vector<Mat6> taus;
  MatX G = MatX::Zero(N, m.nv()), D = MatX::Zero(m.nv(), m.nv());
  for (int k = 1; k <= n; ++k) {
    const Body& B = m.body(k);
    taus.push_back(art.tau_bar(m, x.theta, k));
    G.block(6 * (k - 1), B.v_offset, 6, B.hinge.nv()) = art.G[std::size_t(k - 1)];
    D.block(B.v_offset, B.v_offset, B.hinge.nv(), B.hinge.nv()) = art.D[std::size_t(k - 1)];
  }
  const MatX tau_bar = block_diagonal(taus);
  const MatX K = op.E_phi * G;
  const MatX E_psi = op.E_phi * tau_bar;
  const MatX psi = (MatX::Identity(N, N) - E_psi).inverse();
  const MatX psiMpsi = psi * op.M * psi.transpose();
  double upper = 0, chain = 0, diag = 0;
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) upper = std::max(upper, psi.block<6, 6>(6 * a, 6 * b).norm());
    upper = std::max(upper, (psi.block<6, 6>(6 * a, 6 * a) - Mat6::Identity()).norm());
    for (int b = 0; b < a; ++b)
      chain =
          std::max(chain, (psi.block<6, 6>(6 * a, 6 * b) - psi.block<6, 6>(6 * a, 6 * (a - 1)) *
                                                               psi.block<6, 6>(6 * (a - 1), 6 * b))
                              .norm());
    diag = std::max(diag, (psiMpsi.block<6, 6>(6 * a, 6 * a) - P.block<6, 6>(6 * a, 6 * a)).norm());
  }
  const MatX I_HphiK = MatX::Identity(m.nv(), m.nv()) + op.H * op.phi * K;
  const MatX Mass = op.mass_matrix();
  std::printf("  psi(4,1) = psi(4,3) psi(3,2) psi(2,1), top-left 3x3:\n");
  for (int r = 0; r < 3; ++r)
    std::printf("    %9.5f %9.5f %9.5f\n", psi(18 + r, 0), psi(18 + r, 1), psi(18 + r, 2));
  checks.check("P = E_phi P+ E_phi* + M",
               (P - (op.E_phi * Pp * op.E_phi.transpose() + op.M)).norm(), 64 * kEps * scale);
  checks.check("P = E_psi P E_psi* + M", (P - (E_psi * P * E_psi.transpose() + op.M)).norm(),
               64 * kEps * scale);
  checks.check("P(k) = sum_j psi(k,j) M(j) psi*(k,j) (diagonal of psi M psi*)", diag,
               64 * kEps * scale);
  checks.check("psi block lower triangular, identity diagonal", upper, 16 * kEps);
  checks.check("psi(i,j) = psi(i,i-1) psi(i-1,j)", chain, 16 * kEps * std::max(1.0, psi.norm()));
  checks.check(
      "K(k+1,k) = phi(k+1,k) G(k)",
      (K - op.E_phi * G).norm() +
          (K.bottomRows(N - 6) - op.E_phi.bottomLeftCorner(N - 6, N - 6) * G.topRows(N - 6)).norm(),
      16 * kEps * std::max(1.0, K.norm()));
  checks.check("lesson 7 preview: M = [I + H phi K] D [I + H phi K]*",
               (Mass - I_HphiK * D * I_HphiK.transpose()).norm(),
               64 * kEps * std::max(1.0, Mass.norm()));

  /// ## 5. When \f$D(k)\f$ is singular
  ///
  /// \f$D(k) = H(k)P(k)H^*(k)\f$ is positive definite as long as hinge k moves some mass of
  /// its outboard chain that no free hinge outboard lets go. It is singular for a massless
  /// tip (\f$P(1) = M(1) = 0\f$), and for a point mass on the axis of its revolute hinge
  /// (\f$D(1) = m\,|a \times p|^2 = 0\f$); \f$G = PH^*D^{-1}\f$ does not exist. Nearly
  /// singular is as bad: \f$D^{-1}\f$ loses all its digits. \f$D(k)\f$ is a difference,
  /// \f$D(k) = HQH^* - H\phi\,GDG^*\phi^*H^*\f$ with \f$Q(k) = \phi(k,k-1)P(k-1)\phi^*(k,k-1) +
  /// M(k)\f$ the inertia with hinge k−1 locked for one step, so it keeps about
  /// \f$\log_{10}(\text{ratio}/\varepsilon)\f$ digits, ratio \f$= \lambda_{\min}(D(k)) /
  /// \lambda_{\max}(H(k)Q(k)H^*(k))\f$ (soa::singular_D_ratio(); \f$0 < D \le HQH^* \le HRH^*\f$).
  /// The library stops with a soa::Error naming the body when the ratio is not above
  /// soa::singular_D_threshold() \f$= 10^3\varepsilon\f$: fewer than three digits left.
  std::printf("  singular_D_threshold = %.3g\n", soa::singular_D_threshold<double>());
  const auto diagnose = [](const Model& chain_model) {
    const State x0 = State::rest(chain_model);
    Workspace w(chain_model);
    soa::update_phi(chain_model, x0.theta, w);
    soa::Articulated a(chain_model);
    try {
      soa::articulated_inertias(chain_model, x0, w, a);
    } catch (const soa::Error& e) {
      std::printf("  soa::Error: %s\n", e.what());
      return std::string(e.what());
    }
    std::printf("  no error\n");
    return std::string();
  };
  const SpatialInertia link = inertia(2.0, Vec3(0.3, 0.1, 0.0), Vec3(0.05, 0.05, 0.05));
  const Pose down = at(Vec3::Zero(), Vec3(0.5, 0, 0));
  const std::string massless =
      diagnose(Model::from_base_first({make_body("link", link, at(Vec3::Zero(), Vec3(0, 0, 0.5)),
                                                 hinge(HingeType::Revolute, Vec3::UnitZ())),
                                       make_body("massless_tip", SpatialInertia(), down,
                                                 hinge(HingeType::Revolute, Vec3::UnitZ()))}));
  checks.check("massless tip: soa::Error naming body 'massless_tip' and D(1)",
               massless.rfind("body 'massless_tip': articulated inertia D(1) singular", 0) == 0);
  const std::string bead = diagnose(
      Model::from_base_first({make_body("link", link, at(Vec3::Zero(), Vec3(0, 0, 0.5)),
                                        hinge(HingeType::Revolute, Vec3::UnitZ())),
                              make_body("bead", inertia(1.0, Vec3(0, 0, 0.2), Vec3::Zero()), down,
                                        hinge(HingeType::Revolute, Vec3::UnitZ()))}));
  checks.check("point mass on its hinge axis: soa::Error naming body 'bead'",
               bead.rfind("body 'bead': articulated inertia D(1) singular", 0) == 0);

  /// ## 6. Along a long chain
  ///
  /// Down the 50-link chain from the tip, \f$R(k)\f$ grows like the mass times the square
  /// of the length of the outboard chain, but \f$P(k)\f$ does not: through 49 free hinges the
  /// outboard links give way to a rotation of link k, so \f$D(k)\f$ levels off after a
  /// few links while \f$H R H^*\f$ keeps growing, as \f$k^3\f$ for a straight chain. The figures show \f$D(k)\f$
  /// against \f$H(k)R(k)H^*(k)\f$, and \f$\lambda_{\max}(P(k))/\lambda_{\max}(R(k))\f$ and
  /// \f$\mathrm{tr}\,P(k)/\mathrm{tr}\,R(k)\f$, all \f$\le 1\f$ by section 3.
  std::string source;
  VecX theta50;
  const Model m50 = chain50(source, theta50);
  std::printf("  50-link chain: %s (%d bodies)\n", source.c_str(), m50.n());
  State x50 = State::rest(m50);
  if (theta50.size() == m50.nq()) x50.theta = theta50;
  Workspace ws50(m50);
  soa::update_phi(m50, x50.theta, ws50);
  soa::Articulated art50(m50);
  soa::articulated_inertias(m50, x50, ws50, art50);
  std::ofstream csv(out / "l6_chain50.csv");
  csv << "k,D,HRH,lmaxP_over_lmaxR,trP_over_trR\n";
  double worst_ratio = 0, worst_loewner = 0;
  for (int k = 1; k <= m50.n(); ++k) {
    const std::size_t j = std::size_t(k - 1);
    const Body& B = m50.body(k);
    const soa::JointMap<double> Hs = B.hinge.H_star(x50.theta.data() + B.q_offset);
    const Mat6 R = art50.R[j].matrix();
    const double d = lambda_min(MatX(art50.D[j]));
    const double hrh = lambda_max(MatX(Hs.transpose() * R * Hs));
    const double lr = lambda_max(art50.P[j]) / lambda_max(R);
    const double tr = art50.P[j].trace() / R.trace();
    worst_ratio = std::max({worst_ratio, lr, tr});
    worst_loewner = std::max(worst_loewner, -lambda_min(R - art50.P[j]) / R.norm());
    char line[128];
    std::snprintf(line, sizeof line, "%d,%.6e,%.6e,%.6f,%.6f\n", k, d, hrh, lr, tr);
    csv << line;
    if (k == 1 || k == 10 || k == 25 || k == m50.n())
      std::printf("  k = %2d: D = %.3e, H R H* = %.3e, lmax P/lmax R = %.3f, tr P/tr R = %.3f\n", k,
                  d, hrh, lr, tr);
  }
  csv.close();
  checks.check("chain50: P(k) <= R(k) all along", std::max(0.0, worst_loewner), 64 * kEps);
  checks.check("chain50: lmax(P)/lmax(R) <= 1 and tr P/tr R <= 1", worst_ratio <= 1 + 64 * kEps);
  checks.check("l6_chain50.csv written", bool(csv));
  checks.check("figure written: l6_chain50_D.png",
               soa::lesson::plot("l6_chain50_D.gp", out, "l6_chain50_D.png"));
  checks.check("figure written: l6_chain50_P_vs_R.png",
               soa::lesson::plot("l6_chain50_P_vs_R.gp", out, "l6_chain50_P_vs_R.png"));

  /// ## 7. Stability on extreme chains
  ///
  /// In exact arithmetic the recursions of lessons 5 and 6 are exact; in double precision
  /// every step rounds. Here they meet the chains that break naive methods: n
  /// revolute hinges with every axis along z, links of 1 m, point-like bodies (centre of mass
  /// 0.5 m out along the link, rotational inertia J about it, down to \f$10^{-9}\f$), masses
  /// alternating heavy (1) and light (\f$10^{-3}\f$, \f$10^{-6}\f$, \f$10^{-8}\f$) from the base
  /// out — the *mass ratio* is the second body's mass over the first's, \f$10^{-8}\f$ heavy
  /// first, \f$10^{8}\f$ light first — straight (\f$\theta = 0\f$: every axis parallel, the
  /// chain fully stretched) or in a random pose, n from 10 to 10 000. The chains and their
  /// evaluation are in `extreme_cases.hpp` beside this program. For each case:
  /// - **the mass matrix from \f$R\f$** (lesson 5) against the operator form
  ///   \f$\mathcal M = H\phi M\phi^* H^*\f$ (lesson 4): the dense operators for n ≤ 100; for
  ///   100 < n ≤ 500 every column \f$\mathcal M e_j\f$ by Newton–Euler inverse dynamics at rest
  ///   without gravity (the operator form evaluated by its recursions); beyond, 8 columns
  ///   spread from tip to base, each from \f$R\f$ by an O(n) column routine, so that no
  ///   n x n matrix is formed. The error is
  ///   \f$\max|\mathcal M_R - \mathcal M_{\rm ref}| / \max_k \mathcal M(k,k)\f$ (the largest
  ///   entry of a positive definite matrix is on its diagonal). An entry
  ///   \f$\mathcal M(i,j) = \sum_{k} (H(i)\phi(i,k)) M(k) (H(j)\phi(j,k))^*\f$ is a sum of at
  ///   most n terms whose sizes add up to at most \f$\max_k \mathcal M(k,k)\f$ (Cauchy–Schwarz
  ///   in the metric \f$M(k)\f$), each carried through at most n steps of \f$\phi\f$: the
  ///   tolerance is \f$16\, n\,\varepsilon\f$, whatever the masses;
  /// - **cond(M)** for n ≤ 500, as
  ///   \f$\lambda_{\max}(\mathcal M)\,\lambda_{\max}(\mathcal M^{-1})\f$. A largest eigenvalue
  ///   is well conditioned; a smallest one computed from \f$\mathcal M\f$ is lost once cond(M)
  ///   nears \f$1/(n\varepsilon)\f$. \f$\mathcal M^{-1}\f$ comes column by column from the
  ///   articulated body recursion built on \f$P\f$, \f$D\f$, \f$G\f$ of this lesson (a preview of
  ///   lesson 8), whose rounding depends on the \f$D(k)\f$, not on cond(M); where eig(M) still
  ///   resolves \f$\lambda_{\min}\f$ the two are compared;
  /// - **min D(k)**, and the smallest ratio \f$\lambda_{\min}(D(k))/\lambda_{\max}(H(k)Q(k)H^*(k))\f$
  ///   that the library tests against soa::singular_D_threshold() (section 5), and the
  ///   relative error of the \f$D(k)\f$ against the same Riccati recursion in long double
  ///   (\f$\varepsilon = 1.1\cdot 10^{-19}\f$): the digits really left.
  ///
  /// A case is *solved* when its mass matrix is within tolerance and the Riccati recursion
  /// ran; *diagnosed* when soa::articulated_inertias() stopped with its soa::Error, printed.
  /// A massless tip is the case no method can resolve: \f$\mathcal M(1,1) = D(1) = 0\f$, hinge
  /// 1 moves nothing. The rows go to `l6_extreme.csv`; those with n = 500 and n = 10 000 to
  /// the table `l6_extreme.md` shown on the lesson 6 page.
  namespace ex = soa::lesson::extreme;
  std::vector<ex::Spec> specs;
  for (const int n_case : {10, 100, 500, 2000, 10000}) {
    std::vector<ex::Spec> family = {{"", n_case, 1, 1e-3}, {"", n_case, 1, 1e-9}};
    for (const double r : {1e-3, 1e3, 1e-6, 1e6, 1e-8, 1e8})
      family.push_back({"", n_case, r, 1e-9});
    for (const double r : {1e-8, 1e8}) family.push_back({"", n_case, r, 1e-9, 7});
    if (n_case == 10 || n_case == 10000) family.push_back({"", n_case, 1, 1e-3, 0, 0.0});
    for (ex::Spec& sp : family) {
      sp.name = ex::describe(sp);
      specs.push_back(sp);
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<ex::Result> rows;
  double worst_M = 0, worst_column = 0, worst_D_digits = 0, worst_cond = 0;
  bool d_positive = true, verdicts_agree = true, tip_named = true;
  int n_solved = 0, n_diagnosed = 0, n_cond_compared = 0;
  for (const ex::Spec& sp : specs) {
    rows.push_back(ex::evaluate(sp));
    const ex::Result& r = rows.back();
    std::printf(
        "  %-44s n = %5d  error %.1e (tol %.0e)  cond %9s  min D %.2e  min ratio %.1e"
        "  D vs long double %.0e  %s\n",
        sp.name.c_str(), sp.n, r.error, r.tol, ex::num(r.cond, "%.1e").c_str(), r.min_D,
        r.min_ratio, r.D_error, r.diagnosed ? "diagnosed:" : "solved");
    if (r.diagnosed) std::printf("      soa::Error: %s\n", r.message.c_str());
    worst_M = std::max(worst_M, r.error / r.tol);
    if (!std::isnan(r.column_check)) worst_column = std::max(worst_column, r.column_check / r.tol);
    if (!std::isnan(r.D_error)) worst_D_digits = std::max(worst_D_digits, r.D_error);
    (r.diagnosed ? n_diagnosed : n_solved) += 1;
    if (!r.diagnosed) d_positive = d_positive && r.min_D > 0;
    verdicts_agree =
        verdicts_agree && r.diagnosed == !(r.min_ratio > soa::singular_D_threshold<double>());
    if (sp.tip_mass >= 0)
      tip_named = tip_named && r.diagnosed &&
                  r.message.rfind("body 'b1': articulated inertia D(1) singular", 0) == 0;
    if (!std::isnan(r.cond) && !std::isnan(r.cond_eig) && r.cond_eig < 1e12) {
      // eig(M) finds lambda_min to about n eps lambda_max: cond to n eps cond relative.
      worst_cond = std::max(worst_cond, std::abs(r.cond / r.cond_eig - 1) /
                                            (sp.n * kEps * std::max(1.0, r.cond_eig)));
      ++n_cond_compared;
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("  %zu cases (%d solved, %d diagnosed) in %.1f s\n", rows.size(), n_solved,
              n_diagnosed, seconds);
  std::ofstream extreme_csv(out / "l6_extreme.csv");
  ex::write_csv(extreme_csv, rows);
  extreme_csv.close();
  std::ofstream extreme_md(out / "l6_extreme.md");
  ex::write_markdown(extreme_md, rows, {500, 10000});
  extreme_md.close();
  checks.check("mass matrix from R == operator form, every case (worst error / 16 n eps)", worst_M,
               1.0);
  checks.check("column routine == mass_matrix_crb columns, n <= 500 (worst / 16 n eps)",
               worst_column, 1.0);
  checks.check("cond(M): lmax(M) lmax(M^-1) == eig(M) where cond < 1e12 (/ n eps cond), " +
                   std::to_string(n_cond_compared) + " cases",
               worst_cond, 16.0);
  checks.check("every chain the Riccati recursion ran through: min D(k) > 0", d_positive);
  checks.check("diagnosed exactly where the ratio is not above singular_D_threshold",
               verdicts_agree);
  checks.check("massless tip: diagnosed, soa::Error naming body 'b1' and D(1)", tip_named);
  checks.check("D(k) up to the stop: >= 6 correct digits against long double", worst_D_digits,
               1e-6);
  checks.check("l6_extreme.csv and l6_extreme.md written", bool(extreme_csv) && bool(extreme_md));

  /// What the numbers say. The mass matrix from \f$R\f$ agrees with the operator form to a
  /// few \f$\varepsilon\f$ in every case, even at n = 10 000 with mass ratios \f$10^{\pm 8}\f$
  /// and \f$J = 10^{-9}\f$: it only adds and transforms inertias. cond(M) does not stay
  /// small: it grows with the mass ratio and with a power of n, past \f$1/\varepsilon\f$ at
  /// n = 500; a method that solves with \f$\mathcal M\f$ then has no correct digit, although
  /// \f$\mathcal M\f$ itself is accurate. The Riccati recursion runs through every chain but
  /// the one with the massless tip. Its smallest ratio falls with the mass ratio (a light
  /// body's \f$D(k)\f$ is its own small inertia about its hinge, on a straight chain where
  /// the outboard bodies offer only inertia along the links), and the long double column
  /// confirms what the ratio predicts: \f$D(k)\f$ keeps about \f$\log_{10}(\text{ratio} /
  /// \varepsilon)\f$ digits, 7 or more here. The massless tip is diagnosed at body 1 whatever
  /// n: there the method stops because the problem has no answer.

  /// ## 8. Alternative force decompositions
  ///
  /// The inter-body force \f$f(k)\f$ split into an inertia times an acceleration plus a bias
  /// (slide 1, topic 6; Jain 2011, chapter 6), once with the hinges k−1, ..., 1 locked (the
  /// composite body of lesson 5) and once with them free (section 2). Stacked (lesson 4),
  /// \f$\alpha = \phi^*(H^*\dot\beta + a + w)\f$ and \f$f = \phi(M\alpha + b)\f$, where
  /// \f$w\f$ holds the base acceleration \f$\alpha^+(n) = \phi^*(n+1,n)\alpha(n+1)\f$ in its
  /// block n and zero elsewhere. Write \f$\delta = \alpha - \alpha^+ = H^*\dot\beta + a\f$, so
  /// \f$\alpha^+ = \tilde\phi^*(\delta + w) + w\f$, \f$\tilde\phi = \phi - I = \phi\mathcal
  /// E_\phi = \mathcal E_\phi\phi\f$ (strictly lower: \f$\tilde\phi X w = 0\f$ for block
  /// diagonal \f$X\f$, nothing is inboard of body n).
  ///
  /// **Hinges locked: the composite body.** From \f$R = \mathcal E_\phi R\mathcal E_\phi^* +
  /// M\f$ (lesson 5), \f$\phi M\phi^* = \phi R\phi^* - \tilde\phi R\tilde\phi^*\f$, that is
  /// \f[ \phi M\phi^* = R + \tilde\phi R + R\tilde\phi^* . \f]
  /// Then \f$f = \phi M\phi^*(\delta + w) + \phi b = R\tilde\phi^*(\delta + w) + \phi R(\delta +
  /// w) + \phi b = R\alpha^+ + \phi(R\delta + b) + \tilde\phi R w\f$, and the last term is zero:
  /// \f[ f = R\,\alpha^+ + y, \qquad y = \phi\,(R\,\delta + b), \qquad
  ///     y(k) = \phi(k,k-1)\,y(k-1) + R(k)\bigl(\alpha(k) - \alpha^+(k)\bigr) + b(k). \f]
  /// \f$R(k)\f$ multiplies \f$\alpha^+(k) = \phi^*(k+1,k)\alpha(k+1)\f$, not \f$\alpha(k)\f$:
  /// the acceleration of body k with hinge k locked as well, all of bodies 1..k riding on body
  /// k+1. \f$y(k)\f$ collects, for every body \f$j \le k\f$, its bias \f$b(j)\f$ and the force
  /// \f$R(j)\delta(j)\f$ the composite body 1..j needs to follow the relative acceleration
  /// \f$\delta(j) = H^*(j)\dot\beta(j) + a(j)\f$ of hinge j, moved to \f$O_k\f$ (API:
  /// soa::alpha_plus(), soa::composite_bias(); soa::inverse_dynamics_composite() of lesson 5
  /// computes the same \f$y\f$ on the fly). Taking \f$R(k)H^*(k)\dot\beta(k)\f$ out of
  /// \f$y(k)\f$ gives the analogue of \f$P(\alpha - a) + z\f$:
  /// \f[ f(k) = R(k)\bigl(\alpha(k) - a(k)\bigr) + y^-(k), \qquad y^-(k) = \phi(k,k-1)\,y(k-1) +
  ///     R(k)\,a(k) + b(k). \f]
  ///
  /// *Now do* exercise 6.6 (the composite-body bias \f$y\f$, tip to base).
  ///
  /// **Hinges free: the articulated body.** From the Riccati equation \f$P = \mathcal E_\phi
  /// P^+\mathcal E_\phi^* + M\f$ with \f$P^+ = P - GDG^*\f$ and \f$K = \mathcal E_\phi G\f$,
  /// \f$M = P - \mathcal E_\phi P\mathcal E_\phi^* + KDK^*\f$, and in the same way
  /// \f[ \phi M\phi^* = P + \tilde\phi P + P\tilde\phi^* + \phi K D K^*\phi^* . \f]
  /// Then \f$f = P\alpha^+ + \phi(P\delta + b) + \phi KDK^*\alpha\f$. Here \f$\phi K = \tilde\phi
  /// G\f$ and \f$K^*\alpha = G^*\mathcal E_\phi^*\alpha\f$ equals \f$G^*\alpha^+\f$ but in block
  /// n, which \f$\tilde\phi\f$ drops: \f$\phi KDK^*\alpha = \tilde\phi\, GDG^*\alpha^+\f$. With
  /// \f$P\delta + GDG^*\alpha^+ = Pa + GD(\dot\beta + G^*\alpha^+) = Pa + G\epsilon\f$
  /// (\f$PH^* = GD\f$, \f$\dot\beta = \nu - G^*\alpha^+\f$, section 2):
  /// \f[ f = P^+\alpha^+ + z^+ = P(\alpha - a) + z, \qquad z^+ = \phi\,(Pa + b + G\epsilon),
  ///     \qquad z = z^+ - G\epsilon , \f]
  /// the operator form of the recursions of section 2. Side by side: the same \f$\alpha^+\f$,
  /// and \f$y - z^+ = (P^+ - R)\,\alpha^+\f$; the free hinges take inertia out of the first
  /// term (\f$P^+ \le P \le R\f$) and put the hinge forces \f$T\f$ into the bias.
  ///
  /// **The articulated analogue in full.** From \f$P = \mathcal E_\psi P\mathcal E_\psi^* +
  /// M\f$ (section 4) and \f$\tilde\psi = \psi - I = \psi\mathcal E_\psi\f$, the same two
  /// lines give
  /// \f[ \psi M\psi^* = P + \tilde\psi P + P\tilde\psi^*, \qquad (\psi M\psi^*)(i,j) =
  ///     \psi(i,j)\,P(j),\ i > j, \f]
  /// as \f$(\phi M\phi^*)(i,j) = \phi(i,j)R(j)\f$: section 4 had only its diagonal. The
  /// correction \f$\phi KDK^*\phi^*\f$ of the \f$\phi\f$ form is absorbed by \f$\psi\f$, which
  /// carries forces across the free hinges. Checked on the dense operators and, for the
  /// forces, against Newton–Euler at the moving state of section 2:
  const MatX R_op = soa::composite_inertia_operator(m, ws);
  const MatX I_N = MatX::Identity(N, N);
  const MatX phi_t = op.phi - I_N, psi_t = psi - I_N;
  const MatX phiMphi = op.phi * op.M * op.phi.transpose();
  const MatX free_part = op.phi * K * D * K.transpose() * op.phi.transpose();
  const double op_scale = std::max({1.0, phiMphi.norm(), free_part.norm(), psiMpsi.norm()});
  double psi_blocks = 0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < a; ++b)
      psi_blocks = std::max(psi_blocks, (psiMpsi.block<6, 6>(6 * a, 6 * b) -
                                         psi.block<6, 6>(6 * a, 6 * b) * art.P[std::size_t(b)])
                                            .norm());
  checks.check("phi M phi* = R + phi~ R + R phi~*",
               (phiMphi - (R_op + phi_t * R_op + R_op * phi_t.transpose())).norm(),
               16 * N * kEps * op_scale);
  checks.check("phi M phi* = P + phi~ P + P phi~* + phi K D K* phi*",
               (phiMphi - (P + phi_t * P + P * phi_t.transpose() + free_part)).norm(),
               16 * N * kEps * op_scale);
  checks.check("psi M psi* = P + psi~ P + P psi~*",
               (psiMpsi - (P + psi_t * P + P * psi_t.transpose())).norm(),
               16 * N * kEps * op_scale);
  checks.check("(psi M psi*)(i,j) = psi(i,j) P(j), i > j", psi_blocks, 16 * N * kEps * op_scale);

  // The forces at the moving state of section 2 (mg, xm, T, f_ext; Newton-Euler in ws_ne).
  std::vector<soa::Acceleration> alpha_p(static_cast<std::size_t>(n));
  std::vector<soa::Force> y(static_cast<std::size_t>(n));
  soa::alpha_plus(mg, ws_ne, alpha_p);
  soa::composite_bias(mg, ws_ne, art.R, alpha_p, f_ext, y);
  VecX delta(N), b_stack(N), a_stack(N), Geps(N), y_stack(N), zp_stack(N);
  double comp = 0, comp_minus = 0, alpha_p_err = 0, side = 0, fs = 1e-300;
  std::printf("  k  |f(k)|    |R a+|    |y|       |P+ a+|   |z+|\n");
  for (int k = 1; k <= n; ++k) {
    const std::size_t j = std::size_t(k - 1);
    const Mat6 R = art.R[j].matrix();
    const Vec6 f = ws_ne.f[j].vector(), ap = alpha_p[j].vector();
    const Vec6 a_k = ws_ne.a[j].vector(), alpha_k = ws_ne.alpha[j].vector();
    Vec6 y_minus = R * a_k + ws_fd.b[j].vector();
    if (k > 1) y_minus += ws_ne.phi[j - 1].apply(y[j - 1]).vector();
    comp = std::max(comp, (R * ap + y[j].vector() - f).norm());
    comp_minus = std::max(comp_minus, (R * (alpha_k - a_k) + y_minus - f).norm());
    alpha_p_err = std::max(alpha_p_err, (ap - fd.alpha_plus[j].vector()).norm());
    side = std::max(side, (y[j].vector() - fd.z_plus[j].vector() -
                           (fd.art.P_plus[j] - R) * fd.alpha_plus[j].vector())
                              .norm());
    fs = std::max(
        {fs, f.norm(), R.norm() * ap.norm(), y[j].vector().norm(), R.norm() * alpha_k.norm()});
    delta.segment<6>(6 * int(j)) = alpha_k - ap;
    b_stack.segment<6>(6 * int(j)) = ws_fd.b[j].vector();
    a_stack.segment<6>(6 * int(j)) = ws_fd.a[j].vector();
    Geps.segment<6>(6 * int(j)) = fd.art.G[j] * (fd.art.D[j] * fd.nu[j]);
    y_stack.segment<6>(6 * int(j)) = y[j].vector();
    zp_stack.segment<6>(6 * int(j)) = fd.z_plus[j].vector();
    std::printf("  %d  %8.4f  %8.4f  %8.4f  %8.4f  %8.4f\n", k, f.norm(), (R * ap).norm(),
                y[j].vector().norm(), (fd.art.P_plus[j] * fd.alpha_plus[j].vector()).norm(),
                fd.z_plus[j].vector().norm());
  }
  fs = std::max(fs, f_scale);
  // The composite split only adds and transforms; the articulated one carries G (kappa).
  const double tol_comp = 16 * N * kEps * fs, tol_fs = 16 * N * kEps * kappa * fs;
  checks.check("alpha+(k) = phi*(k+1,k) alpha(k+1) (soa::alpha_plus) == the sweeps' alpha+",
               alpha_p_err, tol_comp);
  checks.check("composite: f(k) = R(k) alpha+(k) + y(k) == Newton-Euler f(k)", comp, tol_comp);
  checks.check("composite: f(k) = R(k) (alpha(k) - a(k)) + y-(k) == Newton-Euler f(k)", comp_minus,
               tol_comp);
  checks.check("operator form y = phi (R delta + b), delta = alpha - alpha+",
               (y_stack - op.phi * (R_op * delta + b_stack)).norm(), tol_comp);
  checks.check("operator form z+ = phi (P a + b + G epsilon)",
               (zp_stack - op.phi * (P * a_stack + b_stack + Geps)).norm(), tol_fs);
  checks.check("side by side: y(k) - z+(k) = (P+(k) - R(k)) alpha+(k)", side, tol_fs);

  return checks.finish();
}
