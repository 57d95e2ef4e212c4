/// \file
/// Property tests of soa/se3.hpp, the SE(3) connections of lesson 1 (slide 63): exp and log
/// of SE(3) (round trips, small angles, angles near pi), Ad as phi*(y,x), ad as the spatial
/// cross product, Ad(exp xi) = exp(ad xi), the derivative of exp, and the left/right
/// trivialized twists of a moving frame. References are independent: a scaling-and-squaring
/// Taylor series of the dense 4x4 or 6x6 matrix exponential in long double, the series of
/// dexp in long double, and central differences.
#include <cmath>

#include "soa/se3.hpp"
#include "spatial_support.hpp"

namespace soa::test {
namespace {

using LD = long double;

template <class S>
S pi() {
  return std::acos(S(-1));
}

/// \f$e^A\f$ of a dense square matrix by scaling and squaring: \f$A/2^s\f$ with norm below
/// 1/2, its Taylor series summed until the terms are below \f$\varepsilon\f$, then squared
/// s times. Used in long double as the reference.
template <class M>
M expm(const M& A) {
  using S = typename M::Scalar;
  int s = 0;
  S norm = A.cwiseAbs().rowwise().sum().maxCoeff();
  while (norm > S(0.5)) {
    norm /= 2;
    ++s;
  }
  const M B = A / std::ldexp(S(1), s);
  M sum = M::Identity(), term = M::Identity();
  for (int k = 1; k < 60 && term.norm() > eps<S>() * S(1e-3); ++k) {
    term = (term * B) / S(k);
    sum += term;
  }
  for (int i = 0; i < s; ++i) sum = sum * sum;
  return sum;
}

/// \f$\sum_k \mathrm{ad}(\xi)^k/(k+1)!\f$, the defining series of dexp (lesson 1), in long
/// double.
Mat6<LD> dexp_series(const VelocityT<LD>& xi) {
  const Mat6<LD> A = ad(xi);
  Mat6<LD> sum = Mat6<LD>::Zero(), term = Mat6<LD>::Identity();
  for (int k = 0; k < 80; ++k) {
    sum += term;
    term = term * A / LD(k + 2);
  }
  return sum;
}

/// A twist \f$[\theta n; v]\f$ with a uniform random axis n and a normal v.
template <class S>
VelocityT<S> twist(Random<S>& rnd, S theta) {
  return VelocityT<S>(theta * rnd.unit3(), rnd.vec3());
}

/// Five-point central difference of \p f at 0 with step h.
template <class F>
auto central(const F& f, double h) {
  using T = decltype(f(0.0));
  using Sc = typename T::Scalar;
  const T d = (f(-2 * h) - Sc(8) * f(-h) + Sc(8) * f(h) - f(2 * h)) / (Sc(12) * Sc(h));
  return d;
}

template <class S>
class spatial_SE3 : public ::testing::Test {};
TYPED_TEST_SUITE(spatial_SE3, Precisions, ScalarNames);

// exp(xi^) by the closed form (lesson 1 eq. SE3-exp) = the dense 4x4 exponential, any angle.
TYPED_TEST(spatial_SE3, ExpIsTheMatrixExponential) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("exp_se3 vs expm(xi^) " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const VelocityT<S> xi = twist(rnd, rnd.uniform(S(0), S(3) * pi<S>()));
    const Mat4<LD> ref = expm(hat(xi.template cast<LD>()));
    worst.add(rel(exp_se3(xi).matrix().template cast<LD>(), ref), i);
  }
  EXPECT_LE(worst.value(), tol<S>(64));  // |v| up to ~4, theta up to 3 pi: 64 eps
}

// log(exp xi) = xi for theta in [0, pi), and exp(log T) = T for uniform random poses.
TYPED_TEST(spatial_SE3, RoundTrips) {
  using S = TypeParam;
  Random<S> rnd;
  Worst log_exp("log(exp xi) = xi, theta < pi " + scalar_name<S>());
  Worst exp_log("exp(log T) = T " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const VelocityT<S> xi = twist(rnd, rnd.uniform(S(0), S(0.999) * pi<S>()));
    log_exp.add(rel(log_se3(exp_se3(xi)).vector(), xi.vector()), i);
    const PoseT<S> T(rnd.rotation(), rnd.vec3());
    exp_log.add(rel(exp_se3(log_se3(T)).matrix(), T.matrix()), i);
  }
  EXPECT_LE(log_exp.value(), tol<S>(64));
  EXPECT_LE(exp_log.value(), tol<S>(64));
}

// theta = 1e-9 .. 1e-4, where (1 - cos)/theta^2 and (theta - sin)/theta^3 lose all digits:
// exp against the long double matrix exponential, log(exp xi) with omega relative to theta
// and v relative to |v|, dexp against its long double series; and theta = 0 exactly.
TYPED_TEST(spatial_SE3, SmallAngles) {
  using S = TypeParam;
  Random<S> rnd;
  Worst exp_w("small theta: exp_se3 vs expm " + scalar_name<S>());
  Worst log_w("small theta: log(exp xi), omega/theta " + scalar_name<S>());
  Worst log_v("small theta: log(exp xi), v/|v| " + scalar_name<S>());
  Worst dexp_w("small theta: dexp_se3 vs series " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const S theta = std::pow(S(10), rnd.uniform(S(-9), S(-4)));
    const VelocityT<S> xi = twist(rnd, theta);
    const PoseT<S> T = exp_se3(xi);
    const Mat4<LD> ref = expm(hat(xi.template cast<LD>()));
    exp_w.add(rel(T.matrix().template cast<LD>(), ref), i);
    const VelocityT<S> back = log_se3(T);
    log_w.add(double((back.angular() - xi.angular()).norm() / theta), i);
    log_v.add(double((back.linear() - xi.linear()).norm() / xi.linear().norm()), i);
    dexp_w.add(rel(dexp_se3(xi).template cast<LD>(), dexp_series(xi.template cast<LD>())), i);
  }
  EXPECT_LE(exp_w.value(), tol<S>(16));
  EXPECT_LE(log_w.value(), tol<S>(16));
  EXPECT_LE(log_v.value(), tol<S>(16));
  EXPECT_LE(dexp_w.value(), tol<S>(16));
  const VelocityT<S> zero_angle(Vec3<S>::Zero(), Vec3<S>(S(1), S(-2), S(0.5)));
  EXPECT_TRUE(exp_se3(zero_angle).R().isIdentity(S(0)));
  EXPECT_TRUE(exp_se3(zero_angle).l() == zero_angle.linear());
  EXPECT_TRUE(log_se3(PoseT<S>(Mat3<S>::Identity(), zero_angle.linear())).vector() ==
              zero_angle.vector());
  EXPECT_TRUE(dexp_se3(VelocityT<S>()).isIdentity(S(0)));
}

// theta = pi - 1e-8 .. pi - 1e-2: log(exp xi) = xi; at theta = pi exactly exp(log T) = T.
TYPED_TEST(spatial_SE3, NearPi) {
  using S = TypeParam;
  Random<S> rnd;
  Worst near("theta near pi: log(exp xi) = xi " + scalar_name<S>());
  Worst at("theta = pi: exp(log T) = T " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const S delta = std::pow(S(10), rnd.uniform(S(-8), S(-2)));
    // The sign of the axis is read from vee(R) = sin(theta) n, of size delta: it is defined
    // only for delta well above eps (float: delta >= 1e-4 of the range).
    if (delta < S(1000) * eps<S>()) continue;
    const VelocityT<S> xi = twist(rnd, pi<S>() - delta);
    near.add(rel(log_se3(exp_se3(xi)).vector(), xi.vector()), i);
    const PoseT<S> T(exp_so3<S>(pi<S>() * rnd.unit3()), rnd.vec3());
    at.add(rel(exp_se3(log_se3(T)).matrix(), T.matrix()), i);
  }
  EXPECT_LE(near.value(), tol<S>(64));
  EXPECT_LE(at.value(), tol<S>(64));
}

// Ad(^xT_y) = phi*(y,x) (slide 63 with slide 43), as 6x6 and applied; Ad(T) xi =
// (T xi^ T^-1)^v; Ad(T1 T2) = Ad(T1) Ad(T2).
TYPED_TEST(spatial_SE3, AdIsPhiStarYX) {
  using S = TypeParam;
  Random<S> rnd;
  Worst star("Ad(xT_y) = phi*(y,x) " + scalar_name<S>());
  Worst apply("Ad_apply = phi*(y,x) V " + scalar_name<S>());
  Worst conj("Ad(T) xi = (T xi^ T^-1)^v " + scalar_name<S>());
  Worst hom("Ad(T1 T2) = Ad(T1) Ad(T2) " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const PhiT<S> phi_xy = rnd.phi(), phi_yz = rnd.phi();
    const PoseT<S>& T = phi_xy.pose();  // ^x T_y
    const VelocityT<S> V = rnd.velocity();
    const Mat6<S> phi_star_yx = phi_xy.inverse().matrix().transpose();
    star.add(rel(Ad(T), phi_star_yx), i);
    apply.add(rel(Ad_apply(T, V).vector(), phi_xy.inverse().transpose_apply(V).vector()), i);
    const Mat4<S> C = T.matrix() * hat(V) * T.inverse().matrix();
    conj.add(rel(vee_se3<S>(C).vector(), Vec6<S>(Ad(T) * V.vector())), i);
    hom.add(rel(Ad(T * phi_yz.pose()), Mat6<S>(Ad(T) * Ad(phi_yz.pose()))), i);
  }
  EXPECT_LE(star.value(), tol<S>(16));
  EXPECT_LE(apply.value(), tol<S>(32));
  EXPECT_LE(conj.value(), tol<S>(64));
  EXPECT_LE(hom.value(), tol<S>(64));
}

// ad(X) Y = ([X^, Y^])^v = X~ Y (slide 63 with slide 53), and ad is the derivative of Ad at
// the identity: d/dh Ad(exp(h X)) at h = 0 = ad(X), by central differences.
TYPED_TEST(spatial_SE3, adIsTheSpatialCrossProduct) {
  using S = TypeParam;
  Random<S> rnd;
  Worst bracket("ad(X)Y = [X^,Y^]^v = X~Y " + scalar_name<S>());
  Worst derivative("d/dh Ad(exp(hX)) = ad(X), FD " + scalar_name<S>());
  const double h = std::pow(double(eps<S>()), 0.2);
  for (int i = 0; i < kCases; ++i) {
    const VelocityT<S> X = rnd.velocity(), Y = rnd.velocity();
    const Mat4<S> Xh = hat(X), Yh = hat(Y);
    const Vec6<S> adXY = ad(X) * Y.vector();
    bracket.add(rel(vee_se3<S>(Mat4<S>(Xh * Yh - Yh * Xh)).vector(), adXY) +
                    rel(cross(X, Y).vector(), adXY),
                i);
    const Mat6<S> dAd = central([&](double s) { return Ad(exp_se3(VelocityT<S>(S(s) * X))); }, h);
    derivative.add(rel(dAd, ad(X)) / double(X.vector().squaredNorm() + 1), i);
  }
  EXPECT_LE(bracket.value(), tol<S>(16));
  EXPECT_LE(derivative.value(), 100 * std::pow(double(eps<S>()), 0.8));
}

// Ad(exp xi) = exp(ad xi), the 6x6 exponential in long double.
TYPED_TEST(spatial_SE3, AdOfExpIsExpOfAd) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("Ad(exp xi) = expm(ad xi) " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const VelocityT<S> xi = twist(rnd, rnd.uniform(S(0), pi<S>()));
    worst.add(rel(Ad(exp_se3(xi)).template cast<LD>(), expm(ad(xi.template cast<LD>()))), i);
  }
  EXPECT_LE(worst.value(), tol<S>(64));
}

