// Lesson 6 exercise tests: each exercise of exercises/06-articulated-body-inertia/exercises.hpp
// against the library, on soa::test::kCases random cases (chains of 1 to 8 bodies, every
// hinge type unless the exercise is for revolute chains; under gravity and moving for 6.5 and
// 6.6) from the fixed seed. Built against
// the solutions (ctest) and against the students' stubs (make exercises).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "exercises.hpp"
#include "property.hpp"
#include "random_chain.hpp"
#include "soa/chain/force_decompositions.hpp"

namespace {

using soa::test::ChainOptions;
using soa::test::kCases;
using soa::test::Random;
using soa::test::Worst;
using Mat6 = soa::Mat6<double>;
using MatX = soa::MatX<double>;
using VecX = soa::VecX<double>;
using Vec6 = soa::Vec6<double>;

constexpr double kEps = soa::eps<double>();

int bodies(int i) {
  return 1 + i % 8;
}

// A random chain at a random state with its library articulated inertias.
struct Case {
  soa::Model m;
  soa::State x;
  soa::Workspace ws;
  soa::Articulated art;
  Case(soa::Model model, Random<double>& rnd)
      : m(std::move(model)), x(soa::test::random_state(rnd, m)), ws(m), art(m) {
    soa::update_phi(m, x.theta, ws);
    soa::articulated_inertias(m, x, ws, art);
  }
  // |P(k)| |D^{-1}(k)|, the growth of rounding in G and P+, largest over bodies 1..k.
  double kappa(int k) const {
    double w = 1;
    for (int j = 1; j <= k; ++j) {
      const MatX D = art.D[std::size_t(j - 1)];
      w = std::max(w, art.P[std::size_t(j - 1)].norm() * D.inverse().norm());
    }
    return w;
  }
};

MatX H_star(const Case& c, int k) {
  const soa::Body& B = c.m.body(k);
  return B.hinge.H_star(c.x.theta.data() + B.q_offset);
}

TEST(Exercise6_1_RiccatiStep, MatchesLibrary) {
  Random<double> rnd;
  Worst w("|step - articulated_inertias| / (|P| kappa)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(soa::test::random_chain(rnd, bodies(i)), rnd);
    for (int k = 1; k <= c.m.n(); ++k) {
      const std::size_t j = std::size_t(k - 1);
      const Mat6 Pp = k > 1 ? c.art.P_plus[j - 1] : Mat6::Zero();
      const soa::Phi phi = k > 1 ? c.ws.phi[j - 1] : soa::Phi();
      const soa::ex06::RiccatiStep s =
          soa::ex06::riccati_step(Pp, phi, c.m.body(k).M, H_star(c, k));
      const double scale = std::max(1.0, c.art.P[j].norm()) * c.kappa(k);
      const MatX D = c.art.D[j], G = c.art.G[j];
      ASSERT_EQ(s.D.rows(), D.rows());
      ASSERT_EQ(s.G.cols(), G.cols());
      w.add(std::max({(s.P - c.art.P[j]).norm(), (s.D - D).norm(), (s.G - G).norm(),
                      (s.P_plus - c.art.P_plus[j]).norm()}) /
                scale,
            i);
    }
  }
  EXPECT_LE(w.value(), 64 * kEps);
}

TEST(Exercise6_2_TauBar, ProjectionMatchesLibrary) {
  Random<double> rnd;
  Worst lib("|tau_bar - library| / kappa"), proj("|tau_bar^2 - tau_bar| / kappa"),
      hp("|H tau_bar P| / (|P| kappa)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(soa::test::random_chain(rnd, bodies(i)), rnd);
    for (int k = 1; k <= c.m.n(); ++k) {
      const Mat6& P = c.art.P[std::size_t(k - 1)];
      const MatX Hs = H_star(c, k);
      const Mat6 t = soa::ex06::tau_bar(P, Hs);
      const double kappa = c.kappa(k);
      lib.add((t - c.art.tau_bar(c.m, c.x.theta, k)).norm() / kappa, i);
      proj.add((t * t - t).norm() / kappa, i);
      hp.add((Hs.transpose() * t * P).norm() / (std::max(1.0, P.norm()) * kappa), i);
    }
  }
  EXPECT_LE(lib.value(), 64 * kEps);
  EXPECT_LE(proj.value(), 64 * kEps);
  EXPECT_LE(hp.value(), 64 * kEps);
}

TEST(Exercise6_3_RevoluteD, MatchesLibrary) {
  Random<double> rnd;
  ChainOptions revolute;
  revolute.all_hinge_types = false;
  Worst w("|D(k) - library| / (|P| kappa)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(soa::test::random_chain(rnd, bodies(i), revolute), rnd);
    const VecX D = soa::ex06::revolute_D(c.m, c.x.theta);
    ASSERT_EQ(D.size(), c.m.n());
    for (int k = 1; k <= c.m.n(); ++k)
      w.add(std::abs(D[k - 1] - c.art.D[std::size_t(k - 1)](0, 0)) /
                (std::max(1.0, c.art.P[std::size_t(k - 1)].norm()) * c.kappa(k)),
            i);
  }
  EXPECT_LE(w.value(), 64 * kEps);
}

TEST(Exercise6_4_TransformSymmetric, MatchesDense) {
  Random<double> rnd;
  Worst w("|phi P phi* - dense| / |dense|");
  for (int i = 0; i < kCases; ++i) {
    const soa::Phi phi = rnd.phi();
    Mat6 A;
    for (int r = 0; r < 6; ++r)
      for (int s = 0; s < 6; ++s) A(r, s) = rnd.normal();
    const Mat6 P = A + A.transpose();
    const Mat6 dense = phi.matrix() * P * phi.matrix().transpose();
    w.add(soa::test::rel(soa::ex06::transform_symmetric(phi, P), dense), i);
  }
  EXPECT_LE(w.value(), 64 * kEps);
}

// The library's f = R alpha+ + y at the state the Newton-Euler pass in ws left (lesson 6,
// section 8): R(k) alpha+(k) + y(k) for every k.
std::vector<Vec6> composite_forces(const soa::Model& m, const soa::Workspace& ws,
                                   std::vector<soa::Force>& y) {
  std::vector<soa::SpatialInertia> R(std::size_t(m.n()));
  soa::composite_inertias(m, ws, R);
  std::vector<soa::Acceleration> ap(std::size_t(m.n()));
  soa::alpha_plus(m, ws, ap);
  y.resize(std::size_t(m.n()));
  soa::composite_bias(m, ws, R, ap, {}, y);
  std::vector<Vec6> f;
  for (int k = 1; k <= m.n(); ++k)
    f.push_back((R[std::size_t(k - 1)] * ap[std::size_t(k - 1)]).vector() +
                y[std::size_t(k - 1)].vector());
  return f;
}

TEST(Exercise6_5_ArticulatedForces, MatchNewtonEulerAndComposite) {
  Random<double> rnd;
  ChainOptions opt;
  opt.gravity = true;
  Worst ne("|P+ alpha+ + z+ - Newton-Euler f| / (|f| 6n kappa)"),
      comp("|P+ alpha+ + z+ - (R alpha+ + y)| / (|f| 6n kappa)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(soa::test::random_chain(rnd, bodies(i), opt), rnd);
    const VecX T = soa::test::random_vector(rnd, c.m.nv());
    soa::Workspace ws(c.m);
    soa::ForwardDynamics fd(c.m);
    VecX bd(c.m.nv()), T_back(c.m.nv());
    soa::forward_dynamics(c.m, c.x, T, {}, ws, fd, bd);
    soa::inverse_dynamics(c.m, c.x, bd, {}, ws, T_back);
    std::vector<soa::Force> y;
    const std::vector<Vec6> f_comp = composite_forces(c.m, ws, y);
    const std::vector<Vec6> f = soa::ex06::articulated_forces(c.m, c.x, T);
    ASSERT_EQ(int(f.size()), c.m.n());
    double scale = 1, e_ne = 0, e_comp = 0;
    for (int k = 1; k <= c.m.n(); ++k) {
      const std::size_t j = std::size_t(k - 1);
      scale = std::max({scale, ws.f[j].vector().norm(), f_comp[j].norm(), y[j].vector().norm()});
      e_ne = std::max(e_ne, (f[j] - ws.f[j].vector()).norm());
      e_comp = std::max(e_comp, (f[j] - f_comp[j]).norm());
    }
    const double tol = scale * 6 * c.m.n() * c.kappa(c.m.n());
    ne.add(e_ne / tol, i);
    comp.add(e_comp / tol, i);
  }
  EXPECT_LE(ne.value(), 16 * kEps);
  EXPECT_LE(comp.value(), 16 * kEps);
}

TEST(Exercise6_6_CompositeBias, MatchesNewtonEulerAndLibrary) {
  Random<double> rnd;
  ChainOptions opt;
  opt.gravity = true;
  Worst ne("|R alpha+ + y - Newton-Euler f| / (|f| 6n)"), lib("|y - composite_bias| / (|f| 6n)");
  for (int i = 0; i < kCases; ++i) {
    const Case c(soa::test::random_chain(rnd, bodies(i), opt), rnd);
    const VecX bd = soa::test::random_vector(rnd, c.m.nv());
    soa::Workspace ws(c.m);
    VecX T(c.m.nv());
    soa::inverse_dynamics(c.m, c.x, bd, {}, ws, T);
    std::vector<soa::SpatialInertia> R(std::size_t(c.m.n()));
    soa::composite_inertias(c.m, ws, R);
    std::vector<soa::Acceleration> ap(std::size_t(c.m.n()));
    soa::alpha_plus(c.m, ws, ap);
    std::vector<soa::Force> y_lib(std::size_t(c.m.n()));
    soa::composite_bias(c.m, ws, R, ap, {}, y_lib);
    const std::vector<Vec6> y = soa::ex06::composite_bias(c.m, c.x, bd);
    ASSERT_EQ(int(y.size()), c.m.n());
    double scale = 1, e_ne = 0, e_lib = 0;
    for (int k = 1; k <= c.m.n(); ++k) {
      const std::size_t j = std::size_t(k - 1);
      const Vec6 Ra = (R[j] * ap[j]).vector();
      scale = std::max({scale, ws.f[j].vector().norm(), Ra.norm(), y_lib[j].vector().norm()});
      e_ne = std::max(e_ne, (Ra + y[j] - ws.f[j].vector()).norm());
      e_lib = std::max(e_lib, (y[j] - y_lib[j].vector()).norm());
    }
    ne.add(e_ne / (scale * 6 * c.m.n()), i);
    lib.add(e_lib / (scale * 6 * c.m.n()), i);
  }
  EXPECT_LE(ne.value(), 16 * kEps);
  EXPECT_LE(lib.value(), 16 * kEps);
}

}  // namespace
