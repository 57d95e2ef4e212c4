// Lesson 7 exercise tests: each exercise of exercises/07-mass-matrix-factorization/exercises.hpp
// against the library, on soa::test::kCases random chains (1 to 8 bodies whose hinge types are
// drawn at random: tests/support/chain_case.hpp) at random configurations, from a fixed seed per
// exercise. Each check names its quantity, and its catalogue of classic mistakes is computed from
// the reference (tests/support/exercise_check.hpp); mistakes inside a recursion come from a small
// parameterized reference in this file (minv_diagonal_variant(), solve_variant(), ...). Built
// against the solutions (ctest), the students' exercises (make exercises) and the solutions with
// planted mistakes (the "planted mistakes" blocks, tests/exercises/plant.cmake).  Tolerances: a
// case passes when its error is at most 4 units, a unit being eps times the size 6n of the
// operators times kappa = max_k |P(k)| |D^-1(k)| (the growth of rounding in G = P H* D^-1) times
// the magnitude of the terms, or eps 6n cond(M) times the magnitude where a result is compared with
// an inverse or a determinant of M.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "chain_case.hpp"
#include "exercise_check.hpp"
#include "exercises.hpp"
#include "property.hpp"
#include "random_chain.hpp"
#include "soa/chain/mass_matrix_inverse_upsilon.hpp"

namespace {

using soa::test::CaseOptions;
using soa::test::Check;
using soa::test::EntryName;
using soa::test::kCases;
using soa::test::Mistake;
using soa::test::Mistakes;
using soa::test::Naming;
using soa::test::Random;
using MatX = soa::MatX<double>;
using VecX = soa::VecX<double>;
using Mat6 = soa::Mat6<double>;

constexpr double kEps = soa::eps<double>();

double at_least_1(double a) {
  return std::max(1.0, a);
}

template <class A, class B>
bool same_shape(const A& a, const B& b) {
  return a.rows() == b.rows() && a.cols() == b.cols();
}

// The per-body quantities of a chain at a configuration: phi(k+1,k), the Riccati results of
// lesson 6, tau_bar(k), H*(k), and Upsilon(k) of lesson 7 (all entry k - 1).
struct Parts {
  int n = 0, nv = 0;
  std::vector<int> off, nk;
  std::vector<Mat6> phi, tau, Ups;
  std::vector<MatX> G, Hs, D, Dinv;
  Parts(const soa::Model& m, const soa::State& x) : n(m.n()), nv(m.nv()) {
    soa::Workspace ws(m);
    soa::update_phi(m, x.theta, ws);
    soa::Upsilon u(m);
    soa::upsilons(m, x, ws, u);
    for (int k = 1; k <= n; ++k) {
      const soa::Body& B = m.body(k);
      const auto j = std::size_t(k - 1);
      off.push_back(B.v_offset);
      nk.push_back(B.hinge.nv());
      phi.push_back(ws.phi[j].matrix());
      tau.push_back(u.art.tau_bar(m, x.theta, k));
      Ups.push_back(u.Upsilon[j]);
      G.push_back(MatX(u.art.G[j]));
      Hs.push_back(MatX(B.hinge.H_star(x.theta.data() + B.q_offset)));
      D.push_back(MatX(u.art.D[j]));
      Dinv.push_back(MatX(u.art.D_inv[j]));
    }
  }
  // psi(k+1,k) = phi(k+1,k) tau_bar(k).
  Mat6 psi_step(int k) const { return phi[std::size_t(k - 1)] * tau[std::size_t(k - 1)]; }
  auto block(MatX& A, int k, int i) const {
    return A.block(off[std::size_t(k - 1)], off[std::size_t(i - 1)], nk[std::size_t(k - 1)],
                   nk[std::size_t(i - 1)]);
  }
};

// A random chain at a random configuration (at rest unless a test sets beta), with the
// library's innovations operators, the mass matrix by composite bodies and its O(N^2) inverse.
struct Case {
  soa::Model m;
  soa::State x;
  unsigned tags = 0;
  soa::InnovationsOperators io;
  MatX M, Minv;
  double kappa = 1, n6 = 6, cond = 1;
  Case(Random<double>& rnd, int i) {
    const CaseOptions opt{true, false, false, false, false, 8};
    soa::test::ChainCase c = soa::test::draw_chain_case(rnd, i, opt);
    m = c.m;
    x = c.x;
    tags = c.tags;
    io = soa::InnovationsOperators::build(m, x);
    soa::Workspace ws(m);
    soa::update_phi(m, x.theta, ws);
    std::vector<soa::SpatialInertia> R(std::size_t(m.n()));
    soa::mass_matrix_crb(m, x, ws, R, M);
    soa::MassMatrixInverse w(m);
    soa::mass_matrix_inverse(m, x, ws, w, Minv);
    for (int k = 1; k <= m.n(); ++k) {
      const int r = 6 * (k - 1), o = m.body(k).v_offset, nk = m.body(k).hinge.nv();
      kappa = std::max(kappa, io.P.block(r, r, 6, 6).norm() * io.D_inv.block(o, o, nk, nk).norm());
    }
    n6 = 6.0 * m.n();
    const VecX ev = Eigen::SelfAdjointEigenSolver<MatX>(M, Eigen::EigenvaluesOnly).eigenvalues();
    cond = ev.maxCoeff() / ev.minCoeff();
  }
  double unit() const { return kEps * n6 * kappa; }
  // The case as code, then the call of the exercise.
  std::string code(const std::string& call) const {
    return soa::test::code("m", m) + soa::test::code("x", x) + call + "\n";
  }
};

// A 6n x nv matrix: block (k, j) of body k's rows and the dofs of body j.
Naming body_dof_blocks(const soa::Model& m, const std::string& sym) {
  return [map = soa::test::DofMap(m), sym](Eigen::Index i, Eigen::Index j) {
    const int body = j < Eigen::Index(map.body.size()) ? map.body[std::size_t(j)] : 0;
    const std::string b = std::to_string(i / 6 + 1) + "," + std::to_string(body);
    return EntryName{sym + "(" + std::to_string(i) + "," + std::to_string(j) + ")",
                     "block (" + b + ") of " + sym};
  };
}

// The strictly block lower triangular 6n x 6n matrix with block (k+1, k) = step(k).
template <class F>
MatX shift_operator(int n, F step) {
  MatX E = MatX::Zero(6 * n, 6 * n);
  for (int k = 1; k < n; ++k) E.block(6 * k, 6 * (k - 1), 6, 6) = step(k);
  return E;
}

MatX inverse_of_unit_lower(const MatX& I_minus_E) {
  const MatX I = MatX::Identity(I_minus_E.rows(), I_minus_E.cols());
  return I_minus_E.triangularView<Eigen::UnitLower>().solve(I);
}

}  // namespace

// --- 7.1 ------------------------------------------------------------------------------------------

// K = E_phi G with a classic mistake in it.
enum class KV { PhiTransposed, SameRow, ShiftUp, HStar };
MatX K_variant(const Parts& p, KV v) {
  MatX K = MatX::Zero(6 * p.n, p.nv);
  for (int k = 1; k <= p.n; ++k) {
    const auto j = std::size_t(k - 1);
    if (v == KV::ShiftUp) {  // E_phi* G: block (k-1, k) = phi*(k,k-1) G(k)
      if (k > 1) K.block(6 * (k - 2), p.off[j], 6, p.nk[j]) = p.phi[j - 1].transpose() * p.G[j];
      continue;
    }
    if (k == p.n) continue;
    const Mat6 phi = v == KV::PhiTransposed ? Mat6(p.phi[j].transpose()) : p.phi[j];
    const MatX rhs = v == KV::HStar ? p.Hs[j] : p.G[j];
    K.block(v == KV::SameRow ? 6 * (k - 1) : 6 * k, p.off[j], 6, p.nk[j]) = phi * rhs;
  }
  return K;
}

// psi = (I - E_psi)^-1 with a classic mistake in E_psi (or in the inverse).
enum class PsiV { PhiTransposed, TauTransposed, Order, NoTau, PlusSign, FirstTerm };
MatX psi_variant(const Parts& p, PsiV v) {
  const MatX E = shift_operator(p.n, [&](int k) -> Mat6 {
    const auto j = std::size_t(k - 1);
    switch (v) {
      case PsiV::PhiTransposed:
        return p.phi[j].transpose() * p.tau[j];
      case PsiV::TauTransposed:
        return p.phi[j] * p.tau[j].transpose();
      case PsiV::Order:
        return p.tau[j + 1] * p.phi[j];
      case PsiV::NoTau:
        return p.phi[j];
      default:
        return p.phi[j] * p.tau[j];
    }
  });
  const MatX I = MatX::Identity(E.rows(), E.cols());
  if (v == PsiV::FirstTerm) return I + E;
  if (v == PsiV::PlusSign) return (I + E).inverse();
  return inverse_of_unit_lower(I - E);
}

