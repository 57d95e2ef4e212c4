/// \file
/// The library's interface as a student meets it: every code snippet of the exercise statements
/// (exercises/*/exercises.hpp), written as a student would write it,
/// compiles and gives what the plain call gives. Free functions take Eigen expressions
/// (`exp_so3(theta * a)`, `tilde(X.angular())`, `VecX<double>::Zero(n)`) through thin
/// forwarding overloads, and `{}` where an argument is naturally empty (external forces, the
/// base acceleration); `Pose(R)` is a pure rotation. Each forwarding overload is called here
/// with an expression, so removing one stops this file from compiling. The results are
/// compared bit for bit with the call on plain Vec3/Mat3/VecX variables (a forwarding
/// overload adds no arithmetic), and with the library to a few eps where the snippet is a
/// formula of its own.
#include <algorithm>
#include <cmath>
#include <vector>

#include "random_chain.hpp"
#include "spatial_support.hpp"

namespace soa::test {
namespace {

/// The coefficients of a result, as a matrix, for Same() and Near().
template <class D>
MatX<typename D::Scalar> flat(const Eigen::MatrixBase<D>& m) {
  return m;
}
template <class S, class K>
MatX<S> flat(const SpatialVector<S, K>& v) {
  return v.vector();
}
template <class S>
MatX<S> flat(const PoseT<S>& T) {
  MatX<S> m(3, 4);
  m << T.R(), T.l();
  return m;
}
template <class S>
MatX<S> flat(const PhiT<S>& phi) {
  return flat(phi.pose());
}
template <class S>
MatX<S> flat(const UnitQuaternionT<S>& q) {
  return q.coeffs();
}
template <class S>
MatX<S> flat(const SpatialInertiaT<S>& M) {
  return M.matrix();
}

/// \p a and \p b have the same coefficients, bit for bit.
template <class A, class B>
::testing::AssertionResult Same(const A& a, const B& b) {
  const auto fa = flat(a), fb = flat(b);
  if (fa.rows() == fb.rows() && fa.cols() == fb.cols() && (fa.array() == fb.array()).all())
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "not the same: " << fa.rows() << "x" << fa.cols() << " vs " << fb.rows() << "x"
         << fb.cols() << ", rel. difference " << rel(fa, fb);
}

/// \p a and \p b agree to \p k eps (rel() of property.hpp).
template <class A, class B>
::testing::AssertionResult Near(const A& a, const B& b, double k) {
  const auto fa = flat(a), fb = flat(b);
  using S = typename decltype(fa)::Scalar;
  const double r = rel(fa, fb);
  if (r <= tol<S>(k)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "rel. difference " << r << " > " << k << " eps";
}

constexpr int kInterfaceCases = 100;

// --- The expression forms -----------------------------------------------------------

template <class S>
class spatial_Interface : public ::testing::Test {};
TYPED_TEST_SUITE(spatial_Interface, Scalars, ScalarNames);

// Rotations and the cross-product matrix of an Eigen expression: exp_so3(theta * a),
// tilde(X.angular()), vee, log_so3, exp_unit_axis, is_rotation, cayley, dexp.
TYPED_TEST(spatial_Interface, RotationHelpersTakeExpressions) {
  using S = TypeParam;
  Random<S> rnd;
  for (int i = 0; i < kInterfaceCases; ++i) {
    const Vec3<S> a = rnd.unit3(), b = rnd.vec3();
    const S theta = rnd.uniform(S(-3), S(3));
    const Mat3<S> R1 = rnd.rotation(), R2 = rnd.rotation();
    const VelocityT<S> X = rnd.velocity(), Y = rnd.velocity();
    EXPECT_TRUE(Same(exp_so3(theta * a), exp_so3(Vec3<S>(theta * a))));
    EXPECT_TRUE(Same(exp_so3(X.angular()), exp_so3(Vec3<S>(X.angular()))));
    EXPECT_TRUE(Same(tilde(X.angular()), tilde(Vec3<S>(X.angular()))));
    EXPECT_TRUE(Same(tilde(a - b), tilde(Vec3<S>(a - b))));
    EXPECT_TRUE(Same(vee(R1 - R1.transpose()), vee(Mat3<S>(R1 - R1.transpose()))));
    EXPECT_TRUE(Same(log_so3(R1 * R2), log_so3(Mat3<S>(R1 * R2))));
    EXPECT_TRUE(Same(exp_unit_axis(-a, theta), exp_unit_axis(Vec3<S>(-a), theta)));
    EXPECT_TRUE(Same(exp_unit_axis(a, 1), exp_unit_axis(a, S(1))));
    EXPECT_EQ(is_rotation(R1 * R2, S(64) * eps<S>()),
              is_rotation(Mat3<S>(R1 * R2), S(64) * eps<S>()));
    EXPECT_TRUE(Same(cayley(b / S(2)), cayley(Vec3<S>(b / S(2)))));
    EXPECT_TRUE(Same(cayley_inverse(R1 * R2), cayley_inverse(Mat3<S>(R1 * R2))));
    EXPECT_TRUE(Same(dexp_so3(X.angular()), dexp_so3(Vec3<S>(X.angular()))));
    EXPECT_TRUE(Same(dexp_so3_inv(theta * a), dexp_so3_inv(Vec3<S>(theta * a))));
    EXPECT_TRUE(Same(vee_se3(hat(X) + hat(Y)), vee_se3(Mat4<S>(hat(X) + hat(Y)))));
    EXPECT_TRUE(Same(dexp_inv_right(theta * a, X.angular()),
                     dexp_inv_right(Vec3<S>(theta * a), Vec3<S>(X.angular()))));
    EXPECT_TRUE(Same(coriolis(DerivativeFrame::C, X, Y, R1 * b),
                     coriolis(DerivativeFrame::C, X, Y, Vec3<S>(R1 * b))));
    // The pure rotation: Pose(R) is (R, 0).
    EXPECT_TRUE(Same(PoseT<S>(exp_so3(theta * a)), PoseT<S>(exp_so3(theta * a), Vec3<S>::Zero())));
  }
}

// The chain functions of lessons 3-8 take an Eigen expression where they take a stacked
// vector, and {} for no external forces or a zero base acceleration.
TYPED_TEST(spatial_Interface, ChainFunctionsTakeExpressionsAndBraces) {
  using S = TypeParam;
  Random<S> rnd;
  const S h = S(0.01);
  for (int i = 0; i < kInterfaceCases; ++i) {
    const ModelT<S> m = random_chain_of_type(rnd, 1 + i % 7, HingeType::Revolute);
    const StateT<S> x = random_state(rnd, m);
    const int nv = m.nv();
    const VecX<S> zero = VecX<S>::Zero(nv);
    const ExternalForces<S> none;
    WorkspaceT<S> ws(m), ws_plain(m);
    VecX<S> T(nv), T_plain(nv);

    inverse_dynamics(m, x, VecX<S>::Zero(nv), {}, ws, T);
    inverse_dynamics(m, x, zero, none, ws_plain, T_plain);
    EXPECT_TRUE(Same(T, T_plain));

    std::vector<SpatialInertiaT<S>> R(std::size_t(m.n())), R_plain(std::size_t(m.n()));
    const VecX<S> e0 = VecX<S>::Unit(nv, 0);
    inverse_dynamics_composite(m, x, VecX<S>::Unit(nv, 0), {}, ws, R, T);
    inverse_dynamics_composite(m, x, e0, none, ws_plain, R_plain, T_plain);
    EXPECT_TRUE(Same(T, T_plain));

    ForwardDynamicsT<S> fd(m), fd_plain(m);
    VecX<S> beta_dot(nv), beta_dot_plain(nv);
    forward_dynamics(m, x, VecX<S>::Zero(nv), {}, ws, fd, beta_dot);
    forward_dynamics(m, x, zero, none, ws_plain, fd_plain, beta_dot_plain);
    EXPECT_TRUE(Same(beta_dot, beta_dot_plain));

    // A configuration a step h along beta (revolute: theta_dot = beta), as RK4 forms it.
    const VecX<S> theta_h = x.theta + h * x.beta;
    update_phi(m, x.theta + h * x.beta, ws);
    update_phi(m, theta_h, ws_plain);
    update_poses(m, ws);
    update_poses(m, ws_plain);
    for (int k = 1; k <= m.n(); ++k) EXPECT_TRUE(Same(ws.pose[k - 1], ws_plain.pose[k - 1]));
    Eigen::Matrix<S, 6, Eigen::Dynamic> J(6, nv), J_plain(6, nv);
    const PoseT<S> frame(rnd.rotation(), rnd.vec3());
    jacobian(m, x.theta + h * x.beta, ws, 1, frame, J);
    jacobian(m, theta_h, ws_plain, 1, frame, J_plain);
    EXPECT_TRUE(Same(J, J_plain));

    VecX<S> theta(m.nq()), theta_plain(m.nq());
    const VecX<S> u = h * x.beta;
    retract(m, x.theta, h * x.beta, theta);
    retract(m, x.theta, u, theta_plain);
    EXPECT_TRUE(Same(theta, theta_plain));

    // update_accelerations: nullptr and {} for beta_dot = 0 and no base acceleration, and a
    // vector (or expression) for beta_dot instead of its data().
    update_phi(m, x.theta, ws);
    update_phi(m, x.theta, ws_plain);
    update_velocities(m, x, ws);
    update_velocities(m, x, ws_plain);
    update_accelerations(m, x, nullptr, {}, ws);
    update_accelerations(m, x, static_cast<const S*>(nullptr), AccelerationT<S>(), ws_plain);
    for (int k = 1; k <= m.n(); ++k) EXPECT_TRUE(Same(ws.alpha[k - 1], ws_plain.alpha[k - 1]));
    update_accelerations(m, x, x.beta, gravity_base_acceleration(m), ws);
    update_accelerations(m, x, x.beta.data(), gravity_base_acceleration(m), ws_plain);
    for (int k = 1; k <= m.n(); ++k) EXPECT_TRUE(Same(ws.alpha[k - 1], ws_plain.alpha[k - 1]));
    update_accelerations(m, x, S(2) * x.beta, {}, ws);
    const VecX<S> two_beta = S(2) * x.beta;
    update_accelerations(m, x, two_beta.data(), AccelerationT<S>(), ws_plain);
    for (int k = 1; k <= m.n(); ++k) EXPECT_TRUE(Same(ws.alpha[k - 1], ws_plain.alpha[k - 1]));
  }
}

// --- The snippets of the statements, lesson by lesson (double, as the exercises) --------

// Lesson 1: 1.1 `Force(N, F)` from `phi_xy.R()`, `phi_xy.l()`, `f_y.angular()`,
// `f_y.linear()`; 1.2 `tilde()` of 3-vectors; 1.3 `SpatialInertia(m, h_x, J_x)`; 1.4
// `UnitQuaternion(q, q0)`; 1.7 the closed form with `tilde(xi.angular())`.
TEST(spatial_InterfaceStatements, Lesson1) {
  Random<double> rnd;
  for (int i = 0; i < kInterfaceCases; ++i) {
    const Phi phi_xy = rnd.phi();
    const Force f_y = rnd.force();
    const Force f_x =
        Force(phi_xy.R() * f_y.angular() + phi_xy.l().cross(phi_xy.R() * f_y.linear()),
              phi_xy.R() * f_y.linear());
    EXPECT_TRUE(Near(f_x, phi_xy.apply(f_y), 16));

    const Velocity X = rnd.velocity(), Y = rnd.velocity();
    const Acceleration XY(tilde(X.angular()) * Y.angular(),
                          tilde(X.linear()) * Y.angular() + tilde(X.angular()) * Y.linear());
    EXPECT_TRUE(Near(XY, cross(X, Y), 16));

    const SpatialInertia M_y = rnd.inertia();
    const double m = M_y.mass();
    const Mat3<double> L = tilde(phi_xy.l()), H = tilde(phi_xy.R() * M_y.h());
    const SpatialInertia M_x =
        SpatialInertia(m, phi_xy.R() * M_y.h() + m * phi_xy.l(),
                       phi_xy.R() * M_y.J() * phi_xy.R().transpose() - L * H - H * L - m * L * L);
    EXPECT_TRUE(Near(M_x, transform(phi_xy, M_y), 64));

    const Vec3<double> n = rnd.vec3();
    const double theta = rnd.uniform(-3, 3);
    const UnitQuaternion q =
        UnitQuaternion(std::sin(theta / 2) * n.normalized(), std::cos(theta / 2));
    EXPECT_TRUE(Near(q, UnitQuaternion::exp(theta * n.normalized()), 8));
    EXPECT_TRUE(Near(q.matrix(), exp_so3(theta * n.normalized()), 16));

    const Velocity xi(theta * n.normalized(), rnd.vec3());
    const double t = std::abs(theta);
    const Mat3<double> W = tilde(xi.angular());
    const double g1 = std::sin(t) / t, g2 = (1 - std::cos(t)) / (t * t),
                 g3 = (t - std::sin(t)) / (t * t * t);
    const Pose T_xi(Mat3<double>::Identity() + g1 * W + g2 * W * W,
                    (Mat3<double>::Identity() + g2 * W + g3 * W * W) * xi.linear());
    if (t > 0.5) {
      EXPECT_TRUE(Near(T_xi, exp_se3(xi), 64));
    }
  }
}

// Lesson 2: the accessors of soa::SpatialInertia, `M.matrix().llt()`, and the stages of 2.4:
// `soa::free_body_rate(M, s_i, Force::Zero())`, `x0.q * UnitQuaternion::exp(delta_i)`,
// `soa::dexp_inv_right(delta_i, d_i.omega)` with delta_i = h/2 e_1 written in place.
TEST(spatial_InterfaceStatements, Lesson2) {
  Random<double> rnd;
  const double h = 0.01;
  for (int i = 0; i < kInterfaceCases; ++i) {
    const SpatialInertia M = rnd.inertia();
    FreeBodyState x0;
    x0.q = UnitQuaternion(rnd.vec3(), rnd.normal());
    x0.r = rnd.vec3();
    x0.V = rnd.velocity();
    const Force f = rnd.force();
    EXPECT_TRUE(Near(M.J_cm() - M.mass() * tilde(M.p()) * tilde(M.p()), M.J(), 64));
    const Vec6<double> alpha = M.matrix().llt().solve((f - gyroscopic_force(M, x0.V)).vector());
    EXPECT_TRUE(Near(alpha, rigid_body_acceleration(M, x0.V, f).vector(), 64));

    const FreeBodyRateT<double> d1 = soa::free_body_rate(M, x0, Force::Zero());
    const FreeBodyRateT<double> d1_plain = soa::free_body_rate(M, x0, Force());
    EXPECT_TRUE(Same(d1.V_dot, d1_plain.V_dot));
    const Vec3<double> e1 = soa::dexp_inv_right(Vec3<double>::Zero(), d1.omega);
    const FreeBodyState s2{x0.q * UnitQuaternion::exp(h / 2 * e1), x0.r + h / 2 * d1.r_dot,
                           Velocity(Vec6<double>(x0.V.vector() + h / 2 * d1.V_dot))};
    const FreeBodyRateT<double> d2 = soa::free_body_rate(M, s2, Force::Zero());
    const Vec3<double> e2 = soa::dexp_inv_right(h / 2 * e1, d2.omega);
    const Vec3<double> delta2 = h / 2 * e1;
    EXPECT_TRUE(Same(e2, soa::dexp_inv_right(delta2, d2.omega)));
  }
}

// Lesson 3: 3.1's universal column from `soa::exp_so3` (\f$e^{-\theta_2\tilde a_2} a\f$);
// 3.5's `hinge.H_star(theta.data() + m.body(i).q_offset)`, `ws.pose[i-1]` after
// soa::update_phi and soa::update_poses, `phi.transpose_apply(V)`, `phi[k-1].matrix()`.
TEST(spatial_InterfaceStatements, Lesson3) {
  Random<double> rnd;
  for (int i = 0; i < kInterfaceCases; ++i) {
    Hinge hinge;
    hinge.type = HingeType::Universal;
    hinge.axis = rnd.unit3();
    hinge.axis2 = rnd.unit3();
    const VecX<double> theta = random_vector(rnd, hinge.nq());
    const Vec3<double> c1 = exp_so3(-theta[1] * hinge.axis2) * hinge.axis;
    EXPECT_TRUE(Near(c1, hinge.H_star(theta.data()).col(0).head<3>(), 16));

    const Model m = random_chain(rnd, 1 + i % 7);
    const State x = random_state(rnd, m);
    Workspace ws(m);
    soa::update_phi(m, x.theta, ws);
    soa::update_poses(m, ws);
    const std::vector<Phi>& phi = ws.phi;
    const int k = 1;
    const Pose frame(rnd.rotation(), rnd.vec3());
    Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, m.nv());
    soa::jacobian(m, x.theta, ws, k, frame, J);
    for (int b = k; b <= m.n(); ++b) {
      const Body& B = m.body(b);
      const Phi phi_iF(ws.pose[b - 1].inverse() * ws.pose[k - 1] * frame);
      const MatX<double> Hs = B.hinge.H_star(x.theta.data() + m.body(b).q_offset);
      const MatX<double> cols = phi_iF.matrix().transpose() * Hs;
      EXPECT_TRUE(Near(cols, J.middleCols(B.v_offset, B.hinge.nv()), 64));
    }
    const Velocity V = rnd.velocity();
    EXPECT_TRUE(
        Near(phi[0].transpose_apply(V).vector(), phi[0].matrix().transpose() * V.vector(), 16));
  }
}

// Lesson 4: 4.1 `m.body(k).hinge.H_times(theta + q_offset, f, T + v_offset)` (the pointers
// theta.data() and T.data()); 4.2 `Phi(B.placement * Pose(exp_so3(theta_k * a_k)))` and
// soa::gyroscopic_force; 4.4 `soa::inverse_dynamics(m, x, VecX<double>::Zero(n), {}, ws, T)`;
// 4.6 `soa::jacobian(m, theta, ws, k, Pose(I, p_k), J)` with `m.body(k).M.p()` and
// `ws.pose[k-1].R()`.
TEST(spatial_InterfaceStatements, Lesson4) {
  Random<double> rnd;
  ChainOptions opt;
  opt.gravity = true;
  for (int i = 0; i < kInterfaceCases; ++i) {
    const Model m = random_chain_of_type(rnd, 1 + i % 7, HingeType::Revolute, opt);
    const State x = random_state(rnd, m);
    const int n = m.n(), nv = m.nv();
    Workspace ws(m);
    soa::update_phi(m, x.theta, ws);
    for (int k = 1; k <= n; ++k) {
      const Body& B = m.body(k);
      const Vec3<double>& a_k = B.hinge.axis;
      const double theta_k = x.theta[B.q_offset];
      const Phi phi_k = Phi(B.placement * Pose(exp_so3(theta_k * a_k)));
      EXPECT_TRUE(Same(phi_k, Phi(B.placement * Pose(exp_so3(Vec3<double>(theta_k * a_k)),
                                                     Vec3<double>::Zero()))));
      EXPECT_TRUE(Near(phi_k, ws.phi[k - 1], 64));
    }

    // Column j of the mass matrix, T(e_j) - T(0), with expressions and {}.
    VecX<double> T0(nv), Tj(nv), T_plain(nv);
    const State x0{x.theta, VecX<double>::Zero(nv)};
    soa::inverse_dynamics(m, x0, VecX<double>::Zero(nv), {}, ws, T0);
    const ExternalForces<double> none;
    const VecX<double> zero = VecX<double>::Zero(nv);
    soa::inverse_dynamics(m, x0, zero, none, ws, T_plain);
    EXPECT_TRUE(Same(T0, T_plain));
    for (int j = 0; j < nv; ++j) {
      soa::inverse_dynamics(m, x0, VecX<double>::Unit(nv, j), {}, ws, Tj);
      VecX<double> ej = VecX<double>::Zero(nv);
      ej[j] = 1;
      soa::inverse_dynamics(m, x0, ej, none, ws, T_plain);
      EXPECT_TRUE(Same(Tj, T_plain));
    }

    // 4.1: T(k) = H(k) f(k) through the pointers, equal to the library's T.
    VecX<double> T(nv), T_lib(nv);
    soa::inverse_dynamics(m, x, VecX<double>::Zero(nv), {}, ws, T_lib);
    for (int k = 1; k <= n; ++k) {
      const Body& B = m.body(k);
      m.body(k).hinge.H_times(x.theta.data() + B.q_offset, ws.f[k - 1], T.data() + B.v_offset);
    }
    EXPECT_TRUE(Same(T, T_lib));
    EXPECT_TRUE(Same(soa::gyroscopic_force(m.body(1).M, ws.V[0]),
                     rigid_body_force(m.body(1).M, ws.V[0], Acceleration())));

    // 4.6: the gravity torques from the Jacobians of the centres of mass.
    soa::update_poses(m, ws);
    VecX<double> G = VecX<double>::Zero(nv);
    Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, nv);
    for (int k = 1; k <= n; ++k) {
      soa::jacobian(m, x.theta, ws, k, Pose(Mat3<double>::Identity(), m.body(k).M.p()), J);
      Vec6<double> f_g;
      f_g << Vec3<double>::Zero(),
          m.body(k).M.mass() * (ws.pose[k - 1].R().transpose() * m.gravity);
      G -= J.transpose() * f_g;
    }
    const State rest{x.theta, VecX<double>::Zero(nv)};
    VecX<double> T_rest(nv);
    soa::inverse_dynamics(m, rest, VecX<double>::Zero(nv), {}, ws, T_rest);
    EXPECT_TRUE(Near(G, T_rest, 1024));
  }
}

// Lesson 5: `soa::transform(phi, M)`; 5.2 `m.body(k).hinge.H_star(theta.data() +
// m.body(k).q_offset)`; 5.3 `Phi(m.body(k).placement * Pose(exp_so3(theta[k-1] * a_k)))`.
TEST(spatial_InterfaceStatements, Lesson5) {
  Random<double> rnd;
  for (int i = 0; i < kInterfaceCases; ++i) {
    const Model m = random_chain_of_type(rnd, 1 + i % 7, HingeType::Revolute);
    const VecX<double> theta = random_vector(rnd, m.nq());
    Workspace ws(m);
    soa::update_phi(m, theta, ws);
    std::vector<SpatialInertia> R(std::size_t(m.n()));
    soa::composite_inertias(m, ws, R);
    for (int k = 1; k <= m.n(); ++k) {
      const Vec3<double>& a_k = m.body(k).hinge.axis;
      const Phi phi = Phi(m.body(k).placement * Pose(exp_so3(theta[k - 1] * a_k)));
      EXPECT_TRUE(Near(phi, ws.phi[k - 1], 64));
      if (k > 1) {
        EXPECT_TRUE(Near(soa::transform(ws.phi[k - 2], R[k - 2]) + m.body(k).M, R[k - 1], 64));
      }
      const MatX<double> Hs = m.body(k).hinge.H_star(theta.data() + m.body(k).q_offset);
      EXPECT_TRUE(Same(Hs.col(0).head<3>(), a_k));
    }
  }
}

// Lessons 6-8: soa::forward_dynamics with an expression for T and {} for f_ext, the fields
// of soa::ForwardDynamics (`fd.art.P_plus[k-1]`, `fd.alpha_plus[k-1]`, `fd.z_plus[k-1]`),
// `art.tau_bar(m, theta, k)`, `w.Upsilon[k-1]` of soa::upsilons and `Phi(frame)`; a lesson 7
// student's `VecX` alias (`VecX::Zero(n)`).
TEST(spatial_InterfaceStatements, Lessons6to8) {
  Random<double> rnd;
  for (int i = 0; i < kInterfaceCases; ++i) {
    const Model m = random_chain(rnd, 1 + i % 7);
    const State x = random_state(rnd, m);
    const int n = m.n(), nv = m.nv();
    using VecX = soa::VecX<double>;  // as exercises 7 name it
    Workspace ws(m);
    ForwardDynamics fd(m);
    VecX beta_dot(nv), beta_dot_plain(nv), T(nv);
    soa::forward_dynamics(m, x, VecX::Zero(nv), {}, ws, fd, beta_dot);
    const VecX zero = VecX::Zero(nv);
    const ExternalForces<double> none;
    ForwardDynamics fd_plain(m);
    soa::forward_dynamics(m, x, zero, none, ws, fd_plain, beta_dot_plain);
    EXPECT_TRUE(Same(beta_dot, beta_dot_plain));
    // The round trip and 6.5's f(k) = P+(k) alpha+(k) + z+(k), loosely: to 1e-9 of the
    // inter-body forces (their conditioning is the exercise tests' business).
    soa::inverse_dynamics(m, x, beta_dot, {}, ws, T);
    double scale = 1;
    for (int k = 1; k <= n; ++k) scale = std::max(scale, ws.f[k - 1].vector().norm());
    EXPECT_LE(T.norm(), 1e-9 * scale);
    for (int k = 1; k <= n; ++k) {
      const Vec6<double> f_k =
          fd.art.P_plus[k - 1] * fd.alpha_plus[k - 1].vector() + fd.z_plus[k - 1].vector();
      EXPECT_LE((f_k - ws.f[k - 1].vector()).norm(), 1e-9 * scale);
    }

    Articulated art(m);
    soa::articulated_inertias(m, x, ws, art);
    const Mat6<double> tau_bar = art.tau_bar(m, x.theta, 1);
    EXPECT_TRUE(Near(tau_bar * tau_bar, tau_bar, 1024));

    Upsilon w(m);
    soa::upsilons(m, x, ws, w);
    const Pose frame(rnd.rotation(), rnd.vec3());
    const Mat6<double> Lambda_inv =
        Phi(frame).matrix().transpose() * w.Upsilon[0] * Phi(frame).matrix();
    Mat6<double> Lambda_inv_lib;
    soa::operational_space_inverse_inertia(frame, w.Upsilon[0], Lambda_inv_lib);
    EXPECT_TRUE(Near(Lambda_inv, Lambda_inv_lib, 1024));
  }
}

}  // namespace
}  // namespace soa::test
