/// # Lesson 7 — Mass matrix factorization and inversion
///
/// Topic 7 of the course (slides 1 and 80; Jain 2011, chapter 7): the spatial operator
/// identities that tie \f$\phi\f$ of lessons 3-4 to \f$\psi\f$ of lesson 6, the
/// **innovations factorization** of the mass matrix
/// \f$\mathcal M = [I + H\phi K]\, D\, [I + H\phi K]^*\f$, the closed-form inverse of its
/// factor, \f$[I + H\phi K]^{-1} = I - H\psi K\f$, and with it
/// \f$\mathcal M^{-1} = [I - H\psi K]^*\, D^{-1}\, [I - H\psi K]\f$: the inverse of the mass
/// matrix in \f$O(N^2)\f$ without ever forming \f$\mathcal M\f$; then what the inverse
/// factorization gives besides: the operator \f$\Omega = \phi^*H^*\mathcal M^{-1}H\phi\f$ and
/// its diagonal \f$\Upsilon\f$ by a Lyapunov recursion, a second \f$O(N^2)\f$ inverse built on
/// \f$\Upsilon\f$, the operational-space inverse inertia \f$J\mathcal M^{-1}J^*\f$ of a frame in
/// \f$O(N)\f$, and the innovations coordinates that decouple the kinetic energy. Every
/// identity is computed on concrete numbers and checked; the program ends with the count of
/// checks that passed.
///
/// Numbering (\ref conventions): **body 1 is the tip, body n is next to the base**, hinge k
/// joins body k+1 to body k, and \f$\theta\f$, \f$\beta\f$ are stacked tip first.
///
/// Learning goals. After this lesson you can
/// - derive \f$\phi^{-1} - \psi^{-1} = -KH\f$ and \f$\psi KH\phi = \phi - \psi = \phi KH\psi\f$
///   from the definitions of lesson 6, in two lines each;
/// - derive the innovations factorization from the Riccati equation, and say why it is a
///   block \f$LDL^*\f$ factorization of \f$\mathcal M\f$ (so \f$\det\mathcal M = \prod_k
///   \det D(k)\f$);
/// - invert its factor and the mass matrix in closed form, and turn
///   \f$[I - H\psi K]^* D^{-1} [I - H\psi K]\f$ into tip-to-base and base-to-tip recursions
///   that give \f$\mathcal M^{-1}\f$ in \f$O(N^2)\f$;
/// - judge the error of an inverse by the condition number of \f$\mathcal M\f$;
/// - derive \f$\phi^*H^*\mathcal M^{-1}H\phi = \psi^*H^*D^{-1}H\psi = \Omega\f$, split it as
///   \f$\Upsilon + \tilde\psi^*\Upsilon + \Upsilon\tilde\psi\f$ and compute \f$\Upsilon\f$ base to
///   tip; build \f$\mathcal M^{-1}\f$ from it, and \f$J\mathcal M^{-1}J^*\f$ of any frame in
///   \f$O(N)\f$;
/// - show that \f$\eta = [I + H\phi K]^*\beta\f$ decouples the kinetic energy, and compute
///   \f$\eta(k) = G^*(k)V(k)\f$ in \f$O(N)\f$.
///
/// Run it as `lesson07 OUTDIR`: it prints each check, and writes the error of
/// \f$\mathcal M^{-1}\f$ on chains of 2 to 200 links (`l7_minv_error.csv`) and its figure
/// (`l7_minv_error.png`).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <random>
#include <string>
#include <vector>

#include "args.hpp"
#include "checklist.hpp"
#include "plot.hpp"
#include "soa/chain.hpp"
#include "soa/chain/mass_matrix_inverse_upsilon.hpp"
#include "soa/chain/operational_space.hpp"
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
using VecX = soa::VecX<double>;
using MatX = soa::MatX<double>;

const double kEps = soa::eps<double>();

/// ## Helpers
///
/// A scene of lesson 3 (`lib/scenes/NAME.json`), with the
/// state the file gives.
bool scene(const std::string& name, Model& m, State& x, std::string& error) {
  try {
    const soa::Scene s = soa::load_scene(SOA_SCENE_DIR "/" + name + ".json");
    m = s.model;
    x = s.state;
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
}

/// A random chain of n bodies whose hinges cycle through every type of lesson 3 (revolute,
/// prismatic, helical, universal, spherical, free, locked; a locked hinge merges its body
/// into the inboard one), with physically valid inertias (mass in [0.5, 5], principal
/// moments obeying the triangle inequality, a random principal frame and centre of mass),
/// random placements and axes, at a random state.
Model random_chain(std::mt19937_64& gen, int n, State& x) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto vec = [&] { return Vec3(normal(gen), normal(gen), normal(gen)); };
  const auto rotation = [&] { return soa::UnitQuaternion(vec(), normal(gen)).matrix(); };
  std::vector<Body> base_first;
  for (int i = 0; i < n; ++i) {
    Body b;
    b.name = "body" + std::to_string(i);
    const double mass = 0.5 + 4.5 * unit(gen), a = 0.2 + 1.8 * unit(gen), c = 0.2 + 1.8 * unit(gen);
    const double lo = std::abs(a - c) + 0.05, d = lo + (a + c - lo) * unit(gen);
    const Mat3 Q = rotation();
    const Mat3 J = Q * Vec3(a, c, d).asDiagonal() * Q.transpose();
    b.M = SpatialInertia::from_cm(mass, vec(), 0.5 * (J + J.transpose()));
    b.placement = Pose(rotation(), vec());
    b.hinge.type = HingeType(i % 7);
    if (i == 0 && b.hinge.type == HingeType::Locked) b.hinge.type = HingeType::Revolute;
    b.hinge.axis = vec().normalized();
    b.hinge.axis2 = vec().normalized();
    b.hinge.pitch = unit(gen) - 0.5;
    base_first.push_back(b);
  }
  Model m = Model::from_base_first(base_first);
  x = State::rest(m);
  for (int i = 0; i < m.nq(); ++i) x.theta[i] = normal(gen);
  for (int k = 1; k <= m.n(); ++k) {
    const Body& B = m.body(k);
    if (B.hinge.type == HingeType::Spherical || B.hinge.type == HingeType::Free)
      x.theta.segment(B.q_offset, 4).normalize();
  }
  return m;
}

/// The chain of the accuracy study (section 5): n links of 0.1 m and 0.2 kg, centre of mass
/// halfway down the link, revolute hinges about x and y in turn (the 50-link chain of lesson
/// 3 for n = 50), every hinge at 0.2 rad.
Model link_chain(int n, State& x) {
  std::vector<Body> base_first;
  for (int i = 0; i < n; ++i) {
    Body b;
    b.name = "link" + std::to_string(i + 1);
    b.M = SpatialInertia::from_cm(0.2, Vec3(0, 0, -0.05),
                                  Vec3(1.7e-4, 1.7e-4, 1e-5).asDiagonal().toDenseMatrix());
    b.placement = Pose(Mat3::Identity(), Vec3(0, 0, i == 0 ? 0.0 : -0.1));
    b.hinge.type = HingeType::Revolute;
    b.hinge.axis = i % 2 == 0 ? Vec3::UnitX() : Vec3::UnitY();
    base_first.push_back(b);
  }
  Model m = Model::from_base_first(base_first);
  x = State::rest(m);
  x.theta.setConstant(0.2);
  return m;
}