// clang-format off
/* planted mistakes of 7.1
soa_plant(7.1 transpose
  FIND [=[phi * r.art.tau_bar(m, x.theta, k)]=]
  WRONG [=[phi.transpose() * r.art.tau_bar(m, x.theta, k)]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(transpose\): your E_psi\(k\+1,k\) is phi\*\(k\+1,k\) tau_bar\(k\)]=])
*/
// clang-format on
TEST(Exercise7_1_KAndPsi, MatchesLibraryAndIdentity) {
  Random<double> rnd(701);
  // Declared in the order of their reports (the table shows the first failure).
  Check K_check("K = E_phi G, the 6n x nv operator", 4.0);
  Check psi_check("psi = (I - E_phi tau_bar)^-1", 4.0);
  Check id_check("phi^-1 - psi^-1 = -K H with your K and psi", 4.0);
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const soa::ex07::KAndPsi kp = soa::ex07::k_and_psi(c.m, c.x);
    const Parts p(c.m, c.x);
    auto inputs = [&] { return c.code("auto kp = soa::ex07::k_and_psi(m, x);"); };
    auto K_mistakes = [&] {
      return Mistakes{
          {"transpose",
           "your K(k+1,k) is phi*(k+1,k) G(k): K = E_phi G takes phi(k+1,k) itself "
           "(ws.phi[k-1].matrix())",
           K_variant(p, KV::PhiTransposed)},
          {"neighbour index",
           "your phi(k+1,k) G(k) sits at block row k: E_phi puts it one body inboard, at block "
           "(k+1, k)",
           K_variant(p, KV::SameRow)},
          {"transpose", "your K is E_phi* G (blocks above the diagonal): K = E_phi G",
           K_variant(p, KV::ShiftUp)},
          {"wrong operator",
           "your K is E_phi H*: K = E_phi G with the gain G(k) = P(k) H*(k) D^-1(k), not H*(k)",
           K_variant(p, KV::HStar)},
      };
    };
    auto psi_mistakes = [&] {
      return Mistakes{
          {"transpose",
           "your E_psi(k+1,k) is phi*(k+1,k) tau_bar(k): E_psi = E_phi tau_bar takes phi(k+1,k) "
           "itself",
           psi_variant(p, PsiV::PhiTransposed)},
          {"transpose", "your tau_bar(k) is transposed (I - H* G*): tau_bar(k) = I - G(k) H(k)",
           psi_variant(p, PsiV::TauTransposed)},
          {"order",
           "your psi is (I - tau_bar E_phi)^-1: E_psi = E_phi tau_bar, with tau_bar(k) on the "
           "right of phi(k+1,k)",
           psi_variant(p, PsiV::Order)},
          {"dropped term", "your psi is phi: E_psi = E_phi tau_bar, tau_bar is missing",
           psi_variant(p, PsiV::NoTau)},
          {"sign", "your psi is (I + E_psi)^-1: psi = (I - E_psi)^-1",
           psi_variant(p, PsiV::PlusSign)},
          {"dropped term",
           "your psi is I + E_psi, the first terms of the series: psi = (I - E_psi)^-1 = I + "
           "E_psi + E_psi^2 + ...",
           psi_variant(p, PsiV::FirstTerm)},
      };
    };
    const bool K_ok = same_shape(kp.K, c.io.K), psi_ok = same_shape(kp.psi, c.io.psi);
    K_check.add(i, kp.K, c.io.K, c.unit() * at_least_1(c.io.K.norm()), c.tags, inputs, K_mistakes,
                body_dof_blocks(c.m, "K"));
    psi_check.add(i, kp.psi, c.io.psi, c.unit() * at_least_1(c.io.psi.norm()), c.tags, inputs,
                  psi_mistakes, soa::test::body_blocks("psi"));
    if (!K_ok || !psi_ok) continue;
    const MatX phi_inv = c.io.op.phi.inverse(), psi_inv = kp.psi.inverse();
    const MatX KH = kp.K * c.io.op.H;
    id_check.add(i, MatX(psi_inv - KH), phi_inv,
                 c.unit() * at_least_1(std::max({phi_inv.norm(), psi_inv.norm(), KH.norm()})),
                 c.tags, inputs, {}, soa::test::body_blocks("psi^-1 - K H"));
  }
}

// --- 7.2 ------------------------------------------------------------------------------------------

// The part of a matrix on and above its diagonal blocks (block lower triangular: zero above).
MatX upper_and_diagonal(const soa::Model& m, const MatX& L) {
  MatX U = MatX::Zero(L.rows(), L.cols());
  for (int k = 1; k <= m.n(); ++k) {
    const int o = m.body(k).v_offset, nk = m.body(k).hinge.nv();
    U.block(0, o, o + nk, nk) = L.block(0, o, o + nk, nk);
  }
  return U;
}

// clang-format off
/* planted mistakes of 7.2
soa_plant(7.2 sign
  FIND [=[I - op.H * psi * K]=]
  WRONG [=[I + op.H * psi * K]=] TYPE [=[MatX]=]
  EXPECT [=[likely mistake \(sign\): your L_inv is I \+ H psi K]=])
*/
// clang-format on
TEST(Exercise7_2_InnovationsFactor, FactorsTheMassMatrix) {
  Random<double> rnd(702);
  // Declared in the order of their reports (the table shows the first failure).
  Check L_check("L = I + H phi K, the innovations factor", 4.0);
  Check Li_check("L_inv = I - H psi K, its inverse", 4.0);
  Check D_check("D = diag(D(k)), the articulated hinge inertias", 4.0);
  Check ldl_check("L D L* = M with your L and D", 4.0);
  Check inv_check("L L_inv = I with your L and L_inv", 4.0);
  Check tri_check("L block unit lower triangular (its diagonal blocks I, zero above)", 4.0);
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const soa::ex07::InnovationsFactor f = soa::ex07::innovations_factor(c.m, c.x);
    const int nv = c.m.nv();
    const MatX I = MatX::Identity(nv, nv);
    const MatX L = c.io.factor(), Li = c.io.factor_inverse();
    const MatX& H = c.io.op.H;
    const MatX HphiK = H * c.io.op.phi * c.io.K, HpsiK = H * c.io.psi * c.io.K;
    auto inputs = [&] { return c.code("auto f = soa::ex07::innovations_factor(m, x);"); };
    const Mistakes L_variants = {
        {"transpose", "your L is [I + H phi K]*, upper triangular: L = I + H phi K", L.transpose()},
        {"sign", "your L is I - H phi K: L = I + H phi K (its inverse is I - H psi K)", I - HphiK},
        {"dropped term", "your L is H phi K without I: L = I + H phi K", HphiK},
        {"wrong operator", "your L has psi where phi belongs: L = I + H phi K", I + HpsiK},
        {"inverse", "your L is the inverse factor I - H psi K: L = I + H phi K", Li},
    };
    auto L_mistakes = [&] { return L_variants; };
    auto Li_mistakes = [&] {
      return Mistakes{
          {"sign", "your L_inv is I + H psi K: L^-1 = I - H psi K", I + HpsiK},
          {"wrong operator", "your L_inv has phi where psi belongs: L^-1 = I - H psi K", I - HphiK},
          {"transpose", "your L_inv is [I - H psi K]*: L^-1 = I - H psi K, lower triangular",
           Li.transpose()},
      };
    };
    auto D_mistakes = [&] {
      return Mistakes{{"inverse", "your D holds D^-1(k): D(k) = H(k) P(k) H*(k)", c.io.D_inv}};
    };
    auto ldl_mistakes = [&] {
      Mistakes out;
      for (const Mistake& mk : L_variants)
        out.push_back(Mistake{mk.kind, mk.says, mk.value * c.io.D * mk.value.transpose()});
      out.push_back(Mistake{"inverse", "your D holds D^-1(k): D(k) = H(k) P(k) H*(k)",
                            L * c.io.D_inv * L.transpose()});
      return out;
    };
    const bool L_ok = same_shape(f.L, L), Li_ok = same_shape(f.L_inv, Li),
               D_ok = same_shape(f.D, c.io.D);
    L_check.add(i, f.L, L, c.unit() * at_least_1(L.norm()), c.tags, inputs, L_mistakes,
                soa::test::dof_blocks(c.m, "L"));
    Li_check.add(i, f.L_inv, Li, c.unit() * at_least_1(Li.norm()), c.tags, inputs, Li_mistakes,
                 soa::test::dof_blocks(c.m, "L_inv"));
    D_check.add(i, f.D, c.io.D, c.unit() * at_least_1(c.io.D.norm()), c.tags, inputs, D_mistakes,
                soa::test::dof_blocks(c.m, "D"));
    if (!L_ok || !Li_ok || !D_ok) continue;
    ldl_check.add(i, MatX(f.L * f.D * f.L.transpose()), c.M,
                  c.unit() * at_least_1(std::max(f.L.squaredNorm() * f.D.norm(), c.M.norm())),
                  c.tags, inputs, ldl_mistakes, soa::test::dof_blocks(c.m, "L D L*"));
    inv_check.add(i, MatX(f.L * f.L_inv), I, c.unit() * at_least_1(f.L.norm() * f.L_inv.norm()),
                  c.tags, inputs, {}, soa::test::dof_blocks(c.m, "L L_inv"));
    tri_check.add(
        i, upper_and_diagonal(c.m, f.L), upper_and_diagonal(c.m, I),
        c.unit() * at_least_1(f.L.norm()), c.tags, inputs,
        [&] {
          return Mistakes{{"transpose", "your L is upper triangular: L = I + H phi K is lower",
                           upper_and_diagonal(c.m, L.transpose())}};
        },
        soa::test::dof_blocks(c.m, "L"));
  }
}

