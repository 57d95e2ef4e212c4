/// \file
/// Property tests of lesson 2, one rigid body: the equations of motion about an arbitrary
/// body point against the centre-of-mass form moved by \f$\phi\f$, the inverse dynamics,
/// the free-body right-hand side against finite differences of closed-form and prescribed
/// motions, and the RK4 simulation (conservation, order of convergence, unit quaternion,
/// agreement of the formulations about x and about the centre of mass).
#include <Eigen/Eigenvalues>

#include "frame_motion.hpp"
#include "spatial_support.hpp"

namespace soa::test {
namespace {

// ---------------------------------------------------------------------------------------
// The equations of motion f(x) = M(x) alpha(x) + b(x).

template <class S>
class rigid_body_Eom : public ::testing::Test {};
TYPED_TEST_SUITE(rigid_body_Eom, Scalars, ScalarNames);

/// |M| (|alpha| + |V|^2): the size of the terms of M alpha + b, against which the residuals
/// of the equations of motion are measured.
template <class S>
double eom_scale(const SpatialInertiaT<S>& M, const VelocityT<S>& V, const AccelerationT<S>& a) {
  return std::max(1.0, double(M.matrix().norm() * (a.vector().norm() + V.vector().squaredNorm())));
}

// The EOM about a body point x against the centre-of-mass form moved by phi (lesson 2):
//   f(x) = phi(x,C) f(C),  f(C) = M(C) alpha(C) + b(C),  V(C) = phi*(x,C) V(x).
// alpha is the inertial derivative of V = [omega; v(point)]. With p = l(x,C) fixed in the
// body, d/dt p = omega x p (inertial derivative), so differentiating
// v(C) = v(x) + omega x p gives the inertial acceleration of the CM point
//   a(C) = a(x) + omega' x p + omega x (omega x p),
// i.e. alpha(C) = phi*(x,C) alpha(x) + [0; omega x (omega x p)]: phi* alone moves the
// acceleration of the body point (the first two terms), the last term is the centripetal
// acceleration of C about x. At C, the EOM are Newton-Euler:
// f(C) = [J(C) omega' + omega x J(C) omega; m a(C)].
// Even cases: coordinate-free phi(x,C) (body frame at x parallel to the CM frame); odd cases:
// the CM frame rotated by ^xR_C, vectors at C in C coordinates.
TYPED_TEST(rigid_body_Eom, MatchesCenterOfMassFormMovedByPhi) {
  using S = TypeParam;
  Random<S> rnd;
  Worst moved("f(x) = phi(x,C) f(C) " + scalar_name<S>());
  Worst newton_euler("f(C) = Newton-Euler " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const SpatialInertiaT<S> body = rnd.inertia();
    const S m = body.mass();
    const Mat3<S> J_C = body.J_cm();
    const Vec3<S> p = rnd.vec3();
    const PhiT<S> phi_xC = i % 2 == 0 ? PhiT<S>::translation(p) : PhiT<S>(rnd.rotation(), p);
    const SpatialInertiaT<S> M_C = SpatialInertiaT<S>::from_cm(m, Vec3<S>::Zero(), J_C);
    const SpatialInertiaT<S> M_x = transform(phi_xC, M_C);
    const VelocityT<S> V_x = rnd.velocity();
    const AccelerationT<S> alpha_x = rnd.acceleration();

    const Vec3<S> w = V_x.angular();
    const VelocityT<S> V_C = phi_xC.transpose_apply(V_x);
    const AccelerationT<S> alpha_C =
        phi_xC.transpose_apply(alpha_x) +
        AccelerationT<S>(Vec3<S>::Zero(), phi_xC.R().transpose() * w.cross(w.cross(p)));
    const ForceT<S> f_C = rigid_body_force(M_C, V_C, alpha_C);
    const ForceT<S> f_x = rigid_body_force(M_x, V_x, alpha_x);
    moved.add(
        double((f_x.vector() - phi_xC.apply(f_C).vector()).norm()) / eom_scale(M_x, V_x, alpha_x),
        i);

    const Vec3<S> w_C = V_C.angular();
    const ForceT<S> f_ne(J_C * Vec3<S>(alpha_C.angular()) + w_C.cross(J_C * w_C),
                         m * Vec3<S>(alpha_C.linear()));
    newton_euler.add(double((f_C.vector() - f_ne.vector()).norm()) / eom_scale(M_C, V_C, alpha_C),
                     i);
  }
  EXPECT_LE(moved.value(), tol<S>(64));
  EXPECT_LE(newton_euler.value(), tol<S>(16));
}

// Power balance: the power of the force the EOM need is the rate of the kinetic energy,
// f*(x) V(x) = d/dt (1/2 V* M V) = V_dot* M V, with V_dot the component rates of V in body
// coordinates, alpha = V_dot + [0; omega x v] (free_body.hpp). About the CM the gyroscopic
// force alone does no work, V*(C) b(C) = 0; about another point it does (b(x) carries
// m omega x (omega x p)), compensated by the [0; omega x v] part of alpha.
TYPED_TEST(rigid_body_Eom, PowerIsRateOfKineticEnergy) {
  using S = TypeParam;
  Random<S> rnd;
  Worst power("f*V = d/dt(1/2 V*MV) " + scalar_name<S>());
  Worst cm("V*(C) b(C) = 0 " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const SpatialInertiaT<S> M = transform(rnd.phi(), rnd.inertia());
    const VelocityT<S> V = rnd.velocity();
    const AccelerationT<S> alpha = rnd.acceleration();
    const Vec3<S> w = V.angular(), v = V.linear();
    const Vec6<S> V_dot = (alpha - AccelerationT<S>(Vec3<S>::Zero(), w.cross(v))).vector();
    const double scale = eom_scale(M, V, alpha) * std::max(1.0, double(V.vector().norm()));
    power.add(std::abs(double(dot(rigid_body_force(M, V, alpha), V) -
                              V_dot.dot(M.matrix() * V.vector()))) /
                  scale,
              i);
    const SpatialInertiaT<S> M_C = SpatialInertiaT<S>::from_cm(M.mass(), Vec3<S>::Zero(), M.J_cm());
    cm.add(std::abs(double(dot(gyroscopic_force(M_C, V), V))) / scale, i);
  }
  EXPECT_LE(power.value(), tol<S>(64));
  EXPECT_LE(cm.value(), tol<S>(16));
}

// rigid_body_acceleration inverts rigid_body_force. Forward (alpha -> f -> alpha): the error
// is bounded by the conditioning, eps (kappa(M) |alpha| + |b| / lambda_min(M)); backward
// (f -> alpha -> f): the residual is at rounding relative to the terms.
TYPED_TEST(rigid_body_Eom, AccelerationInvertsForce) {
  using S = TypeParam;
  Random<S> rnd;
  Worst forward("alpha -> f -> alpha, / conditioning " + scalar_name<S>());
  Worst backward("f -> alpha -> f " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const SpatialInertiaT<S> M = transform(rnd.phi(), rnd.inertia());
    const VelocityT<S> V = rnd.velocity();
    const AccelerationT<S> alpha = rnd.acceleration();
    const Eigen::SelfAdjointEigenSolver<Mat6<S>> es(M.matrix());
    const double lo = double(es.eigenvalues().minCoeff()), hi = double(es.eigenvalues().maxCoeff());
    const double b = double(gyroscopic_force(M, V).vector().norm());
    const AccelerationT<S> alpha2 = rigid_body_acceleration(M, V, rigid_body_force(M, V, alpha));
    forward.add(double((alpha2 - alpha).vector().norm()) /
                    (hi / lo * double(alpha.vector().norm()) + b / lo),
                i);
    const ForceT<S> f = rnd.force();
    const AccelerationT<S> a = rigid_body_acceleration(M, V, f);
    backward.add(double((rigid_body_force(M, V, a) - f).vector().norm()) /
                     std::max(eom_scale(M, V, a), double(f.vector().norm())),
                 i);
  }
  EXPECT_LE(forward.value(), tol<S>(64));
  EXPECT_LE(backward.value(), tol<S>(64));
}

// ---------------------------------------------------------------------------------------
// The free body: right-hand side and simulation (double).

/// The torque-free motion of an axisymmetric body, in closed form. Inertia about the CM
/// J(C) = I1 (I - a a*) + I3 a a* (symmetry axis a, body coordinates), angular momentum L
/// about C (inertial, constant). Then with b = (I1 - I3) (a . R0* L) / (I1 I3),
///   R(t) = exp(t L~ / I1) R0 exp(t b a~),   omega_B = R* L / I1 + b a:
/// indeed J(C) omega_B = I1 omega_B + (I3 - I1)(a . omega_B) a = R* L, because
/// a . omega_B = (a . R0* L) / I3 is constant (exp(t L~) fixes L, exp(t b a~) fixes a).
/// The CM moves uniformly, r_C(t) = r_C0 + t v_C. The body frame is at x with
/// p = l(x, C) (body coordinates): r(t) = r_C(t) - R p, V(x) = [omega_B; R* v_C - omega_B x p].
struct TorqueFreeTop {
  double m, I1, I3, b;
  Vec3<double> a, p, L, v_C, r_C0;
  Mat3<double> R0;