/// The same chain in another precision T (for the long double reference of section 5).
template <class T>
soa::ModelT<T> cast_model(const Model& m) {
  std::vector<soa::BodyT<T>> base_first;
  for (int k = m.n(); k >= 1; --k) {
    const Body& B = m.body(k);
    soa::BodyT<T> b;
    b.name = B.name;
    b.M = B.M.template cast<T>();
    b.placement = B.placement.template cast<T>();
    b.hinge = B.hinge.template cast<T>();
    base_first.push_back(b);
  }
  return soa::ModelT<T>::from_base_first(base_first);
}

/// The mass matrix by composite bodies (lesson 5), and \f$\mathcal M^{-1}\f$ by the
/// \f$O(N^2)\f$ algorithm of section 4, in precision T.
template <class T>
soa::MatX<T> mass_matrix(const soa::ModelT<T>& m, const soa::StateT<T>& x) {
  soa::WorkspaceT<T> ws(m);
  soa::update_phi(m, x.theta, ws);
  std::vector<soa::SpatialInertiaT<T>> R(std::size_t(m.n()));
  soa::MatX<T> M;
  soa::mass_matrix_crb(m, x, ws, R, M);
  return M;
}
template <class T>
soa::MatX<T> inverse_on2(const soa::ModelT<T>& m, const soa::StateT<T>& x) {
  soa::WorkspaceT<T> ws(m);
  soa::update_phi(m, x.theta, ws);
  soa::MassMatrixInverseT<T> w(m);
  soa::MatX<T> Minv;
  soa::mass_matrix_inverse(m, x, ws, w, Minv);
  return Minv;
}
/// \f$\mathcal M^{-1}\f$ by the \f$O(N^2)\f$ algorithm built on \f$\Upsilon\f$ (section 7).
template <class T>
soa::MatX<T> inverse_upsilon(const soa::ModelT<T>& m, const soa::StateT<T>& x) {
  soa::WorkspaceT<T> ws(m);
  soa::update_phi(m, x.theta, ws);
  soa::MassMatrixInverseUpsilonT<T> w(m);
  soa::MatX<T> Minv;
  soa::mass_matrix_inverse_upsilon(m, x, ws, w, Minv);
  return Minv;
}

/// The frame of section 8, fixed on each body in turn: \f${}^{O_k}T_F\f$.
Pose tool_frame() {
  return Pose(soa::UnitQuaternion(Vec3(0.3, -0.2, 0.5), 0.9).matrix(), Vec3(0.1, -0.2, 0.3));
}

/// The generalized velocity of section 9: \f$\beta_i = \cos(1 + i)\f$.
VecX test_velocity(int nv) {
  VecX beta(nv);
  for (int i = 0; i < nv; ++i) beta[i] = std::cos(1.0 + i);
  return beta;
}

/// The innovations coordinates in \f$O(N)\f$ (section 9): \f$\eta(k) = G^*(k)\,V(k)\f$, with
/// \f$V\f$ from the velocity recursion of lesson 3 and \f$G\f$ from the Riccati recursion.
VecX innovations_coordinates(const Model& m, const soa::Articulated& art, const Workspace& ws) {
  VecX eta(m.nv());
  for (int k = 1; k <= m.n(); ++k) {
    const Body& B = m.body(k);
    eta.segment(B.v_offset, B.hinge.nv()) =
        art.G[std::size_t(k - 1)].transpose() * ws.V[std::size_t(k - 1)].vector();
  }
  return eta;
}

/// The 2-norm condition number \f$\lambda_{\max}/\lambda_{\min}\f$ of a symmetric positive
/// definite matrix.
double cond(const MatX& A) {
  const VecX ev = Eigen::SelfAdjointEigenSolver<MatX>(A, Eigen::EigenvaluesOnly).eigenvalues();
  return ev.maxCoeff() / ev.minCoeff();
}

/// The residual of every identity of this lesson for one chain at one state, each divided by
/// its scale: \f$\varepsilon\f$ times the size 6n of the operators times the magnitude of
/// its terms times \f$\kappa = \max_k |P(k)|\,|D^{-1}(k)|\f$ (the growth of rounding in
/// \f$G = PH^*D^{-1}\f$), or times cond(M) where an inverse of \f$\mathcal M\f$ is compared
/// with a dense one. A residual below a few units is rounding.
struct Residuals {
  double phi_inverse = 0;     // phi (I - E_phi) = I
  double E_psi = 0;           // E_psi = E_phi - K H
  double PH_GD = 0;           // P H* = G D
  double riccati = 0;         // M = P - E_phi P E_phi* + K D K*
  double phiMphi = 0;         // phi M phi* = P + phi~ P + P phi~* + phi K D K* phi*
  double phi_psi = 0;         // phi^-1 - psi^-1 = -K H
  double psiKHphi = 0;        // psi K H phi = phi - psi
  double phiKHpsi = 0;        // phi K H psi = phi - psi
  double factorization = 0;   // M = [I + H phi K] D [I + H phi K]*
  double triangular = 0;      // [I + H phi K] block unit lower triangular
  double determinant = 0;     // log det M = sum_k log det D(k)
  double factor_inverse = 0;  // [I + H phi K][I - H psi K] = I = [I - H psi K][I + H phi K]
  double inverse = 0;         // [I - H psi K]* D^-1 [I - H psi K] = inv(M), / cond(M)
  double on2 = 0;             // mass_matrix_inverse = the operator expression
  double on2_dense = 0;       // mass_matrix_inverse = inv(M), / cond(M)
  double omega = 0;           // phi* H* inv(M) H phi = psi* H* D^-1 H psi, / cond(M)
  double omega_split = 0;     // Omega = Upsilon + psi~* Upsilon + Upsilon psi~
  double upsilon_rec = 0;     // upsilons() = diagonal blocks of Omega
  double minv_diag = 0;       // D^-1 + G* Upsilon+ G = diagonal blocks of M^-1
  double on2u = 0;            // mass_matrix_inverse_upsilon = the operator expression
  double on2u_sweep = 0;      // mass_matrix_inverse_upsilon = mass_matrix_inverse, / n cond(M)
  double on2u_dense = 0;      // mass_matrix_inverse_upsilon = inv(M), / cond(M)
  double opspace = 0;         // phi*(O_k,F) Upsilon(k) phi(O_k,F) = J inv(M) J*, / cond(M)
  double eta_energy = 0;      // 1/2 beta* M beta = 1/2 eta* D eta
  double eta_rec = 0;         // G*(k) V(k) = [I + H phi K]* beta
  double eta_back = 0;        // [I - H psi K]* eta = beta
  double cond = 0;            // cond(M)
  double kappa = 0;