// --- 7.3 ------------------------------------------------------------------------------------------

// The diagonal blocks of M^-1 by the recursions of 7.3 with a classic mistake in them, placed
// on the diagonal of an nv x nv matrix.
enum class DiagV {
  TauRight,  // tau_bar U tau_bar* in the Upsilon recursion
  PsiRight,  // psi Upsilon psi*
  Unmoved,   // Upsilon+(k) = Upsilon(k+1), not moved to O_k
  Sign,      // D^-1 - G* Upsilon+ G
  Own,       // D^-1 + G* Upsilon(k) G
  NoTau,     // phi in place of psi in the recursion
  OnlyDinv,  // D^-1(k) alone
  DforDinv,  // D(k) wherever D^-1(k) belongs
};
MatX minv_diagonal_variant(const Parts& p, DiagV v) {
  MatX out = MatX::Zero(p.nv, p.nv);
  Mat6 Ups = Mat6::Zero();  // Upsilon(k+1)
  for (int k = p.n; k >= 1; --k) {
    const auto j = std::size_t(k - 1);
    const MatX& Di = v == DiagV::DforDinv ? p.D[j] : p.Dinv[j];
    const Mat6 phi = p.phi[j], tau = p.tau[j];
    const Mat6 U = k == p.n              ? Mat6::Zero()
                   : v == DiagV::Unmoved ? Ups
                                         : Mat6(phi.transpose() * Ups * phi);
    const Mat6 HDH = p.Hs[j] * Di * p.Hs[j].transpose();
    Mat6 next;
    if (v == DiagV::TauRight)
      next = tau * U * tau.transpose() + HDH;
    else if (v == DiagV::PsiRight)
      next = phi * tau * Ups * tau.transpose() * phi.transpose() + HDH;
    else if (v == DiagV::NoTau)
      next = U + HDH;
    else
      next = tau.transpose() * U * tau + HDH;
    const MatX& G = p.G[j];
    MatX blk = Di + G.transpose() * U * G;
    if (v == DiagV::Sign) blk = Di - G.transpose() * U * G;
    if (v == DiagV::Own) blk = Di + G.transpose() * next * G;
    if (v == DiagV::OnlyDinv) blk = Di;
    p.block(out, k, k) = blk;
    Ups = next;
  }
  return out;
}

// clang-format off
/* planted mistakes of 7.3
soa_plant(7.3 wrong-frame
  FIND [=[phi.transpose() * Upsilon * phi]=]
  WRONG [=[Upsilon]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(wrong frame\): your Upsilon\+\(k\) is Upsilon\(k\+1\) as it is]=])
soa_plant(7.3 transpose
  FIND [=[tau.transpose() * U * tau]=]
  WRONG [=[tau * U * tau.transpose()]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(transpose\): your Upsilon\(k\) = tau_bar\(k\) U tau_bar\*\(k\)]=])
soa_plant(7.3 sign
  FIND [=[D_inv + G.transpose() * U * G]=]
  WRONG [=[D_inv - G.transpose() * U * G]=] TYPE [=[MatX]=]
  EXPECT [=[likely mistake \(sign\): your M\^-1\(k,k\) is D\^-1\(k\) - G\* Upsilon\+ G]=])
*/
// clang-format on
TEST(Exercise7_3_MinvDiagonal, MatchesMassMatrixInverse) {
  Random<double> rnd(703);
  Check check("M^-1(k,k), the diagonal blocks of M^-1", 4.0);
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const std::vector<MatX> d = soa::ex07::minv_diagonal(c.m, c.x);
    if (int(d.size()) != c.m.n()) {
      ADD_FAILURE() << "M^-1(k,k), the diagonal blocks of M^-1: your result has " << d.size()
                    << " blocks, expected one per body, n = " << c.m.n() << " (case " << i << ")";
      return;
    }
    MatX got = MatX::Zero(c.m.nv(), c.m.nv()), expected = got;
    for (int k = 1; k <= c.m.n(); ++k) {
      const int o = c.m.body(k).v_offset, nk = c.m.body(k).hinge.nv();
      const MatX& b = d[std::size_t(k - 1)];
      if (b.rows() != nk || b.cols() != nk) {
        ADD_FAILURE() << "M^-1(k,k), the diagonal blocks of M^-1: your block of body " << k
                      << " is " << b.rows() << " x " << b.cols() << ", expected " << nk << " x "
                      << nk << " (n_k, the hinge's degrees of freedom; case " << i << ")";
        return;
      }
      got.block(o, o, nk, nk) = b;
      expected.block(o, o, nk, nk) = c.Minv.block(o, o, nk, nk);
    }
    const Parts p(c.m, c.x);
    auto mistakes = [&] {
      auto v = [&](DiagV e) { return minv_diagonal_variant(p, e); };
      return Mistakes{
          {"transpose",
           "your Upsilon(k) = tau_bar(k) U tau_bar*(k) + ...: the recursion is psi*(k+1,k) "
           "Upsilon(k+1) psi(k+1,k), tau_bar*(k) U tau_bar(k) with U = phi* Upsilon(k+1) phi",
           v(DiagV::TauRight)},
          {"transpose",
           "your Upsilon(k) = psi(k+1,k) Upsilon(k+1) psi*(k+1,k) + ...: the recursion is psi* "
           "Upsilon psi (the transposes on the left)",
           v(DiagV::PsiRight)},
          {"wrong frame",
           "your Upsilon+(k) is Upsilon(k+1) as it is, in O_{k+1} coordinates: move it to O_k, "
           "phi*(k+1,k) Upsilon(k+1) phi(k+1,k)",
           v(DiagV::Unmoved)},
          {"sign", "your M^-1(k,k) is D^-1(k) - G* Upsilon+ G: the term is added", v(DiagV::Sign)},
          {"neighbour index",
           "your M^-1(k,k) takes Upsilon(k), this body's: it takes Upsilon(k+1), the inboard "
           "body's, moved to O_k",
           v(DiagV::Own)},
          {"dropped term",
           "your Upsilon recursion uses phi(k+1,k) where psi(k+1,k) = phi(k+1,k) tau_bar(k) "
           "belongs",
           v(DiagV::NoTau)},
          {"dropped term", "your M^-1(k,k) is D^-1(k): G*(k) Upsilon+(k) G(k) is missing",
           v(DiagV::OnlyDinv)},
          {"inverse", "you use D(k) where D^-1(k) belongs", v(DiagV::DforDinv)},
      };
    };
    check.add(
        i, got, expected, at_least_1(c.Minv.norm()) * c.unit() * c.kappa, c.tags,
        [&] {
          return c.code("std::vector<soa::MatX<double>> d = soa::ex07::minv_diagonal(m, x);");
        },
        mistakes, soa::test::dof_blocks(c.m, "M^-1"));
  }
}

// --- 7.4 ------------------------------------------------------------------------------------------

