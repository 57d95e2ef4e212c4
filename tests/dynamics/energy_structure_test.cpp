// Property tests of the energy structure of the equations of motion (lesson 4, section 11;
// soa/chain/energy_structure.hpp), on soa::test::kCases random chains of 1 to 7 bodies of
// every hinge type (random_chain() cycles through all seven; locked ones merge) from fixed
// seeds:
// - breve(h) V = bar(V) h and breve(h) is skew;
// - phi_dot(k+1,k) = phi(k+1,k) bar(Delta_V(k)) and H*_dot(k) against finite differences;
// - C_v beta = C(theta, beta) - C(theta, 0) = inverse dynamics at beta_dot = 0 without
//   gravity (and, with gravity, minus inverse dynamics at rest);
// - M_dot by the operator form against finite differences of M(theta(t)) along
//   theta_dot = beta, the configuration moved by the library's soa::retract();
// - M_dot - 2 C_v skew-symmetric and beta* (M_dot - 2 C_v) beta = 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "property.hpp"
#include "random_chain.hpp"
#include "soa/chain.hpp"
#include "soa/chain/energy_structure.hpp"
#include "soa/sim.hpp"

namespace {

using soa::test::ChainOptions;
using soa::test::kCases;
using soa::test::Random;
using soa::test::Worst;
using VecX = soa::VecX<double>;
using MatX = soa::MatX<double>;
constexpr double kEps = soa::eps<double>();

int bodies(int i) {
  return 1 + i % 7;
}

// Inverse dynamics T(x, beta_dot) without external forces.
VecX inverse_dynamics(const soa::Model& m, const soa::State& x, const VecX& beta_dot) {
  soa::Workspace ws(m);
  VecX T(m.nv());
  soa::inverse_dynamics(m, x, beta_dot, {}, ws, T);
  return T;
}

// The local coordinates u with theta(t) = retract(theta, t u) moving along theta_dot =
// beta: u = beta, but for the free hinge's position, which retract() adds in O_k^+
// coordinates, u_l = R v (HingeT::theta_dot()).
VecX direction(const soa::Model& m, const soa::State& x) {
  VecX u = x.beta;
  for (const soa::Body& B : m.bodies())
    if (B.hinge.type == soa::HingeType::Free)
      u.segment<3>(B.v_offset + 3) =
          soa::Hinge::quaternion(x.theta.data() + B.q_offset)
              .rotate(soa::Vec3<double>(x.beta.segment<3>(B.v_offset + 3)));
  return u;
}

// The rate scale of a motion: angles and offsets of order |theta| change at |beta|.
double rate_scale(const soa::State& x) {
  return std::max(1.0, x.beta.lpNorm<Eigen::Infinity>() * (1 + x.theta.norm()));
}

// Five-point central difference of F(theta(t)) at t = 0 along theta(t) = retract(theta, t u).
// Truncation error h^4 |F^(5)| / 30, rounding about (3/2) eps |F| / h: with the rate scale w
// of the motion (|F^(5)| ~ w^5 |F|) they balance at h = eps^(1/5) / w, both of order
// eps^(4/5) w |F|, the unit of the tolerances below.
template <class F>
MatX along(const soa::Model& m, const VecX& theta, const VecX& u, double w, const F& f) {
  const double h = std::pow(kEps, 0.2) / w;
  VecX q(theta.size());
  const auto at = [&](double t) {
    soa::retract(m, theta, VecX(t * u), q);
    return MatX(f(q));
  };
  return (at(-2 * h) - 8.0 * at(-h) + 8.0 * at(h) - at(2 * h)) / (12 * h);
}

}  // namespace

TEST(dynamics_EnergyStructure, BreveIsTheSkewForceCross) {
  Random<double> rnd(101);
  Worst w_apply("|breve(h) V - bar(V) h| / (eps |h| |V|)"), w_skew("|breve + breve*| / |breve|");
  for (int i = 0; i < kCases; ++i) {
    const soa::Force h = rnd.force();
    const soa::Velocity V = rnd.velocity();
    const soa::Mat6<double> Hb = soa::breve(h);
    w_apply.add((Hb * V.vector() - soa::cross_bar(V, h).vector()).norm() /
                    (kEps * h.vector().norm() * V.vector().norm()),
                i);
    w_skew.add((Hb + Hb.transpose()).norm() / Hb.norm(), i);
  }
  EXPECT_LE(w_apply.value(), 8.0);
  EXPECT_EQ(w_skew.value(), 0.0);
}

// phi_dot(k+1,k) and H*_dot(k) of every hinge type against differences of joint_phi() and
// HingeT::H_star() along the hinge's own motion.
TEST(dynamics_EnergyStructure, JointRatesMatchFiniteDifferences) {
  Random<double> rnd(103);
  Worst w_phi("|phi_dot - FD| / (eps^(4/5) w |phi|)"), w_H("|H*_dot - FD| / (eps^(4/5) w)");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, bodies(i));
    const soa::State x = soa::test::random_state(rnd, m);
    const VecX u = direction(m, x);
    const double w = rate_scale(x);
    for (int k = 1; k <= m.n(); ++k) {
      const soa::Body& B = m.body(k);
      const double* th = x.theta.data() + B.q_offset;
      const double* be = x.beta.data() + B.v_offset;
      const soa::Phi phi = soa::joint_phi(B, th);
      const MatX rate = soa::joint_phi_rate(phi, B.hinge.H_star_times(th, be));
      const MatX fd = along(m, x.theta, u, w, [&](const VecX& q) {
        return soa::joint_phi(B, q.data() + B.q_offset).matrix();
      });
      w_phi.add((rate - fd).norm() / (std::pow(kEps, 0.8) * w * phi.matrix().norm()), i);
      const MatX Hd = soa::hinge_map_rate(B.hinge, th, be);
      const MatX fd_H = along(m, x.theta, u, w,
                              [&](const VecX& q) { return B.hinge.H_star(q.data() + B.q_offset); });
      w_H.add((Hd - fd_H).norm() / (std::pow(kEps, 0.8) * w), i);
    }
  }
  EXPECT_LE(w_phi.value(), 100.0);
  EXPECT_LE(w_H.value(), 100.0);
}

