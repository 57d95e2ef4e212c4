/// \file
/// Lesson 5's identities on random chains (every hinge type, 1 to 12 bodies, fixed seed):
///   R(k) = phi(k,k-1) R(k-1) phi*(k,k-1) + M(k)  vs  R - E_phi R E_phi* = M (dense),
///   phi M phi* = R + phi~ R + R phi~*  (phi~ = phi - I),
///   M(i,j) = H(i) phi(i,j) R(j) H*(j): soa::mass_matrix_crb vs soa::OperatorsT::mass_matrix,
///   soa::inverse_dynamics_composite vs soa::inverse_dynamics,
/// and the CRB mass matrix in float, double and long double. Residuals are relative to the
/// magnitude of the terms, in units of N eps<S> (N = 6n).
#include <cstdio>

#include "../chain/chain_support.hpp"

namespace soa::test {
namespace {

constexpr int kMaxBodies = 12;
constexpr double kTol = 2.0;  // in units of N eps; worst seen is reported by Worst

TEST(composite_Lyapunov, RecursionSolvesOperatorEquation) {
  Random<double> rnd;
  Worst w("R - E_phi R E_phi* - M [N eps |M|]"), w_sym("R(k) - R*(k) [N eps |R|]");
  for (int i = 0; i < kCases; ++i) {
    const Model m = random_chain(rnd, chain_size(i, kMaxBodies));
    const State x = random_state(rnd, m);
    const Operators op = Operators::build(m, x);
    Workspace ws(m);
    update_phi(m, x.theta, ws);
    const MatX<double> R = composite_inertia_operator(m, ws);
    const double units = 6 * m.n() * eps<double>();
    const double scale = double(op.E_phi.norm()) * op.E_phi.norm() * R.norm() + op.M.norm();
    w.add(residual(MatX<double>(R - op.E_phi * R * op.E_phi.transpose()), op.M, scale) / units, i);
    w_sym.add(residual(R, MatX<double>(R.transpose()), R.norm()) / units, i);
  }
  EXPECT_LE(w.value(), kTol);
  EXPECT_LE(w_sym.value(), kTol);
}

TEST(composite_Decomposition, PhiMPhiStar) {
  Random<double> rnd;
  Worst w("phi M phi* - (R + phi~ R + R phi~*) [N eps]");
  for (int i = 0; i < kCases; ++i) {
    const Model m = random_chain(rnd, chain_size(i, kMaxBodies));
    const State x = random_state(rnd, m);
    const Operators op = Operators::build(m, x);
    Workspace ws(m);
    update_phi(m, x.theta, ws);
    const MatX<double> R = composite_inertia_operator(m, ws);
    const MatX<double> phi_t = op.phi - MatX<double>::Identity(op.phi.rows(), op.phi.cols());
    const MatX<double> lhs = op.phi * op.M * op.phi.transpose();
    const MatX<double> rhs = R + phi_t * R + R * phi_t.transpose();
    const double scale = double(op.phi.norm()) * op.phi.norm() * op.M.norm();
    w.add(residual(lhs, rhs, scale) / (6 * m.n() * eps<double>()), i);
  }
  EXPECT_LE(w.value(), kTol);
}

TEST(composite_MassMatrix, CrbMatchesNewtonEulerFactorization) {
  Random<double> rnd;
  Worst w("mass_matrix_crb - H phi M phi* H* [N eps]"), w_diag("M(k,k) - H(k) R(k) H*(k) [N eps]"),
      w_R("H (R + phi~ R + R phi~*) H* [N eps]");
  for (int i = 0; i < kCases; ++i) {
    const Model m = random_chain(rnd, chain_size(i, kMaxBodies), ChainOptions{true, true, true});
    const State x = random_state(rnd, m);
    const Operators op = Operators::build(m, x);
    const MatX<double> M_ne = op.mass_matrix();
    Workspace ws(m);
    update_phi(m, x.theta, ws);
    std::vector<SpatialInertia> Rk(std::size_t(m.n()));
    MatX<double> M_crb;
    mass_matrix_crb(m, x, ws, Rk, M_crb);
    const double units = 6 * m.n() * eps<double>();
    const double scale =
        double(op.phi.norm()) * op.phi.norm() * op.M.norm() * op.H.norm() * op.H.norm();
    w.add(residual(M_crb, M_ne, scale) / units, i);
    double gap = 0;
    for (int k = 1; k <= m.n(); ++k) {
      const Body& B = m.body(k);
      const auto Hs = B.hinge.H_star(x.theta.data() + B.q_offset);
      const MatX<double> Mkk = Hs.transpose() * Rk[std::size_t(k - 1)].matrix() * Hs;
      const int o = B.v_offset, nk = B.hinge.nv();
      gap = std::max(gap, residual(MatX<double>(M_crb.block(o, o, nk, nk)), Mkk, scale));
    }
    w_diag.add(gap / units, i);
    const MatX<double> R = composite_inertia_operator(m, ws);
    const MatX<double> phi_t = op.phi - MatX<double>::Identity(op.phi.rows(), op.phi.cols());
    const MatX<double> M_R = op.H * (R + phi_t * R + R * phi_t.transpose()) * op.H.transpose();
    w_R.add(residual(M_R, M_ne, scale) / units, i);
  }
  EXPECT_LE(w.value(), kTol);
  EXPECT_LE(w_diag.value(), kTol);
  EXPECT_LE(w_R.value(), kTol);
}

TEST(composite_InverseDynamics, MatchesNewtonEuler) {
  Random<double> rnd;
  Worst w_T("T composite - T Newton-Euler [N eps |f|]"), w_f("f composite - f [N eps |f|]");
  for (int i = 0; i < kCases; ++i) {
    const Model m = random_chain(rnd, chain_size(i, kMaxBodies), ChainOptions{true, true, true});
    const State x = random_state(rnd, m);
    const VecX<double> beta_dot = random_vector(rnd, m.nv());
    const ExternalForces<double> f_ext = i % 2 ? random_forces(rnd, m) : ExternalForces<double>{};
    Workspace ws(m), ref(m);
    VecX<double> T(m.nv()), T_ref(m.nv());
    std::vector<SpatialInertia> R(std::size_t(m.n()));
    inverse_dynamics_composite(m, x, beta_dot, f_ext, ws, R, T);
    inverse_dynamics(m, x, beta_dot, f_ext, ref, T_ref);
    const Operators op = Operators::build(m, x, f_ext);
    // rounding scales with the largest terms: |phi|^2 |R| |alpha| and |b|
    double s = double(stack(ref.f).norm()) + double(stack(ref.alpha).norm()) * op.M.norm();
    s *= 1 + double(op.phi.norm()) * op.phi.norm();
    const double units = 6 * m.n() * eps<double>();
    w_T.add(residual(T, T_ref, s * (1 + op.H.norm())) / units, i);
    w_f.add(residual(stack(ws.f), stack(ref.f), s) / units, i);
  }
  EXPECT_LE(w_T.value(), kTol);
  EXPECT_LE(w_f.value(), kTol);
}

// The mass matrix with the products hoisted to the inertial frame (soa::mass_matrix_inertial)
// against lesson 5's carried columns (soa::mass_matrix_crb), every hinge type, 1 to 12 bodies
// and, every 50th case, a revolute chain of 50 to 400 bodies. Each entry is one 6-term dot
// product s^*(i) f(j) of vectors seen at the inertial origin, so its rounding is bounded by
// about 6 eps |s(i)| |f(j)| (plus lesson 5's own); the worst ratio to that bound is reported.
// Exactly symmetric: both triangles sum the same products in the same order.
TEST(composite_MassMatrix, InertialMatchesCarriedColumns) {
  Random<double> rnd;
  Worst w("|M_inertial - M_crb| / (6 eps |s(i)| |f(j)| + N eps (M_ii M_jj)^1/2)"),
      w_sym("|M_inertial - M_inertial^*| (exact)");
  for (int i = 0; i < kCases; ++i) {
    const bool is_long = i % 50 == 0;
    Model m;
    if (is_long) {
      m = random_chain(rnd, 50 + (i / 50) % 8 * 50, ChainOptions{false, false, false});
    } else {
      m = random_chain(rnd, chain_size(i, kMaxBodies), ChainOptions{true, true, true});
    }
    const State x = random_state(rnd, m);
    Workspace ws(m);
    update_phi(m, x.theta, ws);
    std::vector<SpatialInertia> Rk(std::size_t(m.n()));
    MatX<double> M_crb, M_in;
    mass_matrix_crb(m, x, ws, Rk, M_crb);
    MassMatrixInertial mw(m);
    mass_matrix_inertial(m, x, ws, mw, M_in);
    const double N_eps = 6 * m.n() * eps<double>();
    double worst = 0;
    for (int c = 0; c < m.nv(); ++c)
      for (int r = 0; r < m.nv(); ++r) {
        const double bound = 6 * eps<double>() * mw.s.row(r).norm() * mw.f.row(c).norm() +
                             N_eps * std::sqrt(M_crb(r, r) * M_crb(c, c));
        worst = std::max(worst, std::abs(M_in(r, c) - M_crb(r, c)) / bound);
      }
    w.add(worst, i);
    w_sym.add((M_in - M_in.transpose()).cwiseAbs().maxCoeff(), i);
  }
  EXPECT_LE(w.value(), 1.0);
  EXPECT_EQ(w_sym.value(), 0.0);
}

// The fast paths of the composite inertias (soa::transform() in the plane of a rotation about
// a coordinate axis) and of the inertial-frame mass matrix (poses composed in that plane, a
// revolute hinge about +-e_i as a column of the pose and of J) against the general path
// (Model::fast_paths = false), on chains of every hinge type whose one-dof axes are +-e_i and
// half of whose placements do not rotate, 1 to 40 bodies and, every 50th case, a revolute
// chain of 50 to 400 bodies. Every fast sum is the general one less products with an exact
// 0 or 1, and a sum that keeps two products rounds alike in any order: the results are the
// same bits where the general path rounds each product. Where the target has FMA, Eigen's
// general 3x3 products fuse their multiply-adds (its packet pmadd, whatever -ffp-contract
// says) and round such a sum once where the fast path rounds it twice; that difference of
// an ulp per step accumulates along the chain like the rounding of either path, so R(k) is
// bounded by 2 k eps |R(k)| and M(i,j) by 2 n eps |s(i)| |f(j)| (the factor 2 a margin over
// the worst seen).
TEST(composite_MassMatrix, FastPathsAgreeWithTheGeneralPath) {
  Random<double> rnd(23);
  std::mt19937 g(kSeed);
  Worst w_R("|R_fast(k) - R_general(k)| / (k eps |R_general(k)|)"),
      w_M("|M_fast - M_general| / (n eps |s(i)| |f(j)|)");
  int fast_bodies = 0, bitwise = 0, bitwise_R = 0;
  for (int i = 0; i < kCases; ++i) {
    Model m = i % 50 == 0 ? random_chain(rnd, 50 + (i / 50) % 8 * 50, ChainOptions{false})
                          : random_chain(rnd, 1 + i % 40, ChainOptions{true});
    for (int k = 1; k <= m.n(); ++k) {
      Body& B = m.body(k);
      if (B.hinge.nv() != 1) continue;
      B.hinge.axis = Vec3<double>::Zero();
      B.hinge.axis[int(g() % 3)] = g() % 2 ? 1.0 : -1.0;
      if (g() % 2) B.placement = Pose(Mat3<double>::Identity(), B.placement.l());
    }
    const State x = random_state(rnd, m);
    Workspace ws(m);
    update_phi(m, x.theta, ws);
    MassMatrixInertial fast(m), general(m);
    MatX<double> M_fast, M_general;
    mass_matrix_inertial(m, x, ws, fast, M_fast);
    m.fast_paths = false;
    mass_matrix_inertial(m, x, ws, general, M_general);
    for (int k = 1; k <= m.n(); ++k) {
      fast_bodies += fast.axis[k - 1] >= 0;
      const SpatialInertia &a = fast.R[k - 1], &b = general.R[k - 1];
      w_R.add((a.matrix() - b.matrix()).cwiseAbs().maxCoeff() /
                  (k * eps<double>() * b.matrix().cwiseAbs().maxCoeff()),
              i);
    }
    bool same_R = true;
    for (int k = 1; k <= m.n(); ++k) same_R &= fast.R[k - 1].matrix() == general.R[k - 1].matrix();
    bitwise_R += same_R;
    double worst = 0;
    for (int c = 0; c < m.nv(); ++c)
      for (int r = 0; r < m.nv(); ++r) {
        const double bound =
            m.n() * eps<double>() * general.s.row(r).norm() * general.f.row(c).norm();
        worst = std::max(worst, std::abs(M_fast(r, c) - M_general(r, c)) / bound);
      }
    w_M.add(worst, i);
    bitwise += M_fast == M_general;
    EXPECT_EQ((M_fast - M_fast.transpose()).cwiseAbs().maxCoeff(), 0.0);
  }
  std::printf("fast paths: %d bodies; bitwise equal in %d (R) and %d (M) of %d cases\n",
              fast_bodies, bitwise_R, bitwise, kCases);
  EXPECT_GT(fast_bodies, kCases);  // the fast paths were taken
  EXPECT_LE(w_R.value(), 2.0);     // worst seen 0.66
  EXPECT_LE(w_M.value(), 2.0);     // worst seen 0.85
}

template <class S>
class composite_Precision : public ::testing::Test {};
TYPED_TEST_SUITE(composite_Precision, Precisions, ScalarNames);

TYPED_TEST(composite_Precision, CrbMassMatrix) {
  using S = TypeParam;
  Random<S> rnd;
  Worst w("mass_matrix_crb - H phi M phi* H* (" + scalar_name<S>() + ") [N eps]");
  for (int i = 0; i < kCases; ++i) {
    const ModelT<S> m = random_chain(rnd, chain_size(i, kMaxBodies));
    const StateT<S> x = random_state(rnd, m);
    const OperatorsT<S> op = OperatorsT<S>::build(m, x);
    WorkspaceT<S> ws(m);
    update_phi(m, x.theta, ws);
    std::vector<SpatialInertiaT<S>> R(std::size_t(m.n()));
    MatX<S> M_crb;
    mass_matrix_crb(m, x, ws, R, M_crb);
    const double scale = double(op.phi.norm()) * double(op.phi.norm()) * double(op.M.norm()) *
                         double(op.H.norm()) * double(op.H.norm());
    w.add(residual(M_crb, op.mass_matrix(), scale) / (6 * m.n() * double(eps<S>())), i);
  }
  EXPECT_LE(w.value(), kTol);
}

}  // namespace
}  // namespace soa::test
