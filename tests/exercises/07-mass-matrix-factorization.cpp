// Lesson 7 exercise tests: each exercise of exercises/07-mass-matrix-factorization/exercises.hpp
// against the library, on soa::test::kCases random chains of 1 to 8 bodies of every hinge type
// at random states, from the fixed seed. Built against the solutions (ctest) and against the
// students' stubs (make exercises). Residuals are relative to the size of the terms and divided
// by eps, the size 6n of the operators and kappa = max_k |P(k)| |D^-1(k)|, or cond(M) where a
// result is compared with an inverse or determinant of M.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "exercises.hpp"
#include "property.hpp"
#include "random_chain.hpp"
#include "soa/chain/mass_matrix_inverse_upsilon.hpp"

namespace {

using soa::test::kCases;
using soa::test::Random;
using soa::test::Worst;
using MatX = soa::MatX<double>;
using VecX = soa::VecX<double>;

constexpr double kEps = soa::eps<double>();

// A random chain at a random state, with the library's innovations operators, the mass matrix
// by composite bodies and its O(N^2) inverse.
struct Case {
  soa::Model m;
  soa::State x;
  soa::InnovationsOperators io;
  MatX M, Minv;
  double kappa = 1, n6 = 6, cond = 1;
  Case(Random<double>& rnd, int i) : m(soa::test::random_chain(rnd, 1 + i % 8)) {
    x = soa::test::random_state(rnd, m);
    io = soa::InnovationsOperators::build(m, x);
    soa::Workspace ws(m);
    soa::update_phi(m, x.theta, ws);
    std::vector<soa::SpatialInertia> R(std::size_t(m.n()));
    soa::mass_matrix_crb(m, x, ws, R, M);
    soa::MassMatrixInverse w(m);
    soa::mass_matrix_inverse(m, x, ws, w, Minv);
    for (int k = 1; k <= m.n(); ++k) {
      const int r = 6 * (k - 1), c = m.body(k).v_offset, nk = m.body(k).hinge.nv();
      kappa = std::max(kappa, io.P.block(r, r, 6, 6).norm() * io.D_inv.block(c, c, nk, nk).norm());
    }
    n6 = 6.0 * m.n();
    const VecX ev = Eigen::SelfAdjointEigenSolver<MatX>(M, Eigen::EigenvaluesOnly).eigenvalues();
    cond = ev.maxCoeff() / ev.minCoeff();
  }
  double unit() const { return kEps * n6 * kappa; }
};

double at_least_1(double a) {
  return std::max(1.0, a);
}

TEST(Exercise7_1_KAndPsi, MatchesLibraryAndIdentity) {
  Random<double> rnd(701);
  Worst lib("|K, psi - library| / (eps 6n kappa |terms|)");
  Worst id("|phi^-1 - psi^-1 + K H| / (eps 6n kappa |terms|)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const soa::ex07::KAndPsi kp = soa::ex07::k_and_psi(c.m, c.x);
    ASSERT_EQ(kp.K.rows(), c.io.K.rows());
    ASSERT_EQ(kp.K.cols(), c.io.K.cols());
    ASSERT_EQ(kp.psi.rows(), c.io.psi.rows());
    ASSERT_EQ(kp.psi.cols(), c.io.psi.cols());
    lib.add(std::max((kp.K - c.io.K).norm() / at_least_1(c.io.K.norm()),
                     (kp.psi - c.io.psi).norm() / at_least_1(c.io.psi.norm())) /
                c.unit(),
            i);
    const MatX phi_inv = c.io.op.phi.inverse(), psi_inv = kp.psi.inverse();
    const MatX KH = kp.K * c.io.op.H;
    id.add((phi_inv - psi_inv + KH).norm() /
               (c.unit() * at_least_1(std::max({phi_inv.norm(), psi_inv.norm(), KH.norm()}))),
           i);
  }
  EXPECT_LE(lib.value(), 4.0);
  EXPECT_LE(id.value(), 4.0);
}

TEST(Exercise7_2_InnovationsFactor, FactorsTheMassMatrix) {
  Random<double> rnd(702);
  Worst ldl("|L D L* - M| / (eps 6n kappa |terms|)");
  Worst inv("|L L_inv - I| / (eps 6n kappa |L| |L_inv|)");
  Worst tri("|upper part and diagonal of L - I| / (eps 6n kappa |L|)");
  Worst lib("|L, L_inv, D - library| / (eps 6n kappa |terms|)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const soa::ex07::InnovationsFactor f = soa::ex07::innovations_factor(c.m, c.x);
    const int nv = c.m.nv();
    ASSERT_EQ(f.L.rows(), nv);
    ASSERT_EQ(f.L.cols(), nv);
    ASSERT_EQ(f.L_inv.rows(), nv);
    ASSERT_EQ(f.L_inv.cols(), nv);
    ASSERT_EQ(f.D.rows(), nv);
    ASSERT_EQ(f.D.cols(), nv);
    ldl.add((f.L * f.D * f.L.transpose() - c.M).norm() /
                (c.unit() * at_least_1(std::max(f.L.squaredNorm() * f.D.norm(), c.M.norm()))),
            i);
    inv.add((f.L * f.L_inv - MatX::Identity(nv, nv)).norm() /
                (c.unit() * at_least_1(f.L.norm() * f.L_inv.norm())),
            i);
    double off = 0;
    for (int k = 1; k <= c.m.n(); ++k) {
      const int o = c.m.body(k).v_offset, nk = c.m.body(k).hinge.nv();
      off = std::max(off, (f.L.block(o, o, nk, nk) - MatX::Identity(nk, nk)).norm());
      if (o > 0) off = std::max(off, f.L.block(0, o, o, nk).norm());
    }
    tri.add(off / (c.unit() * at_least_1(f.L.norm())), i);
    lib.add(
        std::max({soa::test::rel(f.L, c.io.factor()),
                  soa::test::rel(f.L_inv, c.io.factor_inverse()), soa::test::rel(f.D, c.io.D)}) /
            c.unit(),
        i);
  }
  EXPECT_LE(ldl.value(), 4.0);
  EXPECT_LE(inv.value(), 4.0);
  EXPECT_LE(tri.value(), 4.0);
  EXPECT_LE(lib.value(), 4.0);
}

TEST(Exercise7_3_MinvDiagonal, MatchesMassMatrixInverse) {
  Random<double> rnd(703);
  Worst w("|Minv(k,k) - mass_matrix_inverse| / (|Minv| eps 6n kappa^2)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const std::vector<MatX> d = soa::ex07::minv_diagonal(c.m, c.x);
    ASSERT_EQ(int(d.size()), c.m.n());
    double err = 0;
    for (int k = 1; k <= c.m.n(); ++k) {
      const int o = c.m.body(k).v_offset, nk = c.m.body(k).hinge.nv();
      const MatX& b = d[std::size_t(k - 1)];
      ASSERT_EQ(b.rows(), nk);
      ASSERT_EQ(b.cols(), nk);
      err = std::max(err, (b - c.Minv.block(o, o, nk, nk)).norm());
    }
    w.add(err / (at_least_1(c.Minv.norm()) * c.unit() * c.kappa), i);
  }
  EXPECT_LE(w.value(), 4.0);
}

TEST(Exercise7_4_Solve, SolvesMassMatrixSystem) {
  Random<double> rnd(704);
  Worst res("|M y - b| / (|M| |y| eps 6n kappa)");
  Worst ref("|y - Minv b| / (|y| eps 6n cond(M))");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const VecX b = soa::test::random_vector(rnd, c.m.nv());
    const VecX y = soa::ex07::solve(c.m, c.x, b);
    ASSERT_EQ(y.size(), b.size());
    res.add((c.M * y - b).norm() / (c.M.norm() * at_least_1(y.norm()) * c.unit()), i);
    const VecX y_ref = c.Minv * b;
    ref.add((y - y_ref).norm() / (at_least_1(y_ref.norm()) * kEps * c.n6 * c.cond), i);
  }
  EXPECT_LE(res.value(), 4.0);
  EXPECT_LE(ref.value(), 4.0);
}

