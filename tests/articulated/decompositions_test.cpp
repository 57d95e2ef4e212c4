// Property tests of the alternative force decompositions (lesson 6, sections 2 and 8;
// soa/chain/force_decompositions.hpp): on soa::test::kCases random chains of every hinge
// type (1 to 12 bodies before locked hinges merge), under gravity, moving, with random
// hinge and external forces, from the fixed seed,
// - the operator identities, on the dense operators (phi~ = phi - I, psi~ = psi - I):
//   phi M phi* = R + phi~ R + R phi~*,
//   phi M phi* = P + phi~ P + P phi~* + phi K D K* phi*,
//   psi M psi* = P + psi~ P + P psi~*;
// - the force decompositions against the Newton-Euler inter-body forces f(k) at the
//   accelerations of the forward dynamics: f = R alpha+ + y (soa::alpha_plus,
//   soa::composite_bias; hinges locked) and f = P+ alpha+ + z+ = P (alpha - a) + z (hinges
//   free), with the operator forms y = phi (R delta + b) and z+ = phi (P a + b + G epsilon).
// Residuals are relative to the size of the terms, in units of 6n kappa, kappa =
// max_k |P(k)| |D^{-1}(k)| as in articulated_test.cpp (1 for the composite split).
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "property.hpp"
#include "random_chain.hpp"
#include "soa/chain.hpp"
#include "soa/chain/force_decompositions.hpp"
#include "soa/soa.hpp"

