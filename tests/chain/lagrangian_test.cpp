/// \file
/// Inverse dynamics (lesson 4) against the closed-form Lagrangian equations of motion
/// \f$\tau = M(q)\ddot q + C(q,\dot q) + G(q)\f$ of planar 2-link and 3-link arms, derived
/// by hand below, at many random states.
///
/// The arms: revolute hinges about z, link i along its x axis with length \f$L_i\f$, mass
/// \f$m_i\f$ at \f$c_i\f$ along the link, inertia \f$I_i\f$ about the z axis through its
/// centre of mass; gravity g along -y. \f$q_i\f$ is the angle of link i relative to link
/// i-1 (link 1 next to the base), \f$\phi_i = q_1 + \dots + q_i\f$ its absolute angle.
/// Three families of links: point masses (\f$I_i = 0\f$), uniform rods (\f$c_i = L_i/2\f$,
/// \f$I_i = m_i L_i^2/12\f$) and general links (random \f$c_i \in [0, L_i]\f$, \f$I_i\f$ and
/// out-of-plane moments, which do not enter planar motion).
///
/// The library numbers bodies, \f$\theta\f$, \f$\beta\f$ and T tip first (body 1 = the last
/// link), so the library's vectors are the reversed \f$q\f$, \f$\tau\f$, and its mass matrix
/// the reversed M. Checked separately: the mass matrix (OperatorsT, no gravity), the
/// gravity term G (inverse dynamics at rest with \f$\dot\beta = 0\f$), the velocity term C
/// (inverse dynamics at \f$\dot\beta = 0\f$, less G) and the whole \f$\tau\f$. Residuals are
/// relative to \f$\max(1, |M||\ddot q| + |C| + |G|)\f$; both sides take a few dozen rounded
/// operations on numbers of order one, so the tolerance is 64 eps.
#include <cmath>

#include "chain_support.hpp"

