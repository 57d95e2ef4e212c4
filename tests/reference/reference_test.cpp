// Each fast function of the library against its reference form (soa::reference): on
// soa::test::kCases random chains (1 to 12 bodies, every hinge type; locked ones merge) from
// the fixed seed. Case i has gravity when i is odd, springs and dampers unless i % 3 == 0,
// external forces unless i % 4 == 0, is at rest when i % 5 == 0, and when i % 3 == 1 has
// every hinge axis, placement rotation and offset along a coordinate axis (the fast paths).
// Each test reports its worst residual relative to eps times the size and conditioning; the
// last one counts the reference functions' heap allocations.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "count_allocations.hpp"
#include "property.hpp"
#include "random_chain.hpp"
#include "soa/chain.hpp"
#include "soa/reference.hpp"

namespace {

using soa::test::kCases;
using soa::test::Random;
using soa::test::Worst;
using MatX = soa::MatX<double>;
using VecX = soa::VecX<double>;
using Vec3 = soa::Vec3<double>;
namespace ref = soa::reference;

constexpr double kEps = soa::eps<double>();

struct Case {
  soa::Model m;
  soa::State x;
  VecX beta_dot, T;
  soa::ExternalForces<double> f_ext;
  int body = 1;     ///< a body for the Jacobian
  soa::Pose frame;  ///< a frame on it
};

// Hinge axes, placement rotations and offsets along coordinate axes (signs at random).
void align_to_axes(Random<double>& rnd, soa::Model& m) {
  for (int k = 1; k <= m.n(); ++k) {
    soa::Body& B = m.body(k);
    const auto e = [&](int i) { return Vec3(Vec3::Unit(i) * (rnd.engine()() % 2 ? 1.0 : -1.0)); };
    B.hinge.axis = e(k % 3);
    B.placement = soa::Pose(soa::exp_unit_axis<double>(e((k + 1) % 3), rnd.normal()),
                            rnd.normal() * e((k + 2) % 3));
  }
}

Case draw(Random<double>& rnd, int i) {
  soa::test::ChainOptions o;
  o.gravity = i % 2 == 1;
  o.springs = i % 3 != 0;
  Case c{soa::test::random_chain(rnd, 1 + i % 12, o), {}, {}, {}, {}, 1, {}};
  if (i % 3 == 1) align_to_axes(rnd, c.m);
  c.x = soa::test::random_state(rnd, c.m);
  if (i % 5 == 0) c.x.beta.setZero();
  c.beta_dot = soa::test::random_vector(rnd, c.m.nv());
  c.T = soa::test::random_vector(rnd, c.m.nv());
  if (i % 4 != 0) c.f_ext = soa::test::random_forces(rnd, c.m);
  c.body = 1 + int(rnd.engine()() % unsigned(c.m.n()));
  c.frame = soa::Pose(rnd.rotation(), rnd.vec3());
  return c;
}

// The largest norm of a list of spatial vectors, at least 1.
template <class V>
double largest(const std::vector<V>& v) {
  double s = 1;
  for (const auto& e : v) s = std::max(s, double(e.vector().norm()));
  return s;
}

// The largest norm of the difference of two lists of spatial vectors.
template <class V>
double difference(const std::vector<V>& a, const std::vector<V>& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).vector().norm());
  return d;
}

// kappa(M) = |M| |M^-1| (Frobenius) of the reference mass matrix of case c (sets rw.phi).
double condition(const Case& c, ref::Workspace& rw) {
  MatX M(c.m.nv(), c.m.nv());
  ref::mass_matrix(c.m, c.x, rw, M);
  return M.norm() * M.inverse().norm();
}

