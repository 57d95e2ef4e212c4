/// \file
/// Property tests: the O(N) recursions of lessons 3-4 against the operator forms, built as
/// dense matrices by OperatorsT (the notes' page "Conventions", "Serial chains"), on random chains of up
/// to 12 bodies of every kind (all hinge types in one chain, or all of one type):
///   V = phi* H* beta,  alpha = phi* (H* beta_dot + a)  (without and with gravity),
///   f = phi (M alpha + b),  T = H f  (with gravity and external forces);
///   the mass matrix M = H phi M phi* H* against the columns T(e_j) - T(0) of inverse
///   dynamics at rest without gravity, C = H phi (M phi* a + b) against inverse dynamics at
///   beta_dot = 0, and T = M beta_dot + C;
///   E_phi nilpotent, phi = (I - E_phi)^{-1} = I + E_phi + ... + E_phi^{n-1} with blocks
///   phi(i,j) = phi(i,i-1) ... phi(j+1,j);
///   M symmetric positive definite, and 1/2 beta* M beta = sum_k 1/2 V*(k) M(k) V(k).
///
/// Residuals are relative to a bound on the terms (the product of the norms of the factors,
/// which bounds the rounding error of a dense product: |fl(A x) - A x| <= N eps |A| |x|), so
/// the tolerances are a constant times N eps, N = 6n the size of the block vectors.
#include <Eigen/Eigenvalues>

#include "chain_support.hpp"

