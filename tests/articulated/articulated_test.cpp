// Property tests of the articulated body inertias (lesson 6; soa::articulated_inertias):
// on soa::test::kCases random chains of every hinge type (1 to 12 bodies before locked hinges
// merge) from the fixed seed,
// - P(k), P+(k) symmetric positive semidefinite, D(k) positive definite;
// - tau_bar(k) = I - G(k)H(k) a projection, H(k)P+(k) = 0, tau_bar(k)P(k) = P+(k);
// - the definition: P(k) is the Schur complement of the outboard chain's free hinges in
//   the composite inertia, f(k) = P(k) alpha(k) at rest with the outboard hinges free;
// - P(k) <= R(k) in the Loewner order, with equality at the tip (nothing outboard);
// - with no free hinges (tau_bar = I) the Riccati recursion is the Lyapunov recursion of the
//   composite inertias and gives R(k);
// - the dense operator forms P = E_phi P+ E_phi* + M = E_psi P E_psi* + M,
//   P = blockdiag(psi M psi*), psi = (I - E_psi)^{-1} block lower triangular with
//   psi(i,j) = psi(i,i-1) psi(i-1,j), K = E_phi G, E_psi = E_phi tau_bar;
// - transform_symmetric(phi, P) == phi P phi* (dense 6x6);
// - the singular-D diagnostic (a massless tip, a point mass on the hinge axis, a nearly
//   singular inboard hinge) and no false alarm on a light but healthy body.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "property.hpp"
#include "random_chain.hpp"
#include "soa/chain.hpp"
#include "soa/soa.hpp"