// The derivative of exp: d/ds exp(xi + s eta) exp(xi)^-1 = (dexp(xi) eta)^ and
// exp(xi)^-1 d/ds exp(xi + s eta) = (dexp(-xi) eta)^, by central differences; dexp against
// its series; Ad(exp xi) - I = ad(xi) dexp(xi) = dexp(xi) ad(xi); dexp(xi) xi = xi.
TYPED_TEST(spatial_SE3, DerivativeOfExp) {
  using S = TypeParam;
  Random<S> rnd;
  Worst left("FD: dexp(xi) eta (right-trivialized) " + scalar_name<S>());
  Worst right("FD: dexp(-xi) eta (left-trivialized) " + scalar_name<S>());
  Worst series("dexp_se3 vs sum ad^k/(k+1)! " + scalar_name<S>());
  Worst ident("Ad(exp xi) - I = ad dexp = dexp ad " + scalar_name<S>());
  const double h = std::pow(double(eps<S>()), 0.2);
  for (int i = 0; i < kCases; ++i) {
    const VelocityT<S> xi = twist(rnd, rnd.uniform(S(0), pi<S>()));
    const VelocityT<S> eta = rnd.velocity();
    const PoseT<S> E = exp_se3(xi);
    const Mat4<S> dE =
        central([&](double s) { return exp_se3(VelocityT<S>(xi + S(s) * eta)).matrix(); }, h);
    const double scale = double(eta.vector().norm() * (1 + xi.vector().squaredNorm()));
    left.add(double((vee_se3<S>(Mat4<S>(dE * E.inverse().matrix())).vector() -
                     dexp_se3(xi) * eta.vector())
                        .norm()) /
                 scale,
             i);
    right.add(double((vee_se3<S>(Mat4<S>(E.inverse().matrix() * dE)).vector() -
                      dexp_se3(VelocityT<S>(-xi)) * eta.vector())
                         .norm()) /
                  scale,
              i);
    const Mat6<S> D = dexp_se3(xi);
    series.add(rel(D.template cast<LD>(), dexp_series(xi.template cast<LD>())), i);
    const Mat6<S> A = Ad(E) - Mat6<S>::Identity();
    ident.add(rel(A, Mat6<S>(ad(xi) * D)) + rel(A, Mat6<S>(D * ad(xi))) +
                  rel(Vec6<S>(D * xi.vector()), xi.vector()),
              i);
  }
  const double fd = 100 * std::pow(double(eps<S>()), 0.8);
  EXPECT_LE(left.value(), fd);
  EXPECT_LE(right.value(), fd);
  EXPECT_LE(series.value(), tol<S>(64));
  EXPECT_LE(ident.value(), tol<S>(128));
}

