// Lesson 8 exercise tests: each exercise of exercises/08-recursive-forward-dynamics/exercises.hpp
// against the library (soa::forward_dynamics, soa::inverse_dynamics, soa::mass_matrix_crb), on
// soa::test::kCases random cases (chains of 1 to 8 bodies of the hinge types the exercise
// allows, random states, hinge forces, gravity and external forces) from the fixed seed. Built
// against the solutions (ctest) and against the students' stubs (make exercises).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "exercises.hpp"
#include "property.hpp"
#include "random_chain.hpp"

namespace {

using soa::HingeType;
using soa::test::ChainOptions;
using soa::test::kCases;
using soa::test::Random;
using soa::test::Worst;
using Vec6 = soa::Vec6<double>;
using MatX = soa::MatX<double>;
using VecX = soa::VecX<double>;

constexpr double kEps = soa::eps<double>();

int bodies(int i) {
  return 1 + i % 8;
}

// A chain of n bodies whose hinge i has type types[i % size] (a locked first hinge becomes
// revolute), with the random bodies of random_chain.hpp.
soa::Model chain_of(Random<double>& rnd, int n, const std::vector<HingeType>& types,
                    const ChainOptions& opt) {
  std::vector<soa::Body> b;
  for (int i = 0; i < n; ++i)
    b.push_back(soa::test::detail::random_body(rnd, i, types[std::size_t(i) % types.size()], opt));
  return soa::test::detail::finish_chain(std::move(b), opt);
}

// A random case: the chain, a state, hinge forces, external forces (maybe none), and the
// library's forward dynamics with its per-body results.
struct Case {
  soa::Model m;
  soa::State x;
  VecX T;
  soa::ExternalForces<double> f_ext;
  soa::Workspace ws;
  soa::ForwardDynamics fd;
  VecX beta_dot;
  Case(soa::Model model, Random<double>& rnd, bool external)
      : m(std::move(model)),
        x(soa::test::random_state(rnd, m)),
        T(soa::test::random_vector(rnd, m.nv())),
        ws(m),
        fd(m),
        beta_dot(m.nv()) {
    if (external) f_ext = soa::test::random_forces(rnd, m);
    soa::forward_dynamics(m, x, T, f_ext, ws, fd, beta_dot);
  }
  // |P(k)| |D^{-1}(k)|, the growth of rounding in the sweeps, largest over the bodies.
  double kappa() const {
    double w = 1;
    for (std::size_t j = 0; j < fd.art.P.size(); ++j)
      w = std::max(w, fd.art.P[j].norm() * MatX(fd.art.D_inv[j]).norm());
    return w;
  }
  // The 2-norm condition number of the mass matrix (composite bodies, lesson 5).
  double cond() const {
    soa::Workspace w(m);
    soa::update_phi(m, x.theta, w);
    std::vector<soa::SpatialInertia> R(std::size_t(m.n()));
    MatX M;
    soa::mass_matrix_crb(m, x, w, R, M);
    const VecX ev = Eigen::SelfAdjointEigenSolver<MatX>(M, Eigen::EigenvaluesOnly).eigenvalues();
    return ev.maxCoeff() / ev.minCoeff();
  }
};

double rel_worst(const std::vector<Vec6>& a, const std::vector<soa::Force>& b) {
  double err = 0, scale = 1;
  for (std::size_t j = 0; j < b.size(); ++j) {
    err = std::max(err, (a[j] - b[j].vector()).norm());
    scale = std::max(scale, b[j].vector().norm());
  }
  return err / scale;
}

TEST(Exercise8_1_TipToBase, MatchesLibrary) {
  Random<double> rnd;
  ChainOptions revolute;
  revolute.all_hinge_types = false;
  Worst w("|z, z+, eps, nu - library| / (max(1, |library|) kappa)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(soa::test::random_chain(rnd, bodies(i), revolute), rnd, false);
    const soa::ex08::TipToBase r = soa::ex08::tip_to_base(c.m, c.x, c.T);
    const int n = c.m.n();
    ASSERT_EQ(int(r.z.size()), n);
    ASSERT_EQ(int(r.z_plus.size()), n);
    ASSERT_EQ(r.eps.size(), n);
    ASSERT_EQ(r.nu.size(), n);
    double e = std::max(rel_worst(r.z, c.fd.z), rel_worst(r.z_plus, c.fd.z_plus));
    for (int k = 1; k <= n; ++k) {
      const std::size_t j = std::size_t(k - 1);
      const double nu = c.fd.nu[j][0], eps = c.fd.art.D[j](0, 0) * nu;
      e = std::max(e, std::abs(r.nu[k - 1] - nu) / std::max(1.0, std::abs(nu)));
      e = std::max(e, std::abs(r.eps[k - 1] - eps) / std::max(1.0, std::abs(eps)));
    }
    w.add(e / c.kappa(), i);
  }
  EXPECT_LE(w.value(), 64 * 8 * kEps);
}

TEST(Exercise8_2_BaseToTip, MatchesLibrary) {
  Random<double> rnd;
  Worst w("|beta_dot, alpha - library| / (max(1, |library|) kappa)");
  for (int i = 0; i < kCases; ++i) {
    ChainOptions opt;
    opt.gravity = i % 2 == 1;
    const Case c(soa::test::random_chain(rnd, bodies(i), opt), rnd, i % 4 == 0);
    soa::Workspace ws = c.ws;  // phi, V, a of the library's forward dynamics; no alpha
    for (auto& a : ws.alpha) a = soa::Acceleration();
    std::vector<VecX> nu;
    for (const auto& v : c.fd.nu) nu.push_back(v);
    std::vector<soa::Acceleration> alpha;
    const VecX bd = soa::ex08::base_to_tip(c.m, c.x, ws, c.fd.art, nu,
                                           soa::gravity_base_acceleration(c.m), alpha);
    ASSERT_EQ(bd.size(), c.m.nv());
    ASSERT_EQ(int(alpha.size()), c.m.n());
    double e = (bd - c.beta_dot).norm() / std::max(1.0, c.beta_dot.norm());
    double err = 0, scale = 1;
    for (std::size_t j = 0; j < alpha.size(); ++j) {
      err = std::max(err, (alpha[j].vector() - c.ws.alpha[j].vector()).norm());
      scale = std::max(scale, c.ws.alpha[j].vector().norm());
    }
    w.add(std::max(e, err / scale) / c.kappa(), i);
  }
  EXPECT_LE(w.value(), 64 * 8 * kEps);
}

TEST(Exercise8_3_ForwardDynamics1Dof, MatchesLibrary) {
  Random<double> rnd;
  const std::vector<HingeType> one_dof = {HingeType::Revolute, HingeType::Prismatic,
                                          HingeType::Helical};
  Worst w("|beta_dot - library| / |library| / (n eps cond(M))");
  for (int i = 0; i < kCases; ++i) {
    ChainOptions opt;
    opt.all_hinge_types = false;
    opt.gravity = i % 2 == 1;
    std::vector<HingeType> types = one_dof;
    std::rotate(types.begin(), types.begin() + i % 3, types.end());
    const Case c(chain_of(rnd, bodies(i), types, opt), rnd, i % 3 == 0);
    const VecX bd = soa::ex08::forward_dynamics_1dof(c.m, c.x, c.T, c.f_ext);
    ASSERT_EQ(bd.size(), c.m.nv());
    w.add(soa::test::rel(bd, c.beta_dot) / (c.m.nv() * kEps * c.cond()), i);
  }
  EXPECT_LE(w.value(), 16.0);
}

TEST(Exercise8_4_InterBodyForces, MatchNewtonEuler) {
  Random<double> rnd;
  Worst wf("|f - Newton-Euler f| / (n eps cond(M) scale)"),
      wt("|H f - (T + tau_s)| / (n eps cond(M) scale)");
  for (int i = 0; i < kCases; ++i) {
    ChainOptions opt;
    opt.gravity = i % 2 == 1;
    opt.springs = i % 3 == 0;
    const Case c(soa::test::random_chain(rnd, bodies(i), opt), rnd, i % 4 == 0);
    VecX T_hinge;
    const std::vector<soa::Force> f = soa::ex08::inter_body_forces(c.m, c.x, c.fd, T_hinge);
    ASSERT_EQ(int(f.size()), c.m.n());
    ASSERT_EQ(T_hinge.size(), c.m.nv());
    soa::Workspace ne(c.m);
    VecX T_ne(c.m.nv());
    soa::inverse_dynamics(c.m, c.x, c.beta_dot, c.f_ext, ne, T_ne);
    VecX T_s = c.T;  // T + tau_s
    for (const soa::Body& B : c.m.bodies())
      soa::add_spring_force(B, c.x.theta.data() + B.q_offset, c.x.beta.data() + B.v_offset,
                            T_s.data() + B.v_offset);
    const double unit = c.m.nv() * kEps * c.cond();
    double scale = 1, err = 0;
    for (int k = 1; k <= c.m.n(); ++k) {
      const std::size_t j = std::size_t(k - 1);
      scale = std::max({scale, ne.f[j].vector().norm(), c.fd.z_plus[j].vector().norm(),
                        c.fd.art.P_plus[j].norm() * c.fd.alpha_plus[j].vector().norm()});
      err = std::max(err, (f[j].vector() - ne.f[j].vector()).norm());
    }
    wf.add(err / (unit * scale), i);
    wt.add((T_hinge - T_s).norm() / (unit * scale), i);
  }
  EXPECT_LE(wf.value(), 16.0);
  EXPECT_LE(wt.value(), 16.0);
}

TEST(Exercise8_5_Rk4Step, MatchesReferenceRK4) {
  Random<double> rnd;
  const std::vector<HingeType> plain = {HingeType::Revolute, HingeType::Prismatic,
                                        HingeType::Helical, HingeType::Universal};
  const double h = 0.01;
  Worst w("|step - RK4 with soa::forward_dynamics| / (|x| + h |x_dot|) / (n eps cond(M))");
  for (int i = 0; i < kCases; ++i) {
    ChainOptions opt;
    opt.gravity = i % 2 == 1;
    opt.springs = i % 3 == 0;
    std::vector<HingeType> types = plain;
    std::rotate(types.begin(), types.begin() + i % 4, types.end());
    const Case c(chain_of(rnd, bodies(i), types, opt), rnd, false);
    // The reference: the four stages of RK4 (lesson 8, section 7).
    soa::Workspace ws(c.m);
    soa::ForwardDynamics fd(c.m);
    const auto F = [&](const VecX& theta, const VecX& beta) {
      VecX bd(c.m.nv());
      soa::forward_dynamics(c.m, soa::State{theta, beta}, c.T, {}, ws, fd, bd);
      return bd;
    };
    const soa::State& x = c.x;
    const VecX k1v = F(x.theta, x.beta);
    const VecX k2q = x.beta + h / 2 * k1v, k2v = F(x.theta + h / 2 * x.beta, k2q);
    const VecX k3q = x.beta + h / 2 * k2v, k3v = F(x.theta + h / 2 * k2q, k3q);
    const VecX k4q = x.beta + h * k3v, k4v = F(x.theta + h * k3q, k4q);
    const VecX theta = x.theta + h / 6 * (x.beta + 2 * k2q + 2 * k3q + k4q);
    const VecX beta = x.beta + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    const soa::State y = soa::ex08::rk4_step(c.m, x, c.T, h);
    ASSERT_EQ(y.theta.size(), c.m.nq());
    ASSERT_EQ(y.beta.size(), c.m.nv());
    const double scale = x.theta.norm() + x.beta.norm() + h * (x.beta.norm() + k1v.norm());
    const double err = (y.theta - theta).norm() + (y.beta - beta).norm();
    w.add(err / (scale * c.m.nv() * kEps * c.cond()), i);
  }
  EXPECT_LE(w.value(), 16.0);
}

}  // namespace