// C_v beta = C(theta, beta) - gravity part: inverse dynamics at beta_dot = 0 without gravity,
// and with gravity less inverse dynamics at rest. The rounding scales with the terms of
// C_v = B*(M B_dot + h_breve B), |B| (|M| |B_dot| + |h_breve| |B|) |beta|, and with the
// gravity torques |T(rest)| that the second form subtracts; in units of eps n.
TEST(dynamics_EnergyStructure, CoriolisMatrixTimesBetaIsTheBias) {
  Random<double> rnd(107);
  Worst w_no_g("|C_v beta - ID(g = 0)| / (eps n scale)"),
      w_g("|C_v beta - (ID - ID(rest))| / (eps n scale)");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, bodies(i), ChainOptions{true, true, false});
    soa::Model m0 = m;
    m0.gravity.setZero();
    const soa::State x = soa::test::random_state(rnd, m);
    const VecX zero = VecX::Zero(m.nv());
    const soa::EnergyStructure es = soa::EnergyStructure::build(m, x);
    const VecX Cb = es.coriolis_matrix() * x.beta;
    const VecX C0 = inverse_dynamics(m0, x, zero);
    const VecX G = inverse_dynamics(m, soa::State{x.theta, zero}, zero);
    const VecX Cg = inverse_dynamics(m, x, zero) - G;
    const MatX B = es.B();
    const double terms =
        B.norm() * (es.op.M.norm() * es.B_dot().norm() + es.h_breve.norm() * B.norm());
    const double scale = kEps * m.n() * (terms * x.beta.norm() + G.norm());
    w_no_g.add((Cb - C0).norm() / scale, i);
    w_g.add((Cb - Cg).norm() / scale, i);
  }
  EXPECT_LE(w_no_g.value(), 8.0);
  EXPECT_LE(w_g.value(), 8.0);
}

// M_dot by the operator form against the five-point difference of M(theta(t)) (dense H phi M
// phi* H*), theta(t) = retract(theta, t u) with tangent theta_dot (quaternion hinges turn on
// the unit sphere); tolerance in units of eps^(4/5) w |M| (see along()).
TEST(dynamics_EnergyStructure, MassMatrixRateMatchesFiniteDifferences) {
  Random<double> rnd(109);
  Worst worst("|M_dot - FD| / (eps^(4/5) w |M|)");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, bodies(i));
    const soa::State x = soa::test::random_state(rnd, m);
    const soa::EnergyStructure es = soa::EnergyStructure::build(m, x);
    const MatX Md = es.mass_matrix_rate();
    const double w = rate_scale(x);
    const MatX fd = along(m, x.theta, direction(m, x), w, [&](const VecX& q) {
      return soa::Operators::build(m, soa::State{q, x.beta}).mass_matrix();
    });
    worst.add((Md - fd).norm() / (std::pow(kEps, 0.8) * w * es.op.mass_matrix().norm()), i);
  }
  EXPECT_LE(worst.value(), 100.0);
}

// M_dot - 2 C_v is skew-symmetric and beta* (M_dot - 2 C_v) beta = 0: residuals relative to
// |M_dot| + |C_v| or, when that is itself rounding (a single revolute body has M_dot = C_v =
// 0 up to rounding), to the terms C_v is made of, |B| (|M| |B_dot| + |h_breve| |B|); and to
// |beta|^2 for the quadratic form. In units of eps n cond(I - E_phi): the dense phi = (I -
// E_phi)^-1 of the operators is a solve, whose rounding grows with that conditioning.
TEST(dynamics_EnergyStructure, MassMatrixRateMinusTwiceCoriolisIsSkew) {
  Random<double> rnd(113);
  Worst w_skew("|N + N*| / (scale eps n cond), N = M_dot - 2 C_v"),
      w_quad("|beta* N beta| / (scale |beta|^2 eps n cond)");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, bodies(i));
    const soa::State x = soa::test::random_state(rnd, m);
    const soa::EnergyStructure es = soa::EnergyStructure::build(m, x);
    const MatX Md = es.mass_matrix_rate(), C = es.coriolis_matrix();
    const MatX Nm = Md - 2 * C;
    const int N = 6 * m.n();
    const double cond = es.op.phi.norm() * (MatX::Identity(N, N) - es.op.E_phi).norm();
    const MatX B = es.B();
    const double terms =
        B.norm() * (es.op.M.norm() * es.B_dot().norm() + es.h_breve.norm() * B.norm());
    const double scale = std::max(Md.norm() + C.norm(), terms) * kEps * m.n() * cond;
    w_skew.add((Nm + Nm.transpose()).norm() / scale, i);
    w_quad.add(std::abs(x.beta.dot(Nm * x.beta)) / (scale * x.beta.squaredNorm()), i);
  }
  EXPECT_LE(w_skew.value(), 8.0);
  EXPECT_LE(w_quad.value(), 8.0);
}