// Runs \p residual(case, fast workspace, reference workspace) on kCases cases and requires
// the worst, \p what, to be at most 64 (each residual is in units of its tolerance's eps).
template <class F>
void against_reference(const char* what, F residual) {
  Random<double> rnd;
  Worst worst(what);
  for (int i = 0; i < kCases; ++i) {
    const Case c = draw(rnd, i);
    soa::Workspace ws(c.m);
    ref::Workspace rw(c.m);
    worst.add(residual(c, ws, rw), i);
  }
  EXPECT_LE(worst.value(), 64.0);
}

TEST(kinematics, UpdatePhiVelocitiesAccelerations) {
  against_reference("|fast - reference| / (n eps max|.|): phi, V, a, alpha",
                    [](const Case& c, soa::Workspace& ws, ref::Workspace& rw) {
                      soa::update_phi(c.m, c.x.theta, ws);
                      soa::update_velocities(c.m, c.x, ws);
                      soa::update_accelerations(c.m, c.x, c.beta_dot,
                                                soa::gravity_base_acceleration(c.m), ws);
                      ref::kinematics(c.m, c.x, c.beta_dot, rw);
                      double phi = 0, l_scale = 1;
                      for (int k = 1; k <= c.m.n(); ++k) {
                        phi = std::max({phi, (ws.phi[k - 1].R() - rw.phi[k - 1].R()).norm(),
                                        (ws.phi[k - 1].l() - rw.phi[k - 1].l()).norm()});
                        l_scale = std::max(l_scale, double(rw.phi[k - 1].l().norm()));
                      }
                      const double n = c.m.n();
                      return std::max({phi / l_scale, difference(ws.V, rw.V) / largest(rw.V),
                                       difference(ws.a, rw.a) / largest(rw.a),
                                       difference(ws.alpha, rw.alpha) / largest(rw.alpha)}) /
                             (n * kEps);
                    });
}

TEST(inverse_dynamics, NewtonEulerAndComposite) {
  against_reference("|T fast - T reference| / (n eps max|f(k)|)",
                    [](const Case& c, soa::Workspace& ws, ref::Workspace& rw) {
                      VecX T(c.m.nv()), T_composite(c.m.nv()), T_ref(c.m.nv());
                      std::vector<soa::SpatialInertia> R(std::size_t(c.m.n()));
                      soa::inverse_dynamics(c.m, c.x, c.beta_dot, c.f_ext, ws, T);
                      soa::inverse_dynamics_composite(c.m, c.x, c.beta_dot, c.f_ext, ws, R,
                                                      T_composite);
                      ref::inverse_dynamics(c.m, c.x, c.beta_dot, c.f_ext, rw, T_ref);
                      const double scale = c.m.n() * kEps * std::max(largest(rw.f), T_ref.norm());
                      return std::max((T - T_ref).norm(), (T_composite - T_ref).norm()) / scale;
                    });
}

TEST(composite, MassMatrixInertialAndCrb) {
  against_reference("|M fast - M reference| / (n eps |M|)", [](const Case& c, soa::Workspace& ws,
                                                               ref::Workspace& rw) {
    MatX M_inertial(c.m.nv(), c.m.nv()), M_crb(c.m.nv(), c.m.nv()), M_ref(c.m.nv(), c.m.nv());
    soa::update_phi(c.m, c.x.theta, ws);
    soa::MassMatrixInertial mi(c.m);
    soa::mass_matrix_inertial(c.m, c.x, ws, mi, M_inertial);
    std::vector<soa::SpatialInertia> R(std::size_t(c.m.n()));
    soa::mass_matrix_crb(c.m, c.x, ws, R, M_crb);
    ref::mass_matrix(c.m, c.x, rw, M_ref);
    const double scale = c.m.n() * kEps * M_ref.norm();
    return std::max((M_inertial - M_ref).norm(), (M_crb - M_ref).norm()) / scale;
  });
}

