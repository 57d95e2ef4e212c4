/// # Lesson 3 — Serial-chain kinematics
///
/// The third topic of the course (slide 80, topic 3; Jain 2011, chapter 3): the kinematics
/// of a serial chain of rigid bodies in **minimal coordinates**, the hinges and their joint
/// maps \f$H^*(k)\f$, the O(N) **scatter** recursions for poses, velocities and accelerations,
/// the **gather** recursion that is their dual, the first **spatial operators**
/// \f$\mathcal E_\phi\f$, \f$\phi\f$ and \f$H\f$, and Jacobians. Everything here is the
/// velocity propagation of slides 39-42 and the acceleration propagation of slides 59-61,
/// applied hinge after hinge.
///
/// Learning goals. After this lesson you can
/// - describe a chain by its hinges: the configuration \f$\theta\f$, the generalized
///   velocity \f$\beta\f$, and why \f$\dot\theta \ne \beta\f$ for quaternion hinges;
/// - write the joint map \f$H^*(k)\f$ of every hinge type and number the bodies as the course
///   does (tip = 1, base = n);
/// - run the scatter recursions base to tip: \f$\phi(k+1,k)\f$, poses,
///   \f$V(k) = \phi^*(k+1,k)V(k+1) + H^*(k)\beta(k)\f$, and the accelerations with the
///   Coriolis term \f$a(k)\f$, which you derive;
/// - run the gather recursion tip to base, \f$f(k) = \phi(k,k-1)f(k-1) + \dots\f$,
///   \f$T = Hf\f$, and see that it is the dual (the transpose) of the scatter;
/// - build \f$\mathcal E_\phi\f$, \f$\phi = (I - \mathcal E_\phi)^{-1}\f$ and \f$H\f$ as
///   matrices and read \f$V = \phi^* H^* \beta\f$ off the recursion;
/// - write the Jacobian of a frame, \f$J = B^*\phi^*H^*\f$, and the \f$\dot J\beta\f$ term.
///
/// Run it as `lesson03 OUTDIR`: it prints each check and writes `OUTDIR/l3_tip_path.csv`,
/// the figures `l3_tip_path.png` and `l3_tip_velocity.png`, and the 3D viewer of the arm's
/// motion, `OUTDIR/l3_arm7_view/` (open its `index.html` in a browser).
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "args.hpp"
#include "checklist.hpp"
#include "plot.hpp"
#include "soa/chain.hpp"
#include "soa/scene.hpp"
#include "soa/soa.hpp"
#include "soa/view.hpp"
#include "viewer.hpp"

namespace {

using Vec3d = soa::Vec3<double>;
using Mat3d = soa::Mat3<double>;
using Vec6d = soa::Vec6<double>;
using Mat6d = soa::Mat6<double>;
using VecXd = soa::VecX<double>;
using MatXd = soa::MatX<double>;
using Jac = Eigen::Matrix<double, 6, Eigen::Dynamic>;
using soa::HingeType;

const double kEps = soa::eps<double>();

/// Tolerances are written in units of the machine epsilon \f$\varepsilon\f$, times the
/// magnitude of the terms compared: `tol(k, scale)` is \f$k\,\varepsilon\,\mathrm{scale}\f$.
double tol(double k, double scale = 1.0) {
  return k * kEps * scale;
}

/// Prints a vector (as a row) or a matrix, rounded to 4 digits.
template <class Derived>
void show(const std::string& name, const Eigen::MatrixBase<Derived>& m) {
  const Eigen::IOFormat fmt(4, Eigen::DontAlignCols, " ", "; ", "", "", "[", "]");
  std::ostringstream s;
  if (m.cols() == 1)
    s << m.transpose().format(fmt);
  else
    s << m.format(fmt);
  std::printf("  %-10s = %s\n", name.c_str(), s.str().c_str());
}

/// Derivatives of the concrete motions are taken numerically, with the five-point central
/// difference of lesson 1,
/// \f[ \dot x(t) \approx \frac{x(t-2h) - 8\,x(t-h) + 8\,x(t+h) - x(t+2h)}{12\,h},
///     \qquad h = \varepsilon^{1/5}, \f]
/// accurate to about \f$\varepsilon^{4/5}\f$ times the magnitude: the finite-difference
/// checks use `fd_tol`, a hundred times that.
template <class F>
auto derivative(const F& x, double t) {
  const double h = std::pow(kEps, 0.2);
  using T = decltype(x(t));
  const T d = (x(t - 2 * h) - 8.0 * x(t - h) + 8.0 * x(t + h) - x(t + 2 * h)) / (12.0 * h);
  return d;
}
double fd_tol(double scale) {
  return 100.0 * std::pow(kEps, 0.8) * scale;
}

/// The spatial velocity of a moving frame from its pose \f${}^I T(t)\f$, in its own
/// coordinates (slides 32 and 35): \f$\tilde\omega = R^*\dot R\f$, \f$v = R^*\dot l\f$.
template <class PoseAt>
soa::Velocity velocity_of(const PoseAt& pose_at, double t) {
  const soa::Pose T = pose_at(t);
  const Mat3d R_dot = derivative([&](double s) -> Mat3d { return pose_at(s).R(); }, t);
  const Vec3d l_dot = derivative([&](double s) -> Vec3d { return pose_at(s).l(); }, t);
  return soa::Velocity(soa::vee<double>(T.R().transpose() * R_dot), T.R().transpose() * l_dot);
}

/// The inertial derivative of a spatial velocity given in the coordinates of the moving frame
/// (slide 59 with H = the inertial frame): both halves are rotated to inertial coordinates,
/// differentiated there, and rotated back.
template <class PoseAt, class VelocityAt>
soa::Acceleration inertial_derivative(const PoseAt& pose_at, const VelocityAt& V_at, double t) {
  const auto inertial = [&](double s) -> Vec6d {
    const Mat3d R = pose_at(s).R();
    const soa::Velocity V = V_at(s);
    return (Vec6d() << R * V.angular(), R * V.linear()).finished();
  };
  const Vec6d d = derivative(inertial, t);
  const Mat3d Rt = pose_at(t).R().transpose();
  return soa::Acceleration(Rt * d.head<3>(), Rt * d.tail<3>());
}

/// ## A joint motion with known rates
///
/// The finite-difference checks need a motion \f$\theta(t)\f$ of the chain whose generalized
/// velocity \f$\beta(t)\f$ is known exactly, with given \f$\beta(0) = \beta_0\f$ and
/// \f$\dot\beta(0) = \dot\beta_0\f$. For the hinges with angles and offsets,
/// \f$\theta(t) = \theta_0 + t\,\beta_0 + \tfrac{t^2}{2}\dot\beta_0\f$ and \f$\beta =
/// \dot\theta\f$. A quaternion hinge turns as \f$\mathfrak q(t) = \mathfrak q_0 \otimes
/// \exp(t\,w_0) \otimes \exp(s\,w_1)\f$, \f$s = t^2/2\f$; from slide 32,
/// \f$R^*\dot R = (e^{-s\tilde w_1} w_0)^\sim + t\,\tilde w_1\f$, so
/// \f[ \omega(t) = e^{-s\tilde w_1}\, w_0 + t\, w_1, \qquad \omega(0) = w_0, \qquad
///     \dot\omega(0) = w_1 . \f]
/// The free hinge's offset moves as \f$l(t) = l_0 + t\,l_1 + \tfrac{t^2}{2}\, l_2\f$ and its
/// \f$\beta\f$ holds \f$v = R^*\dot l\f$, so \f$l_1 = R_0 v_0\f$ and
/// \f$\dot v(0) = R_0^* l_2 - \omega_0 \times v_0\f$ fix \f$l_2 = R_0(\dot v_0 + \omega_0
/// \times v_0)\f$.
struct JointMotion {
  const soa::Model* m;
  VecXd theta0, beta0, beta_dot0;

