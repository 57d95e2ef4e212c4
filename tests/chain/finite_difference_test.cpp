/// \file
/// Property tests of the chain kinematics of lesson 3 against finite differences of poses
/// and velocities along a motion, on random chains of up to 12 bodies of every kind.
///
/// The motion: \f$\theta(t) = \theta + t\dot\theta\f$ with \f$\dot\theta\f$ from
/// HingeT::theta_dot() and every quaternion renormalized (advance()), \f$\beta(t) = \beta +
/// t\dot\beta\f$. Only the tangent at t = 0 matters for a first derivative, and it is
/// \f$(\dot\theta, \dot\beta)\f$. Derivatives at t = 0 by the fourth-order central difference
/// (derivative() in chain_support.hpp). Checked:
/// - the Jacobian of a frame F at a random offset pose on a random body k:
///   \f$J\beta = V(F) = [\omega; v]\f$ in F coordinates, with \f$\tilde\omega =
///   R_F^*\dot R_F\f$ from \f$\frac{d}{dt}\log(R_F^*(0) R_F(t))\f$ and \f$v =
///   R_F^*\dot p_F\f$ from the poses \f${}^I T_F = (R_F, p_F)\f$ of update_poses(); and
///   \f$J\beta = \phi^*(O_k, F)\,V(k)\f$ (the velocity recursion);
/// - \f$\alpha(k)\f$ of update_accelerations() (no gravity) against the inertial-frame
///   derivative of \f$V(k)\f$: \f$\alpha(k) = \mathrm{diag}(R_k, R_k)^*
///   \frac{d}{dt}[R_k\omega_k; R_k v_k]\f$, for every body;
/// - \f$\dot J\beta\f$ of jacobian_dot_times_beta() against the inertial-frame derivative of
///   \f$J(\theta(t))\beta\f$ at fixed \f$\beta\f$: \f$\mathrm{diag}(R_F, R_F)^*
///   \frac{d}{dt}[\mathrm{diag}(R_F, R_F)\, J\beta]\f$; and, to pin the convention, against
///   the derivative of the F components \f$\frac{d}{dt}(J\beta)\f$, which is smaller by
///   \f$[0;\ \omega\times v]\f$.
///
/// Step and tolerance: h = 5e-4. The truncation of the stencil is \f$h^4|x^{(5)}|/30\f$;
/// the motions turn at rates \f$\nu\f$ of a few rad/s (up to about 10 at the tip of a
/// 12-body chain), so \f$|x^{(5)}| \approx \nu^5|x|\f$ and the truncation is below
/// \f$2\cdot10^{-10}|x|\f$; the rounding is \f$1.5\,\varepsilon|x|/h \approx
/// 7\cdot10^{-13}|x|\f$. Residuals are relative to \f$\max(1, |a|, |b|)\f$ (rel()) and must
/// stay below kFdTol = 1e-8 (the worst seen is about 1e-10), far below the O(1) residual of
/// a wrong term (the \f$[0;\omega\times v]\f$ that separates the two derivatives of
/// \f$J\beta\f$ is one).
#include "chain_support.hpp"