TEST(articulated, RiccatiPDGPplus) {
  against_reference(
      "|fast - reference| / (n eps kappa |P|): P, P+, D, G",
      [](const Case& c, soa::Workspace& ws, ref::Workspace& rw) {
        soa::update_phi(c.m, c.x.theta, ws);
        soa::Articulated art(c.m);
        soa::articulated_inertias(c.m, c.x, ws, art);
        ref::joint_transforms(c.m, c.x.theta, rw);
        ref::articulated_inertias(c.m, c.x, rw);
        double err = 0, kappa = 1, P_scale = 1;
        for (std::size_t j = 0; j < std::size_t(c.m.n()); ++j) {
          kappa = std::max(kappa, rw.P[j].norm() * MatX(rw.D_inv[j]).norm());
          P_scale = std::max(P_scale, rw.P[j].norm());
          err = std::max({err, (art.P[j] - rw.P[j]).norm() / P_scale,
                          (art.P_plus[j] - rw.P_plus[j]).norm() / P_scale,
                          MatX(art.D[j] - rw.D[j]).norm() / P_scale,
                          MatX(art.G[j] - rw.G[j]).norm() / std::max(1.0, MatX(rw.G[j]).norm())});
        }
        return err / (c.m.n() * kEps * kappa);
      });
}

TEST(forward_dynamics, ArticulatedBodyFullAndLean) {
  against_reference("|beta_dot fast - reference| / (n eps kappa(M) max(1, |beta_dot|))",
                    [](const Case& c, soa::Workspace& ws, ref::Workspace& rw) {
                      soa::ForwardDynamics fd(c.m), lean = soa::ForwardDynamics::lean(c.m);
                      VecX bd(c.m.nv()), bd_lean(c.m.nv()), bd_ref(c.m.nv());
                      soa::forward_dynamics(c.m, c.x, c.T, c.f_ext, ws, fd, bd);
                      soa::forward_dynamics(c.m, c.x, c.T, c.f_ext, ws, lean, bd_lean);
                      ref::forward_dynamics(c.m, c.x, c.T, c.f_ext, rw, bd_ref);
                      const double scale = c.m.n() * kEps * condition(c, rw) *
                                           std::max({1.0, bd_ref.norm(), c.T.norm()});
                      return std::max((bd - bd_ref).norm(), (bd_lean - bd_ref).norm()) / scale;
                    });
}

TEST(jacobian, FrameOnRandomBody) {
  against_reference("|J fast - J reference| / (n eps max(1, |J|))",
                    [](const Case& c, soa::Workspace& ws, ref::Workspace& rw) {
                      Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, c.m.nv()), J_ref(6, c.m.nv());
                      soa::update_phi(c.m, c.x.theta, ws);
                      soa::update_poses(c.m, ws);
                      soa::jacobian(c.m, c.x.theta, ws, c.body, c.frame, J);
                      ref::jacobian(c.m, c.x.theta, rw, c.body, c.frame, J_ref);
                      return (J - J_ref).norm() / (c.m.n() * kEps * std::max(1.0, J_ref.norm()));
                    });
}

TEST(innovations, FactorAndItsInverseOnAVector) {
  against_reference(
      "|dense - reference| / (n eps kappa(M) max(1, |v|)): [I + H phi K] v, [I - H psi K] v",
      [](const Case& c, soa::Workspace& /*ws*/, ref::Workspace& rw) {
        const soa::InnovationsOperators io = soa::InnovationsOperators::build(c.m, c.x);
        VecX y(c.m.nv()), beta(c.m.nv()), eps(c.m.nv());
        const double kappa = condition(c, rw);
        ref::articulated_inertias(c.m, c.x, rw);
        ref::innovations_factor_times(c.m, c.x, c.T, rw, y);
        ref::articulated_solve(c.m, c.x, c.T, rw, beta);
        for (int k = 1; k <= c.m.n(); ++k)
          eps.segment(c.m.body(k).v_offset, c.m.body(k).hinge.nv()) =
              rw.epsilon[std::size_t(k - 1)];
        const double scale = c.m.n() * kEps * kappa * std::max(1.0, c.T.norm());
        return std::max((io.factor() * c.T - y).norm(), (io.factor_inverse() * c.T - eps).norm()) /
               scale;
      });
}

