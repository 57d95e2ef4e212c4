// Property tests of the operator Upsilon and what is built on it (lesson 7, sections 6-9),
// on soa::test::kCases random chains of every hinge type at random states, from fixed seeds:
// - phi* H* M^-1 H phi = psi* H* D^-1 H psi = Omega = Upsilon + psi~* Upsilon + Upsilon psi~,
//   and the O(N) recursion soa::upsilons() against the dense blocks of Omega;
// - soa::transpose_transform_symmetric() = phi* U phi;
// - soa::mass_matrix_inverse_upsilon() (O(N^2)) against soa::mass_matrix_inverse() and the
//   dense inverse of M;
// - soa::operational_space_inverse_inertia() (O(N)) against the dense J M^-1 J*;
// - the innovations coordinates eta = [I + H phi K]* beta: 1/2 beta* M beta = 1/2 eta* D eta,
//   and eta(k) = G*(k) V(k).
// Residuals are relative to the size of the terms and divided by eps, the size 6n of the
// operators, and kappa = max_k |P(k)| |D^-1(k)| or cond(M) where an inverse of M is compared;
// each test reports its worst case.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "property.hpp"
#include "random_chain.hpp"
#include "soa/chain.hpp"
#include "soa/chain/mass_matrix_inverse_upsilon.hpp"
#include "soa/chain/operational_space.hpp"

namespace {

using soa::test::kCases;
using soa::test::Random;
using soa::test::Worst;
using MatX = soa::MatX<double>;
using VecX = soa::VecX<double>;
using Mat6 = soa::Mat6<double>;
constexpr double kEps = soa::eps<double>();

double at_least_1(std::initializer_list<double> norms) {
  double s = 1;
  for (double v : norms) s = std::max(s, v);
  return s;
}

// A random chain of 1 to n_max bodies (hinge types in turn) at a random state, its innovations
// operators, the mass matrix by composite bodies (lesson 5) and its condition number.
struct Case {
  soa::Model m;
  soa::State x;
  soa::InnovationsOperators io;
  soa::Workspace ws;
  MatX M;
  double kappa = 1, n6 = 6, cond = 1;
  Case(Random<double>& rnd, int i, int n_max = 8)
      : m(soa::test::random_chain(rnd, 1 + i % n_max)), ws(m) {
    x = soa::test::random_state(rnd, m);
    io = soa::InnovationsOperators::build(m, x);
    soa::update_phi(m, x.theta, ws);
    std::vector<soa::SpatialInertia> R(std::size_t(m.n()));
    soa::mass_matrix_crb(m, x, ws, R, M);
    for (int k = 1; k <= m.n(); ++k) {
      const int r = 6 * (k - 1), c = m.body(k).v_offset, nk = m.body(k).hinge.nv();
      kappa = std::max(kappa, io.P.block(r, r, 6, 6).norm() * io.D_inv.block(c, c, nk, nk).norm());
    }
    n6 = 6.0 * m.n();
    const VecX ev = Eigen::SelfAdjointEigenSolver<MatX>(M, Eigen::EigenvaluesOnly).eigenvalues();
    cond = ev.maxCoeff() / ev.minCoeff();
  }
};

TEST(innovations_Upsilon, OmegaIsPhiStarHStarMinvHPhi) {
  Random<double> rnd(131);
  Worst omega("|phi* H* inv(M) H phi - Omega| / (|Omega| eps 6n cond(M))");
  Worst split("|Omega - (Ups + psi~* Ups + Ups psi~)| / (eps 6n kappa |terms|)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const MatX& phi = c.io.op.phi;
    const MatX& H = c.io.op.H;
    const MatX Omega = c.io.Omega();
    const MatX lhs = phi.transpose() * H.transpose() * c.M.inverse() * H * phi;
    omega.add((lhs - Omega).norm() / (at_least_1({Omega.norm()}) * kEps * c.n6 * c.cond), i);
    const MatX U = c.io.Upsilon();
    const MatX pt = c.io.psi - MatX::Identity(U.rows(), U.cols());
    const MatX rhs = U + pt.transpose() * U + U * pt;
    split.add((Omega - rhs).norm() /
                  (kEps * c.n6 * c.kappa * at_least_1({Omega.norm(), 2 * pt.norm() * U.norm()})),
              i);
  }
  EXPECT_LE(omega.value(), 4.0);
  EXPECT_LE(split.value(), 4.0);
}

TEST(innovations_Upsilon, RecursionMatchesDenseBlocks) {
  Random<double> rnd(137);
  Worst w("|upsilons() - diag blocks of Omega| / (|Omega| eps 6n kappa)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    soa::Upsilon u(c.m);
    soa::upsilons(c.m, c.x, c.ws, u);
    const MatX Omega = c.io.Omega();
    double err = 0;
    for (int k = 1; k <= c.m.n(); ++k)
      err = std::max(
          err,
          (u.Upsilon[std::size_t(k - 1)] - Omega.block(6 * (k - 1), 6 * (k - 1), 6, 6)).norm());
    w.add(err / (at_least_1({Omega.norm()}) * kEps * c.n6 * c.kappa), i);
  }
  EXPECT_LE(w.value(), 4.0);
}

TEST(innovations_Upsilon, TransposeTransformSymmetric) {
  Random<double> rnd(139);
  Worst w("|transpose_transform_symmetric - phi* U phi| / (eps |phi|^2 |U|)");
  for (int i = 0; i < kCases; ++i) {
    const soa::Phi phi = rnd.phi();
    Mat6 A;
    for (int r = 0; r < 6; ++r)
      for (int q = 0; q < 6; ++q) A(r, q) = rnd.normal();
    const Mat6 U = A * A.transpose();
    Mat6 out;
    soa::transpose_transform_symmetric(phi, U, out);
    const Mat6 P = phi.matrix();
    const Mat6 ref = P.transpose() * U * P;
    w.add((out - ref).norm() / (kEps * P.squaredNorm() * U.norm()), i);
  }
  EXPECT_LE(w.value(), 4.0);
}

TEST(innovations_InverseUpsilon, EqualsColumnSweepAndDenseInverse) {
  Random<double> rnd(149);
  Worst sweep("|mass_matrix_inverse_upsilon - mass_matrix_inverse| / (|Minv| eps n cond(M))");
  Worst dense("|mass_matrix_inverse_upsilon - inv(M)| / (|inv(M)| eps n cond(M))");
  Worst sym("|Minv - Minv*| (exact symmetry)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i, 16);
    soa::MassMatrixInverseUpsilon wu(c.m);
    soa::MassMatrixInverse wc(c.m);
    MatX Mu, Mc;
    soa::mass_matrix_inverse_upsilon(c.m, c.x, c.ws, wu, Mu);
    soa::mass_matrix_inverse(c.m, c.x, c.ws, wc, Mc);
    const MatX ref = c.M.inverse();
    const double unit = kEps * c.m.nv() * c.cond;
    sweep.add((Mu - Mc).norm() / (Mc.norm() * unit), i);
    dense.add((Mu - ref).norm() / (ref.norm() * unit), i);
    sym.add((Mu - Mu.transpose()).norm(), i);
  }
  EXPECT_LE(sweep.value(), 4.0);
  EXPECT_LE(dense.value(), 4.0);
  EXPECT_EQ(sym.value(), 0.0);
}

TEST(innovations_InverseUpsilon, WorkspaceReusedAcrossStates) {
  // One workspace, many states of one chain: sized once, the same answers as a fresh one.
  Random<double> rnd(151);
  const soa::Model m = soa::test::random_chain(rnd, 14);
  soa::Workspace ws(m);
  soa::MassMatrixInverseUpsilon w(m);
  Worst d("|reused workspace - fresh workspace| (exact)");
  MatX A, B;
  for (int i = 0; i < 50; ++i) {
    const soa::State x = soa::test::random_state(rnd, m);
    soa::update_phi(m, x.theta, ws);
    soa::mass_matrix_inverse_upsilon(m, x, ws, w, A);
    soa::MassMatrixInverseUpsilon fresh(m);
    soa::mass_matrix_inverse_upsilon(m, x, ws, fresh, B);
    d.add((A - B).norm(), i);
  }
  EXPECT_EQ(d.value(), 0.0);
}

TEST(innovations_OperationalSpace, EqualsDenseJMinvJStar) {
  Random<double> rnd(157);
  Worst w("|phi*(O_k,F) Ups(k) phi(O_k,F) - J inv(M) J*| / (|J inv(M) J*| eps 6n cond(M))");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const int k = 1 + int(rnd.engine()() % unsigned(c.m.n()));
    const soa::Pose frame(rnd.rotation(), rnd.vec3());
    soa::Workspace ws(c.m);
    soa::update_phi(c.m, c.x.theta, ws);
    soa::update_poses(c.m, ws);
    Eigen::Matrix<double, 6, Eigen::Dynamic> J;
    soa::jacobian(c.m, c.x.theta, ws, k, frame, J);
    const Mat6 ref = J * c.M.inverse() * J.transpose();
    soa::Upsilon u(c.m);
    Mat6 out;
    soa::operational_space_inverse_inertia(c.m, c.x, ws, u, k, frame, out);
    w.add((out - ref).norm() / (at_least_1({ref.norm()}) * kEps * c.n6 * c.cond), i);
  }
  EXPECT_LE(w.value(), 4.0);
}

