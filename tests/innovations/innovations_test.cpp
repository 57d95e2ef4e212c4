// Property tests of the innovations operators (lesson 7; soa::InnovationsOperatorsT) on
// soa::test::kCases random chains of 1 to 8 bodies of every hinge type, at random states,
// from the fixed seed:
// - phi^-1 - psi^-1 = -K H, and psi K H phi = phi - psi = phi K H psi;
// - [I + H phi K] is block unit lower triangular and M = [I + H phi K] D [I + H phi K]*;
// - [I + H phi K]^-1 = I - H psi K;
// - M^-1 = [I - H psi K]* D^-1 [I - H psi K] against the dense inverse of M;
// - soa::mass_matrix_inverse (O(N^2)) equals that operator expression.
// Residuals are relative to the size of the terms and divided by eps, the size 6n of the
// operators, and kappa = max_k |P(k)| |D^-1(k)| (the growth of rounding in G = P H* D^-1) or
// cond(M) where an inverse of M is compared; each test reports its worst case.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>

#include "property.hpp"
#include "random_chain.hpp"
#include "soa/chain.hpp"

namespace {

using soa::test::kCases;
using soa::test::Random;
using soa::test::Worst;
using MatX = soa::MatX<double>;
using VecX = soa::VecX<double>;
constexpr double kEps = soa::eps<double>();

// A random chain (1 to 8 bodies, hinge types in turn) at a random state, its innovations
// operators and the mass matrix by composite bodies (lesson 5).
struct Case {
  soa::Model m;
  soa::State x;
  soa::InnovationsOperators io;
  MatX M;        // mass matrix, composite bodies
  double kappa;  // max_k |P(k)| |D^-1(k)|, >= 1
  double n6;     // 6n, the size of the spatial operators
  Case(Random<double>& rnd, int i) : m(soa::test::random_chain(rnd, 1 + i % 8)) {
    x = soa::test::random_state(rnd, m);
    io = soa::InnovationsOperators::build(m, x);
    soa::Workspace ws(m);
    soa::update_phi(m, x.theta, ws);
    std::vector<soa::SpatialInertia> R(std::size_t(m.n()));
    soa::mass_matrix_crb(m, x, ws, R, M);
    kappa = 1;
    for (int k = 1; k <= m.n(); ++k) {
      const int r = 6 * (k - 1), c = m.body(k).v_offset, nk = m.body(k).hinge.nv();
      kappa = std::max(kappa, io.P.block(r, r, 6, 6).norm() * io.D_inv.block(c, c, nk, nk).norm());
    }
    n6 = 6.0 * m.n();
  }
  double cond() const {
    const VecX ev = Eigen::SelfAdjointEigenSolver<MatX>(M, Eigen::EigenvaluesOnly).eigenvalues();
    return ev.maxCoeff() / ev.minCoeff();
  }
};

double norm_sum(std::initializer_list<double> norms) {
  double s = 1;
  for (double v : norms) s = std::max(s, v);
  return s;
}

TEST(innovations_Identities, PhiInverseMinusPsiInverseIsMinusKH) {
  Random<double> rnd(101);
  Worst w("|phi^-1 - psi^-1 + K H| / (eps 6n kappa |terms|)");
  Worst e("|E_psi - (E_phi - K H)| / (eps 6n kappa |terms|)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const soa::InnovationsOperators& io = c.io;
    const MatX phi_inv = io.op.phi.inverse(), psi_inv = io.psi.inverse();
    const MatX KH = io.K * io.op.H;
    const double s = kEps * c.n6 * c.kappa;
    w.add((phi_inv - psi_inv + KH).norm() /
              (s * norm_sum({phi_inv.norm(), psi_inv.norm(), KH.norm()})),
          i);
    e.add((io.E_psi - (io.op.E_phi - KH)).norm() /
              (s * norm_sum({io.E_psi.norm(), io.op.E_phi.norm(), KH.norm()})),
          i);
  }
  EXPECT_LE(w.value(), 4.0);
  EXPECT_LE(e.value(), 4.0);
}

TEST(innovations_Identities, PsiKHPhiEqualsPhiMinusPsiEqualsPhiKHPsi) {
  Random<double> rnd(103);
  Worst left("|psi K H phi - (phi - psi)| / (eps 6n kappa |terms|)");
  Worst right("|phi K H psi - (phi - psi)| / (eps 6n kappa |terms|)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const soa::InnovationsOperators& io = c.io;
    const MatX& phi = io.op.phi;
    const MatX KH = io.K * io.op.H;
    const MatX diff = phi - io.psi;
    const double terms = norm_sum({phi.norm() * KH.norm() * io.psi.norm(), diff.norm()});
    const double s = kEps * c.n6 * c.kappa * terms;
    left.add((io.psi * KH * phi - diff).norm() / s, i);
    right.add((phi * KH * io.psi - diff).norm() / s, i);
  }
  EXPECT_LE(left.value(), 4.0);
  EXPECT_LE(right.value(), 4.0);
}

TEST(innovations_Factorization, MassMatrixIsLDLStar) {
  Random<double> rnd(107);
  Worst w("|[I + H phi K] D [I + H phi K]* - M| / (eps 6n kappa |terms|)");
  Worst tri("|upper part and diagonal of [I + H phi K] - I| / (eps 6n kappa |L|)");
  Worst det("|sum log det D(k) - log det M| / (eps 6n cond(M))");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const MatX L = c.io.factor();
    const double terms = norm_sum({L.norm() * L.norm() * c.io.D.norm(), c.M.norm()});
    w.add((c.io.mass_matrix() - c.M).norm() / (kEps * c.n6 * c.kappa * terms), i);
    // Block unit lower triangular: zero above the diagonal blocks, identity on them.
    double off = 0;
    for (int k = 1; k <= c.m.n(); ++k) {
      const int o = c.m.body(k).v_offset, nk = c.m.body(k).hinge.nv();
      off = std::max(off, (L.block(o, o, nk, nk) - MatX::Identity(nk, nk)).norm());
      if (o > 0) off = std::max(off, L.block(0, o, o, nk).norm());
    }
    tri.add(off / (kEps * c.n6 * c.kappa * L.norm()), i);
    // det M = prod det D(k): L is unit triangular.
    const double log_det_D = std::log(c.io.D.determinant());
    const double log_det_M = std::log(c.M.determinant());
    det.add(std::abs(log_det_D - log_det_M) / (kEps * c.n6 * c.cond()), i);
  }
  EXPECT_LE(w.value(), 4.0);
  EXPECT_LE(tri.value(), 4.0);
  EXPECT_LE(det.value(), 4.0);
}

