/// \file
/// The hinge angles' sines and cosines in one batch (soa/detail/sin_cos.hpp: SLEEF's vector
/// sincos in double, std::sin and std::cos in other scalars) and the recursions that build
/// \f$\phi(k+1,k)\f$ from them (hinge_sin_cos(), joint_phi()). Checked:
/// - soa::detail::sin_cos() against long double std::sin and std::cos: within 1.0 ulp (SLEEF's
///   bound) on random angles from the fixed seed up to |θ| = 1e6, ±0, tiny and subnormal
///   angles, and angles next to multiples of π/2 (where one of the two is tiny);
/// - every length 0 ... 9 (the zero-padded last vector): each angle's sine and cosine are
///   bitwise those of the angle alone, nothing is written past n, and in place (c = θ) gives
///   the same bits;
/// - joint_phi() from hinge_sin_cos() against joint_phi() with std::sin and std::cos and
///   against placement * joint transform, within a few ε in float, double and long double;
///   bitwise the std one but in double;
/// - inverse_dynamics(), forward_dynamics() (both storages) and update_phi() build every
///   \f$\phi(k+1,k)\f$ bitwise from the batch;
/// - the dynamics with the batch against the path it replaced (one std::sin and std::cos per
///   joint, double arithmetic: the counting scalar, lib/support/counted_scalar.hpp), within
///   ε n of the problem's scale, on random chains of every hinge type.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "../dynamics/dynamics_support.hpp"
#include "chain_support.hpp"
#include "counted_scalar.hpp"