  void max_with(const Residuals& r) {
    for (double Residuals::*f :
         {&Residuals::phi_inverse, &Residuals::E_psi,       &Residuals::PH_GD,
          &Residuals::riccati,     &Residuals::phiMphi,     &Residuals::phi_psi,
          &Residuals::psiKHphi,    &Residuals::phiKHpsi,    &Residuals::factorization,
          &Residuals::triangular,  &Residuals::determinant, &Residuals::factor_inverse,
          &Residuals::inverse,     &Residuals::on2,         &Residuals::on2_dense,
          &Residuals::omega,       &Residuals::omega_split, &Residuals::upsilon_rec,
          &Residuals::minv_diag,   &Residuals::on2u,        &Residuals::on2u_sweep,
          &Residuals::on2u_dense,  &Residuals::opspace,     &Residuals::eta_energy,
          &Residuals::eta_rec,     &Residuals::eta_back,    &Residuals::cond,
          &Residuals::kappa})
      this->*f = std::max(this->*f, r.*f);
  }
};

Residuals identities(const Model& m, const State& x) {
  const soa::InnovationsOperators io = soa::InnovationsOperators::build(m, x);
  const int N = 6 * m.n(), nv = m.nv();
  const MatX I = MatX::Identity(N, N), Iv = MatX::Identity(nv, nv);
  const MatX& phi = io.op.phi;
  const MatX& H = io.op.H;
  const MatX KH = io.K * H;
  const MatX Mass = mass_matrix(m, x);
  Residuals r;
  r.kappa = 1;
  for (int k = 1; k <= m.n(); ++k) {
    const int b = 6 * (k - 1), c = m.body(k).v_offset, nk = m.body(k).hinge.nv();
    r.kappa =
        std::max(r.kappa, io.P.block(b, b, 6, 6).norm() * io.D_inv.block(c, c, nk, nk).norm());
  }
  const auto big = [](std::initializer_list<double> v) {
    return std::max(1.0, *std::max_element(v.begin(), v.end()));
  };
  const double u = kEps * N * r.kappa;
  r.cond = cond(Mass);
  r.phi_inverse = (phi * (I - io.op.E_phi) - I).norm() / (u * big({phi.norm()}));
  r.E_psi = (io.E_psi - (io.op.E_phi - KH)).norm() / (u * big({io.op.E_phi.norm(), KH.norm()}));
  r.PH_GD = (io.P * H.transpose() - io.G * io.D).norm() / (u * big({io.P.norm()}));
  const MatX KDK = io.K * io.D * io.K.transpose();
  r.riccati = (io.op.M - (io.P - io.op.E_phi * io.P * io.op.E_phi.transpose() + KDK)).norm() /
              (u * big({io.P.norm(), KDK.norm()}));
  const MatX phi_t = phi - I;
  const MatX A = phi * io.op.M * phi.transpose();
  r.phiMphi =
      (A - (io.P + phi_t * io.P + io.P * phi_t.transpose() + phi * KDK * phi.transpose())).norm() /
      (u * big({A.norm(), phi.norm() * phi.norm() * big({io.P.norm(), KDK.norm()})}));
  const MatX phi_inv = phi.inverse(), psi_inv = io.psi.inverse();
  r.phi_psi =
      (phi_inv - psi_inv + KH).norm() / (u * big({phi_inv.norm(), psi_inv.norm(), KH.norm()}));
  const MatX diff = phi - io.psi;
  const double terms = big({phi.norm() * KH.norm() * io.psi.norm(), diff.norm()});
  r.psiKHphi = (io.psi * KH * phi - diff).norm() / (u * terms);
  r.phiKHpsi = (phi * KH * io.psi - diff).norm() / (u * terms);
  const MatX L = io.factor(), Li = io.factor_inverse();
  r.factorization = (io.mass_matrix() - Mass).norm() /
                    (u * big({L.norm() * L.norm() * io.D.norm(), Mass.norm()}));
  double off = 0;
  for (int k = 1; k <= m.n(); ++k) {
    const int o = m.body(k).v_offset, nk = m.body(k).hinge.nv();
    off = std::max(off, (L.block(o, o, nk, nk) - MatX::Identity(nk, nk)).norm());
    if (o > 0) off = std::max(off, L.block(0, o, o, nk).norm());
  }
  r.triangular = off / (u * big({L.norm()}));
  r.determinant =
      std::abs(std::log(io.D.determinant()) - std::log(Mass.determinant())) / (kEps * N * r.cond);
  r.factor_inverse =
      std::max((L * Li - Iv).norm(), (Li * L - Iv).norm()) / (u * big({L.norm() * Li.norm()}));
  const MatX Minv = io.mass_matrix_inverse(), dense = Mass.inverse();
  r.inverse = (Minv - dense).norm() / (dense.norm() * kEps * N * r.cond);
  const MatX on2 = inverse_on2(m, x);
  r.on2 = (on2 - Minv).norm() / (u * big({Li.norm() * Li.norm() * io.D_inv.norm(), on2.norm()}));
  r.on2_dense = (on2 - dense).norm() / (dense.norm() * kEps * N * r.cond);
  // Sections 6-9.
  const MatX Omega = io.Omega(), U = io.Upsilon(), pt = io.psi - I;
  const MatX lhs = phi.transpose() * H.transpose() * dense * H * phi;
  r.omega = (lhs - Omega).norm() / (big({Omega.norm()}) * kEps * N * r.cond);
  r.omega_split = (Omega - (U + pt.transpose() * U + U * pt)).norm() /
                  (u * big({Omega.norm(), 2 * pt.norm() * U.norm()}));
  Workspace ws(m);
  soa::update_phi(m, x.theta, ws);
  soa::update_poses(m, ws);
  soa::Upsilon ups(m);
  soa::upsilons(m, x, ws, ups);
  const double inv_terms = big({Li.norm() * Li.norm() * io.D_inv.norm(), Minv.norm()});
  double e_rec = 0, e_diag = 0, e_op = 0;
  Eigen::Matrix<double, 6, Eigen::Dynamic> J;
  soa::Mat6<double> op;
  for (int k = 1; k <= m.n(); ++k) {
    const std::size_t i = std::size_t(k - 1);
    const int o = m.body(k).v_offset, nk = m.body(k).hinge.nv(), b = 6 * (k - 1);
    e_rec = std::max(e_rec, (ups.Upsilon[i] - U.block(b, b, 6, 6)).norm());
    e_diag = std::max(e_diag, (MatX(ups.Minv_kk[i]) - Minv.block(o, o, nk, nk)).norm());
    soa::jacobian(m, x.theta, ws, k, tool_frame(), J);
    const MatX ref = J * dense * J.transpose();
    soa::operational_space_inverse_inertia(tool_frame(), ups.Upsilon[i], op);
    e_op = std::max(e_op, (op - ref).norm() / big({ref.norm()}));
  }
  r.upsilon_rec = e_rec / (u * big({Omega.norm()}));
  r.minv_diag = e_diag / (u * inv_terms);
  r.opspace = e_op / (kEps * N * r.cond);
  const MatX on2u = inverse_upsilon(m, x);
  r.on2u = (on2u - Minv).norm() / (u * inv_terms);
  r.on2u_sweep = (on2u - on2).norm() / (on2.norm() * kEps * nv * r.cond);
  r.on2u_dense = (on2u - dense).norm() / (dense.norm() * kEps * N * r.cond);
  State xb = x;
  xb.beta = test_velocity(nv);
  soa::update_velocities(m, xb, ws);
  const VecX eta = io.eta(xb.beta), eta_n = innovations_coordinates(m, ups.art, ws);
  const double T = 0.5 * xb.beta.dot(Mass * xb.beta), Te = 0.5 * eta.dot(io.D * eta);
  r.eta_energy = std::abs(T - Te) /
                 (u * big({Mass.norm() * xb.beta.squaredNorm(), io.D.norm() * eta.squaredNorm()}));
  r.eta_rec = (eta_n - eta).norm() / (u * big({L.norm() * xb.beta.norm()}));
  r.eta_back = (Li.transpose() * eta - xb.beta).norm() / (u * big({Li.norm() * eta.norm()}));
  return r;
}