namespace soa::test {
namespace {

constexpr double kG = 9.81;
constexpr double kPi = 3.14159265358979323846;
constexpr double kTol = 64 * eps<double>();

/// One link of a planar arm.
struct Link {
  double m, L, c, I;  // mass, length, centre of mass along the link, inertia about z at CM
  Vec3<double> J_perp = Vec3<double>::Zero();  // moments about x, y at CM (no effect)
};

/// A random link of family \p family: 0 point mass, 1 uniform rod, 2 general.
Link random_link(Random<double>& rnd, int family) {
  Link l;
  l.m = rnd.uniform(0.5, 5);
  l.L = rnd.uniform(0.3, 2);
  if (family == 0) {
    l.c = l.L;
    l.I = 0;
  } else if (family == 1) {
    l.c = l.L / 2;
    l.I = l.m * l.L * l.L / 12;
    l.J_perp = Vec3<double>(0, l.I, 0);  // a thin rod along x
  } else {
    l.c = rnd.uniform(0, l.L);
    l.I = rnd.uniform(0, 1);
    l.J_perp = Vec3<double>(rnd.uniform(0, 1), rnd.uniform(0, 1), 0);
  }
  return l;
}

/// The planar arm as a chain: body i (base first) has its hinge at the end of link i-1,
/// axis z, centre of mass at (c_i, 0, 0) of its hinge frame; gravity (0, -g, 0).
Model planar_arm(const std::vector<Link>& links) {
  std::vector<Body> bodies;
  for (std::size_t i = 0; i < links.size(); ++i) {
    const Link& l = links[i];
    Body b;
    b.name = "link" + std::to_string(i + 1);
    const Vec3<double> J(l.J_perp.x(), l.J_perp.y(), l.I);
    b.M = SpatialInertia::from_cm(l.m, Vec3<double>(l.c, 0, 0), Mat3<double>(J.asDiagonal()));
    b.placement = Pose(Mat3<double>::Identity(), Vec3<double>(i == 0 ? 0 : links[i - 1].L, 0, 0));
    b.hinge.type = HingeType::Revolute;
    b.hinge.axis = Vec3<double>::UnitZ();
    bodies.push_back(b);
  }
  Model m = Model::from_base_first(bodies);
  m.gravity = Vec3<double>(0, -kG, 0);
  return m;
}

/// \f$M(q)\f$, \f$C(q,\dot q)\f$ and \f$G(q)\f$ in the order of q (base first).
struct Lagrangian {
  MatX<double> M;
  VecX<double> C, G;
};

/// The 2-link arm, from \f$KE = \tfrac12 m_1|\dot p_1|^2 + \tfrac12 I_1\dot q_1^2 +
/// \tfrac12 m_2|\dot p_2|^2 + \tfrac12 I_2(\dot q_1 + \dot q_2)^2\f$ with
/// \f$p_1 = c_1 e(q_1)\f$, \f$p_2 = L_1 e(q_1) + c_2 e(q_1 + q_2)\f$, \f$e(a) = (\cos a,
/// \sin a)\f$, and \f$PE = g(m_1 p_{1y} + m_2 p_{2y})\f$:
///   M11 = I1 + I2 + m1 c1^2 + m2 (L1^2 + c2^2 + 2 L1 c2 cos q2)
///   M12 = M21 = I2 + m2 (c2^2 + L1 c2 cos q2),   M22 = I2 + m2 c2^2
///   with h = m2 L1 c2 sin q2:  C1 = -h (2 q1' q2' + q2'^2),  C2 = h q1'^2
///   G1 = g ((m1 c1 + m2 L1) cos q1 + m2 c2 cos(q1 + q2)),  G2 = g m2 c2 cos(q1 + q2).
Lagrangian two_link(const Link& a, const Link& b, const Eigen::Vector2d& q,
                    const Eigen::Vector2d& qd) {
  const double c2 = std::cos(q[1]), s2 = std::sin(q[1]), c12 = std::cos(q[0] + q[1]);
  Lagrangian r;
  r.M.resize(2, 2);
  r.M(0, 0) = a.I + b.I + a.m * a.c * a.c + b.m * (a.L * a.L + b.c * b.c + 2 * a.L * b.c * c2);
  r.M(0, 1) = r.M(1, 0) = b.I + b.m * (b.c * b.c + a.L * b.c * c2);
  r.M(1, 1) = b.I + b.m * b.c * b.c;
  const double h = b.m * a.L * b.c * s2;
  r.C.resize(2);
  r.C << -h * (2 * qd[0] * qd[1] + qd[1] * qd[1]), h * qd[0] * qd[0];
  r.G.resize(2);
  r.G << kG * ((a.m * a.c + b.m * a.L) * std::cos(q[0]) + b.m * b.c * c12), kG * b.m * b.c * c12;
  return r;
}

/// The 3-link arm, in the absolute angles \f$\phi = A q\f$ (A lower triangular, all ones).
/// With \f$\dot p_i = \sum_{j<i} L_j\dot\phi_j e'(\phi_j) + c_i\dot\phi_i e'(\phi_i)\f$ and
/// \f$e'(a)\cdot e'(b) = \cos(a-b)\f$:
/// \f$KE = \tfrac12\sum_{ij}\mu_{ij}\cos(\phi_i - \phi_j)\dot\phi_i\dot\phi_j\f$ with
///   mu11 = I1 + m1 c1^2 + (m2 + m3) L1^2,  mu22 = I2 + m2 c2^2 + m3 L2^2,  mu33 = I3 + m3 c3^2,
///   mu12 = L1 (m2 c2 + m3 L2),  mu13 = L1 m3 c3,  mu23 = L2 m3 c3  (symmetric),
/// and \f$PE = g\sum_i \gamma_i\sin\phi_i\f$ with
///   gamma1 = m1 c1 + (m2 + m3) L1,  gamma2 = m2 c2 + m3 L2,  gamma3 = m3 c3.
/// Lagrange's equations in \f$\phi\f$ (the terms in \f$\dot\phi_i\dot\phi_j\f$ cancel):
///   tau_phi_i = sum_j mu_ij (cos(phi_i - phi_j) phi_j'' + sin(phi_i - phi_j) phi_j'^2)
///               + g gamma_i cos(phi_i),
/// and the joint torques do the same work, \f$\tau^* \dot q = \tau_\phi^*\dot\phi\f$, so
/// \f$\tau = A^*\tau_\phi\f$: \f$M = A^*[\mu_{ij}\cos(\phi_i - \phi_j)]A\f$,
/// \f$C = A^*[\sum_j\mu_{ij}\sin(\phi_i - \phi_j)\dot\phi_j^2]\f$,
/// \f$G = A^*[g\gamma_i\cos\phi_i]\f$.
Lagrangian three_link(const Link& l1, const Link& l2, const Link& l3, const Vec3<double>& q,
                      const Vec3<double>& qd) {
  Mat3<double> mu;
  mu(0, 0) = l1.I + l1.m * l1.c * l1.c + (l2.m + l3.m) * l1.L * l1.L;
  mu(1, 1) = l2.I + l2.m * l2.c * l2.c + l3.m * l2.L * l2.L;
  mu(2, 2) = l3.I + l3.m * l3.c * l3.c;
  mu(0, 1) = mu(1, 0) = l1.L * (l2.m * l2.c + l3.m * l2.L);
  mu(0, 2) = mu(2, 0) = l1.L * l3.m * l3.c;
  mu(1, 2) = mu(2, 1) = l2.L * l3.m * l3.c;
  const Vec3<double> gamma(l1.m * l1.c + (l2.m + l3.m) * l1.L, l2.m * l2.c + l3.m * l2.L,
                           l3.m * l3.c);
  Mat3<double> A;
  A << 1, 0, 0, 1, 1, 0, 1, 1, 1;
  const Vec3<double> phi = A * q, phid = A * qd;
  Mat3<double> Mphi;
  Vec3<double> Cphi, Gphi;
  for (int i = 0; i < 3; ++i) {
    Cphi[i] = 0;
    for (int j = 0; j < 3; ++j) {
      Mphi(i, j) = mu(i, j) * std::cos(phi[i] - phi[j]);
      Cphi[i] += mu(i, j) * std::sin(phi[i] - phi[j]) * phid[j] * phid[j];
    }
    Gphi[i] = kG * gamma[i] * std::cos(phi[i]);
  }
  Lagrangian r;
  r.M = A.transpose() * Mphi * A;
  r.C = A.transpose() * Cphi;
  r.G = A.transpose() * Gphi;
  return r;
}

/// A base-first vector in the library's tip-first order (and back): reversed.
VecX<double> tip_first(const VecX<double>& v) {
  VecX<double> r(v.size());
  for (Eigen::Index i = 0; i < v.size(); ++i) r[i] = v[v.size() - 1 - i];
  return r;
}

/// A base-first matrix in the tip-first order: rows and columns reversed.
MatX<double> tip_first_matrix(const MatX<double>& M) {
  const Eigen::Index n = M.rows();
  MatX<double> r(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) r(i, j) = M(n - 1 - i, n - 1 - j);
  return r;
}

/// Checks the library against \p lagrangian(links, q, qd) for n-link arms.
template <int N, class F>
void check_arm(F lagrangian, const char* name) {
  Random<double> rnd;
  const std::string s(name);
  Worst wM("M(q), " + s), wC("C(q, q'), " + s), wG("G(q), " + s), wT("tau, " + s);
  for (int i = 0; i < kCases; ++i) {
    std::vector<Link> links;
    for (int j = 0; j < N; ++j) links.push_back(random_link(rnd, i % 3));
    const Model m = planar_arm(links);
    Model m0 = m;
    m0.gravity.setZero();
    Eigen::Matrix<double, N, 1> q, qd, qdd;
    for (int j = 0; j < N; ++j) {
      q[j] = rnd.uniform(-kPi, kPi);
      qd[j] = 2 * rnd.normal();
      qdd[j] = 3 * rnd.normal();
    }
    const Lagrangian L = lagrangian(links, q, qd);
    const VecX<double> tau = L.M * qdd + L.C + L.G;
    const double scale =
        std::max({1.0, double(L.M.norm() * qdd.norm()), double(L.C.norm()), double(L.G.norm())});

    // The library's order is tip first: theta = reversed q.
    const State x{tip_first(VecX<double>(q)), tip_first(VecX<double>(qd))};
    const int nv = m.nv();  // = N
    const State rest{x.theta, VecX<double>::Zero(nv)};
    const VecX<double> zero = VecX<double>::Zero(nv), beta_dot = tip_first(VecX<double>(qdd));
    Workspace ws(m);
    VecX<double> T(nv), G(nv), CG(nv);
    inverse_dynamics(m, x, beta_dot, {}, ws, T);
    inverse_dynamics(m, rest, zero, {}, ws, G);
    inverse_dynamics(m, x, zero, {}, ws, CG);
    const MatX<double> M = Operators::build(m0, rest).mass_matrix();

    wM.add(residual(M, tip_first_matrix(L.M), scale), i);
    wG.add(residual(G, tip_first(L.G), scale), i);
    wC.add(residual(CG - G, tip_first(L.C), scale), i);
    wT.add(residual(T, tip_first(VecX<double>(tau)), scale), i);
  }
  EXPECT_LE(wM.value(), kTol);
  EXPECT_LE(wC.value(), kTol);
  EXPECT_LE(wG.value(), kTol);
  EXPECT_LE(wT.value(), kTol);
}

TEST(chain_Lagrangian, TwoLinkArm) {
  check_arm<2>([](const std::vector<Link>& l, const Eigen::Vector2d& q,
                  const Eigen::Vector2d& qd) { return two_link(l[0], l[1], q, qd); },
               "2-link");
}

TEST(chain_Lagrangian, ThreeLinkArm) {
  check_arm<3>([](const std::vector<Link>& l, const Vec3<double>& q,
                  const Vec3<double>& qd) { return three_link(l[0], l[1], l[2], q, qd); },
               "3-link");
}

}  // namespace
}  // namespace soa::test