TEST(innovations_Coordinates, EtaDecouplesKineticEnergy) {
  Random<double> rnd(163);
  Worst energy("|1/2 eta* D eta - 1/2 beta* M beta| / (eps 6n kappa |terms|)");
  Worst rec("|G*(k) V(k) - [I + H phi K]* beta| / (eps 6n kappa |terms|)");
  Worst back("|[I - H psi K]* eta - beta| / (eps 6n kappa |terms|)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const VecX& beta = c.x.beta;
    const VecX eta = c.io.eta(beta);
    const double T = 0.5 * beta.dot(c.M * beta), Te = 0.5 * eta.dot(c.io.D * eta);
    const double s = kEps * c.n6 * c.kappa;
    energy.add(std::abs(T - Te) / (s * at_least_1({c.M.norm() * beta.squaredNorm(),
                                                   c.io.D.norm() * eta.squaredNorm()})),
               i);
    // O(N): eta(k) = G*(k) V(k), V from the velocity recursion of lesson 3.
    soa::Workspace ws(c.m);
    soa::update_phi(c.m, c.x.theta, ws);
    soa::update_velocities(c.m, c.x, ws);
    VecX eta_n(c.m.nv());
    for (int k = 1; k <= c.m.n(); ++k) {
      const soa::Body& B = c.m.body(k);
      eta_n.segment(B.v_offset, B.hinge.nv()) =
          c.io.G.block(6 * (k - 1), B.v_offset, 6, B.hinge.nv()).transpose() *
          ws.V[std::size_t(k - 1)].vector();
    }
    const MatX L = c.io.factor();
    rec.add((eta_n - eta).norm() / (s * at_least_1({L.norm() * beta.norm()})), i);
    const MatX Li = c.io.factor_inverse();
    back.add((Li.transpose() * eta - beta).norm() / (s * at_least_1({Li.norm() * eta.norm()})), i);
  }
  EXPECT_LE(energy.value(), 4.0);
  EXPECT_LE(rec.value(), 4.0);
  EXPECT_LE(back.value(), 4.0);
}

}  // namespace