namespace soa::test {
namespace {

constexpr int kMaxBodies = 12;

class chain_Operators : public ::testing::TestWithParam<ChainKind> {};

// Residuals are recorded in units of N eps, N = 6n (the "[N eps]" of the reports), and must
// stay below kTol. The operator side goes through the dense inverse (I - E_phi)^{-1}, whose
// error is about cond(I - E_phi) eps |phi| (cond of order 10-100 for these chains).
// The bound is loose (observed worst about 0.2 N eps), so that kTol = 2 leaves a margin of
// 10; any wrong term gives a residual of order 1e10 N eps.
constexpr double kTol = 2.0;

/// Cases per chain kind: kCases on the mixed chains (every hinge type), half as many on each
/// single-type kind (the dense inverse of each case costs O(n^3)).
int cases(ChainKind kind) {
  return kind == ChainKind::Mixed ? kCases : kCases / 2;
}

double units(int n) {
  return 6 * n * eps<double>();
}

// V, alpha (without and with gravity), f and T (gravity and external forces) by the
// recursions against the operator forms.
TEST_P(chain_Operators, RecursionsMatchOperatorForms) {
  const ChainKind kind = GetParam();
  Random<double> rnd;
  Worst wV("V = phi* H* beta [N eps]"), wa("alpha = phi* (H* beta_dot + a) [N eps]"),
      wag("alpha = phi* (H* beta_dot + a), gravity [N eps]"), wf("f = phi (M alpha + b) [N eps]"),
      wT("T = H f [N eps]"), wId("inverse dynamics alpha = operator alpha [N eps]");
  for (int i = 0; i < cases(kind); ++i) {
    const int n0 = chain_size(i, kMaxBodies);
    ChainOptions opt;
    opt.gravity = true;
    const Model mg = make_chain(rnd, kind, n0, opt);
    Model m0 = mg;
    m0.gravity.setZero();
    const int n = mg.n();
    const State x = random_state(rnd, mg);
    const VecX<double> beta_dot = random_vector(rnd, mg.nv());
    const ExternalForces<double> f_ext = random_forces(rnd, mg);
    const Operators op0 = Operators::build(m0, x);
    const Operators opg = Operators::build(mg, x, f_ext);
    const double nphi = op0.phi.norm(), nH = op0.H.norm(), nM = op0.M.norm();

    Workspace ws(mg);
    update_phi(mg, x.theta, ws);
    update_velocities(mg, x, ws);
    wV.add(residual(stack(ws.V), op0.V(x.beta), nphi * nH * x.beta.norm()) / units(n), i);

    update_accelerations(m0, x, beta_dot.data(), Acceleration(), ws);
    const double s_alpha = nphi * (nH * beta_dot.norm() + op0.a.norm());
    wa.add(residual(stack(ws.alpha), op0.alpha(beta_dot), s_alpha) / units(n), i);

    update_accelerations(mg, x, beta_dot.data(), gravity_base_acceleration(mg), ws);
    const VecX<double> alpha_g = opg.alpha(beta_dot);
    const double s_alpha_g = nphi * (nH * beta_dot.norm() + opg.a.norm());
    wag.add(residual(stack(ws.alpha), alpha_g, s_alpha_g) / units(n), i);

    VecX<double> T(mg.nv());
    inverse_dynamics(mg, x, beta_dot, f_ext, ws, T);
    wId.add(residual(stack(ws.alpha), alpha_g, s_alpha_g) / units(n), i);
    const double s_f = nphi * (nM * s_alpha_g + opg.b.norm());
    wf.add(residual(stack(ws.f), opg.f(beta_dot), s_f) / units(n), i);
    wT.add(residual(T, opg.T(beta_dot), nH * s_f) / units(n), i);
  }
  EXPECT_LE(wV.value(), kTol);
  EXPECT_LE(wa.value(), kTol);
  EXPECT_LE(wag.value(), kTol);
  EXPECT_LE(wId.value(), kTol);
  EXPECT_LE(wf.value(), kTol);
  EXPECT_LE(wT.value(), kTol);
}

// M = H phi M phi* H* against the columns of inverse dynamics: at rest and without gravity,
// T(e_j) - T(0) = M e_j. C = H phi (M phi* a + b) against inverse dynamics at beta_dot = 0
// (gravity and external forces included), and T = M beta_dot + C.
TEST_P(chain_Operators, MassMatrixAndBiasMatchInverseDynamics) {
  const ChainKind kind = GetParam();
  Random<double> rnd;
  Worst wM("M e_j = T(e_j) - T(0) [N eps]"), wC("C = T(beta_dot = 0) [N eps]"),
      wEom("T = M beta_dot + C [N eps]");
  for (int i = 0; i < cases(kind); ++i) {
    const int n0 = chain_size(i, kMaxBodies);
    ChainOptions opt;
    opt.gravity = true;
    const Model mg = make_chain(rnd, kind, n0, opt);
    Model m0 = mg;
    m0.gravity.setZero();
    const int n = mg.n(), nv = mg.nv();
    const State x = random_state(rnd, mg);
    const VecX<double> beta_dot = random_vector(rnd, nv);
    const ExternalForces<double> f_ext = random_forces(rnd, mg);
    const Operators op = Operators::build(mg, x, f_ext);
    const MatX<double> M = op.mass_matrix();
    const double nphi = op.phi.norm(), nH = op.H.norm(), nM = op.M.norm();
    const double s_M = nH * nH * nphi * nphi * nM;

    Workspace ws(mg);
    const State rest{x.theta, VecX<double>::Zero(nv)};
    VecX<double> T0(nv), Tj(nv), e = VecX<double>::Zero(nv);
    inverse_dynamics(m0, rest, e, {}, ws, T0);
    double r = 0;
    for (int j = 0; j < nv; ++j) {
      e[j] = 1;
      inverse_dynamics(m0, rest, e, {}, ws, Tj);
      e[j] = 0;
      r = std::max(r, residual(Tj - T0, M.col(j), s_M));
    }
    wM.add(r / units(n), i);

    VecX<double> C(nv), T(nv);
    inverse_dynamics(mg, x, VecX<double>(VecX<double>::Zero(nv)), f_ext, ws, C);
    const double s_C = nH * nphi * (nM * nphi * op.a.norm() + op.b.norm());
    wC.add(residual(C, op.bias(), s_C) / units(n), i);
    inverse_dynamics(mg, x, beta_dot, f_ext, ws, T);
    wEom.add(residual(T, M * beta_dot + op.bias(), s_M * beta_dot.norm() + s_C) / units(n), i);
  }
  EXPECT_LE(wM.value(), kTol);
  EXPECT_LE(wC.value(), kTol);
  EXPECT_LE(wEom.value(), kTol);
}

// E_phi is nilpotent of index n (E_phi^n = 0 exactly: its only blocks are below the
// diagonal, and a product of structural zeros stays exactly zero), and
// phi = (I - E_phi)^{-1} = I + E_phi + ... + E_phi^{n-1}, whose block (i,j) is the product
// phi(i,i-1) ... phi(j+1,j) for i > j (composed as poses, PhiT::operator*), I for i = j and
// 0 for i < j. On the mixed chains only: E_phi does not depend on the kind of hinge but
// through phi(k+1,k), and the powers cost O(n^4).
TEST(chain_Shift, PhiIsTheInverseOfOneMinusTheShift) {
  Random<double> rnd;
  Worst wProd("phi(i,j) = phi(i,i-1)...phi(j+1,j) [N eps]"),
      wNeu("phi = I + E + ... + E^(n-1) [N eps]");
  int not_nilpotent = 0, index_too_small = 0;
  for (int i = 0; i < kCases; ++i) {
    const Model m = random_chain(rnd, chain_size(i, kMaxBodies));
    const int n = m.n(), N = 6 * n;
    const State x = random_state(rnd, m);
    const Operators op = Operators::build(m, x);
    Workspace ws(m);
    update_phi(m, x.theta, ws);

    MatX<double> P = MatX<double>::Identity(N, N), sum = MatX<double>::Zero(N, N);
    for (int p = 0; p < n; ++p) {
      sum += P;
      P = P * op.E_phi;
      if (p == n - 2 && P.isZero(0)) ++index_too_small;  // E^(n-1) must not vanish
    }
    if (!P.isZero(0)) ++not_nilpotent;  // E^n
    const double s = op.phi.norm() * (MatX<double>::Identity(N, N) - op.E_phi).norm();
    wNeu.add(residual(op.phi, sum, s) / units(n), i);

    double r = 0;
    for (int a = 1; a <= n; ++a)
      for (int b = 1; b <= n; ++b) {
        Mat6<double> expected = Mat6<double>::Zero();
        if (a == b) expected.setIdentity();
        if (a > b) {
          Phi prod = ws.phi[a - 2];  // phi(a, a-1)
          for (int k = a - 2; k >= b; --k) prod = prod * ws.phi[k - 1];
          expected = prod.matrix();
        }
        const Mat6<double> block = op.phi.block<6, 6>(6 * (a - 1), 6 * (b - 1));
        r = std::max(r, residual(block, expected, s));
      }
    wProd.add(r / units(n), i);
  }
  EXPECT_EQ(not_nilpotent, 0);
  EXPECT_EQ(index_too_small, 0);
  EXPECT_LE(wProd.value(), kTol);
  EXPECT_LE(wNeu.value(), kTol);
}

// M = H phi M phi* H* is symmetric (relative asymmetry ~ eps) and positive definite
// (smallest eigenvalue > 0); 1/2 beta* M beta is the kinetic energy sum_k 1/2 V*(k) M(k) V(k)
// of the bodies (lesson 2's kinetic energy, with V from the velocity recursion).
TEST_P(chain_Operators, MassMatrixIsSymmetricPositiveDefinite) {
  const ChainKind kind = GetParam();
  Random<double> rnd;
  Worst wSym("|M - M*| / |M| [N eps]"), wCond("lambda_max / lambda_min of M"),
      wKE("1/2 beta* M beta = sum 1/2 V* M V [N eps]");
  int not_positive = 0;
  for (int i = 0; i < cases(kind); ++i) {
    const Model m = make_chain(rnd, kind, chain_size(i, kMaxBodies));
    const int n = m.n();
    const State x = random_state(rnd, m);
    const Operators op = Operators::build(m, x);
    const MatX<double> M = op.mass_matrix();
    wSym.add(double((M - M.transpose()).norm() / M.norm()) / units(n), i);
    const Eigen::SelfAdjointEigenSolver<MatX<double>> eig(MatX<double>(0.5 * (M + M.transpose())),
                                                          Eigen::EigenvaluesOnly);
    const double lmin = eig.eigenvalues().minCoeff(), lmax = eig.eigenvalues().maxCoeff();
    if (!(lmin > 0)) ++not_positive;
    wCond.add(lmax / lmin, i);

    Workspace ws(m);
    update_phi(m, x.theta, ws);
    update_velocities(m, x, ws);
    double ke = 0, s = 0;
    for (int k = 1; k <= n; ++k) {
      ke += m.body(k).M.kinetic_energy(ws.V[k - 1]);
      s += m.body(k).M.matrix().norm() * ws.V[k - 1].vector().squaredNorm() / 2;
    }
    const double ke_op = x.beta.dot(M * x.beta) / 2;
    wKE.add(
        std::abs(ke - ke_op) / std::max(s, double(M.norm() * x.beta.squaredNorm() / 2)) / units(n),
        i);
  }
  EXPECT_EQ(not_positive, 0);
  EXPECT_LE(wSym.value(), kTol);
  EXPECT_LE(wKE.value(), kTol);
}

INSTANTIATE_TEST_SUITE_P(Kinds, chain_Operators, all_chain_kinds(), ChainKindName());

}  // namespace
}  // namespace soa::test