// y = M^-1 b by the two sweeps of 7.4 with a classic mistake in them.
enum class SolveV { NeighbourPhi, TransposedPhi, NoGain, SignEps, NoBackSweep };
VecX solve_variant(const Parts& p, const VecX& b, SolveV v) {
  std::vector<VecX> nu(std::size_t(p.n));
  soa::Vec6<double> z_plus = soa::Vec6<double>::Zero();
  for (int k = 1; k <= p.n; ++k) {
    const auto j = std::size_t(k - 1);
    soa::Vec6<double> z = soa::Vec6<double>::Zero();
    if (k > 1) {
      const Mat6 phi = v == SolveV::NeighbourPhi    ? p.phi[j]
                       : v == SolveV::TransposedPhi ? Mat6(p.phi[j - 1].transpose())
                                                    : p.phi[j - 1];
      z = phi * z_plus;
    }
    const VecX Hz = p.Hs[j].transpose() * z;
    const VecX eps = b.segment(p.off[j], p.nk[j]) + (v == SolveV::SignEps ? Hz : VecX(-Hz));
    nu[j] = p.Dinv[j] * eps;
    z_plus = z;
    if (v != SolveV::NoGain) z_plus += p.G[j] * eps;
  }
  VecX y(p.nv);
  soa::Vec6<double> alpha = soa::Vec6<double>::Zero();
  for (int k = p.n; k >= 1; --k) {
    const auto j = std::size_t(k - 1);
    const soa::Vec6<double> alpha_plus =
        k < p.n ? soa::Vec6<double>(p.phi[j].transpose() * alpha) : soa::Vec6<double>::Zero();
    const VecX yk =
        v == SolveV::NoBackSweep ? nu[j] : VecX(nu[j] - p.G[j].transpose() * alpha_plus);
    y.segment(p.off[j], p.nk[j]) = yk;
    alpha = alpha_plus + p.Hs[j] * yk;
  }
  return y;
}

// clang-format off
/* planted mistakes of 7.4
soa_plant(7.4 neighbour-index
  FIND [=[r.ws.phi[j - 1].apply(z_plus)]=]
  WRONG [=[r.ws.phi[j].apply(z_plus)]=]
  EXPECT [=[likely mistake \(neighbour index\): your z\(k\) takes phi\(k\+1,k\) z\+\(k-1\)]=])
soa_plant(7.4 dropped-gain
  FIND [=[z.vector() + r.art.G[j] * eps]=]
  WRONG [=[z.vector()]=] TYPE [=[Vec6<double>]=]
  EXPECT [=[likely mistake \(dropped term\): your z\+\(k\) is z\(k\): the gain term]=])
soa_plant(7.4 alpha-doubled
  FIND [=[alpha_plus.vector() + H_star(m, x, k) * yk]=]
  WRONG [=[2.0 * alpha_plus.vector() + H_star(m, x, k) * yk]=] TYPE [=[Vec6<double>]=]
  EXPECT [=[symptom: it fails only where there is more than one body: [0-9]+ of those [0-9]+ cases fail, and every other case passes]=])
*/
// clang-format on
TEST(Exercise7_4_Solve, SolvesMassMatrixSystem) {
  Random<double> rnd(704);
  // Declared in the order of their reports (the table shows the first failure).
  Check ref("y = M^-1 b", 4.0);
  Check res("M y, which must be b", 4.0);
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const VecX b = soa::test::random_vector(rnd, c.m.nv());
    const VecX y = soa::ex07::solve(c.m, c.x, b);
    const VecX y_ref = c.Minv * b;
    const Parts p(c.m, c.x);
    auto inputs = [&] {
      return c.code(soa::test::code("b", b) + "soa::VecX<double> y = soa::ex07::solve(m, x, b);");
    };
    const auto variants = [&] {
      auto v = [&](SolveV e) { return solve_variant(p, b, e); };
      return Mistakes{
          {"neighbour index",
           "your z(k) takes phi(k+1,k) z+(k-1), i.e. ws.phi[k-1]: phi(k,k-1) is ws.phi[k-2]",
           v(SolveV::NeighbourPhi)},
          {"transpose",
           "your z(k) takes phi*(k,k-1) z+(k-1): z is a force, it goes tip to base with phi "
           "(.apply)",
           v(SolveV::TransposedPhi)},
          {"dropped term",
           "your z+(k) is z(k): the gain term G(k) eps(k) is missing (z+(k) = z(k) + G(k) "
           "eps(k))",
           v(SolveV::NoGain)},
          {"sign", "your eps(k) is b(k) + H(k) z(k): eps(k) = b(k) - H(k) z(k)",
           v(SolveV::SignEps)},
          {"dropped term",
           "your y is nu = D^-1 [I - H psi K] b: the base-to-tip sweep, y(k) = nu(k) - G*(k) "
           "alpha+(k), is missing",
           v(SolveV::NoBackSweep)},
          soa::test::negated(y_ref, "your y is -M^-1 b: M y = b, not -b"),
      };
    };
    if (!same_shape(y, y_ref)) {
      ref.add(i, y, y_ref, 1.0, c.tags, inputs);
      continue;
    }
    res.add(
        i, VecX(c.M * y), b, c.M.norm() * at_least_1(y.norm()) * c.unit(), c.tags, inputs,
        [&] {
          Mistakes out = variants();
          for (Mistake& mk : out) mk.value = c.M * mk.value;
          return out;
        },
        soa::test::per_dof(c.m, "M y"));
    ref.add(i, y, y_ref, at_least_1(y_ref.norm()) * kEps * c.n6 * c.cond, c.tags, inputs, variants,
            soa::test::per_dof(c.m, "y"));
  }
}

// --- 7.5 ------------------------------------------------------------------------------------------

// clang-format off
/* planted mistakes of 7.5
soa_plant(7.5 sign
  FIND [=[std::log(MatX(D).determinant())]=]
  WRONG [=[-std::log(MatX(D).determinant())]=] TYPE [=[double]=]
  EXPECT [=[likely mistake \(sign\): your result is sum_k log det D\^-1\(k\) = -log det M]=])
# Not in the catalogue: the result doubled. What was measured: the constant factor.
soa_plant(7.5 doubled
  FIND [=[double(std::log(MatX(D).determinant()))]=]
  WRONG [=[2.0 * std::log(MatX(D).determinant())]=] TYPE [=[double]=]
  EXPECT [=[log det M: wrong in [0-9]+ of [0-9]+ cases.*symptom: your result is 2.000 times the expected value in every (failing )?case]=]
  REJECT [=[the formula itself|likely mistake]=])
*/
// clang-format on
TEST(Exercise7_5_LogDet, EqualsLogDetOfM) {
  Random<double> rnd(705);
  Check check("log det M", 4.0);
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const double ld = soa::ex07::log_det_mass_matrix(c.m, c.x);
    const double ld_ref = std::log(c.M.determinant());
    auto one = [](double a) { return MatX::Constant(1, 1, a); };
    auto mistakes = [&] {
      double diag = 0;
      for (int k = 1; k <= c.m.n(); ++k) {
        const int o = c.m.body(k).v_offset, nk = c.m.body(k).hinge.nv();
        for (int d = 0; d < nk; ++d) diag += std::log(c.io.D(o + d, o + d));
      }
      return Mistakes{
          {"sign", "your result is sum_k log det D^-1(k) = -log det M: take D(k), not D^-1(k)",
           one(-ld_ref)},
          {"units", "your logarithm is log10: log det M is the natural logarithm (std::log)",
           one(ld_ref / std::log(10.0))},
          {"not the logarithm", "your result is det M itself: return its logarithm",
           one(std::exp(ld_ref))},
          {"dropped term",
           "your sum takes the diagonal entries of each D(k) only: log det D(k) of a "
           "multi-dof hinge needs its whole n_k x n_k block (its determinant)",
           one(diag)},
      };
    };
    check.add(
        i, one(ld), one(ld_ref), kEps * c.n6 * c.cond, c.tags,
        [&] { return c.code("double ld = soa::ex07::log_det_mass_matrix(m, x);"); }, mistakes);
  }
}

// --- 7.6 ------------------------------------------------------------------------------------------