// A moving frame ^A T_B(t) = (exp(t a~) R0 exp(t b~), p0 + t p1 + t^2 p2), whose course
// velocity ^B V(A,B) = [R* a + b; R* (p1 + 2 t p2)] is known in closed form (lesson 1):
// T^-1 dT/dt = ^B V(A,B)^ (left-trivialized twist) and dT/dt T^-1 = (Ad(T) ^B V(A,B))^ =
// (phi*(B,A) V(A,B))^ (right-trivialized), whose linear part is not the course's
// ^A v(A,B) = dl/dt but the velocity of the body point at A's origin.
TYPED_TEST(spatial_SE3, TwistsOfAMovingFrame) {
  using S = TypeParam;
  Random<S> rnd;
  Worst body("T^-1 dT/dt = B V(A,B), FD " + scalar_name<S>());
  Worst spatial("dT/dt T^-1 = phi*(B,A) V(A,B), FD " + scalar_name<S>());
  Worst differ("spatial twist linear = dl/dt + l x w " + scalar_name<S>());
  const double h = std::pow(double(eps<S>()), 0.2);
  for (int i = 0; i < kCases; ++i) {
    const Vec3<S> a = rnd.vec3(), b = rnd.vec3(), p0 = rnd.vec3(), p1 = rnd.vec3(), p2 = rnd.vec3();
    const Mat3<S> R0 = rnd.rotation();
    const S t0 = rnd.uniform(S(-1), S(1));
    const auto T_at = [&](double t) {
      const S s = S(t) + t0;
      return PoseT<S>(exp_so3<S>(s * a) * R0 * exp_so3<S>(s * b), p0 + s * p1 + s * s * p2);
    };
    const PoseT<S> T = T_at(0);
    const VelocityT<S> V_B(T.R().transpose() * a + b, T.R().transpose() * (p1 + S(2) * t0 * p2));
    const Mat4<S> dT = central([&](double t) { return T_at(t).matrix(); }, h);
    const double scale = double(1 + V_B.vector().squaredNorm() + T.l().squaredNorm());
    body.add(rel(vee_se3<S>(Mat4<S>(T.inverse().matrix() * dT)).vector(), V_B.vector()) / scale, i);
    const VelocityT<S> xi_s = vee_se3<S>(Mat4<S>(dT * T.inverse().matrix()));
    spatial.add(rel(xi_s.vector(), PhiT<S>(T.inverse()).transpose_apply(V_B).vector()) / scale, i);
    const Vec3<S> w_A = T.R() * V_B.angular(), l_dot = p1 + S(2) * t0 * p2;
    differ.add(rel(Vec3<S>(xi_s.linear()), Vec3<S>(l_dot + T.l().cross(w_A))) / scale, i);
  }
  const double fd = 100 * std::pow(double(eps<S>()), 0.8);
  EXPECT_LE(body.value(), fd);
  EXPECT_LE(spatial.value(), fd);
  EXPECT_LE(differ.value(), fd);
}

}  // namespace
}  // namespace soa::test