  static TorqueFreeTop random(Random<double>& rnd) {
    TorqueFreeTop top;
    top.m = rnd.uniform(0.5, 5);
    top.I1 = rnd.uniform(0.3, 2);
    // I3 <= 2 I1 (the triangle inequality); I3 >= I1 / 3 keeps the spin rate b below about
    // twice |omega| (a needle-like body, I3 -> 0, spins arbitrarily fast).
    top.I3 = rnd.uniform(top.I1 / 3, 2 * top.I1);
    top.a = rnd.unit3();
    top.p = rnd.vec3();
    top.L = top.I1 * rnd.vec3();
    top.v_C = rnd.vec3();
    top.r_C0 = rnd.vec3();
    top.R0 = rnd.rotation();
    top.b = (top.I1 - top.I3) * top.a.dot(top.R0.transpose() * top.L) / (top.I1 * top.I3);
    return top;
  }
  SpatialInertia M() const {
    const Mat3<double> J = I1 * Mat3<double>::Identity() + (I3 - I1) * a * a.transpose();
    return SpatialInertia::from_cm(m, p, J);
  }
  Mat3<double> R(double t) const {
    return exp_so3<double>(t * L / I1) * R0 * exp_so3<double>(t * b * a);
  }
  FreeBodyState state(double t) const {
    const Mat3<double> Rt = R(t);
    const Vec3<double> w = Rt.transpose() * L / I1 + b * a;
    FreeBodyState s;
    s.q = UnitQuaternion::from_matrix(Rt);
    s.r = r_C0 + t * v_C - Rt * p;
    s.V = Velocity(w, Rt.transpose() * v_C - w.cross(p));
    return s;
  }
};

/// The largest difference between two states: attitude matrices, positions, velocities.
double state_error(const FreeBodyState& x, const FreeBodyState& y) {
  return std::max({(x.q.matrix() - y.q.matrix()).norm(), (x.r - y.r).norm(),
                   (x.V.vector() - y.V.vector()).norm()});
}

/// The least-squares slope of log(e) against log(h): the observed order of convergence.
double observed_order(const std::vector<double>& h, const std::vector<double>& e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(h.size());
  for (size_t k = 0; k < h.size(); ++k) {
    const double x = std::log(h[k]), y = std::log(e[k]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// The finite differences and their tolerance (kFdTolerance = 1e-8 relative) are those of
// frame_motion.hpp: fourth-order central differences with h = 3e-4.

// free_body_rate (f = 0) against central differences of the closed-form torque-free motion
// of an axisymmetric body with the body frame away from the CM: the component rates of
// V(x), r_dot and omega (from R* dR/dt).
TEST(rigid_body_FreeBody, RateMatchesClosedFormMotion) {
  Random<double> rnd;
  Worst worst("free_body_rate vs FD of closed-form motion");
  for (int i = 0; i < kCases; ++i) {
    const TorqueFreeTop top = TorqueFreeTop::random(rnd);
    const double t = rnd.uniform(0, 5);
    const FreeBodyState x = top.state(t);
    const FreeBodyRateT<double> d = free_body_rate(top.M(), x, Force::Zero());
    const Vec6<double> V_dot = derivative([&](double u) { return top.state(u).V.vector(); }, t);
    const Vec3<double> r_dot = derivative([&](double u) { return top.state(u).r; }, t);
    const Vec3<double> omega =
        vee<double>(x.q.matrix().transpose() * derivative([&](double u) { return top.R(u); }, t));
    worst.add(rel(d.V_dot, V_dot), i);
    worst.add(rel(d.r_dot, r_dot), i);
    worst.add(rel(d.omega, omega), i);
  }
  EXPECT_LE(worst.value(), kFdTolerance);
}

// free_body_rate with an applied force, against a prescribed smooth motion of a general
// body (frame_motion.hpp: attitude ^I R_B(t) and origin r(t) with exact rates). The force
// is the one the motion needs, f = M alpha + b, with alpha = the inertial derivative of
// V(x) (central differences of its inertial components, rotated to body coordinates);
// free_body_rate must give back the component rates of ^B V(x) (central differences),
// r_dot and omega.
TEST(rigid_body_FreeBody, RateMatchesPrescribedMotion) {
  Random<double> rnd;
  Worst worst("free_body_rate vs FD of prescribed motion");
  const auto inertial_velocity = [](const RelativeMotion& m, double t) {
    return velocity_of(m.R(t), m.R_dot(t), m.l_dot(t));  // [omega; r_dot], inertial coords
  };
  for (int i = 0; i < kCases; ++i) {
    const RelativeMotion motion = RelativeMotion::random(rnd);
    const SpatialInertia M = transform(rnd.phi(), rnd.inertia());
    const double t = rnd.uniform(0, 5);
    const Mat3<double> R = motion.R(t), Rt = R.transpose();
    FreeBodyState x;
    x.q = UnitQuaternion::from_matrix(R);
    x.r = motion.l(t);
    x.V = rotated(Rt, inertial_velocity(motion, t));
    const Acceleration alpha =
        rotated(Rt, spatial<AccelerationKind>(Vec6<double>(derivative(
                        [&](double u) { return inertial_velocity(motion, u).vector(); }, t))));
    const FreeBodyRateT<double> d = free_body_rate(M, x, rigid_body_force(M, x.V, alpha));
    const Vec6<double> V_dot = derivative(
        [&](double u) {
          return rotated(Mat3<double>(motion.R(u).transpose()), inertial_velocity(motion, u))
              .vector();
        },
        t);
    worst.add(rel(d.V_dot, V_dot), i);
    worst.add(rel(d.r_dot, motion.l_dot(t)), i);
    worst.add(rel(d.omega, Vec3<double>(x.V.angular())), i);
  }
  EXPECT_LE(worst.value(), kFdTolerance);
}

/// Simulates \p n torque-free RK4 steps of size \p h, calling \p each(k, state) after each.
template <class F>
FreeBodyState simulate(const SpatialInertia& M, FreeBodyState x, double h, int n, F each) {
  for (int k = 1; k <= n; ++k) {
    x = rk4_step(M, x, h);
    each(k, x);
  }
  return x;
}

FreeBodyState random_state(Random<double>& rnd) {
  FreeBodyState x;
  x.q = UnitQuaternion(rnd.vec3(), rnd.normal());
  x.r = rnd.vec3();
  x.V = rnd.velocity();
  return x;
}

// Torque-free, frame away from the CM: the kinetic energy and the inertial momentum h(O)
// are conserved up to the integration error. RK4's global error over a horizon T is
// ~ T |omega| (|omega| h)^4 times a constant; the tolerance is T |omega| (|omega| h)^4
// relative (the constant taken as 1), plus rounding, per body. An integrator of order 2 or 3
// would exceed it by orders of magnitude (h = 0.01).
TEST(rigid_body_FreeBody, Rk4ConservesEnergyAndMomentum) {
  Random<double> rnd;
  Worst energy("RK4 energy drift / bound");
  Worst momentum("RK4 momentum drift / bound");
  const double h = 0.01, T = 5;
  const int n = int(T / h + 0.5);
  for (int b = 0; b < 40; ++b) {
    const SpatialInertia M = transform(Phi::translation(rnd.vec3()), rnd.inertia());
    const FreeBodyState x0 = random_state(rnd);
    const double E0 = kinetic_energy(M, x0);
    const Vec6<double> h0 = inertial_momentum(M, x0).vector();
    const double w = x0.V.angular().norm();
    const double bound = T * w * std::pow(w * h, 4) + n * eps<double>();
    simulate(M, x0, h, n, [&](int k, const FreeBodyState& x) {
      energy.add(std::abs(kinetic_energy(M, x) - E0) / E0 / bound, b * n + k);
      momentum.add(rel(inertial_momentum(M, x).vector(), h0) / bound, b * n + k);
    });
  }
  EXPECT_LE(energy.value(), 1.0);
  EXPECT_LE(momentum.value(), 1.0);
}

// RK4 converges at order 4: the error of the state against the closed-form motion (max over
// a horizon of 4 s) for h = T/50 ... T/400, and the least-squares slope of log(error) over
// log(h) must lie in [3.5, 4.5]. The energy error converges at least as fast; observed
// about 5 for most bodies (the leading local energy error of RK4 vanishes for this
// quadratic invariant, as for the harmonic oscillator where |R(iy)|^2 = 1 - y^6/72 + ...),
// so only a lower bound of 3.5 is required for it.
TEST(rigid_body_FreeBody, Rk4ConvergesAtOrderFour) {
  Random<double> rnd;
  const double T = 4;
  for (int b = 0; b < 8; ++b) {
    const TorqueFreeTop top = TorqueFreeTop::random(rnd);
    const SpatialInertia M = top.M();
    const double E0 = kinetic_energy(M, top.state(0));
    std::vector<double> hs, state_errors, energy_errors;
    for (const int n : {50, 100, 200, 400}) {
      const double h = T / n;
      double e_state = 0, e_energy = 0;
      simulate(M, top.state(0), h, n, [&](int k, const FreeBodyState& x) {
        e_state = std::max(e_state, state_error(x, top.state(k * h)));
        e_energy = std::max(e_energy, std::abs(kinetic_energy(M, x) - E0) / E0);
      });
      hs.push_back(h);
      state_errors.push_back(e_state);
      energy_errors.push_back(e_energy);
    }
    const double order = observed_order(hs, state_errors);
    const double energy_order = observed_order(hs, energy_errors);
    std::printf("[ order    ] top %d: state error %.2e .. %.2e, order %.3f; energy order %.3f\n", b,
                state_errors.front(), state_errors.back(), order, energy_order);
    EXPECT_GE(order, 3.5) << "top " << b;
    EXPECT_LE(order, 4.5) << "top " << b;
    EXPECT_GE(energy_order, 3.5) << "top " << b;
  }
}

// The attitude stays a unit quaternion over a long run (RKMK: products of unit quaternions,
// normalized): |q| - 1 and the orthonormality of R at rounding after 100000 steps.
TEST(rigid_body_FreeBody, QuaternionStaysUnitOverLongRun) {
  Random<double> rnd;
  Worst worst("| |q| - 1 | over 1e5 steps");
  const SpatialInertia M = transform(Phi::translation(rnd.vec3()), rnd.inertia());
  const FreeBodyState x = simulate(
      M, random_state(rnd), 1e-3, 100000,
      [&](int k, const FreeBodyState& s) { worst.add(std::abs(s.q.coeffs().norm() - 1), k); });
  EXPECT_LE(worst.value(), tol<double>(4));
  EXPECT_TRUE(is_rotation(x.q.matrix(), 8 * eps<double>()));
}

// The same body simulated about x (M(x)) and about its CM (M(C)), from the same motion:
// V(C) = phi*(x,C) V(x), r_C = r + R p. The attitudes agree to rounding accumulated over
// the n steps (the angular equations are the same), the CM trajectories and V(C) to the
// integration error ~ T |omega| (|omega| h)^4 |p| (the two RK4 discretizations differ at
// that order).
TEST(rigid_body_FreeBody, CenterOfMassAndBodyPointFormulationsAgree) {
  Random<double> rnd;
  Worst attitude("attitude about x vs about C");
  Worst center("CM motion about x vs about C / bound");
  const double h = 0.01, T = 5;
  const int n = int(T / h + 0.5);
  for (int b = 0; b < 40; ++b) {
    const SpatialInertia body = rnd.inertia();
    const Vec3<double> p = rnd.vec3();
    const SpatialInertia M_C =
        SpatialInertia::from_cm(body.mass(), Vec3<double>::Zero(), body.J_cm());
    const SpatialInertia M_x = SpatialInertia::from_cm(body.mass(), p, body.J_cm());
    const Phi phi_xC = Phi::translation(p);
    FreeBodyState x = random_state(rnd), c = x;
    c.r = x.r + x.q.rotate(p);
    c.V = phi_xC.transpose_apply(x.V);
    const double w = x.V.angular().norm();
    const double bound = T * w * std::pow(w * h, 4) * std::max(1.0, p.norm()) + n * eps<double>();
    for (int k = 1; k <= n; ++k) {
      x = rk4_step(M_x, x, h);
      c = rk4_step(M_C, c, h);
      attitude.add(rel(x.q.matrix(), c.q.matrix()), b * n + k);
      center.add(rel(Vec3<double>(x.r + x.q.rotate(p)), c.r) / bound, b * n + k);
      center.add(rel(phi_xC.transpose_apply(x.V).vector(), c.V.vector()) / bound, b * n + k);
    }
  }
  EXPECT_LE(attitude.value(), n * tol<double>(64));
  EXPECT_LE(center.value(), 1.0);
}

}  // namespace
}  // namespace soa::test