// Omega assembled from Upsilon with a classic mistake.
enum class OmegaV {
  BlockTransposed,
  NeighbourUpsilon,
  ReversedProduct,
  NoTau,
  DiagonalOnly,
  LowerOnly
};
MatX omega_variant(const Parts& p, OmegaV v) {
  MatX Omega = MatX::Zero(6 * p.n, 6 * p.n);
  for (int j = 1; j <= p.n; ++j) {
    Mat6 psi_ij = Mat6::Identity();
    for (int i = j; i <= p.n; ++i) {
      if (i > j) {
        const Mat6 step = v == OmegaV::NoTau ? p.phi[std::size_t(i - 2)] : p.psi_step(i - 1);
        psi_ij = v == OmegaV::ReversedProduct ? Mat6(psi_ij * step) : Mat6(step * psi_ij);
      }
      const Mat6& U = p.Ups[std::size_t((v == OmegaV::NeighbourUpsilon ? j : i) - 1)];
      const Mat6 block =
          v == OmegaV::BlockTransposed ? Mat6(psi_ij.transpose() * U) : Mat6(U * psi_ij);
      if (v == OmegaV::DiagonalOnly && i > j) continue;
      Omega.block(6 * (i - 1), 6 * (j - 1), 6, 6) = block;
      if (v != OmegaV::LowerOnly || i == j)
        Omega.block(6 * (j - 1), 6 * (i - 1), 6, 6) = block.transpose();
    }
  }
  return Omega;
}

// clang-format off
/* planted mistakes of 7.6
soa_plant(7.6 transpose
  FIND [=[u.Upsilon[std::size_t(i - 1)] * psi_ij]=]
  WRONG [=[psi_ij.transpose() * u.Upsilon[std::size_t(i - 1)]]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(transpose\): your Omega\(i,j\) is psi\*\(i,j\) Upsilon\(i\)]=])
*/
// clang-format on
TEST(Exercise7_6_OmegaFromUpsilon, MatchesPhiHMinvHPhiAndLibrary) {
  Random<double> rnd(706);
  // Declared in the order of their reports (the table shows the first failure).
  Check lib("Omega against the library's psi* H* D^-1 H psi", 4.0);
  Check dense("Omega against phi* H* M^-1 H phi (dense)", 4.0);
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const MatX Omega = soa::ex07::omega_from_upsilon(c.m, c.x);
    const MatX ref = c.io.Omega();
    const Parts p(c.m, c.x);
    auto inputs = [&] {
      return c.code("soa::MatX<double> Omega = soa::ex07::omega_from_upsilon(m, x);");
    };
    auto mistakes = [&] {
      auto v = [&](OmegaV e) { return omega_variant(p, e); };
      return Mistakes{
          {"transpose",
           "your Omega(i,j) is psi*(i,j) Upsilon(i), the transpose of each block: Omega(i,j) = "
           "Upsilon(i) psi(i,j) for i >= j",
           v(OmegaV::BlockTransposed)},
          {"neighbour index",
           "your Omega(i,j) takes Upsilon(j), the outboard body's: Omega(i,j) = Upsilon(i) "
           "psi(i,j), i >= j",
           v(OmegaV::NeighbourUpsilon)},
          {"order",
           "your psi(i,j) multiplies the steps in the wrong order: psi(i,j) = psi(i,i-1) ... "
           "psi(j+1,j), each new step on the left",
           v(OmegaV::ReversedProduct)},
          {"dropped term",
           "your psi(i,j) is phi(i,j): each step is psi(k+1,k) = phi(k+1,k) tau_bar(k)",
           v(OmegaV::NoTau)},
          {"dropped term", "your Omega is Upsilon alone: the off-diagonal blocks are missing",
           v(OmegaV::DiagonalOnly)},
          {"symmetry",
           "your Omega has only its lower blocks: Omega(j,i) = Omega*(i,j) fills the upper ones",
           v(OmegaV::LowerOnly)},
      };
    };
    if (!same_shape(Omega, ref)) {
      lib.add(i, Omega, ref, 1.0, c.tags, inputs);
      continue;
    }
    lib.add(i, Omega, ref, at_least_1(ref.norm()) * c.unit(), c.tags, inputs, mistakes,
            soa::test::body_blocks("Omega"));
    const MatX& phi = c.io.op.phi;
    const MatX& H = c.io.op.H;
    const MatX lhs = phi.transpose() * H.transpose() * c.M.inverse() * H * phi;
    dense.add(i, Omega, lhs, at_least_1(ref.norm()) * kEps * c.n6 * c.cond, c.tags, inputs,
              mistakes, soa::test::body_blocks("Omega"));
  }
}

// --- 7.7 ------------------------------------------------------------------------------------------

// M^-1 by the O(N^2) algorithm of 7.7 with a classic mistake in it.
enum class MinvV { SignL, NoGH, Unmoved, NoTauUpsilon, NoPhiZ, LowerOnly };
MatX minv_upsilon_variant(const Parts& p, MinvV v) {
  // Upsilon, from the library, or by the recursion with phi in place of psi.
  std::vector<Mat6> Ups = p.Ups;
  if (v == MinvV::NoTauUpsilon) {
    Mat6 U = Mat6::Zero();
    for (int k = p.n; k >= 1; --k) {
      const auto j = std::size_t(k - 1);
      U = (k < p.n ? Mat6(p.phi[j].transpose() * U * p.phi[j]) : Mat6::Zero()) +
          p.Hs[j] * p.Dinv[j] * p.Hs[j].transpose();
      Ups[j] = U;
    }
  }
  std::vector<MatX> L(std::size_t(p.n)), Mkk(std::size_t(p.n));
  for (int k = 1; k <= p.n; ++k) {
    const auto j = std::size_t(k - 1);
    const Mat6 Up = k == p.n              ? Mat6::Zero()
                    : v == MinvV::Unmoved ? Ups[j + 1]
                                          : Mat6(p.phi[j].transpose() * Ups[j + 1] * p.phi[j]);
    Mkk[j] = p.Dinv[j] + p.G[j].transpose() * Up * p.G[j];
    const MatX MH = Mkk[j] * p.Hs[j].transpose();
    L[j] = p.G[j].transpose() * Up + (v == MinvV::SignL ? MH : MatX(-MH));
  }
  MatX Minv = MatX::Zero(p.nv, p.nv);
  for (int i = 1; i <= p.n; ++i) {
    const auto ii = std::size_t(i - 1);
    p.block(Minv, i, i) = Mkk[ii];
    if (i == p.n) continue;
    MatX z = v == MinvV::NoPhiZ ? p.G[ii] : MatX(p.phi[ii] * p.G[ii]);
    for (int k = i + 1; k <= p.n; ++k) {
      const auto j = std::size_t(k - 1);
      const MatX block = L[j] * z;
      p.block(Minv, k, i) = block;
      if (v != MinvV::LowerOnly) p.block(Minv, i, k) = block.transpose();
      if (k < p.n) {
        const MatX step = v == MinvV::NoGH ? z : MatX(z - p.G[j] * (p.Hs[j].transpose() * z));
        z = p.phi[j] * step;
      }
    }
  }
  return Minv;
}

// clang-format off
/* planted mistakes of 7.7
soa_plant(7.7 dropped-term
  FIND [=[z - MatX(art.G[std::size_t(k - 1)]) * Hz]=]
  WRONG [=[z]=] TYPE [=[MatX]=]
  EXPECT [=[likely mistake \(dropped term\): your z_i\(k\+1\) is phi\(k\+1,k\) z_i\(k\)]=])
*/
// clang-format on
TEST(Exercise7_7_MinvFromUpsilon, MatchesLibraryAndDenseInverse) {
  Random<double> rnd(707);
  // Declared in the order of their reports (the table shows the first failure).
  Check lib("M^-1 against the library's mass_matrix_inverse_upsilon", 4.0);
  Check dense("M^-1 against the dense inverse of M", 4.0);
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const MatX Minv = soa::ex07::minv_from_upsilon(c.m, c.x);
    soa::Workspace ws(c.m);
    soa::update_phi(c.m, c.x.theta, ws);
    soa::MassMatrixInverseUpsilon w(c.m);
    MatX ref;
    soa::mass_matrix_inverse_upsilon(c.m, c.x, ws, w, ref);
    const Parts p(c.m, c.x);
    const double unit = kEps * c.m.nv() * c.cond;
    auto inputs = [&] {
      return c.code("soa::MatX<double> Minv = soa::ex07::minv_from_upsilon(m, x);");
    };
    auto mistakes = [&] {
      auto v = [&](MinvV e) { return minv_upsilon_variant(p, e); };
      return Mistakes{
          {"sign", "your L(k) adds M^-1(k,k) H(k): L(k) = G*(k) Upsilon+(k) - M^-1(k,k) H(k)",
           v(MinvV::SignL)},
          {"dropped term",
           "your z_i(k+1) is phi(k+1,k) z_i(k): the term - G(k) H(k) z_i(k) is missing (z_i "
           "moves by psi(k+1,k) = phi(k+1,k) tau_bar(k))",
           v(MinvV::NoGH)},
          {"wrong frame",
           "your Upsilon+(k) is Upsilon(k+1) as it is, in O_{k+1} coordinates: phi*(k+1,k) "
           "Upsilon(k+1) phi(k+1,k)",
           v(MinvV::Unmoved)},
          {"dropped term",
           "your Upsilon recursion uses phi(k+1,k) where psi(k+1,k) = phi(k+1,k) tau_bar(k) "
           "belongs",
           v(MinvV::NoTauUpsilon)},
          {"wrong frame",
           "your z_i(i+1) is G(i), still at O_i: z_i(i+1) = phi(i+1,i) G(i), moved to O_{i+1}",
           v(MinvV::NoPhiZ)},
          {"symmetry",
           "your M^-1 has only its lower blocks: the upper triangle is the transpose "
           "(M^-1(i,k) = M^-1(k,i)*)",
           v(MinvV::LowerOnly)},
      };
    };
    if (!same_shape(Minv, ref)) {
      lib.add(i, Minv, ref, 1.0, c.tags, inputs);
      continue;
    }
    lib.add(i, Minv, ref, ref.norm() * unit, c.tags, inputs, mistakes,
            soa::test::dof_blocks(c.m, "M^-1"));
    const MatX inv = c.M.inverse();
    dense.add(i, Minv, inv, inv.norm() * unit, c.tags, inputs, mistakes,
              soa::test::dof_blocks(c.m, "M^-1"));
  }
}