TEST(Exercise7_5_LogDet, EqualsLogDetOfM) {
  Random<double> rnd(705);
  Worst w("|log det - log det(M)| / (eps 6n cond(M))");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const double ld = soa::ex07::log_det_mass_matrix(c.m, c.x);
    w.add(std::abs(ld - std::log(c.M.determinant())) / (kEps * c.n6 * c.cond), i);
  }
  EXPECT_LE(w.value(), 4.0);
}

TEST(Exercise7_6_OmegaFromUpsilon, MatchesPhiHMinvHPhiAndLibrary) {
  Random<double> rnd(706);
  Worst lib("|Omega - library psi* H* D^-1 H psi| / (|Omega| eps 6n kappa)");
  Worst dense("|Omega - phi* H* inv(M) H phi| / (|Omega| eps 6n cond(M))");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const MatX Omega = soa::ex07::omega_from_upsilon(c.m, c.x);
    const MatX ref = c.io.Omega();
    ASSERT_EQ(Omega.rows(), ref.rows());
    ASSERT_EQ(Omega.cols(), ref.cols());
    lib.add((Omega - ref).norm() / (at_least_1(ref.norm()) * c.unit()), i);
    const MatX& phi = c.io.op.phi;
    const MatX& H = c.io.op.H;
    const MatX lhs = phi.transpose() * H.transpose() * c.M.inverse() * H * phi;
    dense.add((Omega - lhs).norm() / (at_least_1(ref.norm()) * kEps * c.n6 * c.cond), i);
  }
  EXPECT_LE(lib.value(), 4.0);
  EXPECT_LE(dense.value(), 4.0);
}

