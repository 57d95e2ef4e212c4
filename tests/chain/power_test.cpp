/// \file
/// Power balance of inverse dynamics (lesson 4) on random chains of up to 8 bodies of every
/// kind, with gravity, hinge springs and dampers, and external forces.
///
/// What is checked, at a random state \f$(\theta, \beta)\f$ and a random \f$\dot\beta\f$,
/// with \f$T\f$ = inverse_dynamics() (the hinge forces the actuators must apply):
/// \f[ \beta^* T + \sum_k f_{ext}^*(k)\, V(k) = \frac{d}{dt}\big(KE + PE\big) +
///     \sum_k c_k\,|\beta(k)|^2, \f]
/// the instantaneous work-energy identity: the power of the actuators and the external
/// forces goes into the energy or is dissipated by the dampers. The energy is computed
/// independently of the dynamics:
/// - \f$KE = \sum_k \tfrac12 V^*(k) M(k) V(k)\f$ with \f$V(k)\f$ from the velocity recursion;
/// - gravity: \f$-\sum_k m_k\, g \cdot p_{C_k}\f$, \f$p_{C_k}\f$ the centre of mass of body
///   k placed by update_poses();
/// - springs: \f$\sum_k \tfrac12 k_k |\delta_k|^2\f$ with the displacement \f$\delta_k\f$ of
///   BodyT (\f$\theta - \theta_0\f$ for 1-dof and universal hinges, the rotation vector
///   \f$\log R\f$ of the hinge rotation for spherical ones, \f$[\log R;\ R^* l]\f$ for free
///   ones), written here from the hinge transform, not from add_spring_force(). Its rate is
///   \f$k\,\delta^*\beta\f$ for every hinge type (\f$w^*\dot w = w^*\omega\f$ for the
///   rotation vector, \f$l^*\dot l = (R^*l)^* v\f$). The rotation vector flips to
///   \f$-w\f$ where the angle reaches \f$\pi\f$, a kink of this potential (the spring force
///   jumps there), so states with a hinge rotation within 0.05 rad of \f$\pi\f$ are redrawn.
///
/// \f$\frac{d}{dt}\f$ is the fourth-order central difference along \f$\theta(t) = \theta +
/// t\dot\theta\f$ (quaternions renormalized), \f$\beta(t) = \beta + t\dot\beta\f$, whose
/// tangent at t = 0 is the motion \f$(\dot\theta, \dot\beta)\f$; the energy depends on the
/// state only, so its rate along any curve with this tangent is the rate along the motion.
/// Step h = 5e-4 as in finite_difference_test.cpp (truncation \f$h^4|E^{(5)}|/30 \lesssim
/// 2\cdot10^{-10}\,|E|\f$ at rates up to 10 rad/s). The energy, whose potential part can be
/// larger than the powers, is rounded by \f$1.5\,\varepsilon|E|/h\f$, so the tolerance,
/// relative to the largest power, is 1e-7 (the worst seen is about 1e-9).
#include "chain_support.hpp"

namespace soa::test {
namespace {

constexpr int kMaxBodies = 8;
constexpr double kStep = 5e-4;
constexpr double kFdTol = 1e-7;
constexpr double kPi = 3.14159265358979323846;

/// KE + PE (gravity and springs) at the state (\p theta, \p beta).
double energy(const Model& m, const VecX<double>& theta, const VecX<double>& beta) {
  Workspace ws(m);
  update_phi(m, theta, ws);
  update_poses(m, ws);
  update_velocities(m, State{theta, beta}, ws);
  double E = 0;
  for (int k = 1; k <= m.n(); ++k) {
    const Body& B = m.body(k);
    E += B.M.kinetic_energy(ws.V[k - 1]);
    E -= B.M.mass() * m.gravity.dot(ws.pose[k - 1].apply(B.M.p()));
    if (B.stiffness == 0) continue;
    const double* th = theta.data() + B.q_offset;
    VecX<double> delta;
    switch (B.hinge.type) {
      case HingeType::Spherical:
        delta = log_so3<double>(B.hinge.transform(th).R());
        break;
      case HingeType::Free: {
        const Pose T = B.hinge.transform(th);
        delta.resize(6);
        delta << log_so3<double>(T.R()), T.R().transpose() * T.l();
        break;
      }
      default:
        delta = Eigen::Map<const VecX<double>>(th, B.hinge.nq()) - B.rest;
    }
    E += B.stiffness * delta.squaredNorm() / 2;
  }
  return E;
}

/// The largest rotation angle of the spherical and free hinges of \p m at \p theta.
double largest_hinge_angle(const Model& m, const VecX<double>& theta) {
  double a = 0;
  for (int k = 1; k <= m.n(); ++k) {
    const Body& B = m.body(k);
    if (B.hinge.type == HingeType::Spherical || B.hinge.type == HingeType::Free)
      a = std::max(
          a, double(log_so3<double>(B.hinge.transform(theta.data() + B.q_offset).R()).norm()));
  }
  return a;
}

class chain_Power : public ::testing::TestWithParam<ChainKind> {};

TEST_P(chain_Power, HingeAndExternalPowerIsEnergyRatePlusDissipation) {
  const ChainKind kind = GetParam();
  Random<double> rnd;
  Worst w("beta* T + f_ext* V = dE/dt + c |beta|^2");
  for (int i = 0; i < kCases; ++i) {
    ChainOptions opt;
    opt.gravity = true;
    opt.springs = true;
    Model m = make_chain(rnd, kind, chain_size(i, kMaxBodies), opt);
    for (int k = 1; k <= m.n(); ++k)  // springs about a random rest position
      for (int j = 0; j < m.body(k).rest.size(); ++j) m.body(k).rest[j] = rnd.normal();
    // The spring potential 1/2 k |log R|^2 has a kink where the rotation angle reaches pi
    // (the rotation vector flips to -w there, so the spring force jumps): states within
    // 0.05 rad of it, farther than a difference step moves (2h times the rates), are drawn
    // again.
    State x = random_state(rnd, m);
    while (largest_hinge_angle(m, x.theta) > kPi - 0.05) x = random_state(rnd, m);
    const VecX<double> beta_dot = random_vector(rnd, m.nv());
    const ExternalForces<double> f_ext = random_forces(rnd, m);

    Workspace ws(m);
    VecX<double> T(m.nv());
    inverse_dynamics(m, x, beta_dot, f_ext, ws, T);
    const double P_hinge = x.beta.dot(T);
    double P_ext = 0, D = 0;
    for (int k = 1; k <= m.n(); ++k) {
      const Body& B = m.body(k);
      P_ext += dot(f_ext[k - 1], ws.V[k - 1]);
      D += B.damping * x.beta.segment(B.v_offset, B.hinge.nv()).squaredNorm();
    }
    const VecX<double> qd = theta_dot(m, x);
    const auto E = [&](double t) {
      Eigen::Matrix<double, 1, 1> e;
      e[0] = energy(m, advance(m, x.theta, qd, t), VecX<double>(x.beta + t * beta_dot));
      return e;
    };
    const double dE = derivative(E, kStep)[0];
    const double scale = std::max({1.0, std::abs(P_hinge), std::abs(P_ext), D, std::abs(dE)});
    w.add(std::abs(P_hinge + P_ext - dE - D) / scale, i);
  }
  EXPECT_LE(w.value(), kFdTol);
}

INSTANTIATE_TEST_SUITE_P(Kinds, chain_Power, all_chain_kinds(), ChainKindName());

}  // namespace
}  // namespace soa::test