// --- 7.8 ------------------------------------------------------------------------------------------

// The operational-space inverse inertia with a classic mistake, or (DNotInverse) the
// Upsilon recursion of lesson 7, section 8 with D(j) where D^-1(j) belongs.
enum class OpV { Transposed, Unmoved, InverseFrame, OneEarly, NoTau, DNotInverse };
Mat6 opspace_variant(const Parts& p, int k, const soa::Pose& frame, OpV v) {
  const auto j = std::size_t(k - 1);
  Mat6 U = p.Ups[j];
  if (v == OpV::OneEarly)
    U = k < p.n ? Mat6(p.phi[j].transpose() * p.Ups[j + 1] * p.phi[j]) : Mat6::Zero();
  if (v == OpV::NoTau || v == OpV::DNotInverse) {
    // Upsilon(l) = psi*(l+1,l) Upsilon(l+1) psi(l+1,l) + H*(l) D^-1(l) H(l), l = n ... k.
    U.setZero();
    for (int l = p.n; l >= k; --l) {
      const auto jl = std::size_t(l - 1);
      const Mat6 step = v == OpV::NoTau ? p.phi[jl] : p.psi_step(l);
      const MatX& D = v == OpV::NoTau ? p.Dinv[jl] : p.D[jl];
      U = (l < p.n ? Mat6(step.transpose() * U * step) : Mat6::Zero()) +
          p.Hs[jl] * D * p.Hs[jl].transpose();
    }
  }
  const Mat6 X = soa::Phi(v == OpV::InverseFrame ? frame.inverse() : frame).matrix();
  if (v == OpV::Unmoved) return U;
  if (v == OpV::Transposed) return X * U * X.transpose();
  return X.transpose() * U * X;
}

// clang-format off
/* planted mistakes of 7.8
soa_plant(7.8 wrong-frame
  FIND [=[phi.transpose() * U * phi]=]
  WRONG [=[U]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(wrong frame\): your result is Upsilon\(k\), at O_k]=])
soa_plant(7.8 d-for-d-inverse
  FIND [=[Hs * MatX(r.art.D_inv[i]) * Hs.transpose()]=]
  WRONG [=[Hs * MatX(r.art.D[i]) * Hs.transpose()]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[symptom: in every case, your result matches the expected value with D\(j\) in place of D\^-1\(j\) in the Upsilon recursion]=]
  REJECT [=[the formula itself|likely mistake]=])
*/
// clang-format on
TEST(Exercise7_8_OperationalInverseInertia, MatchesDenseJMinvJStar) {
  Random<double> rnd(708);
  Check check("J M^-1 J*, the operational-space inverse inertia", 4.0);
  for (int i = 0; i < kCases; ++i) {
    Case c(rnd, i);
    const int k = 1 + int(rnd.engine()() % unsigned(c.m.n()));
    soa::Mat3<double> R = rnd.rotation();
    soa::Vec3<double> l = rnd.vec3();
    // The frame varies: rotated or not, offset or not (tags for the symptoms).
    if (i % 4 == 0) R.setIdentity();
    if (i % 3 == 0) l.setZero();
    if (i % 4 != 0) c.tags |= soa::test::kRotated;
    if (i % 3 != 0) c.tags |= soa::test::kTranslated;
    const soa::Pose frame(R, l);
    soa::Workspace ws(c.m);
    soa::update_phi(c.m, c.x.theta, ws);
    soa::update_poses(c.m, ws);
    Eigen::Matrix<double, 6, Eigen::Dynamic> J;
    soa::jacobian(c.m, c.x.theta, ws, k, frame, J);
    const MatX ref = J * c.M.inverse() * J.transpose();
    const MatX got = soa::ex07::operational_inverse_inertia(c.m, c.x, k, frame);
    const Parts p(c.m, c.x);
    auto mistakes = [&] {
      auto v = [&](OpV e) { return MatX(opspace_variant(p, k, frame, e)); };
      return Mistakes{
          {"transpose",
           "your result is phi(O_k,F) Upsilon(k) phi*(O_k,F): it is phi*(O_k,F) Upsilon(k) "
           "phi(O_k,F)",
           v(OpV::Transposed)},
          {"wrong frame", "your result is Upsilon(k), at O_k: move it to the frame F",
           v(OpV::Unmoved)},
          {"wrong frame",
           "your result moves Upsilon(k) by phi(F,O_k) = Phi(frame.inverse()): it is "
           "phi(O_k,F) = Phi(frame)",
           v(OpV::InverseFrame)},
          {"neighbour index",
           "your Upsilon recursion stopped one body early (Upsilon+(k), without H*(k) D^-1(k) "
           "H(k)): run it down to Upsilon(k)",
           v(OpV::OneEarly)},
          {"dropped term",
           "your Upsilon recursion uses phi(j+1,j) where psi(j+1,j) = phi(j+1,j) tau_bar(j) "
           "belongs",
           v(OpV::NoTau)},
          {soa::test::kMeasured,
           "the expected value with D(j) in place of D^-1(j) in the Upsilon recursion",
           v(OpV::DNotInverse)},
      };
    };
    check.add(
        i, got, ref, at_least_1(ref.norm()) * kEps * c.n6 * c.cond, c.tags,
        [&] {
          return c.code("int k = " + std::to_string(k) + ";\n" + soa::test::code("frame", frame) +
                        "soa::Mat6<double> A = soa::ex07::operational_inverse_inertia(m, x, k, "
                        "frame);");
        },
        mistakes, soa::test::blocks6("J M^-1 J*"));
  }
}

// --- 7.9 ------------------------------------------------------------------------------------------