/// Prints a small matrix, rows indented.
void print(const char* name, const MatX& A) {
  std::printf("  %s =\n", name);
  for (int i = 0; i < A.rows(); ++i) {
    std::printf("    ");
    for (int j = 0; j < A.cols(); ++j) std::printf(" %10.5f", A(i, j));
    std::printf("\n");
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path out = soa::lesson::output_dir(argc, argv);
  soa::lesson::Checklist checks;

  /// ## 1. The operators, and the chains of this lesson
  ///
  /// From lesson 6, with the Riccati quantities stacked tip first (block diagonal \f$P\f$,
  /// \f$P^+\f$, \f$D\f$, \f$G\f$, \f$\bar\tau\f$):
  /// \f[ K = \mathcal E_\phi G, \qquad \mathcal E_\psi = \mathcal E_\phi\bar\tau, \qquad
  ///     \psi = (I - \mathcal E_\psi)^{-1}, \qquad \bar\tau = I - GH, \f]
  /// \f$K\f$ with the only non-zero blocks \f$K(k+1,k) = \phi(k+1,k)G(k)\f$, and from lessons
  /// 3-4 \f$\phi = (I - \mathcal E_\phi)^{-1}\f$ and \f$\mathcal M = H\phi M\phi^*H^*\f$. As
  /// dense matrices for small n: soa::InnovationsOperatorsT (on top of soa::OperatorsT and
  /// soa::articulated_inertias()). The chains: the double pendulum and the 7-joint arm of
  /// lesson 3 in the states their scene files give, and 200 random chains of 1 to 8 bodies
  /// whose hinges run through every type of lesson 3, in random states.
  ///
  /// *Now do exercise 7.1* (`soa::ex07::k_and_psi`): \f$K\f$ and \f$\psi\f$ as dense matrices,
  /// built block by block from \f$\phi(k+1,k)\f$, \f$G(k)\f$ and \f$\bar\tau(k)\f$.
  checks.section("1. the chains");
  struct Named {
    std::string name;
    Model m;
    State x;
  };
  std::vector<Named> scenes;
  for (const char* name : {"double_pendulum", "arm7"}) {
    Named s{name, Model{}, State{}};
    std::string error;
    const bool ok = scene(name, s.m, s.x, error);
    checks.check(std::string(name) + ".json loads" + (ok ? "" : " (" + error + ")"), ok);
    if (ok) scenes.push_back(s);
  }
  std::mt19937_64 gen(20261125u);
  std::vector<Named> randoms;
  for (int i = 0; i < 200; ++i) {
    Named s{"random" + std::to_string(i), Model{}, State{}};
    s.m = random_chain(gen, 1 + i % 8, s.x);
    randoms.push_back(s);
  }
  for (const Named& s : scenes)
    std::printf("  %-16s n = %d bodies, %d degrees of freedom\n", s.name.c_str(), s.m.n(),
                s.m.nv());
  std::vector<Residuals> scene_r;
  for (const Named& s : scenes) scene_r.push_back(identities(s.m, s.x));
  Residuals random_r;
  for (const Named& s : randoms) random_r.max_with(identities(s.m, s.x));
  // Each identity below is checked on every scene and, as the worst case, on the random
  // chains; residuals in the units of identities() (tolerance 4).
  const auto check_all = [&](const std::string& what, double Residuals::*field) {
    for (std::size_t i = 0; i < scenes.size(); ++i)
      checks.check(scenes[i].name + ": " + what, scene_r[i].*field, 4.0);
    checks.check("200 random chains, worst: " + what, random_r.*field, 4.0);
  };

  /// ## 2. Spatial operator identities
  ///
  /// Lesson 3 gave \f$\phi^{-1} = I - \mathcal E_\phi\f$ and lesson 6 defined
  /// \f$\psi^{-1} = I - \mathcal E_\psi\f$. Since \f$\mathcal E_\psi = \mathcal E_\phi(I - GH)
  /// = \mathcal E_\phi - KH\f$,
  /// \f[ \phi^{-1} - \psi^{-1} = \mathcal E_\psi - \mathcal E_\phi = -KH . \f]
  /// Multiply on the left by \f$\psi\f$ and on the right by \f$\phi\f$, then on the left by
  /// \f$\phi\f$ and on the right by \f$\psi\f$:
  /// \f[ \psi KH\phi = \phi - \psi = \phi KH\psi . \f]
  /// These say how the free hinges turn the rigid-body transformation \f$\phi\f$ into the
  /// articulated one \f$\psi\f$: \f$\phi - \psi\f$ is what the hinges let go, and it factors
  /// through \f$KH\f$. The computed \f$\phi^{-1}\f$ and \f$\psi^{-1}\f$ below are the dense
  /// inverses of the matrices \f$\phi\f$ and \f$\psi\f$, not \f$I - \mathcal E\f$.
  checks.section("2. spatial operator identities");
  check_all("phi (I - E_phi) = I", &Residuals::phi_inverse);
  check_all("E_psi = E_phi - K H", &Residuals::E_psi);
  check_all("phi^-1 - psi^-1 = -K H", &Residuals::phi_psi);
  check_all("psi K H phi = phi - psi", &Residuals::psiKHphi);
  check_all("phi K H psi = phi - psi", &Residuals::phiKHpsi);

  /// Two more that the factorization needs. \f$G = PH^*D^{-1}\f$ gives
  /// \f$PH^* = GD\f$ (block by block), and \f$P^+ = \bar\tau P = P - GHP = P - GDG^*\f$ turns
  /// the Riccati equation \f$P = \mathcal E_\phi P^+\mathcal E_\phi^* + M\f$ of lesson 6 into
  /// \f[ M = P - \mathcal E_\phi P\,\mathcal E_\phi^* + KDK^* . \f]
  /// Put \f$\mathcal E_\phi = I - \phi^{-1}\f$ in it and multiply by \f$\phi\f$ and
  /// \f$\phi^*\f$: with \f$\tilde\phi = \phi - I\f$,
  /// \f[ \phi M\phi^* = P + \tilde\phi P + P\tilde\phi^* + \phi KDK^*\phi^* , \f]
  /// the articulated analogue of \f$\phi M\phi^* = R + \tilde\phi R + R\tilde\phi^*\f$ of
  /// lesson 5.
  check_all("P H* = G D", &Residuals::PH_GD);
  check_all("M = P - E_phi P E_phi* + K D K*", &Residuals::riccati);
  check_all("phi M phi* = P + phi~ P + P phi~* + phi K D K* phi*", &Residuals::phiMphi);

  /// ## 3. The innovations factorization
  ///
  /// Sandwich the last identity between \f$H\f$ and \f$H^*\f$. \f$HPH^* = D\f$;
  /// \f$\tilde\phi = \phi\mathcal E_\phi\f$ (from \f$\phi = I + \phi\mathcal E_\phi\f$), so
  /// \f$H\tilde\phi PH^* = H\phi\mathcal E_\phi GD = H\phi KD\f$; hence
  /// \f[ \mathcal M = H\phi M\phi^*H^* = D + H\phi KD + DK^*\phi^*H^* + H\phi KDK^*\phi^*H^*
  ///     = [I + H\phi K]\, D\, [I + H\phi K]^* . \f]
  /// \f$(H\phi K)(i,j) = H(i)\phi(i,j+1)\phi(j+1,j)G(j) = H(i)\phi(i,j)G(j)\f$ for \f$i > j\f$
  /// and 0 otherwise: the factor is block lower triangular with identity blocks on its
  /// diagonal, and this is the block \f$LDL^*\f$ factorization of \f$\mathcal M\f$, its pivots
  /// the articulated hinge inertias \f$D(k)\f$. Hence \f$\det\mathcal M = \prod_k\det D(k)\f$,
  /// and \f$\mathcal M > 0\f$ exactly when every \f$D(k) > 0\f$. Jain calls it the
  /// *innovations* factorization after the Kalman filter it mirrors: the Riccati recursion
  /// is the filter's covariance recursion, \f$D\f$ the covariance of the innovations and
  /// \f$G\f$ the Kalman gain (Jain 2011, chapter 7).
  ///
  /// *Now do exercise 7.5* (`soa::ex07::log_det_mass_matrix`): \f$\log\det\mathcal M\f$ from
  /// the pivots \f$D(k)\f$ alone.
  checks.section("3. innovations factorization");
  check_all("M = [I + H phi K] D [I + H phi K]*", &Residuals::factorization);
  check_all("[I + H phi K] block unit lower triangular", &Residuals::triangular);
  check_all("log det M = sum_k log det D(k) (/ cond(M))", &Residuals::determinant);
  if (!scenes.empty()) {
    const soa::InnovationsOperators io = soa::InnovationsOperators::build(scenes[0].m, scenes[0].x);
    std::printf("  the double pendulum (body 1 = the tip):\n");
    print("[I + H phi K]", io.factor());
    print("D", io.D);
    print("M = [I + H phi K] D [I + H phi K]*", io.mass_matrix());
  }

  /// ## 4. Inverting the factor and the mass matrix
  ///
  /// The inverse of the factor is again a closed-form operator:
  /// \f[ [I + H\phi K][I - H\psi K] = I + H(\phi - \psi - \phi KH\psi)K = I , \f]
  /// by section 2; so \f$[I + H\phi K]^{-1} = I - H\psi K\f$, and inverting the
  /// factorization,
  /// \f[ \mathcal M^{-1} = [I - H\psi K]^*\, D^{-1}\, [I - H\psi K] . \f]
  /// Only \f$D^{-1}\f$ is inverted: n small blocks \f$D(k)\f$ of size \f$n_k \le 6\f$. The
  /// comparison with Eigen's dense inverse of \f$\mathcal M\f$ (from lesson 5) is scaled by
  /// cond(M): the dense inverse itself is only that accurate.
  ///
  /// *Now do exercise 7.2* (`soa::ex07::innovations_factor`): the factor, its inverse in
  /// closed form and \f$D\f$, checked against \f$\mathcal M = LDL^*\f$.
  checks.section("4. inverse of the factor and of M");
  check_all("[I + H phi K]^-1 = I - H psi K (both products = I)", &Residuals::factor_inverse);
  check_all("[I - H psi K]* D^-1 [I - H psi K] = inv(M) (/ cond(M))", &Residuals::inverse);

  /// ### The O(N²) algorithm
  ///
  /// Apply the inverse to a hinge force \f$T\f$ and read it right to left. Let
  /// \f$z = \psi KT\f$: \f$z = \mathcal E_\psi z + KT\f$, and with \f$\epsilon = T - Hz\f$,
  /// \f$z^+(k) = z(k) + G(k)\epsilon(k)\f$, tip to base,
  /// \f[ z(k) = \phi(k,k-1)\,z^+(k-1), \quad \epsilon(k) = T(k) - H(k)z(k), \quad
  ///     \nu(k) = D^{-1}(k)\,\epsilon(k), \quad z^+(k) = z(k) + G(k)\,\epsilon(k) , \f]
  /// so \f$\nu = D^{-1}[I - H\psi K]T\f$. Then \f$\dot\beta = [I - H\psi K]^*\nu = \nu -
  /// K^*\alpha\f$ with \f$\alpha = \psi^*H^*\nu\f$, i.e. \f$\alpha = \mathcal E_\psi^*\alpha +
  /// H^*\nu\f$; base to tip, with \f$\alpha^+(k) = \phi^*(k+1,k)\,\alpha(k+1)\f$,
  /// \f[ \dot\beta(k) = \nu(k) - G^*(k)\,\alpha^+(k), \qquad
  ///     \alpha(k) = \alpha^+(k) + H^*(k)\,\dot\beta(k) , \f]
  /// since \f$\bar\tau^*(k)\alpha^+(k) + H^*(k)\nu(k) = \alpha^+(k) + H^*(k)\dot\beta(k)\f$.
  /// These are the recursions of the articulated body forward dynamics of lesson 8 without
  /// the velocity and gravity terms: \f$O(N)\f$ per column. With \f$T = e_j\f$ for every
  /// hinge coordinate j they give \f$\mathcal M^{-1}\f$ column by column, \f$O(N^2)\f$ in all,
  /// with the Riccati recursion run once and no \f$\mathcal M\f$, no dense operator and no
  /// 6x6 \f$\phi\f$ formed: soa::reference::mass_matrix_inverse() and
  /// soa::reference::mass_matrix_inverse_times() (lib/include/soa/reference/) as written here.
  /// Their fast form soa::mass_matrix_inverse() runs all columns at once and uses the
  /// structure: in the tip-to-base pass only the columns of the hinges outboard of k are
  /// non-zero, in the base-to-tip pass only rows k..1 are needed (the rest by symmetry).
  /// From the command line: `soa mass-matrix --inverse SCENE.json`.
  ///
  /// *Now do exercise 7.4* (`soa::ex07::solve`): \f$\mathcal M y = b\f$ by these two sweeps,
  /// then *exercise 7.11* (`soa::ex07::sweep_operator`): the dense operator of the first
  /// sweep, its blocks derived from the recursion.
  check_all("mass_matrix_inverse (O(N^2)) = [I - H psi K]* D^-1 [I - H psi K]", &Residuals::on2);
  check_all("mass_matrix_inverse (O(N^2)) = inv(M) (/ cond(M))", &Residuals::on2_dense);
  for (std::size_t i = 0; i < scenes.size(); ++i)
    std::printf("  %-16s cond(M) = %.3e, kappa = %.3e\n", scenes[i].name.c_str(), scene_r[i].cond,
                scene_r[i].kappa);
  std::printf("  random chains: worst cond(M) = %.3e, worst kappa = %.3e\n", random_r.cond,
              random_r.kappa);

  /// ## 5. Accuracy against the length of the chain
  ///
  /// How many digits does \f$\mathcal M^{-1}\f$ keep as the chain grows? On the chain of
  /// 0.1 m, 0.2 kg links with hinges about x and y in turn (lesson 3's 50-link chain, here
  /// with n = 2 to 200 links), three inverses in double precision: the \f$O(N^2)\f$ algorithm,
  /// Eigen's dense inverse of the mass matrix (LU, from the composite bodies of lesson 5),
  /// and the reference, the \f$O(N^2)\f$ algorithm in long double (\f$\varepsilon = 1.1\cdot
  /// 10^{-19}\f$), itself checked against Eigen's dense inverse in long double. The relative
  /// error \f$\|X - X_{\rm ref}\|/\|X_{\rm ref}\|\f$ (also of the \f$\Upsilon\f$-based inverse of
  /// section 7, the fourth curve) of an inverse computed by a backward
  /// stable method is bounded by about \f$n\,\varepsilon\,\mathrm{cond}(\mathcal M)\f$; the
  /// dense inverse reaches it, since rounding \f$\mathcal M\f$ alone costs that much. The
  /// \f$O(N^2)\f$ algorithm never rounds \f$\mathcal M\f$: its error follows the articulated
  /// quantities \f$D(k)\f$ and \f$G(k)\f$ instead, and stays below the dense one here.
  checks.section("5. accuracy against n");
  std::ofstream csv(out / "l7_minv_error.csv");
  csv << "n,cond,err_on2,err_dense,eps_cond,on2_vs_dense_over_eps_n_cond,err_upsilon\n";
  double worst_on2 = 0, worst_on2_n = 0, worst_dense = 0, worst_vs = 0, worst_ref = 0;
  double worst_ups = 0;
  int n_on2_better = 0, n_cases = 0;
  for (const int n : {2, 3, 5, 7, 10, 15, 20, 30, 50, 70, 100, 150, 200}) {
    State x;
    const Model m = link_chain(n, x);
    const MatX Mass = mass_matrix(m, x);
    const double c = cond(Mass);
    const MatX on2 = inverse_on2(m, x);
    const MatX dense = Mass.inverse();
    const MatX on2u = inverse_upsilon(m, x);
    using L = long double;
    const soa::ModelT<L> mL = cast_model<L>(m);
    const soa::StateT<L> xL{x.theta.cast<L>(), x.beta.cast<L>()};
    const soa::MatX<L> ref = inverse_on2(mL, xL);
    const soa::MatX<L> ref_dense = mass_matrix(mL, xL).inverse();
    const L ref_norm = ref.norm();
    const double err_on2 = double((on2.cast<L>() - ref).norm() / ref_norm);
    const double err_dense = double((dense.cast<L>() - ref).norm() / ref_norm);
    const double err_ups = double((on2u.cast<L>() - ref).norm() / ref_norm);
    worst_ups = std::max(worst_ups, err_ups / (kEps * n * c));
    const double vs = (on2 - dense).norm() / dense.norm() / (kEps * n * c);
    worst_on2 = std::max(worst_on2, err_on2 / (kEps * n * c));
    worst_on2_n = std::max(worst_on2_n, err_on2 / (kEps * n));
    worst_dense = std::max(worst_dense, err_dense / (kEps * n * c));
    worst_vs = std::max(worst_vs, vs);
    worst_ref = std::max(
        worst_ref, double((ref_dense - ref).norm() / ref_norm) / (double(soa::eps<L>()) * n * c));
    n_on2_better += err_on2 <= err_dense ? 1 : 0;
    ++n_cases;
    std::printf(
        "  n = %3d  cond(M) = %.3e  error O(N^2) %.2e  Upsilon %.2e  dense %.2e  eps cond %.2e\n",
        n, c, err_on2, err_ups, err_dense, kEps * c);
    char line[200];
    std::snprintf(line, sizeof line, "%d,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e\n", n, c, err_on2, err_dense,
                  kEps * c, vs, err_ups);
    csv << line;
  }
  csv.close();
  checks.check("reference: long double O(N^2) = long double inv(M) (/ eps_ld n cond)", worst_ref,
               4.0);
  checks.check("O(N^2) error <= n eps cond(M) (worst ratio)", worst_on2, 1.0);
  checks.check("dense inverse error <= n eps cond(M) (worst ratio)", worst_dense, 1.0);
  checks.check("Upsilon-based O(N^2) error <= n eps cond(M) (worst ratio)", worst_ups, 1.0);
  checks.check("this chain: O(N^2) error <= 4 n eps, whatever cond(M) (worst / n eps)", worst_on2_n,
               4.0);
  checks.check("O(N^2) = dense inverse to n eps cond(M) (worst ratio)", worst_vs, 2.0);
  checks.check("O(N^2) at least as accurate as the dense inverse in " +
                   std::to_string(n_on2_better) + " of " + std::to_string(n_cases) + " chains",
               n_on2_better * 4 >= n_cases * 3);
  checks.check("l7_minv_error.csv written", bool(csv));
  checks.check("figure written: l7_minv_error.png",
               soa::lesson::plot("l7_minv_error.gp", out, "l7_minv_error.png"));

  /// What the numbers say. cond(M) of this chain grows like a power of n (the whole chain
  /// swinging about the base gives \f$\mathcal M\f$ a large eigenvalue, the short light links
  /// at the tip small ones), and the error of the dense inverse grows with it, staying a
  /// little below \f$\varepsilon\,\mathrm{cond}(\mathcal M)\f$. The error of the
  /// \f$O(N^2)\f$ algorithm does not follow cond(M) on this chain: it stays within a few
  /// \f$n\varepsilon\f$, because it never rounds \f$\mathcal M\f$ and works with the
  /// \f$D(k)\f$, which stay of the size of one link's inertia (lesson 6). The bound
  /// \f$n\,\varepsilon\,\mathrm{cond}(\mathcal M)\f$ is what any method may lose; the
  /// recursions lose less when the articulated quantities are well conditioned. Lesson 8
  /// solves \f$\mathcal M\dot\beta = T - \mathcal C\f$ with one column's worth of the same
  /// recursions, \f$O(N)\f$.

  /// ## 6. The operator \f$\Omega\f$ and its diagonal \f$\Upsilon\f$
  ///
  /// The inverse factor acting on \f$H\phi\f$: by section 2, \f$H\psi KH\phi = H(\phi - \psi)\f$,
  /// so \f$[I - H\psi K]H\phi = H\psi\f$. Between \f$\phi^*H^*\f$ and \f$H\phi\f$ the inverse
  /// factorization of section 4 becomes
  /// \f[ \phi^*H^*\mathcal M^{-1}H\phi = (H\phi)^*[I - H\psi K]^*D^{-1}[I - H\psi K]H\phi
  ///     = \psi^*H^*D^{-1}H\psi \equiv \Omega , \f]
  /// the articulated analogue of \f$\phi M\phi^*\f$ (Jain 2011, chapter 7). \f$\Omega\f$ is a
  /// sum over bodies, \f$\Omega(i,j) = \sum_{k \ge \max(i,j)}\psi^*(k,i)\,H^*(k)D^{-1}(k)H(k)\,
  /// \psi(k,j)\f$. For \f$i \ge j\f$, \f$\psi(k,j) = \psi(k,i)\psi(i,j)\f$, so
  /// \f$\Omega(i,j) = \Upsilon(i)\,\psi(i,j)\f$ with
  /// \f$\Upsilon(i) = \sum_{k \ge i}\psi^*(k,i)H^*(k)D^{-1}(k)H(k)\psi(k,i) = \Omega(i,i)\f$:
  /// with \f$\Upsilon = \mathrm{diag}(\Upsilon(k))\f$ and \f$\tilde\psi = \psi - I\f$ (strictly
  /// lower triangular),
  /// \f[ \Omega = \Upsilon + \tilde\psi^*\Upsilon + \Upsilon\tilde\psi . \f]
  /// Splitting off the term \f$k = i\f$ of the sum gives the backward Lyapunov recursion, base
  /// to tip, with \f$\psi(k+1,k) = \phi(k+1,k)\bar\tau(k)\f$:
  /// \f[ \Upsilon(n+1) = 0, \qquad \Upsilon(k) = \psi^*(k+1,k)\,\Upsilon(k+1)\,\psi(k+1,k) +
  ///     H^*(k)D^{-1}(k)H(k) , \f]
  /// the mirror image of the Riccati recursion for \f$P\f$ (tip to base, \f$\psi\f$ in place of
  /// \f$\psi^*\f$). Written with \f$\Upsilon^+(k) = \phi^*(k+1,k)\Upsilon(k+1)\phi(k+1,k)\f$ and
  /// \f$Y = \Upsilon^+(k)G(k)\f$, \f$\bar\tau^*\Upsilon^+\bar\tau + H^*D^{-1}H = \Upsilon^+ -
  /// H^*Y^* - YH + H^*[D^{-1} + G^*Y]H\f$: one transform of a symmetric 6x6 (no 6x6
  /// \f$\phi\f$: soa::transpose_transform_symmetric()) and products with the \f$6 \times n_k\f$
  /// blocks, \f$O(N)\f$ in all (soa::upsilons(), soa::upsilon_step()). The bracket is a diagonal
  /// block of \f$\mathcal M^{-1}\f$ (exercise 7.3): \f$H\psi K\f$ is strictly lower triangular,
  /// so in \f$\mathcal M^{-1} = D^{-1} - D^{-1}H\psi K - K^*\psi^*H^*D^{-1} + K^*\Omega K\f$ only
  /// the first and last terms reach the diagonal,
  /// \f[ \mathcal M^{-1}(k,k) = D^{-1}(k) + G^*(k)\,\Upsilon^+(k)\,G(k) . \f]
  ///
  /// *Now do exercises 7.3* (`soa::ex07::minv_diagonal`: the diagonal blocks of
  /// \f$\mathcal M^{-1}\f$ in \f$O(N)\f$), *7.6* (`soa::ex07::omega_from_upsilon`:
  /// \f$\Omega\f$ block by block from \f$\Upsilon\f$) and *7.10*
  /// (`soa::ex07::minv_zero_pattern`: predict, from the hinge types alone, which blocks of
  /// \f$\mathcal M^{-1}\f$ are zero).
  checks.section("6. Omega and Upsilon");
  check_all("phi* H* inv(M) H phi = psi* H* D^-1 H psi (/ cond(M))", &Residuals::omega);
  check_all("Omega = Upsilon + psi~* Upsilon + Upsilon psi~", &Residuals::omega_split);
  check_all("upsilons() (O(N), base to tip) = diagonal blocks of Omega", &Residuals::upsilon_rec);
  check_all("D^-1(k) + G*(k) Upsilon+(k) G(k) = M^-1(k,k)", &Residuals::minv_diag);
  if (!scenes.empty()) {
    const Named& s = scenes[0];
    Workspace ws(s.m);
    soa::update_phi(s.m, s.x.theta, ws);
    soa::Upsilon ups(s.m);
    soa::upsilons(s.m, s.x, ws, ups);
    std::printf("  the double pendulum, from upsilons():\n");
    for (int k = s.m.n(); k >= 1; --k) {
      const std::string name = "Upsilon(" + std::to_string(k) + ")";
      print(name.c_str(), ups.Upsilon[std::size_t(k - 1)]);
    }
    for (int k = s.m.n(); k >= 1; --k)
      std::printf("  M^-1(%d,%d) = %.6f from Upsilon, %.6f from the inverse of M\n", k, k,
                  ups.Minv_kk[std::size_t(k - 1)](0, 0),
                  mass_matrix(s.m, s.x).inverse()(s.m.body(k).v_offset, s.m.body(k).v_offset));
  }

  /// ## 7. \f$\mathcal M^{-1}\f$ in \f$O(N^2)\f$ from \f$\Upsilon\f$
  ///
  /// The off-diagonal blocks of the same expansion. For \f$k > i\f$ (hinge k inboard of hinge
  /// i), \f$(D^{-1}H\psi K)(k,i) = D^{-1}(k)H(k)\psi(k,i+1)\phi(i+1,i)G(i)\f$, the term
  /// \f$K^*\psi^*H^*D^{-1}\f$ is zero there (it is strictly upper triangular), and
  /// \f$(K^*\Omega K)(k,i) = G^*(k)\phi^*(k+1,k)\,\Omega(k+1,i+1)\,\phi(i+1,i)G(i)\f$ with
  /// \f$\Omega(k+1,i+1) = \Upsilon(k+1)\psi(k+1,k)\psi(k,i+1)\f$. Since
  /// \f$\phi^*(k+1,k)\Upsilon(k+1)\psi(k+1,k) = \Upsilon^+(k)\bar\tau(k)\f$ and
  /// \f$G^*\Upsilon^+\bar\tau = G^*\Upsilon^+ - G^*\Upsilon^+GH\f$,
  /// \f[ \mathcal M^{-1}(k,i) = L(k)\,z_i(k), \qquad L(k) = G^*(k)\Upsilon^+(k) -
  ///     \mathcal M^{-1}(k,k)\,H(k), \qquad z_i(k) = \psi(k,i+1)\,\phi(i+1,i)\,G(i) , \f]
  /// and \f$z_i\f$ is carried tip to base by one propagation per column,
  /// \f$z_i(i+1) = \phi(i+1,i)G(i)\f$, \f$z_i(k+1) = \phi(k+1,k)[z_i(k) - G(k)H(k)z_i(k)]\f$.
  /// The algorithm: the Riccati recursion tip to base; \f$\Upsilon\f$, \f$\mathcal M^{-1}(k,k)\f$
  /// and \f$L(k)\f$ base to tip, \f$O(N)\f$; then tip to base, all columns at once, \f$O(N)\f$
  /// per column, \f$O(N^2)\f$ in all; the upper triangle by symmetry. No \f$\mathcal M\f$, no
  /// dense operator, no 6x6 \f$\phi\f$ (\f$z\f$ is moved as rows of an \f$n_v \times 6\f$
  /// block, by \f$(R, l)\f$). soa::mass_matrix_inverse_upsilon(); `make bench` times it
  /// against soa::mass_matrix_inverse() (MassMatrixInverseUpsilon and MassMatrixInverse in
  /// `build/bench/forward_bench.json`). Its accuracy on the link chains is the fourth curve
  /// of section 5.
  ///
  /// *Now do exercise 7.7* (`soa::ex07::minv_from_upsilon`): this algorithm.
  checks.section("7. M^-1 in O(N^2) from Upsilon");
  check_all("mass_matrix_inverse_upsilon = [I - H psi K]* D^-1 [I - H psi K]", &Residuals::on2u);
  check_all("mass_matrix_inverse_upsilon = mass_matrix_inverse (/ n cond(M))",
            &Residuals::on2u_sweep);
  check_all("mass_matrix_inverse_upsilon = inv(M) (/ cond(M))", &Residuals::on2u_dense);

  /// ## 8. The operational-space inverse inertia in \f$O(N)\f$
  ///
  /// A frame F fixed on body k at \f${}^{O_k}T_F\f$ (an end effector, a tool) has the Jacobian
  /// \f$J = B^*\phi^*H^*\f$ of lesson 3, \f$B^*\f$ picking body k and moving it to F by
  /// \f$\phi^*(O_k,F)\f$. Its operational-space inverse inertia, the map from a spatial force
  /// at F to the spatial acceleration it causes there, is then a single block of
  /// \f$\Omega\f$:
  /// \f[ \Lambda^{-1} = J\mathcal M^{-1}J^* = B^*\,\phi^*H^*\mathcal M^{-1}H\phi\,B = B^*\Omega B
  ///     = \phi^*(O_k,F)\,\Upsilon(k)\,\phi(O_k,F) , \f]
  /// for the tip (k = 1) \f$\phi^*(O_1,F)\Upsilon(1)\phi(O_1,F)\f$: the Riccati recursion tip
  /// to base and the \f$\Upsilon\f$ recursion base to tip down to body k, \f$O(N)\f$, against
  /// \f$O(N^2)\f$ for \f$\mathcal M^{-1}\f$ and \f$O(N)\f$ more for \f$J\f$ in the dense form.
  /// soa::operational_space_inverse_inertia(); from the command line,
  /// `soa mass-matrix --operational BODY SCENE.json`. Checked on every body of every chain
  /// with the frame of tool_frame(), against \f$J\f$ of soa::jacobian() and the dense inverse.
  ///
  /// *Now do exercise 7.8* (`soa::ex07::operational_inverse_inertia`): the \f$\Upsilon\f$
  /// recursion down to body k, then the move to F.
  checks.section("8. operational space");
  check_all("phi*(O_k,F) Upsilon(k) phi(O_k,F) = J inv(M) J*, every body (/ cond(M))",
            &Residuals::opspace);
  if (scenes.size() > 1) {
    const Named& s = scenes[1];
    Workspace ws(s.m);
    soa::update_phi(s.m, s.x.theta, ws);
    soa::Upsilon ups(s.m);
    soa::Mat6<double> op;
    soa::operational_space_inverse_inertia(s.m, s.x, ws, ups, 1, Pose(), op);
    std::printf("  %s, the tip frame O_1:\n", s.name.c_str());
    print("J M^-1 J* = Upsilon(1)", op);
  }

  /// ## 9. Innovations coordinates
  ///
  /// With \f$\eta = [I + H\phi K]^*\beta\f$ the factorization of section 3 diagonalizes the
  /// kinetic energy:
  /// \f[ \tfrac12\beta^*\mathcal M\beta = \tfrac12\beta^*[I + H\phi K]\,D\,[I + H\phi K]^*\beta
  ///     = \tfrac12\eta^*D\eta = \tfrac12\sum_k \eta^*(k)D(k)\eta(k) , \f]
  /// a sum of decoupled terms, one per hinge, each weighted by its articulated hinge inertia;
  /// back, \f$\beta = [I - H\psi K]^*\eta\f$ (section 4). \f$\eta\f$ in \f$O(N)\f$:
  /// \f$\eta = \beta + K^*\phi^*H^*\beta = \beta + K^*V\f$ with \f$V = \phi^*H^*\beta\f$ the
  /// velocities of lesson 3, so \f$\eta(k) = \beta(k) + G^*(k)\phi^*(k+1,k)V(k+1)\f$; and since
  /// \f$G^*(k)H^*(k) = D^{-1}HPH^* = I\f$ and \f$V(k) = \phi^*(k+1,k)V(k+1) + H^*(k)\beta(k)\f$,
  /// \f[ \eta(k) = G^*(k)\,V(k) , \f]
  /// one product per body after the velocity recursion (innovations_coordinates()). Checked
  /// at the velocity \f$\beta_i = \cos(1 + i)\f$ of test_velocity().
  ///
  /// *Now do exercise 7.9* (`soa::ex07::innovations_coordinates`): \f$\eta\f$ in \f$O(N)\f$,
  /// then *exercise 7.12* (`soa::ex07::beta_from_eta`): find the bug in the way back,
  /// \f$\beta = [I - H\psi K]^*\eta\f$, base to tip.
  checks.section("9. innovations coordinates");
  check_all("1/2 beta* M beta = 1/2 eta* D eta", &Residuals::eta_energy);
  check_all("eta(k) = G*(k) V(k) (O(N)) = [I + H phi K]* beta", &Residuals::eta_rec);
  check_all("[I - H psi K]* eta = beta", &Residuals::eta_back);

  return checks.finish();
}