namespace soa::test {
namespace {

/// The error of \p got against \p exact in units in the last place of a double at
/// |exact|: \f$2^{e-53}\f$ for \f$|exact| \in [2^{e-1}, 2^e)\f$, at least the smallest
/// subnormal.
double ulps(double got, long double exact) {
  int e = 0;
  (void)std::frexp(exact, &e);
  const long double ulp =
      std::max(std::ldexp(1.0L, e - 53), (long double)(std::numeric_limits<double>::denorm_min()));
  return double(std::fabs((long double)(got)-exact) / ulp);
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

/// The angles of the accuracy test: random ones at three scales, signed zeros, tiny and
/// subnormal ones, and the doubles nearest to multiples of pi/2 with their neighbours.
std::vector<double> test_angles() {
  Random<double> rnd;
  std::vector<double> t;
  for (int i = 0; i < 20000; ++i) t.push_back(rnd.uniform(-10.0, 10.0));
  for (const double scale : {1e3, 1e6})
    for (int i = 0; i < 5000; ++i) t.push_back(rnd.uniform(-scale, scale));
  for (const double x : {0.0, 1e-300, 1e-160, 1e-8, std::numeric_limits<double>::denorm_min(),
                         std::numeric_limits<double>::min()})
    t.push_back(x), t.push_back(-x);
  const long double half_pi = std::acos(-1.0L) / 2;
  for (int k = -400; k <= 400; ++k) {
    double x = double(k * half_pi);
    for (int j = 0; j < 3; ++j) x = std::nextafter(x, -INFINITY);
    for (int j = 0; j < 7; ++j, x = std::nextafter(x, INFINITY)) t.push_back(x);
  }
  return t;
}

TEST(chain_SinCos, WithinAnUlpOfExact) {
  const std::vector<double> t = test_angles();
  const int n = int(t.size());
  std::vector<double> s(t.size()), c(t.size());
  soa::detail::sin_cos(t.data(), n, s.data(), c.data());
  Worst ws("sin: SLEEF batch vs exact [ulp]"), wc("cos: SLEEF batch vs exact [ulp]");
  Worst ls("sin: glibc std::sin vs exact [ulp]"), lc("cos: glibc std::cos vs exact [ulp]");
  for (int i = 0; i < n; ++i) {
    const long double x = t[std::size_t(i)];
    ws.add(ulps(s[std::size_t(i)], std::sin(x)), i);
    wc.add(ulps(c[std::size_t(i)], std::cos(x)), i);
    ls.add(ulps(std::sin(t[std::size_t(i)]), std::sin(x)), i);
    lc.add(ulps(std::cos(t[std::size_t(i)]), std::cos(x)), i);
    if (x == 0) {  // sin(+-0) = +-0, cos(+-0) = 1
      EXPECT_TRUE(same_bits(s[std::size_t(i)], t[std::size_t(i)]) && c[std::size_t(i)] == 1.0)
          << "angle " << t[std::size_t(i)];
    }
  }
  EXPECT_LE(ws.value(), 1.0);
  EXPECT_LE(wc.value(), 1.0);
}

TEST(chain_SinCos, EveryLengthAnglesOnTheirOwnInPlace) {
  Random<double> rnd(3);
  constexpr double kUntouched = 12345.0;
  for (int n = 0; n <= 9; ++n) {
    std::vector<double> t(std::size_t(n) + 4), s(t.size(), kUntouched), c(t.size(), kUntouched);
    for (int i = 0; i < n; ++i)  // small and large angles side by side in one vector
      t[std::size_t(i)] = i % 3 == 2 ? rnd.uniform(-1e6, 1e6) : rnd.uniform(-4.0, 4.0);
    soa::detail::sin_cos(t.data(), n, s.data(), c.data());
    for (int i = 0; i < n; ++i) {
      double si = 0, ci = 0;
      soa::detail::sin_cos(&t[std::size_t(i)], 1, &si, &ci);
      EXPECT_TRUE(same_bits(s[std::size_t(i)], si) && same_bits(c[std::size_t(i)], ci))
          << "n = " << n << ", angle " << i << " differs from the angle alone";
    }
    for (std::size_t i = std::size_t(n); i < t.size(); ++i)
      EXPECT_TRUE(s[i] == kUntouched && c[i] == kUntouched) << "n = " << n << ": wrote " << i;
    std::vector<double> in_place = t, s2(t.size(), kUntouched);
    soa::detail::sin_cos(in_place.data(), n, s2.data(), in_place.data());
    for (int i = 0; i < n; ++i)
      EXPECT_TRUE(same_bits(s2[std::size_t(i)], s[std::size_t(i)]) &&
                  same_bits(in_place[std::size_t(i)], c[std::size_t(i)]))
          << "n = " << n << ", in place, angle " << i;
  }
}

template <class S>
class chain_SinCosPhi : public ::testing::Test {};
TYPED_TEST_SUITE(chain_SinCosPhi, Precisions, ScalarNames);

constexpr int kMaxBodies = 12;

// phi from the batch's sines and cosines against phi with std::sin and std::cos and against
// the general placement * transform (Rodrigues' formula in its other order): each is within
// a few rounding errors of the exact rotation, so the distance is a few eps.
TYPED_TEST(chain_SinCosPhi, MatchesTheGeneralPhi) {
  using S = TypeParam;
  const std::string p = " (" + scalar_name<S>() + ") [eps]";
  Random<S> rnd;
  Worst w_libm("|phi(batch) - phi(std sin, cos)|" + p), w_gen("|phi(batch) - placement T_h|" + p);
  int revolute = 0, differs = 0;
  for (int i = 0; i < kCases; ++i) {
    const ModelT<S> m = random_chain(rnd, chain_size(i, kMaxBodies));
    StateT<S> x = random_state(rnd, m);
    if (i % 4 == 3) x.theta *= S(100);  // angles of many turns (quaternions renormalized below)
    for (int k = 1; k <= m.n(); ++k)
      if (m.body(k).hinge.nq() >= 4) x.theta.segment(m.body(k).q_offset, 4).normalize();
    WorkspaceT<S> ws = WorkspaceT<S>::lazy();
    hinge_sin_cos(m, x.theta.data(), ws);
    for (int k = 1; k <= m.n(); ++k) {
      const BodyT<S>& B = m.body(k);
      const S* th = x.theta.data() + B.q_offset;
      const PhiT<S> fast = joint_phi(B, th, ws.hinge_sin[k - 1], ws.hinge_cos[k - 1]);
      const PhiT<S> libm = joint_phi(B, th);
      const PhiT<S> general(B.placement * B.hinge.transform(th));
      const auto dist = [](const PhiT<S>& a, const PhiT<S>& b) {
        return std::max(rel(a.R(), b.R()), rel(a.l(), b.l())) / double(eps<S>());
      };
      w_libm.add(dist(fast, libm), i);
      w_gen.add(dist(fast, general), i);
      if (B.hinge.type != HingeType::Revolute) continue;
      ++revolute;
      const bool same = fast.R() == libm.R() && fast.l() == libm.l();
      differs += !same;
      if (!std::is_same_v<S, double>) {  // std::sin and std::cos: the same arithmetic
        EXPECT_TRUE(same) << "case " << i << ", body " << k;
      }
    }
  }
  EXPECT_GT(revolute, kCases);
  std::printf("[ note     ] %d of %d revolute phi (%s) differ from std::sin's\n", differs, revolute,
              scalar_name<S>().c_str());
  EXPECT_LE(w_libm.value(), 8.0);
  EXPECT_LE(w_gen.value(), 8.0);
}

// Every recursion that builds phi(k+1,k) takes it from the batch, bit for bit: the results of
// inverse dynamics, forward dynamics (both storages) and the functions after update_phi()
// rest on the same phi.
TEST(chain_SinCos, RecursionsTakePhiFromTheBatch) {
  Random<double> rnd(5);
  int bodies = 0;
  for (int i = 0; i < kCases; ++i) {
    const DynamicsCase<double> c(rnd, i);
    const Model& m = c.m;
    Workspace ws_id(m), ws_fd(m), ws_lean = Workspace::lazy(), ws_phi(m);
    ForwardDynamics fd(m), lean = ForwardDynamics::lean(m);
    VecX<double> T(m.nv()), bd(m.nv());
    inverse_dynamics(m, c.x, c.T, c.f_ext, ws_id, T);
    forward_dynamics(m, c.x, c.T, c.f_ext, ws_fd, fd, bd);
    forward_dynamics(m, c.x, c.T, c.f_ext, ws_lean, lean, bd);
    update_phi(m, c.x.theta, ws_phi);
    for (int k = 1; k <= m.n(); ++k) {
      const Body& B = m.body(k);
      const double* th = c.x.theta.data() + B.q_offset;
      double s = 0, co = 0;
      soa::detail::sin_cos(th, 1, &s, &co);
      const Phi expected = joint_phi(B, th, s, co);
      const auto same = [&](const Workspace& ws) {
        return ws.phi[k - 1].R() == expected.R() && ws.phi[k - 1].l() == expected.l();
      };
      EXPECT_TRUE(same(ws_id)) << "inverse_dynamics, case " << i << ", body " << k;
      EXPECT_TRUE(same(ws_fd)) << "forward_dynamics, case " << i << ", body " << k;
      EXPECT_TRUE(same(ws_lean)) << "forward_dynamics (lean), case " << i << ", body " << k;
      EXPECT_TRUE(same(ws_phi)) << "update_phi, case " << i << ", body " << k;
      bodies += B.hinge.type == HingeType::Revolute;
    }
  }
  EXPECT_GT(bodies, kCases);
}

/// \p m in the counting scalar: double arithmetic with one std::sin and std::cos per
/// revolute joint, the path the batch replaced.
ModelT<Counted> counted(const Model& m) {
  std::vector<BodyT<Counted>> base_first;
  for (int k = m.n(); k >= 1; --k) {
    const Body& B = m.body(k);
    BodyT<Counted> b;
    b.name = B.name;
    b.M = B.M.cast<Counted>();
    b.placement = B.placement.cast<Counted>();
    b.hinge = B.hinge.cast<Counted>();
    b.stiffness = B.stiffness;
    b.damping = B.damping;
    b.rest = B.rest.cast<Counted>();
    base_first.push_back(b);
  }
  ModelT<Counted> mc = ModelT<Counted>::from_base_first(std::move(base_first));
  mc.gravity = m.gravity.cast<Counted>();
  return mc;
}

// Inverse and forward dynamics with the batch against one std::sin and std::cos per joint:
// the two phi differ by an ulp or so in a few entries, which the recursions carry like any
// rounding error (the bounds of forward_dynamics_test.cpp: eps n cond(M) for beta_dot, eps n
// times the terms' size for T).
TEST(chain_SinCos, DynamicsMatchTheLibmPath) {
  Random<double> rnd(17);
  Worst w_id("|T(batch) - T(libm)| / (eps n (|T| + |C| + |M||bd|))"),
      w_fd("|bd(batch) - bd(libm)|/|bd| / (eps n cond(M))");
  constexpr double kEps = eps<double>();
  for (int i = 0; i < kCases; ++i) {
    const DynamicsCase<double> c(rnd, i);
    const VecX<double> beta_dot = random_vector(rnd, c.m.nv());
    const MassAndBias<double> mb(c);
    const ModelT<Counted> mc = counted(c.m);
    const StateT<Counted> xc{c.x.theta.cast<Counted>(), c.x.beta.cast<Counted>()};
    ExternalForces<Counted> fc;
    for (const Force& f : c.f_ext) fc.push_back(f.cast<Counted>());
    const int nv = c.m.nv();

    Workspace ws(c.m);
    WorkspaceT<Counted> wc(mc);
    VecX<double> T(nv), bd(nv);
    VecX<Counted> Tc(nv), bdc(nv);
    inverse_dynamics(c.m, c.x, beta_dot, c.f_ext, ws, T);
    inverse_dynamics(mc, xc, VecX<Counted>(beta_dot.cast<Counted>()), fc, wc, Tc);
    const double scale = T.norm() + mb.C.norm() + mb.M.norm() * beta_dot.norm();
    w_id.add((T - Tc.cast<double>()).norm() / (kEps * nv * scale), i);

    ForwardDynamics fd(c.m);
    ForwardDynamicsT<Counted> fdc(mc);
    forward_dynamics(c.m, c.x, c.T, c.f_ext, ws, fd, bd);
    forward_dynamics(mc, xc, VecX<Counted>(c.T.cast<Counted>()), fc, wc, fdc, bdc);
    w_fd.add(rel(bd, bdc.cast<double>()) / (kEps * nv * mb.cond()), i);
  }
  EXPECT_LE(w_id.value(), 10.0);
  EXPECT_LE(w_fd.value(), 10.0);
}

}  // namespace
}  // namespace soa::test