TEST(Exercise7_9_InnovationsCoordinates, DecoupleKineticEnergy) {
  Random<double> rnd(709);
  // Declared in the order of their reports (the table shows the first failure).
  Check lib("eta = [I + H phi K]* beta", 4.0);
  Check energy("1/2 eta* D eta, which must be the kinetic energy 1/2 beta* M beta", 4.0);
  for (int i = 0; i < kCases; ++i) {
    Case c(rnd, i);
    c.x.beta = soa::test::random_vector(rnd, c.m.nv());
    c.tags |= soa::test::kMoving;
    const VecX eta = soa::ex07::innovations_coordinates(c.m, c.x);
    const VecX& beta = c.x.beta;
    const MatX L = c.io.factor();
    const VecX eta_ref = L.transpose() * beta;
    auto inputs = [&] {
      return c.code("soa::VecX<double> eta = soa::ex07::innovations_coordinates(m, x);");
    };
    const auto variants = [&] {
      soa::Workspace ws(c.m);
      soa::update_phi(c.m, c.x.theta, ws);
      soa::update_velocities(c.m, c.x, ws);
      const Parts p(c.m, c.x);
      VecX HV(c.m.nv());
      for (int k = 1; k <= c.m.n(); ++k) {
        const auto j = std::size_t(k - 1);
        HV.segment(p.off[j], p.nk[j]) = p.Hs[j].transpose() * ws.V[j].vector();
      }
      return Mistakes{
          {"transpose", "your eta is [I + H phi K] beta: eta = [I + H phi K]* beta",
           VecX(L * beta)},
          {"neighbour index",
           "your eta(k) is G*(k) phi*(k+1,k) V(k+1), from the inboard body's velocity: take "
           "V(k), which adds H*(k) beta(k)",
           VecX(eta_ref - beta)},
          {"wrong operator", "your eta(k) is H(k) V(k): eta(k) = G*(k) V(k)", HV},
          {"dropped term", "your eta is beta: eta(k) = G*(k) V(k)", beta},
          soa::test::negated(eta_ref, "your eta has the opposite sign: eta(k) = G*(k) V(k)"),
      };
    };
    if (!same_shape(eta, eta_ref)) {
      lib.add(i, eta, eta_ref, 1.0, c.tags, inputs);
      continue;
    }
    const double T = 0.5 * beta.dot(c.M * beta), Te = 0.5 * eta.dot(c.io.D * eta);
    auto one = [](double a) { return MatX::Constant(1, 1, a); };
    energy.add(i, one(Te), one(T),
               c.unit() * at_least_1(std::max(c.M.norm() * beta.squaredNorm(),
                                              c.io.D.norm() * eta.squaredNorm())),
               c.tags, inputs, [&] {
                 Mistakes out = variants();
                 for (Mistake& mk : out) {
                   const VecX e = mk.value;
                   mk.value = one(0.5 * e.dot(c.io.D * e));
                 }
                 return out;
               });
    lib.add(i, eta, eta_ref, c.unit() * at_least_1(L.norm() * beta.norm()), c.tags, inputs,
            variants, soa::test::per_dof(c.m, "eta"));
  }
}

// --- 7.10 -----------------------------------------------------------------------------------------

// Which blocks of M^-1 are zero, by a rule with a classic mistake in it: a block (i, k), i < k,
// is zero when a hinge f with zero(f, i, k) separates them.
template <class Rule>
MatX pattern_by(const std::vector<soa::HingeType>& h, Rule zero) {
  const int n = int(h.size());
  MatX p = MatX::Ones(n, n);
  for (int i = 1; i <= n; ++i)
    for (int k = i + 1; k <= n; ++k)
      for (int f = 1; f <= n; ++f)
        if (zero(h[std::size_t(f - 1)], f, i, k)) p(i - 1, k - 1) = p(k - 1, i - 1) = 0;
  return p;
}

// The blocks (i, j) of M^-1 below 1e-9 |M^-1|: 0, else 1.
MatX measured_pattern(const Case& c) {
  const int n = c.m.n();
  MatX p = MatX::Ones(n, n);
  const double small = 1e-9 * c.Minv.norm();
  for (int i = 1; i <= n; ++i)
    for (int j = 1; j <= n; ++j) {
      const soa::Body &Bi = c.m.body(i), &Bj = c.m.body(j);
      if (c.Minv.block(Bi.v_offset, Bj.v_offset, Bi.hinge.nv(), Bj.hinge.nv()).norm() <= small)
        p(i - 1, j - 1) = 0;
    }
  return p;
}

// clang-format off
/* planted mistakes of 7.10
soa_plant(7.10 neighbour-index
  FIND [=[f + 1]=]
  WRONG [=[f]=] TYPE [=[int]=]
  EXPECT [=[your pattern of the non-zero blocks of M\^-1: wrong in [0-9]+ of [0-9]+ cases.*the checker knows this mistake: it names it after 3 failed runs.*where, in case [0-9]+ \(the simplest that fails\): the row of body]=]
  REJECT [=[likely mistake|perhaps \(|strictly between|psi\(k,i\+1\)]=]
  NAMED [=[likely mistake \(neighbour index\): your zeros include the free hinge's own blocks with the bodies outboard]=])
*/
// clang-format on
TEST(Exercise7_10_MinvZeroPattern, PredictsTheZerosOfTheInverse) {
  Random<double> rnd(710);
  // The pattern is compared exactly (entries 0 and 1).
  Check check("your pattern of the non-zero blocks of M^-1", 1e-6);
  using HT = soa::HingeType;
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    std::vector<HT> hinges;
    for (int k = 1; k <= c.m.n(); ++k) hinges.push_back(c.m.body(k).hinge.type);
    const MatX got = soa::ex07::minv_zero_pattern(hinges);
    const MatX expected = measured_pattern(c);
    auto inputs = [&] {
      std::string s = "std::vector<soa::HingeType> hinges = {";
      for (std::size_t k = 0; k < hinges.size(); ++k)
        s += std::string(k ? ", " : "") + "soa::HingeType::" + soa::test::hinge_enum(hinges[k]);
      return s +
             "};  // tip first\nsoa::MatX<double> pattern = "
             "soa::ex07::minv_zero_pattern(hinges);\n";
    };
    auto mistakes = [&] {
      return Mistakes{
          {"predicted dense",
           "you predict no zeros, as in M: look at tau_bar(f) = I - G(f) H(f) of a free hinge "
           "(H(f) is 6 x 6 and invertible)",
           MatX::Ones(c.m.n(), c.m.n())},
          {"wrong hinge",
           "you predict zeros across spherical (or universal) hinges too: only a free hinge "
           "has tau_bar = 0 (a ball joint still transmits a force)",
           pattern_by(hinges,
                      [](HT t, int f, int i, int k) {
                        return (t == HT::Free || t == HT::Spherical || t == HT::Universal) &&
                               i < f && f < k;
                      })},
          {"wrong hinge",
           "you predict zeros across spherical hinges too: only a free hinge has tau_bar = 0 "
           "(a ball joint still transmits a force)",
           pattern_by(hinges,
                      [](HT t, int f, int i, int k) {
                        return (t == HT::Free || t == HT::Spherical) && i < f && f < k;
                      })},
          {"neighbour index",
           "your zeros include the free hinge's own blocks with the bodies outboard of it "
           "(M^-1(i,f), i < f): psi(k,i+1) holds tau_bar(j) for i < j < k only, so the free "
           "hinge f must lie strictly between",
           pattern_by(hinges,
                      [](HT t, int f, int i, int k) { return t == HT::Free && i < f && f <= k; })},
          {"neighbour index",
           "your zeros include the free hinge's own row and column: the free hinge f must lie "
           "strictly between i and k",
           pattern_by(hinges,
                      [](HT t, int f, int i, int k) { return t == HT::Free && i <= f && f <= k; })},
          {"symmetry",
           "your pattern is lower triangular (that of [I - H psi K]): M^-1 is symmetric, "
           "M^-1(i,k) = M^-1(k,i)*",
           MatX(expected.triangularView<Eigen::Lower>())},
      };
    };
    check.add(i, got, expected, 1.0, c.tags, inputs, mistakes, [](Eigen::Index r, Eigen::Index s) {
      const std::string b = std::to_string(r + 1) + "," + std::to_string(s + 1);
      return EntryName{
          "pattern(" + std::to_string(r) + "," + std::to_string(s) + ") (block M^-1(" + b + "))",
          "the row of body " + std::to_string(r + 1)};
    });
  }
}

// --- 7.11 -----------------------------------------------------------------------------------------

// The dense operator of the tip-to-base sweep with a classic mistake in its blocks.
enum class SweepV { Right, Sign, NoTau, TauFirst, Reversed, PhiTransposed };
MatX sweep_variant(const Parts& p, SweepV v) {
  MatX A = MatX::Identity(p.nv, p.nv);
  for (int i = 1; i < p.n; ++i) {
    const auto ii = std::size_t(i - 1);
    auto phi = [&](std::size_t j) {
      return v == SweepV::PhiTransposed ? Mat6(p.phi[j].transpose()) : p.phi[j];
    };
    // X = phi(k,k-1) tau_bar(k-1) ... tau_bar(i+1) phi(i+1,i), or its reversed product.
    Mat6 X = phi(ii);
    if (v == SweepV::TauFirst) X = X * p.tau[ii];
    for (int k = i + 1; k <= p.n; ++k) {
      const auto j = std::size_t(k - 1);
      const MatX blk = p.Hs[j].transpose() * X * p.G[ii];
      p.block(A, k, i) = v == SweepV::Sign ? blk : MatX(-blk);
      if (k == p.n) continue;
      const Mat6 step = v == SweepV::NoTau ? phi(j) : Mat6(phi(j) * p.tau[j]);
      X = v == SweepV::Reversed ? Mat6(X * p.tau[j] * p.phi[j]) : Mat6(step * X);
    }
  }
  return A;
}