namespace {

using soa::test::kCases;
using soa::test::Random;
using soa::test::Worst;
using Mat6 = soa::Mat6<double>;
using MatX = soa::MatX<double>;
using Vec6 = soa::Vec6<double>;
using VecX = soa::VecX<double>;

constexpr double kEps = soa::eps<double>();

int bodies(int i) {
  return 1 + i % 12;
}

// One random chain under gravity at a random moving state, with hinge forces T and external
// forces: the forward dynamics (beta_dot, z, z+, alpha+), Newton-Euler at its beta_dot (f,
// alpha, a), the composite split (R, alpha+, y) and the dense operators.
struct Case {
  soa::Model m;
  soa::State x;
  soa::ExternalForces<double> f_ext;
  soa::Workspace ws_fd, ws_ne;
  soa::ForwardDynamics fd;
  std::vector<soa::SpatialInertia> R;
  std::vector<soa::Acceleration> alpha_p;
  std::vector<soa::Force> y;
  soa::InnovationsOperators io;
  MatX R_op;
  double kappa = 1;
  Case(soa::Model model, Random<double>& rnd)
      : m(std::move(model)),
        x(soa::test::random_state(rnd, m)),
        f_ext(soa::test::random_forces(rnd, m)),
        ws_fd(m),
        ws_ne(m),
        fd(m),
        R(std::size_t(m.n())),
        alpha_p(std::size_t(m.n())),
        y(std::size_t(m.n())) {
    const VecX T = soa::test::random_vector(rnd, m.nv());
    VecX bd(m.nv()), T_back(m.nv());
    soa::forward_dynamics(m, x, T, f_ext, ws_fd, fd, bd);
    soa::inverse_dynamics(m, x, bd, f_ext, ws_ne, T_back);
    soa::composite_inertias(m, ws_ne, R);
    soa::alpha_plus(m, ws_ne, alpha_p);
    soa::composite_bias(m, ws_ne, R, alpha_p, f_ext, y);
    io = soa::InnovationsOperators::build(m, x);
    R_op = soa::composite_inertia_operator(m, ws_ne);
    for (int k = 1; k <= m.n(); ++k)
      kappa = std::max(kappa, fd.art.P[std::size_t(k - 1)].norm() *
                                  MatX(fd.art.D_inv[std::size_t(k - 1)]).norm());
  }
  double units() const { return 6 * m.n() * kappa; }
};

TEST(articulated_Decompositions, OperatorIdentities) {
  Random<double> rnd;
  Worst comp("phi M phi* = R + phi~R + R phi~* / (|terms| 6n)"),
      art("phi M phi* = P + phi~P + P phi~* + phi KDK* phi* / (|terms| 6n kappa)"),
      psi("psi M psi* = P + psi~P + P psi~* / (|terms| 6n kappa)");
  for (int i = 0; i < kCases; ++i) {
    soa::test::ChainOptions opt;
    opt.gravity = true;
    const Case c(soa::test::random_chain(rnd, bodies(i), opt), rnd);
    const soa::Operators& op = c.io.op;
    const int N = 6 * c.m.n();
    const MatX I = MatX::Identity(N, N);
    const MatX phi_t = op.phi - I, psi_t = c.io.psi - I;
    const MatX phiMphi = op.phi * op.M * op.phi.transpose();
    const MatX psiMpsi = c.io.psi * op.M * c.io.psi.transpose();
    const MatX free_part = op.phi * c.io.K * c.io.D * c.io.K.transpose() * op.phi.transpose();
    const MatX phiR = phi_t * c.R_op, phiP = phi_t * c.io.P, psiP = psi_t * c.io.P;
    const double s_comp = std::max({1.0, phiMphi.norm(), c.R_op.norm(), 2 * phiR.norm()});
    const double s_art =
        std::max({1.0, phiMphi.norm(), c.io.P.norm(), 2 * phiP.norm(), free_part.norm()});
    const double s_psi = std::max({1.0, psiMpsi.norm(), c.io.P.norm(), 2 * psiP.norm()});
    comp.add((phiMphi - (c.R_op + phiR + phiR.transpose())).norm() / (s_comp * 6 * c.m.n()), i);
    art.add((phiMphi - (c.io.P + phiP + phiP.transpose() + free_part)).norm() / (s_art * c.units()),
            i);
    psi.add((psiMpsi - (c.io.P + psiP + psiP.transpose())).norm() / (s_psi * c.units()), i);
  }
  EXPECT_LE(comp.value(), 16 * kEps);
  EXPECT_LE(art.value(), 16 * kEps);
  EXPECT_LE(psi.value(), 16 * kEps);
}

TEST(articulated_Decompositions, InterBodyForces) {
  Random<double> rnd;
  Worst comp("|R alpha+ + y - f_NE| / (|terms| 6n)"),
      comp_op("|y - phi (R delta + b)| / (|terms| 6n)"),
      plus("|P+ alpha+ + z+ - f_NE| / (|terms| 6n kappa)"),
      ansatz("|P (alpha - a) + z - f_NE| / (|terms| 6n kappa)"),
      z_op("|z+ - phi (P a + b + G eps)| / (|terms| 6n kappa)"),
      ap("|alpha_plus - forward dynamics alpha+| / (|alpha| 6n kappa)");
  for (int i = 0; i < kCases; ++i) {
    soa::test::ChainOptions opt;
    opt.gravity = true;
    const Case c(soa::test::random_chain(rnd, bodies(i), opt), rnd);
    const int n = c.m.n(), N = 6 * n;
    VecX delta(N), b(N), a(N), Geps(N), y(N), z_plus(N), RD(N);
    double s = 1, s_alpha = 1, e_comp = 0, e_plus = 0, e_ansatz = 0, e_ap = 0;
    for (int k = 1; k <= n; ++k) {
      const std::size_t j = std::size_t(k - 1);
      const Mat6 Rk = c.R[j].matrix();
      const Mat6& Pk = c.fd.art.P[j];
      const Mat6& Pp = c.fd.art.P_plus[j];
      const Vec6 f = c.ws_ne.f[j].vector(), alpha = c.ws_ne.alpha[j].vector();
      const Vec6 a_k = c.ws_ne.a[j].vector(), apl = c.alpha_p[j].vector();
      const Vec6 apl_fd = c.fd.alpha_plus[j].vector();
      s = std::max({s, f.norm(), Rk.norm() * apl.norm(), c.y[j].vector().norm(),
                    Pk.norm() * (alpha - a_k).norm(), c.fd.z[j].vector().norm(),
                    Pp.norm() * apl_fd.norm(), c.fd.z_plus[j].vector().norm(),
                    c.ws_fd.b[j].vector().norm()});
      s_alpha = std::max({s_alpha, alpha.norm(), apl.norm()});
      e_comp = std::max(e_comp, (Rk * apl + c.y[j].vector() - f).norm());
      e_plus = std::max(e_plus, (Pp * apl_fd + c.fd.z_plus[j].vector() - f).norm());
      e_ansatz = std::max(e_ansatz, (Pk * (alpha - a_k) + c.fd.z[j].vector() - f).norm());
      e_ap = std::max(e_ap, (apl - apl_fd).norm());
      delta.segment<6>(6 * int(j)) = alpha - apl;
      b.segment<6>(6 * int(j)) = c.ws_fd.b[j].vector();
      a.segment<6>(6 * int(j)) = c.ws_fd.a[j].vector();
      Geps.segment<6>(6 * int(j)) = c.fd.art.G[j] * (c.fd.art.D[j] * c.fd.nu[j]);
      y.segment<6>(6 * int(j)) = c.y[j].vector();
      z_plus.segment<6>(6 * int(j)) = c.fd.z_plus[j].vector();
    }
    const soa::Operators& op = c.io.op;
    const VecX y_op = op.phi * (c.R_op * delta + b);
    const VecX z_op_v = op.phi * (c.io.P * a + b + Geps);
    const double s_y = std::max({s, y_op.norm(), (c.R_op * delta).norm()});
    const double s_z = std::max({s, z_op_v.norm(), Geps.norm(), (c.io.P * a).norm()});
    comp.add(e_comp / (s * 6 * n), i);
    comp_op.add((y - y_op).norm() / (s_y * 6 * n), i);
    plus.add(e_plus / (s * c.units()), i);
    ansatz.add(e_ansatz / (s * c.units()), i);
    z_op.add((z_plus - z_op_v).norm() / (s_z * c.units()), i);
    ap.add(e_ap / (s_alpha * c.units()), i);
  }
  EXPECT_LE(comp.value(), 16 * kEps);
  EXPECT_LE(comp_op.value(), 16 * kEps);
  EXPECT_LE(plus.value(), 16 * kEps);
  EXPECT_LE(ansatz.value(), 16 * kEps);
  EXPECT_LE(z_op.value(), 16 * kEps);
  EXPECT_LE(ap.value(), 16 * kEps);
}

}  // namespace