namespace soa::test {
namespace {

constexpr int kMaxBodies = 12;
constexpr double kStep = 5e-4;
constexpr double kFdTol = 1e-8;

/// The poses of every body at configuration \p theta.
std::vector<Pose> poses(const Model& m, const VecX<double>& theta) {
  Workspace ws(m);
  update_phi(m, theta, ws);
  update_poses(m, ws);
  return ws.pose;
}

/// The velocities V(k) at state (\p theta, \p beta), in body coordinates.
std::vector<Velocity> velocities(const Model& m, const VecX<double>& theta,
                                 const VecX<double>& beta) {
  Workspace ws(m);
  update_phi(m, theta, ws);
  update_velocities(m, State{theta, beta}, ws);
  return ws.V;
}

/// The spatial vector \p v (6 coefficients) with both parts rotated by \p R.
Vec6<double> rotate6(const Mat3<double>& R, const Vec6<double>& v) {
  Vec6<double> r;
  r << R * v.head<3>(), R * v.tail<3>();
  return r;
}

/// Relative residual of \p a against the reference \p b (max(1, |a|, |b|)).
double rel6(const Vec6<double>& a, const Vec6<double>& b) {
  return rel(a, b);
}

class chain_Kinematics : public ::testing::TestWithParam<ChainKind> {};

// J beta against the spatial velocity of F from finite differences of its pose, and
// against phi*(O_k, F) V(k).
TEST_P(chain_Kinematics, JacobianMatchesPoseDifferences) {
  const ChainKind kind = GetParam();
  Random<double> rnd;
  Worst wFd("J beta = V(F) from pose differences"), wRec("J beta = phi*(O_k,F) V(k) [N eps]");
  for (int i = 0; i < kCases; ++i) {
    const Model m = make_chain(rnd, kind, chain_size(i, kMaxBodies));
    const State x = random_state(rnd, m);
    const int k = 1 + int(rnd.engine()() % unsigned(m.n()));
    const Pose frame(rnd.rotation(), rnd.vec3());
    const VecX<double> qd = theta_dot(m, x);

    Workspace ws(m);
    update_phi(m, x.theta, ws);
    update_poses(m, ws);
    update_velocities(m, x, ws);
    Eigen::Matrix<double, 6, Eigen::Dynamic> J;
    jacobian(m, x.theta, ws, k, frame, J);
    const Vec6<double> JB = J * x.beta;

    const Pose F0 = ws.pose[k - 1] * frame;
    const auto pose_F = [&](double t) {
      return poses(m, advance(m, x.theta, qd, t))[k - 1] * frame;
    };
    const Vec3<double> w = derivative(
        [&](double t) { return log_so3<double>(F0.R().transpose() * pose_F(t).R()); }, kStep);
    const Vec3<double> pd = derivative([&](double t) { return pose_F(t).l(); }, kStep);
    Vec6<double> V_fd;
    V_fd << w, F0.R().transpose() * pd;
    wFd.add(rel6(JB, V_fd), i);
    // Against the recursion, in units of N eps (N = 6n), relative to |J| |beta| (1 + d):
    // jacobian() forms phi(O_i, F) from absolute poses, (^I T_{O_i})^{-1} ^I T_F, whose
    // offset is rounded by eps times d, the largest distance of O_i or F from the origin.
    double d = F0.l().norm();
    for (int j = k; j <= m.n(); ++j) d = std::max(d, double(ws.pose[j - 1].l().norm()));
    const double s = J.norm() * x.beta.norm() * (1 + d) * 6 * m.n() * eps<double>();
    wRec.add(residual(JB, Phi(frame).transpose_apply(ws.V[k - 1]).vector(), s), i);
  }
  EXPECT_LE(wFd.value(), kFdTol);
  EXPECT_LE(wRec.value(), 4.0);  // the worst seen is 0.4
}

// alpha(k) (no gravity) against the inertial-frame derivative of V(k) along the motion
// (theta_dot, beta_dot), for every body k.
TEST_P(chain_Kinematics, AccelerationMatchesVelocityDifferences) {
  const ChainKind kind = GetParam();
  Random<double> rnd;
  Worst w("alpha(k) = d/dt V(k), inertial");
  for (int i = 0; i < kCases; ++i) {
    const Model m = make_chain(rnd, kind, chain_size(i, kMaxBodies));
    const int n = m.n();
    const State x = random_state(rnd, m);
    const VecX<double> beta_dot = random_vector(rnd, m.nv());
    const VecX<double> qd = theta_dot(m, x);

    Workspace ws(m);
    update_phi(m, x.theta, ws);
    update_poses(m, ws);
    update_velocities(m, x, ws);
    update_accelerations(m, x, beta_dot.data(), Acceleration(), ws);

    // All bodies' V(k) in inertial coordinates, stacked.
    const auto W = [&](double t) {
      const VecX<double> th = advance(m, x.theta, qd, t);
      const std::vector<Pose> T = poses(m, th);
      const std::vector<Velocity> V = velocities(m, th, VecX<double>(x.beta + t * beta_dot));
      VecX<double> s(6 * n);
      for (int k = 0; k < n; ++k) s.segment<6>(6 * k) = rotate6(T[k].R(), V[k].vector());
      return s;
    };
    const VecX<double> dW = derivative(W, kStep);
    double r = 0;
    for (int k = 0; k < n; ++k) {
      const Vec6<double> alpha_fd = rotate6(ws.pose[k].R().transpose(), dW.segment<6>(6 * k));
      r = std::max(r, rel6(ws.alpha[k].vector(), alpha_fd));
    }
    w.add(r, i);
  }
  EXPECT_LE(w.value(), kFdTol);
}

// Jdot beta of a frame F on body k against the inertial-frame derivative of J(theta(t)) beta
// at fixed beta; and the component derivative d/dt (J beta) = Jdot beta - [0; w x v].
TEST_P(chain_Kinematics, JacobianDotTimesBetaMatchesDifferences) {
  const ChainKind kind = GetParam();
  Random<double> rnd;
  Worst wI("Jdot beta = d/dt (J beta), inertial"), wC("d/dt (J beta) components + [0; w x v]");
  for (int i = 0; i < kCases; ++i) {
    const Model m = make_chain(rnd, kind, chain_size(i, kMaxBodies));
    const State x = random_state(rnd, m);
    const int k = 1 + int(rnd.engine()() % unsigned(m.n()));
    const Pose frame(rnd.rotation(), rnd.vec3());
    const VecX<double> qd = theta_dot(m, x);

    Workspace ws(m);
    update_phi(m, x.theta, ws);
    update_poses(m, ws);
    update_velocities(m, x, ws);
    const Vec6<double> JdB = jacobian_dot_times_beta(m, x, ws, k, frame).vector();
    const Mat3<double> R0 = (ws.pose[k - 1] * frame).R();

    // J(theta(t)) beta in F coordinates, and rotated to inertial coordinates.
    const auto JB = [&](double t, bool inertial) {
      const VecX<double> th = advance(m, x.theta, qd, t);
      Workspace w(m);
      update_phi(m, th, w);
      update_poses(m, w);
      Eigen::Matrix<double, 6, Eigen::Dynamic> J;
      jacobian(m, th, w, k, frame, J);
      const Vec6<double> v = J * x.beta;
      return inertial ? rotate6((w.pose[k - 1] * frame).R(), v) : v;
    };
    const Vec6<double> d_inertial =
        rotate6(R0.transpose(), derivative([&](double t) { return JB(t, true); }, kStep));
    const Vec6<double> d_comp = derivative([&](double t) { return JB(t, false); }, kStep);
    const Vec6<double> V = JB(0, false);
    Vec6<double> wxv = Vec6<double>::Zero();
    wxv.tail<3>() = V.head<3>().cross(V.tail<3>());
    wI.add(rel6(JdB, d_inertial), i);
    wC.add(rel6(JdB, d_comp + wxv), i);
  }
  EXPECT_LE(wI.value(), kFdTol);
  EXPECT_LE(wC.value(), kFdTol);
}

INSTANTIATE_TEST_SUITE_P(Kinds, chain_Kinematics, all_chain_kinds(), ChainKindName());

}  // namespace
}  // namespace soa::test