TEST(innovations_Factorization, FactorInverseIsIMinusHPsiK) {
  Random<double> rnd(109);
  Worst a("|[I + H phi K][I - H psi K] - I| / (eps 6n kappa |terms|)");
  Worst b("|[I - H psi K][I + H phi K] - I| / (eps 6n kappa |terms|)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const MatX L = c.io.factor(), Li = c.io.factor_inverse();
    const MatX I = MatX::Identity(c.m.nv(), c.m.nv());
    const double s = kEps * c.n6 * c.kappa * norm_sum({L.norm() * Li.norm()});
    a.add((L * Li - I).norm() / s, i);
    b.add((Li * L - I).norm() / s, i);
  }
  EXPECT_LE(a.value(), 4.0);
  EXPECT_LE(b.value(), 4.0);
}

TEST(innovations_Inverse, OperatorExpressionIsTheInverseOfM) {
  Random<double> rnd(113);
  Worst dense("|[I - H psi K]* D^-1 [I - H psi K] - inv(M)| / (|inv(M)| eps 6n cond(M))");
  Worst id("|M [I - H psi K]* D^-1 [I - H psi K] - I| / (eps 6n cond(M))");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const MatX Minv = c.io.mass_matrix_inverse();
    const MatX ref = c.M.inverse();
    const double s = kEps * c.n6 * c.cond();
    dense.add((Minv - ref).norm() / (ref.norm() * s), i);
    id.add((c.M * Minv - MatX::Identity(c.m.nv(), c.m.nv())).norm() / s, i);
  }
  EXPECT_LE(dense.value(), 4.0);
  EXPECT_LE(id.value(), 4.0);
}

TEST(innovations_Inverse, MassMatrixInverseEqualsOperatorExpression) {
  Random<double> rnd(127);
  Worst w("|mass_matrix_inverse - [I - H psi K]* D^-1 [I - H psi K]| / (eps 6n kappa |terms|)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    soa::Workspace ws(c.m);
    soa::update_phi(c.m, c.x.theta, ws);
    soa::MassMatrixInverse mw(c.m);
    MatX Minv;
    soa::mass_matrix_inverse(c.m, c.x, ws, mw, Minv);
    const MatX Li = c.io.factor_inverse();
    const double terms = norm_sum({Li.norm() * Li.norm() * c.io.D_inv.norm(), Minv.norm()});
    w.add((Minv - c.io.mass_matrix_inverse()).norm() / (kEps * c.n6 * c.kappa * terms), i);
  }
  EXPECT_LE(w.value(), 4.0);
}

}  // namespace