namespace {

using soa::test::kCases;
using soa::test::Random;
using soa::test::Worst;
using Mat6 = soa::Mat6<double>;
using MatX = soa::MatX<double>;
using Vec3 = soa::Vec3<double>;

constexpr double kEps = soa::eps<double>();

int bodies(int i) {
  return 1 + i % 12;
}

// Smallest eigenvalue of a symmetric matrix (its symmetric part).
double lambda_min(const MatX& A) {
  const MatX S = 0.5 * (A + A.transpose());
  return Eigen::SelfAdjointEigenSolver<MatX>(S, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
}

// One random chain, its state, its articulated inertias and its dense operators.
struct Case {
  soa::Model m;
  soa::State x;
  soa::Articulated art;
  soa::Operators op;
  std::vector<Mat6> tau_bar;
  // The rounding of the Riccati step grows with kappa(k) = |P(k)| |D^{-1}(k)| (G = P H* D^{-1}):
  // kappa[k-1] is its largest value at bodies 1..k (errors travel inboard).
  std::vector<double> kappa;
  Case(soa::Model model, soa::State state)
      : m(std::move(model)), x(std::move(state)), art(m), op() {
    soa::Workspace ws(m);
    soa::update_phi(m, x.theta, ws);
    soa::articulated_inertias(m, x, ws, art);
    op = soa::Operators::build(m, x, {});
    double worst = 1;
    for (int k = 1; k <= m.n(); ++k) {
      tau_bar.push_back(art.tau_bar(m, x.theta, k));
      const MatX D = art.D[std::size_t(k - 1)];
      worst = std::max(worst, art.P[std::size_t(k - 1)].norm() * D.inverse().norm());
      kappa.push_back(worst);
    }
  }
};

Case random_case(Random<double>& rnd, int i) {
  soa::Model m = soa::test::random_chain(rnd, bodies(i));
  soa::State x = soa::test::random_state(rnd, m);
  return Case(std::move(m), std::move(x));
}

// The block diagonal 6n x 6n matrix of per-body 6x6 blocks, tip first.
MatX block_diagonal(const std::vector<Mat6>& b) {
  const int n = int(b.size());
  MatX out = MatX::Zero(6 * n, 6 * n);
  for (int k = 0; k < n; ++k) out.block<6, 6>(6 * k, 6 * k) = b[std::size_t(k)];
  return out;
}

// G = diag(G(k)), 6n x nv.
MatX dense_G(const Case& c) {
  MatX G = MatX::Zero(6 * c.m.n(), c.m.nv());
  for (int k = 1; k <= c.m.n(); ++k) {
    const soa::Body& B = c.m.body(k);
    G.block(6 * (k - 1), B.v_offset, 6, B.hinge.nv()) = c.art.G[std::size_t(k - 1)];
  }
  return G;
}

TEST(articulated_Riccati, InertiasSymmetricPositiveAndDPositiveDefinite) {
  Random<double> rnd;
  Worst sym("|P - P*|, |P+ - P+*| / (|P| kappa)"),
      psd("-lambda_min(P), -lambda_min(P+) / (|P| kappa)"), dpd("-lambda_min(D)/|D| (must be < 0)");
  double d_lowest = 1;
  for (int i = 0; i < kCases; ++i) {
    const Case c = random_case(rnd, i);
    for (int k = 1; k <= c.m.n(); ++k) {
      const Mat6& P = c.art.P[std::size_t(k - 1)];
      const Mat6& Pp = c.art.P_plus[std::size_t(k - 1)];
      const MatX D = c.art.D[std::size_t(k - 1)];
      const double scale = std::max(1.0, P.norm()) * c.kappa[std::size_t(k - 1)];
      sym.add(std::max((P - P.transpose()).norm(), (Pp - Pp.transpose()).norm()) / scale, i);
      psd.add(std::max({0.0, -lambda_min(P), -lambda_min(Pp)}) / scale, i);
      const double d = lambda_min(D) / D.norm();
      d_lowest = std::min(d_lowest, d);
      dpd.add(-d, i);
    }
  }
  EXPECT_LE(sym.value(), 64 * kEps);
  EXPECT_LE(psd.value(), 256 * kEps);
  EXPECT_GT(d_lowest, 0.0);
}

TEST(articulated_Riccati, TauBarProjection) {
  Random<double> rnd;
  Worst proj("|tau_bar^2 - tau_bar| / (|tau_bar| kappa)"), hp("|H P+| / (|P| kappa)"),
      tp("|tau_bar P - P+| / (|P| kappa)"), sym("|tau_bar P tau_bar* - P+| / (|P| kappa)");
  for (int i = 0; i < kCases; ++i) {
    const Case c = random_case(rnd, i);
    for (int k = 1; k <= c.m.n(); ++k) {
      const soa::Body& B = c.m.body(k);
      const Mat6& T = c.tau_bar[std::size_t(k - 1)];
      const Mat6& P = c.art.P[std::size_t(k - 1)];
      const Mat6& Pp = c.art.P_plus[std::size_t(k - 1)];
      const double scale = std::max(1.0, P.norm()) * c.kappa[std::size_t(k - 1)];
      const soa::JointMap<double> Hs = B.hinge.H_star(c.x.theta.data() + B.q_offset);
      proj.add((T * T - T).norm() / (std::max(1.0, T.norm()) * c.kappa[std::size_t(k - 1)]), i);
      hp.add((Hs.transpose() * Pp).norm() / scale, i);
      tp.add((T * P - Pp).norm() / scale, i);
      sym.add((T * P * T.transpose() - Pp).norm() / scale, i);
    }
  }
  EXPECT_LE(proj.value(), 64 * kEps);
  EXPECT_LE(hp.value(), 64 * kEps);
  EXPECT_LE(tp.value(), 64 * kEps);
  EXPECT_LE(sym.value(), 64 * kEps);
}

TEST(articulated_Riccati, BelowCompositeInLoewnerOrder) {
  Random<double> rnd;
  Worst loewner("-lambda_min(R - P) / |R|"), tip("|P(1) - R(1)|, |P(1) - M(1)|");
  for (int i = 0; i < kCases; ++i) {
    const Case c = random_case(rnd, i);
    for (int k = 1; k <= c.m.n(); ++k) {
      const Mat6 R = c.art.R[std::size_t(k - 1)].matrix();
      const Mat6& P = c.art.P[std::size_t(k - 1)];
      loewner.add(std::max(0.0, -lambda_min(R - P)) / std::max(1.0, R.norm()), i);
    }
    const Mat6 M1 = c.m.body(1).M.matrix();
    tip.add(
        std::max(soa::test::rel(c.art.P[0], c.art.R[0].matrix()), soa::test::rel(c.art.P[0], M1)),
        i);
  }
  EXPECT_LE(loewner.value(), 256 * kEps);
  EXPECT_LE(tip.value(), 16 * kEps);
}

// With no free hinge outboard of body k the outboard bodies move with it: tau_bar = I in the
// Riccati recursion (P+ = P), which is then the Lyapunov recursion of the composite
// inertias, R(k) = phi(k,k-1) R(k-1) phi*(k,k-1) + M(k).
TEST(articulated_Riccati, NoFreeHingesGivesComposite) {
  Random<double> rnd;
  Worst w("|P(tau_bar = I) - R| / |R|");
  for (int i = 0; i < kCases; ++i) {
    const Case c = random_case(rnd, i);
    soa::Workspace ws(c.m);
    soa::update_phi(c.m, c.x.theta, ws);
    Mat6 P = Mat6::Zero();
    for (int k = 1; k <= c.m.n(); ++k) {
      const Mat6 Pp = P;  // tau_bar = I: nothing taken out
      P = c.m.body(k).M.matrix();
      if (k > 1) P += soa::transform_symmetric(ws.phi[std::size_t(k - 2)], Pp);
      w.add(soa::test::rel(P, c.art.R[std::size_t(k - 1)].matrix()), i);
    }
  }
  EXPECT_LE(w.value(), 64 * kEps);
}

// The definition: at rest, with the hinges k-1..1 free (T = 0 there), the force that gives
// body k the acceleration alpha(k) is f(k) = P(k) alpha(k), where eliminating the outboard
// hinge accelerations gives the Schur complement P(k) = R(k) - X M'^{-1} X* with, on bodies
// 1..k, A = phi M phi*, R(k) = E_k* A E_k, X = E_k* A H'*, M' = H' A H'*.
TEST(articulated_Riccati, DefinitionSchurComplement) {
  Random<double> rnd;
  Worst w("|P(k) - (R - X M'^-1 X*)| / (|R| kappa)");
  for (int i = 0; i < kCases; ++i) {
    const Case c = random_case(rnd, i);
    for (int k = 1; k <= c.m.n(); ++k) {
      const int nv_out = c.m.body(k).v_offset;  // the dofs of bodies 1..k-1
      const MatX phi = c.op.phi.topLeftCorner(6 * k, 6 * k);
      const MatX A = phi * c.op.M.topLeftCorner(6 * k, 6 * k) * phi.transpose();
      Mat6 P = A.bottomRightCorner<6, 6>();
      if (nv_out > 0) {
        const MatX Hp = c.op.H.topLeftCorner(nv_out, 6 * k);
        const MatX X = A.bottomRows<6>() * Hp.transpose();
        P -= X * (Hp * A * Hp.transpose()).ldlt().solve(X.transpose());
      }
      w.add((P - c.art.P[std::size_t(k - 1)]).norm() /
                (std::max(1.0, A.norm()) * c.kappa[std::size_t(k - 1)]),
            i);
    }
  }
  EXPECT_LE(w.value(), 256 * kEps);
}

TEST(articulated_Operators, DenseForms) {
  Random<double> rnd;
  Worst lyap_phi("|P - (E_phi P+ E_phi* + M)| / (|E_phi P+ E_phi*| kappa)"),
      lyap_psi("|P - (E_psi P E_psi* + M)|"), unrolled("|P - blockdiag(psi M psi*)|"),
      lower("|upper blocks of psi|, |psi(i,i) - I|"), chain("|psi(i,j) - psi(i,i-1) psi(i-1,j)|"),
      kk("|K - E_phi G|, |E_psi - E_phi tau_bar|");
  for (int i = 0; i < kCases; ++i) {
    const Case c = random_case(rnd, i);
    const int n = c.m.n(), N = 6 * n;
    const MatX P = block_diagonal(c.art.P), Pp = block_diagonal(c.art.P_plus);
    const MatX tau_bar = block_diagonal(c.tau_bar);
    const MatX G = dense_G(c);
    const MatX K = c.op.E_phi * G;
    const MatX E_psi = c.op.E_phi * tau_bar;
    const MatX psi = (MatX::Identity(N, N) - E_psi).inverse();
    const double scale = std::max(1.0, P.norm());
    const MatX moved = c.op.E_phi * Pp * c.op.E_phi.transpose();
    // transform_symmetric reads P+ as symmetric; P+ = P - G D G* is so to eps kappa only.
    lyap_phi.add((P - (moved + c.op.M)).norm() / (std::max(scale, moved.norm()) * c.kappa.back()),
                 i);
    // E_psi and psi carry G = P H* D^{-1}: their rounding grows with kappa.
    lyap_psi.add((P - (E_psi * P * E_psi.transpose() + c.op.M)).norm() / (scale * c.kappa.back()),
                 i);
    const MatX full = psi * c.op.M * psi.transpose();
    double diag = 0;
    for (int k = 0; k < n; ++k)
      diag = std::max(diag, (P.block<6, 6>(6 * k, 6 * k) - full.block<6, 6>(6 * k, 6 * k)).norm());
    unrolled.add(diag / (scale * c.kappa.back()), i);
    double up = 0, ch = 0, kd = 0;
    const double ps = std::max(1.0, psi.norm());
    for (int a = 0; a < n; ++a) {
      for (int b = a + 1; b < n; ++b) up = std::max(up, psi.block<6, 6>(6 * a, 6 * b).norm());
      up = std::max(up, (psi.block<6, 6>(6 * a, 6 * a) - Mat6::Identity()).norm());
      for (int b = 0; b < a; ++b)
        ch = std::max(ch, (psi.block<6, 6>(6 * a, 6 * b) - psi.block<6, 6>(6 * a, 6 * (a - 1)) *
                                                               psi.block<6, 6>(6 * (a - 1), 6 * b))
                              .norm());
      if (a > 0) {
        // Block (k+1, k) of E_psi is phi(k+1,k) tau_bar(k); of K, phi(k+1,k) G(k).
        const Mat6 phi = c.op.E_phi.block<6, 6>(6 * a, 6 * (a - 1));
        kd = std::max(
            kd,
            (E_psi.block<6, 6>(6 * a, 6 * (a - 1)) - phi * c.tau_bar[std::size_t(a - 1)]).norm());
        const soa::Body& B = c.m.body(a);
        kd = std::max(
            kd, (K.block(6 * a, B.v_offset, 6, B.hinge.nv()) - phi * c.art.G[std::size_t(a - 1)])
                    .norm());
      }
    }
    lower.add(up / ps, i);
    chain.add(ch / ps, i);
    kk.add(kd / std::max(1.0, K.norm() + E_psi.norm()), i);
  }
  EXPECT_LE(lyap_phi.value(), 64 * kEps);
  EXPECT_LE(lyap_psi.value(), 256 * kEps);
  EXPECT_LE(unrolled.value(), 256 * kEps);
  EXPECT_LE(lower.value(), 1e3 * kEps);
  EXPECT_LE(chain.value(), 1e4 * kEps);
  EXPECT_LE(kk.value(), 64 * kEps);
}

TEST(articulated_Operators, TransformSymmetric) {
  Random<double> rnd;
  Worst w("|transform_symmetric(phi, P) - phi P phi*| / |phi P phi*|");
  for (int i = 0; i < kCases; ++i) {
    const soa::Phi phi = rnd.phi();
    Mat6 A;
    for (int r = 0; r < 6; ++r)
      for (int s = 0; s < 6; ++s) A(r, s) = rnd.normal();
    const Mat6 P = A + A.transpose();
    const Mat6 dense = phi.matrix() * P * phi.matrix().transpose();
    w.add(soa::test::rel(soa::transform_symmetric(phi, P), dense), i);
  }
  EXPECT_LE(w.value(), 64 * kEps);
}

// The shift along a coordinate axis (detail::shift_on_axis()) drops only products with the
// exact zeros of l and sums with exactly zero terms: with a general rotation, so that only
// the shift differs, the fast path equals the general one bit for bit (== counts -0 as 0).
TEST(articulated_Operators, TransformSymmetricShiftOnAnAxisIsBitwiseGeneral) {
  Random<double> rnd;
  int differing = 0, taken = 0;
  for (int i = 0; i < kCases; ++i) {
    const soa::Phi general = rnd.phi();
    Vec3 l = Vec3::Zero();
    l[i % 3] = (i % 2 ? -1.0 : 1.0) * general.l().norm();
    const soa::Phi phi(general.R(), l);
    taken += soa::detail::coordinate_offset(phi.l()) == i % 3;
    Mat6 A;
    for (int r = 0; r < 6; ++r)
      for (int s = 0; s < 6; ++s) A(r, s) = rnd.normal();
    const Mat6 P = A + A.transpose();
    Mat6 fast, slow;
    soa::transform_symmetric(phi, P, fast, true);
    soa::transform_symmetric(phi, P, slow, false);
    differing += !(fast.array() == slow.array()).all();
  }
  EXPECT_EQ(taken, kCases);
  EXPECT_EQ(differing, 0);
}

// --- the singular-D diagnostic -----------------------------------------------------------

soa::Hinge revolute(const Vec3& axis) {
  soa::Hinge h;
  h.type = soa::HingeType::Revolute;
  h.axis = axis.normalized();
  return h;
}

soa::Body body(const std::string& name, const soa::SpatialInertia& M, const Vec3& offset,
               const soa::Hinge& h) {
  soa::Body b;
  b.name = name;
  b.M = M;
  b.placement = soa::Pose(soa::Mat3<double>::Identity(), offset);
  b.hinge = h;
  return b;
}

// A point mass m at p about O_k, with rotational inertia scale*m|p|^2 * I about its centre.
soa::SpatialInertia point_mass(double m, const Vec3& p, double J) {
  return soa::SpatialInertia::from_cm(m, p, J * soa::Mat3<double>::Identity());
}

// The message thrown by articulated_inertias on chain m, or "" when it does not throw.
std::string diagnostic(const soa::Model& m) {
  const soa::State x = soa::State::rest(m);
  soa::Workspace ws(m);
  soa::update_phi(m, x.theta, ws);
  soa::Articulated art(m);
  try {
    soa::articulated_inertias(m, x, ws, art);
  } catch (const soa::Error& e) {
    return e.what();
  }
  return "";
}

const soa::SpatialInertia kLink = point_mass(2.0, Vec3(0.3, 0.1, 0.0), 0.05);

TEST(articulated_SingularD, MasslessTip) {
  const soa::Model m = soa::Model::from_base_first(
      {body("link", kLink, Vec3(0, 0, 0.5), revolute(Vec3::UnitZ())),
       body("massless_tip", soa::SpatialInertia(), Vec3(0.5, 0, 0), revolute(Vec3::UnitZ()))});
  const std::string msg = diagnostic(m);
  EXPECT_EQ(msg.rfind("body 'massless_tip': articulated inertia D(1) singular: "
                      "lambda_min(D)/lambda_max(H Q H*) = 0,",
                      0),
            0u)
      << msg;
}

TEST(articulated_SingularD, PointMassOnTheAxis) {
  const soa::Model m =
      soa::Model::from_base_first({body("link", kLink, Vec3(0, 0, 0.5), revolute(Vec3::UnitZ())),
                                   body("bead", point_mass(1.0, Vec3(0, 0, 0.2), 0.0),
                                        Vec3(0.5, 0, 0), revolute(Vec3::UnitZ()))});
  const std::string msg = diagnostic(m);
  EXPECT_EQ(msg.rfind("body 'bead': articulated inertia D(1) singular: ", 0), 0u) << msg;
}

// Inboard, D(2) is what hinge 2 feels through the free spherical hinge of the tip: only the
// tip's mass at the joint (on axis 2) and body 2's own rotational inertia J about axis 2.
// With J = 1e-20 of H Q H* (Q = phi P(1) phi* + M(2) counts the tip's rotational inertia)
// D(2) is numerically singular; with J = 1e-6 it is light but healthy.
soa::Model spherical_tip_chain(double J) {
  soa::Hinge ball;
  ball.type = soa::HingeType::Spherical;
  return soa::Model::from_base_first(
      {body("carrier", point_mass(1.0, Vec3(0, 0, 0.1), J), Vec3(0, 0, 0.5),
            revolute(Vec3::UnitZ())),
       body("ball", point_mass(1.0, Vec3(0.2, 0, 0), 0.5), Vec3(0, 0, 0.3), ball)});
}

TEST(articulated_SingularD, NearlySingularInboard) {
  const std::string msg = diagnostic(spherical_tip_chain(1e-20));
  EXPECT_EQ(msg.rfind("body 'carrier': articulated inertia D(2) singular: ", 0), 0u) << msg;
  EXPECT_NE(msg.find("below the threshold"), std::string::npos) << msg;
  // The ratio reported is that of J = 1e-20 to the composite inertia about axis 2.
  const std::size_t at = msg.find("= ");
  ASSERT_NE(at, std::string::npos) << msg;
  const double ratio = std::stod(msg.substr(at + 2));
  std::printf("  reported ratio %.3g (threshold %.3g)\n", ratio,
              soa::singular_D_threshold<double>());
  EXPECT_GE(ratio, 0.0);
  EXPECT_LT(ratio, 1e-18);
}

TEST(articulated_SingularD, LightButHealthy) {
  EXPECT_EQ(diagnostic(spherical_tip_chain(1e-6)), "");
}

}  // namespace