TEST(mass_matrix_inverse, ONSquaredAgainstColumnByColumn) {
  against_reference("|Minv fast - Minv reference| / (n eps kappa(M) |Minv|)",
                    [](const Case& c, soa::Workspace& ws, ref::Workspace& rw) {
                      soa::update_phi(c.m, c.x.theta, ws);
                      soa::MassMatrixInverse w(c.m);
                      MatX Minv(c.m.nv(), c.m.nv()), Minv_ref(c.m.nv(), c.m.nv());
                      soa::mass_matrix_inverse(c.m, c.x, ws, w, Minv);
                      ref::mass_matrix_inverse(c.m, c.x, rw, Minv_ref);
                      return (Minv - Minv_ref).norm() /
                             (c.m.n() * kEps * condition(c, rw) * Minv_ref.norm());
                    });
}

TEST(mass_matrix_inverse_times, ONOnAVector) {
  against_reference("|Minv T fast - reference| / (n eps kappa(M) |Minv| |T|)",
                    [](const Case& c, soa::Workspace& ws, ref::Workspace& rw) {
                      soa::ForwardDynamics fd(c.m);
                      VecX out(c.m.nv()), out_ref(c.m.nv());
                      MatX Minv_ref(c.m.nv(), c.m.nv());
                      soa::mass_matrix_inverse_times(c.m, c.x, c.T, ws, fd, out);
                      ref::mass_matrix_inverse(c.m, c.x, rw, Minv_ref);
                      ref::mass_matrix_inverse_times(c.m, c.x, c.T, rw, out_ref);
                      return (out - out_ref).norm() /
                             (c.m.n() * kEps * condition(c, rw) * Minv_ref.norm() * c.T.norm());
                    });
}

// No reference function allocates once its workspace (ref::Workspace) and its outputs are
// sized: the project's rule of no allocation per call, which the reference tier keeps too.
TEST(allocation, NoneInTheReferenceFunctions) {
  ASSERT_GT(soa::test::allocations_in([] { soa::test::allocate_something(); }), 0);
  Random<double> rnd;
  for (int i = 0; i < 60; ++i) {
    const Case c = draw(rnd, i);
    const soa::Model& m = c.m;
    ref::Workspace rw(m);
    VecX out(m.nv());
    MatX M(m.nv(), m.nv());
    Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, m.nv());
    const auto none = [&](const char* what, auto&& f) {
      EXPECT_EQ(soa::test::allocations_in(f), 0) << what << ", case " << i;
    };
    none("joint_transforms", [&] { ref::joint_transforms(m, c.x.theta, rw); });
    none("velocities", [&] { ref::velocities(m, c.x, rw); });
    none("kinematics", [&] { ref::kinematics(m, c.x, c.beta_dot, rw); });
    none("inverse_dynamics", [&] { ref::inverse_dynamics(m, c.x, c.beta_dot, c.f_ext, rw, out); });
    none("mass_matrix", [&] { ref::mass_matrix(m, c.x, rw, M); });
    none("jacobian", [&] { ref::jacobian(m, c.x.theta, rw, c.body, c.frame, J); });
    none("articulated_inertias", [&] { ref::articulated_inertias(m, c.x, rw); });
    none("forward_dynamics", [&] { ref::forward_dynamics(m, c.x, c.T, c.f_ext, rw, out); });
    none("innovations_factor_times", [&] { ref::innovations_factor_times(m, c.x, c.T, rw, out); });
    none("articulated_solve", [&] { ref::articulated_solve(m, c.x, c.T, rw, out); });
    none("mass_matrix_inverse_times",
         [&] { ref::mass_matrix_inverse_times(m, c.x, c.T, rw, out); });
    none("mass_matrix_inverse", [&] { ref::mass_matrix_inverse(m, c.x, rw, M); });
  }
}

}  // namespace