// clang-format off
/* planted mistakes of 7.11
soa_plant(7.11 dropped-term
  FIND [=[r.art.tau_bar(m, x.theta, k) * z]=]
  WRONG [=[z]=] TYPE [=[MatX]=]
  EXPECT [=[A, the dense operator of the sweep, against the library's operator: wrong in [0-9]+ of [0-9]+ cases.*the checker knows this mistake: it names it after 4 failed runs.*where, in case [0-9]+ \(the simplest that fails\): A\(]=]
  REJECT [=[likely mistake|perhaps \(|tau_bar\(j\) z\(j\)]=]
  NAMED [=[likely mistake \(dropped term\): your A\(k,i\) is -H\(k\) phi\(k,i\) G\(i\)]=])
*/
// clang-format on
TEST(Exercise7_11_SweepOperator, IsTheInverseFactor) {
  Random<double> rnd(711);
  // Declared in the order of their reports (the table shows the first failure).
  Check lib("A, the dense operator of the sweep, against the library's operator", 4.0);
  Check inv("A [I + H phi K] = I with your A", 4.0);
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const MatX A = soa::ex07::sweep_operator(c.m, c.x);
    const MatX ref = c.io.factor_inverse(), L = c.io.factor();
    const int nv = c.m.nv();
    const Parts p(c.m, c.x);
    auto inputs = [&] { return c.code("soa::MatX<double> A = soa::ex07::sweep_operator(m, x);"); };
    const auto variants = [&] {
      auto v = [&](SweepV e) { return sweep_variant(p, e); };
      return Mistakes{
          {"sign", "your blocks A(k,i) have the opposite sign: eps(k) = b(k) - H(k) z(k)",
           v(SweepV::Sign)},
          {"dropped term",
           "your A(k,i) is -H(k) phi(k,i) G(i): each body j between passes z+(j) = z(j) + "
           "G(j) eps(j) = tau_bar(j) z(j) on, not z(j)",
           v(SweepV::NoTau)},
          {"neighbour index",
           "your blocks below the diagonal vanish: tau_bar(i) G(i) = 0, so the product must "
           "start at z(i+1) = phi(i+1,i) G(i) b(i), without tau_bar(i) (and end at H(k), "
           "without tau_bar(k): H(k) tau_bar(k) = 0 too)",
           v(SweepV::TauFirst)},
          {"order",
           "your product runs the wrong way: A(k,i) = -H(k) phi(k,k-1) tau_bar(k-1) ... "
           "tau_bar(i+1) phi(i+1,i) G(i), the body nearest the base on the left",
           v(SweepV::Reversed)},
          {"transpose",
           "your blocks use phi*(j+1,j): z is a force and goes tip to base by phi(j+1,j) "
           "itself",
           v(SweepV::PhiTransposed)},
          {"transpose",
           "your A is upper triangular: A(k,i) with k > i (k inboard of i) is below the "
           "diagonal",
           MatX(ref.transpose())},
      };
    };
    if (!same_shape(A, ref)) {
      lib.add(i, A, ref, 1.0, c.tags, inputs);
      continue;
    }
    lib.add(i, A, ref, c.unit() * at_least_1(ref.norm()), c.tags, inputs, variants,
            soa::test::dof_blocks(c.m, "A"));
    inv.add(
        i, MatX(A * L), MatX::Identity(nv, nv), c.unit() * at_least_1(A.norm() * L.norm()), c.tags,
        inputs,
        [&] {
          Mistakes out = variants();
          for (Mistake& mk : out) mk.value = mk.value * L;
          return out;
        },
        soa::test::dof_blocks(c.m, "A L"));
  }
}

// --- 7.12 -----------------------------------------------------------------------------------------

// beta from eta by the base-to-tip sweep of 7.12 with a classic mistake (the bug of the
// stub among them).
enum class BetaV { BugLeft, NoG, Sign, PhiNotTransposed };
VecX beta_variant(const Parts& p, const VecX& eta, BetaV v) {
  VecX beta(p.nv);
  soa::Vec6<double> V = soa::Vec6<double>::Zero();
  for (int k = p.n; k >= 1; --k) {
    const auto j = std::size_t(k - 1);
    soa::Vec6<double> V_plus = soa::Vec6<double>::Zero();
    if (k < p.n)
      V_plus = v == BetaV::PhiNotTransposed ? soa::Vec6<double>(p.phi[j] * V)
                                            : soa::Vec6<double>(p.phi[j].transpose() * V);
    const VecX eta_k = eta.segment(p.off[j], p.nk[j]);
    const VecX GV = p.G[j].transpose() * V_plus;
    const VecX beta_k = v == BetaV::NoG    ? eta_k
                        : v == BetaV::Sign ? VecX(eta_k + GV)
                                           : VecX(eta_k - GV);
    beta.segment(p.off[j], p.nk[j]) = beta_k;
    V = V_plus + p.Hs[j] * (v == BetaV::BugLeft ? eta_k : beta_k);
  }
  return beta;
}

// clang-format off
/* planted mistakes of 7.12
soa_plant(7.12 bug-left
  FIND [=[Hs * beta_k]=]
  WRONG [=[Hs * eta_k]=] TYPE [=[VecX]=]
  EXPECT [=[beta, recovered from eta = \[I \+ H phi K\]\* beta: wrong in [0-9]+ of [0-9]+ cases.*the checker knows this mistake: it names it after 3 failed runs.*where, in case [0-9]+ \(the simplest that fails\): beta of body]=]
  REJECT [=[likely mistake|perhaps \(|eta\(k\)|beta\(k\)]=]
  NAMED [=[likely mistake \(the bug\): the bug is still there: your V\(k\) adds H\*\(k\) eta\(k\)]=])
soa_feedback_test(7.12 bug-left
  [=[likely mistake \(the bug\): the bug is still there: your V\(k\) adds H\*\(k\) eta\(k\)]=])
# Not in the catalogue: V(k+1) not carried to O_k by phi*(k+1,k). What was measured: only the
# cases with more than one body fail; no cause is guessed.
soa_plant(7.12 dropped-phi-star
  FIND [=[r.ws.phi[std::size_t(k - 1)].transpose_apply(V)]=]
  WRONG [=[V]=] TYPE [=[Velocity]=]
  EXPECT [=[beta, recovered from eta = \[I \+ H phi K\]\* beta: wrong in [0-9]+ of [0-9]+ cases.*symptom: it fails only where there is more than one body: [0-9]+ of those [0-9]+ cases fail, and every other case passes.*known mistakes are named after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|index|direction of the sweep]=])
*/
// clang-format on
TEST(Exercise7_12_BetaFromEta, InvertsTheInnovationsCoordinates) {
  Random<double> rnd(712);
  Check check("beta, recovered from eta = [I + H phi K]* beta", 4.0);
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const VecX beta = soa::test::random_vector(rnd, c.m.nv());
    const VecX eta = c.io.factor().transpose() * beta;
    const VecX got = soa::ex07::beta_from_eta(c.m, c.x, eta);
    const MatX Li = c.io.factor_inverse();
    const Parts p(c.m, c.x);
    auto mistakes = [&] {
      auto v = [&](BetaV e) { return beta_variant(p, eta, e); };
      return Mistakes{
          {"the bug",
           "the bug is still there: your V(k) adds H*(k) eta(k), but the velocity recursion of "
           "lesson 3 adds the hinge velocity, H*(k) beta(k)",
           v(BetaV::BugLeft)},
          {"dropped term", "your beta is eta: beta(k) = eta(k) - G*(k) phi*(k+1,k) V(k+1)",
           v(BetaV::NoG)},
          {"sign", "your beta(k) adds G*(k) phi*(k+1,k) V(k+1): it is subtracted", v(BetaV::Sign)},
          {"transpose",
           "you move V(k+1) to O_k with phi(k+1,k): velocities go base to tip with phi*(k+1,k) "
           "(.transpose_apply)",
           v(BetaV::PhiNotTransposed)},
          {"transpose", "your beta is [I - H psi K] eta: it is [I - H psi K]* eta", VecX(Li * eta)},
      };
    };
    check.add(
        i, got, beta, c.unit() * at_least_1(Li.norm() * eta.norm()), c.tags,
        [&] {
          return c.code(soa::test::code("eta", eta) +
                        "soa::VecX<double> beta = soa::ex07::beta_from_eta(m, x, eta);");
        },
        mistakes, soa::test::per_dof(c.m, "beta"));
  }
}