TEST(Exercise7_7_MinvFromUpsilon, MatchesLibraryAndDenseInverse) {
  Random<double> rnd(707);
  Worst lib("|Minv - mass_matrix_inverse_upsilon| / (|Minv| eps n cond(M))");
  Worst dense("|Minv - inv(M)| / (|inv(M)| eps n cond(M))");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const MatX Minv = soa::ex07::minv_from_upsilon(c.m, c.x);
    ASSERT_EQ(Minv.rows(), c.m.nv());
    ASSERT_EQ(Minv.cols(), c.m.nv());
    soa::Workspace ws(c.m);
    soa::update_phi(c.m, c.x.theta, ws);
    soa::MassMatrixInverseUpsilon w(c.m);
    MatX ref;
    soa::mass_matrix_inverse_upsilon(c.m, c.x, ws, w, ref);
    const double unit = kEps * c.m.nv() * c.cond;
    lib.add((Minv - ref).norm() / (ref.norm() * unit), i);
    const MatX inv = c.M.inverse();
    dense.add((Minv - inv).norm() / (inv.norm() * unit), i);
  }
  EXPECT_LE(lib.value(), 4.0);
  EXPECT_LE(dense.value(), 4.0);
}

TEST(Exercise7_8_OperationalInverseInertia, MatchesDenseJMinvJStar) {
  Random<double> rnd(708);
  Worst w("|J M^-1 J* - dense| / (|J M^-1 J*| eps 6n cond(M))");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const int k = 1 + int(rnd.engine()() % unsigned(c.m.n()));
    const soa::Pose frame(rnd.rotation(), rnd.vec3());
    soa::Workspace ws(c.m);
    soa::update_phi(c.m, c.x.theta, ws);
    soa::update_poses(c.m, ws);
    Eigen::Matrix<double, 6, Eigen::Dynamic> J;
    soa::jacobian(c.m, c.x.theta, ws, k, frame, J);
    const MatX ref = J * c.M.inverse() * J.transpose();
    const MatX got = soa::ex07::operational_inverse_inertia(c.m, c.x, k, frame);
    w.add((got - ref).norm() / (at_least_1(ref.norm()) * kEps * c.n6 * c.cond), i);
  }
  EXPECT_LE(w.value(), 4.0);
}

TEST(Exercise7_9_InnovationsCoordinates, DecoupleKineticEnergy) {
  Random<double> rnd(709);
  Worst energy("|1/2 eta* D eta - 1/2 beta* M beta| / (eps 6n kappa |terms|)");
  Worst lib("|eta - [I + H phi K]* beta| / (eps 6n kappa |terms|)");
  for (int i = 0; i < kCases; ++i) {
    Case c(rnd, i);
    c.x.beta = soa::test::random_vector(rnd, c.m.nv());
    const VecX eta = soa::ex07::innovations_coordinates(c.m, c.x);
    ASSERT_EQ(eta.size(), c.m.nv());
    const VecX& beta = c.x.beta;
    const double T = 0.5 * beta.dot(c.M * beta), Te = 0.5 * eta.dot(c.io.D * eta);
    energy.add(
        std::abs(T - Te) / (c.unit() * at_least_1(std::max(c.M.norm() * beta.squaredNorm(),
                                                           c.io.D.norm() * eta.squaredNorm()))),
        i);
    const MatX L = c.io.factor();
    lib.add((eta - L.transpose() * beta).norm() / (c.unit() * at_least_1(L.norm() * beta.norm())),
            i);
  }
  EXPECT_LE(energy.value(), 4.0);
  EXPECT_LE(lib.value(), 4.0);
}

}  // namespace