  soa::State at(double t) const {
    soa::State x{theta0, beta0};
    for (int k = 1; k <= m->n(); ++k) {
      const soa::Body& B = m->body(k);
      const int q = B.q_offset, v = B.v_offset;
      const HingeType type = B.hinge.type;
      if (type != HingeType::Spherical && type != HingeType::Free) {
        for (int i = 0; i < B.hinge.nv(); ++i) {
          x.theta[q + i] = theta0[q + i] + t * beta0[v + i] + 0.5 * t * t * beta_dot0[v + i];
          x.beta[v + i] = beta0[v + i] + t * beta_dot0[v + i];
        }
        continue;
      }
      const Vec3d w0 = beta0.segment<3>(v), w1 = beta_dot0.segment<3>(v);
      const double s = 0.5 * t * t;
      const soa::UnitQuaternion q0 = soa::Hinge::quaternion(theta0.data() + q);
      const soa::UnitQuaternion qt =
          q0 * soa::UnitQuaternion::exp(t * w0) * soa::UnitQuaternion::exp(s * w1);
      x.theta.segment<4>(q) = qt.coeffs();
      x.beta.segment<3>(v) = soa::exp_so3<double>(-s * w1) * w0 + t * w1;
      if (type == HingeType::Free) {
        const Mat3d R0 = q0.matrix();
        const Vec3d v0 = beta0.segment<3>(v + 3), v0_dot = beta_dot0.segment<3>(v + 3);
        const Vec3d l1 = R0 * v0, l2 = R0 * (v0_dot + w0.cross(v0));
        x.theta.segment<3>(q + 4) = theta0.segment<3>(q + 4) + t * l1 + s * l2;
        x.beta.segment<3>(v + 3) = qt.matrix().transpose() * (l1 + t * l2);
      }
    }
    return x;
  }
};

/// The pose \f${}^I T_{O_k}\f$ of body k at configuration \p theta (library scatter, below).
soa::Pose pose_of(const soa::Model& m, const VecXd& theta, int k) {
  soa::Workspace ws(m);
  soa::update_phi(m, theta, ws);
  soa::update_poses(m, ws);
  return ws.pose[k - 1];
}

/// The velocities \f$V(k)\f$ at state \p x (library scatter, below).
std::vector<soa::Velocity> velocities_of(const soa::Model& m, const soa::State& x) {
  soa::Workspace ws(m);
  soa::update_phi(m, x.theta, ws);
  soa::update_velocities(m, x, ws);
  return ws.V;
}

/// A body with its center of mass at \p p from \f$O_k\f$ and principal moments \p J.
soa::Body make_body(const std::string& name, HingeType type, double mass, const Vec3d& p,
                    const Vec3d& J, const soa::Pose& placement) {
  soa::Body b;
  b.name = name;
  b.M = soa::SpatialInertia::from_cm(mass, p, Mat3d(J.asDiagonal()));
  b.placement = placement;
  b.hinge.type = type;
  return b;
}

/// A 7-joint arm built in code (revolute axes z, y, z, y, z, y, z, link offsets along z, as
/// in common lightweight arms), for when the scene file cannot be read.
soa::Model arm7_in_code() {
  const double d[7] = {0.1575, 0.2025, 0.2045, 0.2155, 0.1845, 0.2155, 0.081};
  const double mass[7] = {4.0, 4.0, 3.0, 2.7, 1.7, 1.8, 0.3};
  const Vec3d axis[7] = {Vec3d::UnitZ(), Vec3d::UnitY(), Vec3d::UnitZ(), Vec3d::UnitY(),
                         Vec3d::UnitZ(), Vec3d::UnitY(), Vec3d::UnitZ()};
  std::vector<soa::Body> base_first;
  for (int i = 0; i < 7; ++i) {
    soa::Body b = make_body("link" + std::to_string(i + 1), HingeType::Revolute, mass[i],
                            Vec3d(0.0, 0.01, 0.08), Vec3d(0.02, 0.02, 0.01) * mass[i],
                            soa::Pose(Mat3d::Identity(), Vec3d(0.0, 0.0, d[i])));
    b.hinge.axis = axis[i];
    base_first.push_back(b);
  }
  return soa::Model::from_base_first(base_first);
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path out = soa::lesson::output_dir(argc, argv);
  soa::lesson::Checklist checks;

  /// ## 1. Minimal coordinates
  ///
  /// A free rigid body has six degrees of freedom (lesson 2); n free bodies have 6n. In a
  /// chain the hinges remove most of them: hinge k lets body k move relative to its inboard
  /// neighbour only in \f$n_k \le 6\f$ ways. The **minimal coordinate formulation**
  /// (slide 80, topic 3) describes the chain by the hinges alone: the configuration
  /// \f$\theta = \{\theta(k)\}\f$ and the generalized velocity \f$\beta = \{\beta(k)\}\f$ with
  /// \f$\sum_k n_k\f$ entries, instead of 6n body velocities tied together by constraints.
  /// Everything else, poses, velocities and accelerations of the bodies, is a function of
  /// \f$(\theta, \beta, \dot\beta)\f$, computed by the recursions below: slide 42's
  /// "propagating spatial velocities" from the base, across hinge after hinge, to the tip.
  ///
  /// ## 2. Hinges and their joint maps
  ///
  /// Hinge k joins the frame \f$O_k^+\f$, fixed on the inboard body k+1, to the frame
  /// \f$O_k\f$ of body k. Its joint transform \f${}^{O_k^+}T_{O_k}(\theta(k))\f$ is the pose
  /// of \f$O_k\f$ relative to \f$O_k^+\f$, and its relative spatial velocity, in \f$O_k\f$
  /// coordinates, is linear in \f$\beta(k)\f$ (slides 39-41):
  /// \f[ \Delta_V(k) = V(O_k^+, O_k) = H^*(k)\,\beta(k) , \f]
  /// with the **joint map** \f$H^*(k)\f$, a \f$6 \times n_k\f$ matrix whose columns are the
  /// directions in which the hinge lets body k move. For a unit axis \f$a\f$ fixed in
  /// \f$O_k\f$:
  ///
  /// | hinge | \f$\theta(k)\f$ | \f$\beta(k)\f$ | \f$H^*(k)\f$ |
  /// |---|---|---|---|
  /// | revolute | angle (1) | rate (1) | \f$[a;\ 0]\f$ |
  /// | prismatic | offset (1) | rate (1) | \f$[0;\ a]\f$ |
  /// | helical, pitch \f$h\f$ | angle (1) | rate (1) | \f$[a;\ h\,a]\f$ |
  /// | universal, \f$a_1\f$ then \f$a_2\f$ | 2 angles | 2 rates | \f$\begin{pmatrix} e^{-\theta_2\tilde a_2} a_1 & a_2 \\ 0 & 0 \end{pmatrix}\f$ |
  /// | spherical | quaternion (4) | \f$\omega\f$ (3) | \f$[I_3;\ 0]\f$ |
  /// | free | quaternion, offset (7) | \f$[\omega; v]\f$ (6) | \f$I_6\f$ |
  /// | locked | none (0) | none (0) | (no columns: merged into body k+1) |
  ///
  /// The universal hinge turns first about \f$a_1\f$ (fixed in \f$O_k^+\f$), then about
  /// \f$a_2\f$ (fixed in \f$O_k\f$): \f${}^{O_k^+}R_{O_k} = e^{\theta_1\tilde a_1}
  /// e^{\theta_2\tilde a_2}\f$, and seen from \f$O_k\f$ its first axis is
  /// \f$e^{-\theta_2\tilde a_2}a_1\f$: this \f$H^*(k)\f$ depends on \f$\theta\f$, and its rate
  /// seen from \f$O_k\f$, \f$\mathring H^*(k)\beta(k) = [\beta_1\beta_2\, (e^{-\theta_2\tilde
  /// a_2} a_1) \times a_2;\ 0]\f$, enters the accelerations (section 7).
  ///
  /// For the quaternion hinges \f$\theta\f$ and \f$\beta\f$ differ in size, so
  /// \f$\dot\theta \ne \beta\f$: \f$\dot{\mathfrak q} = \tfrac12\,\mathfrak q \otimes
  /// [\omega; 0]\f$ (lesson 2) and, for the free hinge, \f$\dot l = R\, v\f$ with
  /// \f$v\f$ in \f$O_k\f$ coordinates. \f$\beta\f$ is the physical velocity, \f$\theta\f$ only
  /// a parametrization of the pose.
  ///
  /// Each hinge type below is checked on one hinge: \f$H^*\beta\f$ against the velocity
  /// of the joint transform along a motion (finite differences), \f$\dot\theta\f$ against
  /// soa::HingeT::theta_dot(), and \f$\mathring H^*\beta\f$ against the finite difference of
  /// \f$H^*(\theta(t))\,\beta\f$ at fixed \f$\beta\f$.
  ///
  /// Now do exercise 3.1, the joint map of every hinge type, then 3.7: derive the joint map
  /// of a planar hinge (a turn and two slides) and the rate of its columns
  /// (`exercises/03-serial-chain-kinematics/exercises.hpp`).
  checks.section("2. Hinges and their joint maps H*(k)");
  const Vec3d a1 = Vec3d(1.0, 2.0, 2.0) / 3.0, a2 = Vec3d(0.0, 0.6, -0.8);
  std::printf("  %-10s %3s %3s   H*(k) at the test configuration\n", "hinge", "nq", "nv");
  for (const HingeType type : {HingeType::Revolute, HingeType::Prismatic, HingeType::Helical,
                               HingeType::Universal, HingeType::Spherical, HingeType::Free}) {
    soa::Body b = make_body("hinge", type, 1.0, Vec3d::Zero(), Vec3d::Ones(), soa::Pose());
    b.hinge.axis = a1;
    b.hinge.axis2 = a2;
    b.hinge.pitch = 0.25;
    const soa::Model one = soa::Model::from_base_first({b});
    const soa::Hinge& hinge = one.body(1).hinge;
    const int nq = hinge.nq(), nv = hinge.nv();
    // A configuration away from zero, a velocity and an acceleration.
    JointMotion motion{&one, one.neutral(), VecXd(nv), VecXd(nv)};
    for (int i = 0; i < nv; ++i) {
      motion.beta0[i] = 0.7 - 0.3 * i;
      motion.beta_dot0[i] = 0.2 + 0.1 * i;
    }
    if (nq == nv) {
      for (int i = 0; i < nq; ++i) motion.theta0[i] = 0.4 + 0.2 * i;
    } else {
      motion.theta0.head<4>() = soa::UnitQuaternion::exp(Vec3d(0.3, -0.5, 0.4)).coeffs();
      if (type == HingeType::Free) motion.theta0.tail<3>() = Vec3d(0.1, 0.2, -0.3);
    }
    const soa::State x = motion.at(0.0);
    const std::string name = soa::hinge_type_name(type);
    std::ostringstream Hs_text;
    Hs_text << hinge.H_star(x.theta.data())
                   .format(Eigen::IOFormat(3, Eigen::DontAlignCols, " ", "; ", "", "", "[", "]"));
    std::printf("  %-10s %3d %3d   %s\n", name.c_str(), nq, nv, Hs_text.str().c_str());

    const soa::JointMap<double> Hs = hinge.H_star(x.theta.data());
    const soa::Velocity dV = hinge.H_star_times(x.theta.data(), x.beta.data());
    const soa::Velocity dV_fd =
        velocity_of([&](double t) { return hinge.transform(motion.at(t).theta.data()); }, 0.0);
    checks.check(name + ": H*(k) beta(k) = dense H*(k) times beta(k)",
                 (dV.vector() - Hs * x.beta).norm(), tol(8, x.beta.norm()));
    checks.check(name + ": H*(k) beta(k) = velocity of the joint transform (fd)",
                 (dV - dV_fd).vector().norm(), fd_tol(1.0 + x.beta.norm()));
    VecXd theta_dot(nq);
    hinge.theta_dot(x.theta.data(), x.beta.data(), theta_dot.data());
    const VecXd theta_dot_fd = derivative([&](double t) { return motion.at(t).theta; }, 0.0);
    checks.check(name + ": theta_dot (" + std::to_string(nq) + ") from beta (" +
                     std::to_string(nv) + "), fd",
                 (theta_dot - theta_dot_fd).norm(), fd_tol(1.0 + x.beta.norm()));
    const Vec6d Hdot_beta_fd = derivative(
        [&](double t) -> Vec6d { return hinge.H_star(motion.at(t).theta.data()) * x.beta; }, 0.0);
    checks.check(
        name + ": rate of H*(k) seen from O_k, times beta (fd)",
        (hinge.H_star_dot_times(x.theta.data(), x.beta.data()).vector() - Hdot_beta_fd).norm(),
        fd_tol(1.0 + x.beta.squaredNorm()));
  }

  /// ## 3. Numbering the bodies: tip = 1, base = n
  ///
  /// The course numbers the bodies from the **tip** (body 1) to the body next to the base
  /// (body n); the inertial frame is body n+1, and hinge k joins body k+1 to body k
  /// (the course's convention). \f$\theta\f$ and \f$\beta\f$ are stacked in the same order,
  /// tip first.
  /// Chains are usually described from the base out (as scene files do), so
  /// soa::ModelT::from_base_first() reverses the list; it also merges every body behind a
  /// locked hinge into its inboard neighbour, adding its inertia moved with the parallel axis
  /// theorem,
  /// \f$M \leftarrow M + \phi M_{\text{locked}} \phi^*\f$ (slide 74): a locked hinge is no
  /// degree of freedom, so it is no body of the minimal formulation either.
  ///
  /// The chain of this section and the next four has every hinge type: from the base a slider,
  /// a turret, a screw with a bracket locked to it, a universal wrist, a ball joint and,
  /// at the tip, a drone on a free hinge (which here only fixes the numbering of its
  /// coordinates).
  checks.section("3. Numbering the bodies: tip = 1, base = n");
  std::vector<soa::Body> base_first;
  {
    using soa::Pose;
    base_first.push_back(make_body("slider", HingeType::Prismatic, 3.0, Vec3d(0.1, 0.0, 0.05),
                                   Vec3d(0.05, 0.06, 0.04), Pose()));
    base_first.back().hinge.axis = Vec3d::UnitX();
    base_first.push_back(make_body("turret", HingeType::Revolute, 2.0, Vec3d(0.0, 0.05, 0.2),
                                   Vec3d(0.03, 0.03, 0.02),
                                   Pose(soa::exp_so3(Vec3d(0.0, 0.0, 0.3)), Vec3d(0.2, 0, 0.1))));
    base_first.push_back(make_body("screw", HingeType::Helical, 1.5, Vec3d(0.0, 0.0, 0.15),
                                   Vec3d(0.02, 0.02, 0.01),
                                   Pose(soa::exp_so3(Vec3d(0.4, 0.0, 0.0)), Vec3d(0.0, 0.1, 0.4))));
    base_first.back().hinge.pitch = 0.05;
    base_first.push_back(make_body("bracket", HingeType::Locked, 0.5, Vec3d(0.05, 0.0, 0.0),
                                   Vec3d(0.004, 0.005, 0.006),
                                   Pose(soa::exp_so3(Vec3d(0.0, 0.5, 0.0)), Vec3d(0, 0, 0.3))));
    base_first.push_back(make_body("wrist", HingeType::Universal, 1.0, Vec3d(0.0, 0.0, 0.1),
                                   Vec3d(0.01, 0.012, 0.008),
                                   Pose(soa::exp_so3(Vec3d(0.2, -0.1, 0.3)), Vec3d(0.1, 0, 0.2))));
    base_first.back().hinge.axis = Vec3d::UnitX();
    base_first.back().hinge.axis2 = Vec3d::UnitY();
    base_first.push_back(make_body("ball", HingeType::Spherical, 0.8, Vec3d(0.0, 0.1, 0.0),
                                   Vec3d(0.006, 0.004, 0.005),
                                   Pose(Mat3d::Identity(), Vec3d(0.0, 0.0, 0.25))));
    base_first.push_back(make_body("drone", HingeType::Free, 0.6, Vec3d(0.02, 0.0, 0.01),
                                   Vec3d(0.003, 0.004, 0.006),
                                   Pose(soa::exp_so3(Vec3d(-0.3, 0.2, 0.0)), Vec3d(0, 0.3, 0.1))));
  }
  const soa::Model chain = soa::Model::from_base_first(base_first);
  std::printf("  %2s  %-8s %-10s %3s %3s %8s %8s\n", "k", "body", "hinge", "nq", "nv", "theta at",
              "beta at");
  for (int k = 1; k <= chain.n(); ++k) {
    const soa::Body& B = chain.body(k);
    std::printf("  %2d  %-8s %-10s %3d %3d %8d %8d\n", k, B.name.c_str(),
                soa::hinge_type_name(B.hinge.type), B.hinge.nq(), B.hinge.nv(), B.q_offset,
                B.v_offset);
  }
  std::printf("  n = %d bodies, nq = %d, nv = %d (a maximal formulation: 6n = %d)\n", chain.n(),
              chain.nq(), chain.nv(), 6 * chain.n());
  checks.check("7 bodies, one locked: n = 6, the tip is body 1 (drone)",
               chain.n() == 6 && chain.body(1).name == "drone" && chain.body(6).name == "slider");
  checks.check("nq = 7+4+2+1+1+1 = 16, nv = 6+3+2+1+1+1 = 14",
               chain.nq() == 16 && chain.nv() == 14);
  checks.check(
      "theta and beta stacked tip first: body 1 at 0, body 2 at 7 and 6",
      chain.body(1).q_offset == 0 && chain.body(2).q_offset == 7 && chain.body(2).v_offset == 6);
  checks.check("the bracket is merged into the screw: find(bracket) = find(screw) = 4",
               chain.find("bracket") == 4 && chain.find("screw") == 4);
  checks.check("merged mass = 1.5 + 0.5 kg", std::abs(chain.body(4).M.mass() - 2.0), tol(4, 2.0));

  /// ## 4. From body k+1 to body k: placement and joint transform
  ///
  /// From \f$O_{k+1}\f$ to \f$O_k\f$ are two steps: the **placement**
  /// \f${}^{O_{k+1}}T_{O_k^+}\f$, fixed on body k+1, then the joint transform. Poses compose
  /// (slides 25-27), and so do rigid body transformations (slide 45):
  /// \f[ {}^{O_{k+1}}T_{O_k} = {}^{O_{k+1}}T_{O_k^+}\; {}^{O_k^+}T_{O_k}(\theta(k)),
  ///     \qquad \phi(k+1,k) = \phi(O_{k+1}, O_k^+)\; \phi(O_k^+, O_k) , \f]
  /// stored, as everywhere in the library, as \f$(R, l)\f$ and not as the 6x6 (slide 79).
  /// For k = n the placement is relative to the inertial frame. soa::update_phi() computes all
  /// of them in one pass; checked against the product of the two 6x6 matrices of slide 43.
  checks.section("4. phi(k+1,k) from the placement and the joint transform");
  VecXd theta0 = chain.neutral(), beta0(chain.nv()), beta_dot0(chain.nv());
  for (int i = 0; i < chain.nq(); ++i) theta0[i] = 0.3 + 0.1 * std::sin(1.0 + i);
  for (int k = 1; k <= chain.n(); ++k) {
    const soa::Body& B = chain.body(k);
    if (B.hinge.nq() == 4 || B.hinge.nq() == 7)
      theta0.segment<4>(B.q_offset) = soa::UnitQuaternion::exp(Vec3d(0.2 * k, -0.3, 0.5)).coeffs();
  }
  for (int i = 0; i < chain.nv(); ++i) {
    beta0[i] = 0.8 * std::cos(0.7 * i + 0.2);
    beta_dot0[i] = 0.5 * std::sin(1.3 * i + 0.4);
  }
  const JointMotion motion{&chain, theta0, beta0, beta_dot0};
  const soa::State x0 = motion.at(0.0);
  soa::Workspace ws(chain);
  soa::update_phi(chain, x0.theta, ws);
  double phi_residual = 0;
  for (int k = 1; k <= chain.n(); ++k) {
    const soa::Body& B = chain.body(k);
    const Mat6d product = soa::Phi(B.placement).matrix() *
                          soa::Phi(B.hinge.transform(x0.theta.data() + B.q_offset)).matrix();
    phi_residual = std::max(phi_residual, (ws.phi[k - 1].matrix() - product).norm());
  }
  checks.check("phi(k+1,k) = phi(O_k+1, O_k+) phi(O_k+, O_k), every k", phi_residual, tol(32, 4));

  /// ## 5. Poses: the first scatter recursion
  ///
  /// Base to tip, each pose from its inboard neighbour's (slides 25-27):
  /// \f[ {}^I T_{O_k} = {}^I T_{O_{k+1}}\; {}^{O_{k+1}}T_{O_k}, \qquad k = n, n-1, \dots, 1,
  ///     \qquad {}^I T_{O_{n+1}} = I . \f]
  /// One product per body: O(N). It is a **scatter** recursion: information flows from the
  /// base out to the tip. Unrolled, \f${}^I T_{O_k}\f$ is the product of all the transforms
  /// between the base and body k, checked here as 4x4 homogeneous matrices (slide 25).
  checks.section("5. Poses: the scatter recursion");
  soa::update_poses(chain, ws);
  double pose_residual = 0;
  for (int k = 1; k <= chain.n(); ++k) {
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    for (int i = chain.n(); i >= k; --i) T = T * ws.phi[i - 1].pose().matrix();
    pose_residual = std::max(pose_residual, (ws.pose[k - 1].matrix() - T).norm());
  }
  show("I l(O_1)", ws.pose[0].l());
  checks.check("I T_Ok = phi(n+1,n) ... phi(k+1,k) as 4x4 products, every k", pose_residual,
               tol(64, 4));

  /// ## 6. Velocities: the scatter recursion
  ///
  /// Slide 39's propagation \f$V(A,C) = \phi^*(B,C)\, V(A,B) + V(B,C)\f$ with A the inertial
  /// frame, B = \f$O_{k+1}\f$ and C = \f$O_k\f$: the velocity of body k is that of body k+1
  /// moved rigidly to \f$O_k\f$ (slide 41), plus the hinge's relative velocity. Writing
  /// \f$V(k) = V(I, O_k)\f$ in \f$O_k\f$ coordinates,
  /// \f[ V(k) = \phi^*(k+1,k)\, V(k+1) + H^*(k)\,\beta(k), \qquad k = n, \dots, 1, \qquad
  ///     V(n+1) = 0 . \f]
  /// \f$V(O_{k+1}, O_k) = V(O_k^+, O_k)\f$ because \f$O_k^+\f$ is fixed on body k+1. The loop
  /// below is the whole algorithm, as soa::reference::velocities() writes it
  /// (lib/include/soa/reference/kinematics.hpp); its fast form soa::update_velocities() runs
  /// it in the library. Both are
  /// checked against the velocities of the poses of section 5 along the motion \f$\theta(t)\f$
  /// (slides 32 and 35, by finite differences).
  ///
  /// Now do exercise 3.2, this recursion on its own, then 3.8: find the bug in code that
  /// gives the inertial velocity of a point of the chain.
  checks.section("6. Velocities: the scatter recursion");
  std::vector<soa::Velocity> V(chain.n());
  {
    soa::Velocity V_parent;  // V(n+1) = 0
    for (int k = chain.n(); k >= 1; --k) {
      const soa::Body& B = chain.body(k);
      V[k - 1] = ws.phi[k - 1].transpose_apply(V_parent) +
                 B.hinge.H_star_times(x0.theta.data() + B.q_offset, x0.beta.data() + B.v_offset);
      V_parent = V[k - 1];
    }
  }
  soa::update_velocities(chain, x0, ws);
  double V_lib = 0, V_fd = 0, V_scale = 0;
  for (int k = 1; k <= chain.n(); ++k) {
    const soa::Velocity Vk_fd =
        velocity_of([&](double t) { return pose_of(chain, motion.at(t).theta, k); }, 0.0);
    V_lib = std::max(V_lib, (V[k - 1] - ws.V[k - 1]).vector().norm());
    V_fd = std::max(V_fd, (V[k - 1] - Vk_fd).vector().norm());
    V_scale = std::max(V_scale, V[k - 1].vector().norm());
  }
  show("V(1)", V[0].vector());
  checks.check("loop above = soa::update_velocities", V_lib, tol(8, V_scale));
  checks.check("V(k) = velocity of I T_Ok(theta(t)) (fd), every k", V_fd, fd_tol(V_scale));

  /// ## 7. Accelerations and the Coriolis term
  ///
  /// Differentiate the velocity recursion in the inertial frame. Slide 61, with H = A = I,
  /// B = \f$O_{k+1}\f$, C = \f$O_k\f$, gives
  /// \f[ \alpha(k) = \phi^*(k+1,k)\,\alpha(k+1) + \alpha_I(O_{k+1}, O_k) + a_I, \qquad
  ///     a_I = \begin{pmatrix} 0 \\ \omega(k+1) \times \big(v(k) - v(k+1)\big) \end{pmatrix}
  ///     , \f]
  /// \f$a_I\f$ the Coriolis term of lesson 1 (slide 60, H = A), with \f$v(k) - v(k+1) =
  /// {}^I\frac{d}{dt}\, l(O_{k+1}, O_k)\f$ the difference of the two points' velocities. The
  /// middle term is the inertial derivative of \f$\Delta_V = [\Delta_\omega; \Delta_v] =
  /// H^*(k)\beta(k)\f$. Slide 33 turns it into a derivative seen from \f$O_k\f$, where
  /// \f$H^*(k)\f$ lives: \f${}^I\frac{d}{dt}x = {}^{O_k}\frac{d}{dt}x + \omega(k) \times x\f$
  /// on each half, and \f${}^{O_k}\frac{d}{dt}(H^*\beta) = H^*\dot\beta + \mathring H^*\beta\f$:
  /// \f[ \alpha_I(O_{k+1}, O_k) = H^*(k)\dot\beta(k) + \mathring H^*(k)\beta(k) +
  ///     \begin{pmatrix} \omega(k) \times \Delta_\omega \\ \omega(k) \times \Delta_v
  ///     \end{pmatrix} . \f]
  /// With \f$\omega(k) = \omega(k+1) + \Delta_\omega\f$, \f$\omega(k)\times\Delta_\omega =
  /// \omega(k+1)\times\Delta_\omega\f$, and the acceleration recursion is
  /// \f[ \alpha(k) = \phi^*(k+1,k)\,\alpha(k+1) + H^*(k)\dot\beta(k) + a(k), \f]
  /// \f[ a(k) = \begin{pmatrix} \omega(k+1) \times \Delta_\omega
  ///     \\ \omega(k+1) \times \Delta_v + \omega(k+1) \times \big(v(k) - v(k+1)\big) \end{pmatrix}
  ///     + \begin{pmatrix} 0 \\ \Delta_\omega \times \Delta_v \end{pmatrix}
  ///     + \mathring H^*(k)\beta(k) . \f]
  /// The middle term vanishes for every hinge but the free one: \f$\Delta_\omega \parallel
  /// \Delta_v\f$ for revolute, prismatic and helical hinges, \f$\Delta_v = 0\f$ for universal
  /// and spherical ones. (It is absorbed into \f$\mathring H^*\beta\f$ when the rate of
  /// \f$H^*\beta\f$ is taken as seen from \f$O_{k+1}\f$ instead of \f$O_k\f$: by slide 33
  /// the two rates differ by \f$\Delta_\omega\,\times\f$ each half,
  /// \f$[\Delta_\omega\times\Delta_\omega;\ \Delta_\omega\times\Delta_v] =
  /// [0;\ \Delta_\omega\times\Delta_v]\f$. In that form every cross product of
  /// \f$a(k)\f$ is with \f$\omega(k+1)\f$.)
  ///
  /// The library works in body coordinates. There, differentiating the components of
  /// \f$V(k) = \phi^*(k+1,k)V(k+1) + H^*\beta\f$ needs the rate of \f$\phi^*(k+1,k)\f$, which
  /// changes only through the hinge: \f$\frac{d}{dt}\phi^*(k+1,k) = -\tilde\Delta_V\,
  /// \phi^*(k+1,k)\f$ (the adjoint map of slide 63, differentiated). Since
  /// \f$\phi^*(k+1,k)V(k+1) = V(k) - \Delta_V\f$, the rate term is \f$-\tilde\Delta_V V(k) =
  /// \tilde V(k)\Delta_V\f$. Component rates and inertial derivatives differ by
  /// \f$[0;\ \omega \times v]\f$ (lesson 2, body coordinates), and \f$\phi^*\f$ moves a pure
  /// linear vector by the rotation \f$R^* = {}^{k}R_{k+1}\f$ alone, so
  /// \f[ a(k) = \tilde V(k)\,\Delta_V + \mathring H^*(k)\beta(k) + \begin{pmatrix} 0
  ///     \\ \omega_k \times v_k - R^*(\omega_{k+1} \times v_{k+1}) \end{pmatrix}, \f]
  /// all in body coordinates: soa::coriolis_term(), which soa::update_velocities() calls.
  /// Checked: the rate of \f$\phi^*\f$ (finite differences), the two forms of \f$a(k)\f$
  /// against each other, and \f$\alpha(k)\f$ from the recursion against the inertial
  /// derivative of \f$V(k)\f$ along the motion, whose \f$\dot\beta(0)\f$ is known.
  ///
  /// Now do exercise 3.6: a(k) in its coordinate-free form, in \f$O_k\f$ coordinates.
  checks.section("7. Accelerations and the Coriolis term a(k)");
  double dphi_res = 0, dphi_scale = 0, a_cf_res = 0, a_body_res = 0, a_scale = 0;
  std::printf("  %2s  %-8s %-10s %12s %12s\n", "k", "body", "hinge", "|a(k)|", "|dw x dv|");
  for (int k = 1; k <= chain.n(); ++k) {
    const soa::Body& B = chain.body(k);
    const double* th = x0.theta.data() + B.q_offset;
    const double* be = x0.beta.data() + B.v_offset;
    const soa::Velocity dV = B.hinge.H_star_times(th, be);
    const soa::Acceleration Hdot_beta = B.hinge.H_star_dot_times(th, be);
    const soa::Velocity V_parent = k < chain.n() ? ws.V[k] : soa::Velocity();
    const soa::Phi& phi = ws.phi[k - 1];
    // d/dt phi*(k+1,k) = -dV~ phi*(k+1,k), by finite differences of the 6x6.
    const Mat6d phi_star_dot = derivative(
        [&](double t) -> Mat6d {
          const soa::State xt = motion.at(t);
          return soa::Phi(B.placement * B.hinge.transform(xt.theta.data() + B.q_offset))
              .matrix()
              .transpose();
        },
        0.0);
    dphi_res =
        std::max(dphi_res, (phi_star_dot + soa::tilde(dV) * phi.matrix().transpose()).norm());
    dphi_scale = std::max(dphi_scale, dV.vector().norm() * phi.matrix().squaredNorm());
    // Coordinate-free form, every vector in O_k coordinates.
    const Vec3d w_p = phi.R().transpose() * V_parent.angular();
    const Vec3d v_p = phi.R().transpose() * V_parent.linear();  // velocity of the point O_k+1
    const Vec3d v_k = ws.V[k - 1].linear(), dw = dV.angular(), dv = dV.linear();
    const soa::Acceleration a_cf =
        soa::Acceleration(w_p.cross(dw), w_p.cross(dv) + dw.cross(dv) + w_p.cross(v_k - v_p)) +
        Hdot_beta;
    // Body-coordinates form.
    const soa::Velocity& Vk = ws.V[k - 1];
    const soa::Acceleration a_body =
        soa::cross(Vk, dV) + Hdot_beta +
        soa::Acceleration(
            Vec3d::Zero(),
            Vec3d(Vk.angular()).cross(Vec3d(Vk.linear())) -
                phi.R().transpose() * Vec3d(V_parent.angular()).cross(Vec3d(V_parent.linear())));
    a_cf_res = std::max(a_cf_res, (a_cf - ws.a[k - 1]).vector().norm());
    a_body_res = std::max(a_body_res, (a_body - ws.a[k - 1]).vector().norm());
    a_scale = std::max(a_scale, Vk.vector().squaredNorm());
    std::printf("  %2d  %-8s %-10s %12.4e %12.4e\n", k, B.name.c_str(),
                soa::hinge_type_name(B.hinge.type), ws.a[k - 1].vector().norm(),
                dw.cross(dv).norm());
  }
  checks.check("d/dt phi*(k+1,k) = -dV~ phi*(k+1,k) (fd), every k", dphi_res, fd_tol(dphi_scale));
  checks.check("a(k): coordinate-free form = soa::coriolis_term, every k", a_cf_res,
               tol(64, a_scale));
  checks.check("a(k): body-coordinates form = soa::coriolis_term, every k", a_body_res,
               tol(64, a_scale));
  soa::update_accelerations(chain, x0, beta_dot0.data(), soa::Acceleration(), ws);
  double alpha_res = 0, alpha_scale = 0;
  for (int k = 1; k <= chain.n(); ++k) {
    const soa::Acceleration alpha_fd = inertial_derivative(
        [&](double t) { return pose_of(chain, motion.at(t).theta, k); },
        [&](double t) { return velocities_of(chain, motion.at(t))[k - 1]; }, 0.0);
    alpha_res = std::max(alpha_res, (ws.alpha[k - 1] - alpha_fd).vector().norm());
    alpha_scale = std::max(alpha_scale, alpha_fd.vector().norm());
  }
  show("alpha(1)", ws.alpha[0].vector());
  checks.check("alpha(k) = phi* alpha(k+1) + H* beta_dot + a(k) = I d/dt V(k) (fd)", alpha_res,
               fd_tol(alpha_scale));

  /// ## 8. The gather recursion, the dual of the scatter
  ///
  /// Forces travel the other way. Let spatial forces \f$g(k)\f$ act on the bodies at
  /// \f$O_k\f$ (body coordinates). What hinge k must transmit to body k is the sum of those
  /// on body k and outboard of it, moved to \f$O_k\f$ with \f$\phi\f$ (slides 49-51):
  /// \f[ f(k) = \phi(k,k-1)\, f(k-1) + g(k), \qquad k = 1, \dots, n, \qquad f(0) = 0, \f]
  /// a **gather** recursion, tip to base, with \f$\phi(k,k-1)\f$ the same transforms as the
  /// scatter's \f$\phi^*(k,k-1)\f$ (velocities move with \f$\phi^*\f$, forces with
  /// \f$\phi\f$: slide 50). The hinge can react to any force except along its own freedoms;
  /// the components along them, \f$T(k) = H(k)\, f(k)\f$ with \f$H = (H^*)^*\f$, are the
  /// generalized forces that hold the chain still against \f$g\f$. In lesson 4, \f$g(k)\f$
  /// becomes \f$M(k)\alpha(k) + b(k)\f$ and this is the Newton-Euler inverse dynamics. The two
  /// recursions are dual through the power (slide 50): \f$T^*\beta = \sum_k g^*(k)\, V(k)\f$.
  checks.section("8. The gather recursion (tip to base), dual of the scatter");
  std::vector<soa::Force> g(chain.n()), f(chain.n());
  for (int k = 1; k <= chain.n(); ++k)
    g[k - 1] = soa::Force(Vec3d(0.1 * k, -0.2, 0.3), Vec3d(1.0, 0.5 * k, -2.0));
  VecXd T(chain.nv());
  for (int k = 1; k <= chain.n(); ++k) {
    f[k - 1] = g[k - 1];
    if (k > 1) f[k - 1] += ws.phi[k - 2].apply(f[k - 2]);  // phi(k,k-1) f(k-1)
    const soa::Body& B = chain.body(k);
    B.hinge.H_times(x0.theta.data() + B.q_offset, f[k - 1], T.data() + B.v_offset);
  }
  double power_g = 0, g_scale = 0;
  for (int k = 1; k <= chain.n(); ++k) {
    power_g += soa::dot(g[k - 1], ws.V[k - 1]);
    g_scale += g[k - 1].vector().norm() * ws.V[k - 1].vector().norm();
  }
  show("T", T);
  std::printf("  T* beta = %.15f, sum g*(k) V(k) = %.15f\n", T.dot(x0.beta), power_g);
  checks.check("power: T* beta = sum g*(k) V(k)", std::abs(T.dot(x0.beta) - power_g),
               tol(64, g_scale));

  /// ## 9. The first spatial operators
  ///
  /// Stack the per-body quantities into block vectors, body 1 first:
  /// \f$V = [V(1); \dots; V(n)]\f$, and \f$\beta\f$, \f$f\f$, \f$g\f$ alike. The velocity
  /// recursion for all k at once is
  /// \f$V = \mathcal E_\phi^*\, V + H^*\beta\f$, with the **shift operator**
  /// \f$\mathcal E_\phi\f$ whose only non-zero blocks are \f$\phi(k+1,k)\f$ at block row k+1,
  /// column k, and the block-diagonal \f$H^* = \mathrm{diag}(H^*(k))\f$. So
  /// \f[ V = \phi^* H^* \beta, \qquad \phi = (I - \mathcal E_\phi)^{-1} . \f]
  /// \f$\mathcal E_\phi\f$ is strictly lower triangular, hence **nilpotent**,
  /// \f$\mathcal E_\phi^n = 0\f$, and the inverse is the finite sum
  /// \f$\phi = I + \mathcal E_\phi + \dots + \mathcal E_\phi^{n-1}\f$: block (i, j) of
  /// \f$\mathcal E_\phi^{i-j}\f$ is \f$\phi(i,i-1)\cdots\phi(j+1,j) = \phi(i,j)\f$, so
  /// \f[ \phi = \begin{pmatrix} I & 0 & \cdots & 0 \\ \phi(2,1) & I & \cdots & 0
  ///     \\ \vdots & & \ddots & \vdots \\ \phi(n,1) & \phi(n,2) & \cdots & I \end{pmatrix}, \f]
  /// block lower triangular, with every \f$\phi(i,j)\f$, \f$i \ge j\f$. The gather is the
  /// transpose: \f$f = \mathcal E_\phi f + g\f$, so \f$f = \phi\, g\f$ and \f$T = H\phi\, g\f$,
  /// and the accelerations are \f$\alpha = \phi^*(H^*\dot\beta + a)\f$.
  /// The duality of section 8 is now one line:
  /// \f$T^*\beta = g^*\phi^* H^*\beta = g^* V\f$.
  ///
  /// These 6n x 6n matrices are for understanding and testing: the recursions apply them in
  /// O(N) without forming them. A three-body chain with mixed hinges (universal at the base,
  /// helical, spherical at the tip) shows them; soa::OperatorsT builds them in the library.
  ///
  /// Now do exercises 3.3, the shift operator \f$\mathcal E_\phi\f$, and 3.4, \f$\phi\f$
  /// block by block without inverting a matrix.
  checks.section("9. The first spatial operators");
  std::vector<soa::Body> three;
  {
    using soa::Pose;
    three.push_back(make_body("hip", HingeType::Universal, 2.0, Vec3d(0.0, 0.0, 0.2),
                              Vec3d(0.04, 0.05, 0.02), Pose()));
    three.back().hinge.axis = Vec3d::UnitZ();
    three.back().hinge.axis2 = Vec3d::UnitY();
    three.push_back(make_body("screw", HingeType::Helical, 1.2, Vec3d(0.0, 0.0, 0.15),
                              Vec3d(0.02, 0.02, 0.01),
                              Pose(soa::exp_so3(Vec3d(0.3, 0.0, 0.1)), Vec3d(0.0, 0.05, 0.4))));
    three.back().hinge.pitch = 0.1;
    three.push_back(make_body("ball", HingeType::Spherical, 0.7, Vec3d(0.05, 0.0, 0.1),
                              Vec3d(0.006, 0.005, 0.004),
                              Pose(soa::exp_so3(Vec3d(0.0, -0.4, 0.0)), Vec3d(0.0, 0.0, 0.3))));
  }
  const soa::Model m3 = soa::Model::from_base_first(three);
  const int n3 = m3.n(), N3 = 6 * n3;
  VecXd theta3 = m3.neutral(), beta3(m3.nv()), beta_dot3(m3.nv());
  theta3.segment<4>(m3.body(1).q_offset) = soa::UnitQuaternion::exp(Vec3d(0.4, 0.1, -0.6)).coeffs();
  theta3[m3.body(2).q_offset] = 0.7;
  theta3.segment<2>(m3.body(3).q_offset) = Eigen::Vector2d(-0.5, 0.9);
  beta3 << 0.3, -0.8, 0.5, 1.1, 0.6, -0.4;
  beta_dot3 << -0.2, 0.4, 0.9, -0.7, 0.3, 0.5;
  const JointMotion motion3{&m3, theta3, beta3, beta_dot3};
  const soa::State x3{theta3, beta3};
  soa::Workspace ws3(m3);
  soa::update_phi(m3, x3.theta, ws3);
  soa::update_poses(m3, ws3);
  soa::update_velocities(m3, x3, ws3);
  soa::update_accelerations(m3, x3, beta_dot3.data(), soa::Acceleration(), ws3);
  const soa::Operators op = soa::Operators::build(m3, x3);

  MatXd E_phi = MatXd::Zero(N3, N3), H = MatXd::Zero(m3.nv(), N3);
  for (int k = 1; k < n3; ++k) E_phi.block<6, 6>(6 * k, 6 * (k - 1)) = ws3.phi[k - 1].matrix();
  for (int k = 1; k <= n3; ++k) {
    const soa::Body& B = m3.body(k);
    H.block(B.v_offset, 6 * (k - 1), B.hinge.nv(), 6) =
        B.hinge.H_star(x3.theta.data() + B.q_offset).transpose();
  }
  const MatXd I = MatXd::Identity(N3, N3);
  const MatXd phi = (I - E_phi).inverse();
  const double phi_scale = phi.norm();
  std::printf("  block norms |phi(i,j)|, i, j = 1..3 (zero above the diagonal):\n");
  double blocks_res = 0;
  for (int i = 1; i <= n3; ++i) {
    std::printf("   ");
    for (int j = 1; j <= n3; ++j) {
      const Mat6d block = phi.block<6, 6>(6 * (i - 1), 6 * (j - 1));
      std::printf(" %8.4f", block.norm());
      Mat6d expected = Mat6d::Identity() * (i < j ? 0.0 : 1.0);
      for (int l = i; l > j; --l) expected = expected * ws3.phi[l - 2].matrix();  // phi(l,l-1)
      blocks_res = std::max(blocks_res, (block - expected).norm());
    }
    std::printf("\n");
  }
  const MatXd E2 = E_phi * E_phi;
  checks.check("E_phi = soa::Operators::E_phi", (E_phi - op.E_phi).norm(), 0.0);
  checks.check("H = diag(H(k)) = soa::Operators::H", (H - op.H).norm(), 0.0);
  checks.check("E_phi is nilpotent: E_phi^2 != 0, E_phi^3 = 0",
               E2.norm() > 0.1 && (E2 * E_phi).norm() == 0.0);
  checks.check("phi = (I - E_phi)^-1 = I + E_phi + E_phi^2", (phi - (I + E_phi + E2)).norm(),
               tol(64, phi_scale));
  checks.check("block (i,j) of phi = phi(i,i-1)...phi(j+1,j), 0 for i < j", blocks_res,
               tol(64, phi_scale));
  checks.check("phi = soa::Operators::phi", (phi - op.phi).norm(), tol(64, phi_scale));

  VecXd V_rec(N3), alpha_rec(N3), a_rec(N3), g3(N3), f_rec(N3);
  VecXd T_rec(m3.nv());
  for (int k = 1; k <= n3; ++k) {
    V_rec.segment<6>(6 * (k - 1)) = ws3.V[k - 1].vector();
    alpha_rec.segment<6>(6 * (k - 1)) = ws3.alpha[k - 1].vector();
    a_rec.segment<6>(6 * (k - 1)) = ws3.a[k - 1].vector();
    g3.segment<6>(6 * (k - 1)) << 0.2 * k, -0.1, 0.4, -1.0, 0.3 * k, 2.0;
  }
  for (int k = 1; k <= n3; ++k) {  // the gather of section 8
    soa::Force fk(Vec6d(g3.segment<6>(6 * (k - 1))));
    if (k > 1) fk += ws3.phi[k - 2].apply(soa::Force(Vec6d(f_rec.segment<6>(6 * (k - 2)))));
    f_rec.segment<6>(6 * (k - 1)) = fk.vector();
    const soa::Body& B = m3.body(k);
    B.hinge.H_times(x3.theta.data() + B.q_offset, fk, T_rec.data() + B.v_offset);
  }
  const VecXd V_op = phi.transpose() * H.transpose() * beta3;
  const double V3_scale = V_rec.norm(), f3_scale = phi_scale * g3.norm();
  show("V = phi*H*b", V_op.head<6>());
  checks.check("V = phi* H* beta = the velocity recursion", (V_op - V_rec).norm(),
               tol(64, V3_scale));
  checks.check("V = E_phi* V + H* beta",
               (E_phi.transpose() * V_rec + H.transpose() * beta3 - V_rec).norm(),
               tol(64, V3_scale));
  checks.check("alpha = phi* (H* beta_dot + a) = the acceleration recursion",
               (phi.transpose() * (H.transpose() * beta_dot3 + a_rec) - alpha_rec).norm(),
               tol(64, alpha_rec.norm() + phi_scale * a_rec.norm()));
  checks.check("f = phi g = the gather recursion", (phi * g3 - f_rec).norm(), tol(64, f3_scale));
  checks.check("T = H phi g = H f", (H * phi * g3 - T_rec).norm(), tol(64, f3_scale));
  checks.check("duality: T* beta = g* V", std::abs(T_rec.dot(beta3) - g3.dot(V_rec)),
               tol(64, f3_scale * V3_scale));

  /// ## 10. Jacobians
  ///
  /// A frame F fixed on body k (a tool, a sensor: slide 42's sensor node) at the pose
  /// \f${}^{O_k}T_F\f$ moves with \f$V(F) = \phi^*(O_k, F)\, V(k)\f$ (slide 41). Picking
  /// \f$V(k)\f$ out of the stacked \f$V\f$ and moving it to F is one linear map,
  /// \f[ V(F) = B^* V, \qquad B = \begin{pmatrix} 0 \\ \vdots \\ \phi(O_k, F) \\ \vdots \\ 0
  ///     \end{pmatrix} \ (6n \times 6,\ \text{block } k), \f]
  /// the **pick-and-move** operator; its transpose \f$B\f$ takes a force at F to the stacked
  /// forces, at \f$O_k\f$ on body k (slide 49). With \f$V = \phi^*H^*\beta\f$:
  /// \f[ V(F) = J\beta, \qquad J = B^*\phi^*H^* . \f]
  /// Block row k of \f$\phi^*\f$ holds \f$\phi^*(i,k)\f$ at column i for \f$i \ge k\f$, and
  /// \f$\phi(i,k)\,\phi(O_k,F) = \phi(O_i,F)\f$ (slide 45), so column block i of J is
  /// \f$\phi^*(O_i, F)\, H^*(i)\f$ for the hinges inboard of F (\f$i \ge k\f$) and zero for
  /// the others: outboard hinges do not move F. soa::reference::jacobian()
  /// (lib/include/soa/reference/jacobian.hpp) computes them so; its fast form soa::jacobian()
  /// computes them from the poses. Dually, a force \f$F_F\f$ at F needs the hinge forces \f$T = H\phi B F_F =
  /// J^* F_F\f$: the gather of section 8 with \f$g = B F_F\f$.
  ///
  /// Differentiating \f$V(F) = J\beta\f$ in the inertial frame:
  /// \f$\alpha(F) = J\dot\beta + \dot J\beta\f$, \f$\dot J\f$ the inertial rate of the
  /// columns. \f$\dot J\beta\f$ is the acceleration of F when \f$\dot\beta = 0\f$: the
  /// recursion of section 7 with \f$\dot\beta = 0\f$ gives \f$\alpha(k)\f$, moved rigidly to
  /// F as lesson 2 moves accelerations, \f$\phi^*(O_k,F)\,\alpha(k) + [0;\ \omega\times(\omega
  /// \times l(O_k, F))]\f$ (soa::jacobian_dot_times_beta()). Checked against the velocity and
  /// the acceleration of F along the motion, by finite differences of its pose.
  ///
  /// Now do exercise 3.5: the columns of J from the poses.
  checks.section("10. Jacobians: J = B* phi* H*");
  const soa::Pose tool(soa::exp_so3(Vec3d(0.1, 0.2, -0.3)), Vec3d(0.05, -0.02, 0.12));
  for (const int k : {1, 2}) {
    MatXd B = MatXd::Zero(N3, 6);
    B.block<6, 6>(6 * (k - 1), 0) = soa::Phi(tool).matrix();
    const MatXd J_op = B.transpose() * phi.transpose() * H.transpose();
    Jac J;
    soa::jacobian(m3, x3.theta, ws3, k, tool, J);
    const double J_scale = J_op.norm();
    const std::string on = "frame on body " + std::to_string(k) + ": ";
    if (k == 1) show("J", J);
    checks.check(on + "B* phi* H* = soa::jacobian", (J_op - MatXd(J)).norm(), tol(64, J_scale));
    double outboard = 0;
    for (int i = 1; i < k; ++i)
      outboard += J.middleCols(m3.body(i).v_offset, m3.body(i).hinge.nv()).norm();
    checks.check(on + "columns of the outboard hinges are zero", outboard, 0.0);
    const auto pose_F = [&](double t) { return pose_of(m3, motion3.at(t).theta, k) * tool; };
    const soa::Velocity V_F_fd = velocity_of(pose_F, 0.0);
    checks.check(on + "J beta = velocity of I T_F(theta(t)) (fd)",
                 (J * beta3 - V_F_fd.vector()).norm(), fd_tol(J_scale * beta3.norm()));
    const soa::Force F_tool(Vec3d(0.3, -0.2, 0.1), Vec3d(1.0, 2.0, -0.5));
    checks.check(on + "T = H phi B F = J* F",
                 (H * phi * B * F_tool.vector() - J.transpose() * F_tool.vector()).norm(),
                 tol(64, J_scale * F_tool.vector().norm()));
    soa::Workspace ws_dot = ws3;
    const soa::Acceleration Jdot_beta = soa::jacobian_dot_times_beta(m3, x3, ws_dot, k, tool);
    const soa::Acceleration alpha_F_fd = inertial_derivative(
        pose_F,
        [&](double t) {
          const soa::State xt = motion3.at(t);
          soa::Workspace w(m3);
          soa::update_phi(m3, xt.theta, w);
          soa::update_velocities(m3, xt, w);
          return soa::Phi(tool).transpose_apply(w.V[k - 1]);
        },
        0.0);
    checks.check(on + "alpha(F) = J beta_dot + Jdot beta (fd)",
                 (J * beta_dot3 + Jdot_beta.vector() - alpha_F_fd.vector()).norm(),
                 fd_tol(alpha_F_fd.vector().norm() + J_scale * beta_dot3.norm()));
  }

  /// ## 11. A 7-joint arm: the path of its tool
  ///
  /// A concrete robot: the default scene `lib/scenes/arm7.json`, a seven-joint revolute arm whose
  /// gripper sits on a locked hinge, merged into the last link as in section 3 (the scene
  /// files are described on the "Scene files" page of the notes). If the scene cannot be
  /// read, the same arm without the gripper is built in code. Its tool frame F sits 0.1 m out along the
  /// last joint's axis. The scene gives the geometry; the motion is this lesson's: from
  /// \f$\theta_s\f$, the elbow bent (away from the stretched-out arm, where J loses rank),
  /// the joints move smoothly by \f$\Delta\theta\f$,
  /// \f[ \theta(t) = \theta_s + \Delta\theta\; \tfrac12\big(1 - \cos(\pi t / t_f)\big),
  ///     \qquad \beta(t) = \Delta\theta\; \tfrac{\pi}{2 t_f} \sin(\pi t / t_f), \f]
  /// and at every sample the tool's pose comes from the scatter recursion and its velocity
  /// from the Jacobian, \f$v_F = R_F\,[J\beta]_v\f$ in inertial coordinates, checked against
  /// the finite difference of the path. `l3_tip_path.csv` has the samples.
  ///
  /// Seven joints for six tool coordinates: J is 6 x 7 and, away from singular
  /// configurations, has rank 6, so it has a null space. A joint velocity \f$\beta_0\f$ in it
  /// moves the arm but not the tool, \f$J\beta_0 = 0\f$: the arm's **self-motion**.
  checks.section("11. A 7-joint arm: the path of its tool");
  const std::string scene_path = std::string(SOA_SCENE_DIR) + "/arm7.json";
  soa::Model arm;
  soa::Scene arm_scene;  // for the viewer: the file's bodies, the gripper included
  bool from_scene = false;
  if (std::filesystem::exists(scene_path)) {
    try {
      arm_scene = soa::load_scene(scene_path);
      arm = arm_scene.model;
      from_scene = true;
    } catch (const soa::Error& e) {
      std::printf("  scene not read (%s): the arm is built in code\n", e.what());
    }
  } else {
    std::printf("  %s not found: the arm is built in code\n", scene_path.c_str());
  }
  if (!from_scene) {
    arm = arm7_in_code();
    arm_scene = soa::lesson::scene_of(arm, "7-joint arm");
  }
  std::printf("  arm from %s: %d bodies, nq = %d, nv = %d\n",
              from_scene ? "lib/scenes/arm7.json" : "code", arm.n(), arm.nq(), arm.nv());
  // Joint motion: every scalar hinge from the base out gets its entries of bend (theta_s)
  // and d_theta (Delta theta).
  const double d_theta[7] = {1.2, -0.4, 0.6, 0.7, -0.8, 0.5, 1.0};
  const double bend[7] = {0.0, 0.5, 0.0, 1.2, 0.0, 0.8, 0.0};
  VecXd theta_s = arm.neutral(), delta = VecXd::Zero(arm.nv());
  for (int k = arm.n(), i = 0; k >= 1; --k) {
    const soa::Body& B = arm.body(k);
    if (B.hinge.nq() != B.hinge.nv()) continue;
    for (int c = 0; c < B.hinge.nv(); ++c, ++i) {
      delta[B.v_offset + c] = d_theta[i % 7];
      theta_s[B.q_offset + c] = bend[i % 7];
    }
  }
  const soa::Pose tool7(Mat3d::Identity(), 0.1 * arm.body(1).hinge.axis);
  const double t_f = 4.0, pi = std::acos(-1.0);
  const auto arm_state = [&](double t) {
    soa::State x = soa::State::rest(arm);
    x.theta = theta_s;
    const double s = 0.5 * (1 - std::cos(pi * t / t_f)),
                 s_dot = 0.5 * pi / t_f * std::sin(pi * t / t_f);
    for (int k = 1; k <= arm.n(); ++k) {
      const soa::Body& B = arm.body(k);
      if (B.hinge.nq() != B.hinge.nv()) continue;
      for (int c = 0; c < B.hinge.nv(); ++c) {
        x.theta[B.q_offset + c] += s * delta[B.v_offset + c];
        x.beta[B.v_offset + c] = s_dot * delta[B.v_offset + c];
      }
    }
    return x;
  };
  const auto tool_pose = [&](double t) { return pose_of(arm, arm_state(t).theta, 1) * tool7; };
  soa::Workspace wa(arm);
  double v_res = 0, v_max = 0, path_length = 0;
  Vec3d previous = tool_pose(0.0).l();
  {
    std::ofstream csv(out / "l3_tip_path.csv");
    csv << "t,x,y,z,vx,vy,vz,vx_fd,vy_fd,vz_fd\n";
    const int samples = 200;
    for (int i = 0; i <= samples; ++i) {
      const double t = t_f * i / samples;
      const soa::State x = arm_state(t);
      soa::update_phi(arm, x.theta, wa);
      soa::update_poses(arm, wa);
      Jac J;
      soa::jacobian(arm, x.theta, wa, 1, tool7, J);
      const soa::Pose T_F = wa.pose[0] * tool7;
      const Vec3d v = T_F.R() * (J * x.beta).tail<3>();
      const Vec3d v_fd = derivative([&](double s) -> Vec3d { return tool_pose(s).l(); }, t);
      v_res = std::max(v_res, (v - v_fd).norm());
      v_max = std::max(v_max, v.norm());
      path_length += (T_F.l() - previous).norm();
      previous = T_F.l();
      char line[320];
      std::snprintf(line, sizeof line, "%.4f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", t,
                    T_F.l()[0], T_F.l()[1], T_F.l()[2], v[0], v[1], v[2], v_fd[0], v_fd[1],
                    v_fd[2]);
      csv << line;
    }
    checks.check("l3_tip_path.csv written", bool(csv));
  }
  std::printf("  tool path length %.3f m, largest speed %.3f m/s\n", path_length, v_max);
  checks.check("tool velocity R_F [J beta]_v = d/dt of the path (fd), all 201 samples", v_res,
               fd_tol(v_max + 1.0));

  /// The same motion in 3D: the viewer `l3_arm7_view` (\ref viewer) draws the arm at 401 instants,
  /// 10 ms apart: the poses of every body, the gripper on its locked hinge included, by the scatter
  /// recursion of section 5, \f$V(k)\f$ by that of section 6 (in inertial axes), and the path of
  /// the tool frame's origin, that of `l3_tip_path.csv` (checked).
  {
    const int frames = 401;
    soa::view::Recorder rec(arm_scene, t_f, frames, {true, false});
    for (int i = 0; i < frames; ++i)
      rec.offer(t_f * i / (frames - 1), arm_state(t_f * i / (frames - 1)));
    soa::view::View view = soa::view::view_of(arm_scene);
    view.title = "7-joint arm (lesson 3): poses and velocities along a joint motion";
    view.note = rec.note();
    view.runs.push_back(rec.take("the joint motion of section 11, 4 s"));
    int tool_body = 0;  // the file body whose frame is O_1, where the tool frame F sits
    while (arm_scene.frames[std::size_t(tool_body)].k != 1 ||
           arm_scene.frames[std::size_t(tool_body)].locked)
      ++tool_body;
    soa::lesson::set_tip(view, tool_body, tool7.l());
    double tip_gap = 0;
    for (const soa::view::Frame& f : view.runs.front().frames)
      tip_gap = std::max(tip_gap, (f.tip - tool_pose(f.t).l()).norm());
    checks.check("viewer: its tip path is the tool path (m)", tip_gap, tol(64));
    soa::lesson::check_viewer(checks, out, "l3_arm7_view", view,
                              "paused=1&t=2&show=frames,axes,V,tip");
  }

  const soa::State xs = arm_state(0.0);
  soa::update_phi(arm, xs.theta, wa);
  soa::update_poses(arm, wa);
  Jac J7;
  soa::jacobian(arm, xs.theta, wa, 1, tool7, J7);
  const Eigen::JacobiSVD<MatXd> svd(J7, Eigen::ComputeFullV);
  const VecXd sigma = svd.singularValues();
  show("sigma(J)", sigma);
  const bool redundant = arm.nv() == 7 && sigma[5] > 1e-3 * sigma[0];
  checks.check("J is 6 x 7 with rank 6 at the start", redundant);
  if (redundant) {
    const VecXd beta_null = svd.matrixV().col(6);  // the null space of J
    checks.check("self-motion: J beta_0 = 0 for beta_0 in the null space", (J7 * beta_null).norm(),
                 tol(64, sigma[0]));
    soa::State xn = xs;
    const soa::Velocity V_self = velocity_of(
        [&](double t) {
          xn.theta = xs.theta + t * beta_null;
          return pose_of(arm, xn.theta, 1) * tool7;
        },
        0.0);
    std::printf("  self-motion: joint speed |beta_0| = 1, tool speed (fd) = %.2e\n",
                V_self.vector().norm());
    checks.check("self-motion: the tool stands still (fd)", V_self.vector().norm(),
                 fd_tol(sigma[0]));
  }

  /// ## 12. Figures
  ///
  /// `l3_tip_path.png`: the tool's path in space over the joint motion, with its projection
  /// on the floor; `l3_tip_velocity.png`: the tool velocity's components, from the Jacobian
  /// (lines) and from finite differences of the path (points).
  ///
  /// \image html l3_tip_path.png "The 7-joint arm: path of the tool frame" width=600px
  ///
  /// \image html l3_tip_velocity.png "Tool velocity: Jacobian and finite differences" width=600px
  checks.section("12. Figures");
  checks.check("figure written: l3_tip_path.png",
               soa::lesson::plot("tip_path.gp", out, "l3_tip_path.png"));
  checks.check("figure written: l3_tip_velocity.png",
               soa::lesson::plot("tip_velocity.gp", out, "l3_tip_velocity.png"));

  /// ## What comes next
  ///
  /// Lesson 4 puts the bodies' inertias into the gather: \f$g(k) = M(k)\alpha(k) + b(k)\f$
  /// gives the Newton-Euler inverse dynamics \f$T = H\phi(M\alpha + b)\f$ and, with
  /// \f$\alpha = \phi^*(H^*\dot\beta + a)\f$, the mass matrix
  /// \f$\mathcal M = H\phi M\phi^* H^*\f$.
  return checks.finish();
}
