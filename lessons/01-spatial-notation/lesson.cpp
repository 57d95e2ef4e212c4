/// # Lesson 1 — Spatial notation
///
/// The "Spatial Notation" part of the course (slides 8-77), in the order of the slides. Every
/// identity is stated, computed on concrete numbers and checked; the program ends with the
/// count of checks that passed.
///
/// Learning goals. After this lesson you can
/// - write a cross product as a matrix, \f$\tilde x\, y = x \times y\f$, and accumulate
///   positions and rotations across frames with matching indices;
/// - move between the attitude representations (rotation matrix, unit quaternion with the
///   vector part first, Gibbs/Rodrigues parameters, Euler angles, axis-angle and the Cayley
///   map) in the course's aerospace (passive) convention, and say where each one is singular;
/// - compose and invert homogeneous transforms;
/// - differentiate a vector in different frames and read off an angular velocity;
/// - propagate spatial velocities \f$V = [\omega; v]\f$ with \f$\phi^*\f$ and spatial forces
///   \f$f = [N; F]\f$ with \f$\phi\f$, reverse a relative velocity, and see that power does
///   not depend on the point where it is computed;
/// - use the spatial cross products \f$\tilde X\f$ and \f$\bar X\f$ and their identities;
/// - derive the Coriolis term of the spatial acceleration propagation for each choice of the
///   derivative frame;
/// - see \f$\phi^*\f$ as the adjoint Ad of the Lie group SE(3) and the spatial cross product
///   as its bracket ad, prove the Jacobi and commutator identities from it, use the
///   exponential and logarithm of SE(3) at small angles and near \f$\pi\f$, and tell the
///   course's spatial velocity from the body and spatial twists of the robotics literature;
/// - move a spatial inertia with the parallel axis theorem, and compute kinetic energy and
///   spatial momentum about any point of a body.
///
/// Run it as `lesson01 OUTDIR`: it prints each check and writes `OUTDIR/attitude.txt`, one
/// rotation in every representation of slides 18-20.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <Eigen/Eigenvalues>
#include <unsupported/Eigen/MatrixFunctions>

#include "args.hpp"
#include "checklist.hpp"
#include "soa/soa.hpp"

namespace {

using Vec3d = soa::Vec3<double>;
using Mat3d = soa::Mat3<double>;
using Vec6d = soa::Vec6<double>;
using Mat6d = soa::Mat6<double>;
using soa::DerivativeFrame;

const double kEps = soa::eps<double>();

/// Tolerances are written in units of the machine epsilon \f$\varepsilon\f$, times the
/// magnitude of the terms compared: `tol(k, scale)` is \f$k\,\varepsilon\,\mathrm{scale}\f$.
double tol(double k, double scale = 1.0) {
  return k * kEps * scale;
}

/// Prints a vector (as a row) or a matrix, rounded to 6 digits.
template <class Derived>
void show(const std::string& name, const Eigen::MatrixBase<Derived>& m) {
  const Eigen::IOFormat fmt(6, Eigen::DontAlignCols, " ", "; ", "", "", "[", "]");
  std::ostringstream s;
  if (m.cols() == 1)
    s << m.transpose().format(fmt);
  else
    s << m.format(fmt);
  std::printf("  %-14s = %s\n", name.c_str(), s.str().c_str());
}

/// Derivatives of the concrete motions are taken numerically, with the five-point central
/// difference
/// \f[ \dot x(t) \approx \frac{x(t-2h) - 8\,x(t-h) + 8\,x(t+h) - x(t+2h)}{12\,h} . \f]
/// Its truncation error \f$O(h^4)\f$ and its rounding error \f$O(\varepsilon/h)\f$ balance at
/// \f$h = \varepsilon^{1/5}\f$, where both are of order \f$\varepsilon^{4/5} \approx 3 \cdot
/// 10^{-13}\f$: the finite-difference checks use `fd_tol`, a hundred times that, times the
/// magnitude.
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

/// A spatial vector with both halves rotated, \f$\mathrm{diag}(R, R)\, V\f$: the same vector
/// in the coordinates of another frame.
template <class K>
soa::SpatialVector<double, K> rotated(const Mat3d& R, const soa::SpatialVector<double, K>& V) {
  return soa::SpatialVector<double, K>(R * V.angular(), R * V.linear());
}

/// ## A concrete motion
///
/// Three frames: A (inertial), B moving in A, and C moving in B. Each relative motion (of a
/// "to" frame G in a "from" frame F) is given in closed form,
/// \f[ {}^F R_G(t) = \exp(t\,\tilde a)\, R_0\, \exp(t\,\tilde b), \qquad
///     {}^F l(F,G)(t) = p_0 + t\, p_1 + t^2 p_2 , \f]
/// so that its angular and linear velocities are known exactly. With slide 32's definition
/// of the angular velocity, \f${}^F\dot R_G = {}^F\tilde\omega(F,G)\; {}^F R_G\f$, and
/// \f$\dot R = \tilde a R + R \tilde b = (a + R b)^\sim R\f$ (the identity
/// \f$R\tilde b R^* = (Rb)^\sim\f$ of slide 8):
/// \f[ {}^F\omega(F,G) = a + {}^F R_G\, b, \qquad {}^G\omega(F,G) = {}^F R_G^*\, a + b,
///     \qquad {}^F v(F,G) = {}^F\frac{d}{dt}\, l(F,G) = p_1 + 2t\, p_2 . \f]
struct RelativeMotion {
  Vec3d a, b;
  Mat3d R0;
  Vec3d p0, p1, p2;

  Mat3d R(double t) const { return soa::exp_so3<double>(t * a) * R0 * soa::exp_so3<double>(t * b); }
  Vec3d l(double t) const { return p0 + t * p1 + t * t * p2; }
  soa::Pose T(double t) const { return soa::Pose(R(t), l(t)); }
  // V(F,G) = [w(F,G); v(F,G)] in the coordinates of G, the frame that moves.
  soa::Velocity V(double t) const {
    const Mat3d Rt = R(t).transpose();
    return soa::Velocity(Rt * a + b, Rt * (p1 + 2.0 * t * p2));
  }
};

/// Runs `f`, expecting it to throw soa::Error; prints the message.
template <class F>
bool throws_soa_error(const F& f) {
  try {
    f();
  } catch (const soa::Error& e) {
    std::printf("  soa::Error: %s\n", e.what());
    return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path out_dir = soa::lesson::output_dir(argc, argv);
  soa::lesson::Checklist checks;

  /// ## The cross-product matrix (slide 8)
  ///
  /// `*` denotes the transpose and `~` turns a 3-vector into the skew-symmetric matrix of its
  /// cross product:
  /// \f[ \tilde x = \begin{pmatrix} 0 & -x_3 & x_2 \\ x_3 & 0 & -x_1 \\ -x_2 & x_1 & 0
  ///     \end{pmatrix}, \qquad \tilde x\, y = x \times y, \qquad \tilde x^* = -\tilde x,
  ///     \qquad \tilde x\, x = 0 . \f]
  /// A cross product does not depend on the frame it is computed in: for a rotation \f$R\f$,
  /// \f$(R x)^\sim = R\, \tilde x\, R^*\f$. This identity is what lets the rigid body
  /// transformation \f$\phi\f$ carry rotations later on.
  checks.section("Cross-product matrix (slide 8)");
  const Vec3d x(1.0, 2.0, 3.0), y(-2.0, 0.5, 4.0);
  const Mat3d x_tilde = soa::tilde(x);
  show("x~", x_tilde);
  checks.check("x~ y = x cross y", (x_tilde * y - x.cross(y)).norm(), tol(4, x.norm() * y.norm()));
  checks.check("x~* = -x~", (x_tilde.transpose() + x_tilde).norm(), 0.0);
  checks.check("x~ x = 0", (x_tilde * x).norm(), tol(4, x.squaredNorm()));
  const Mat3d R_any = soa::exp_so3(Vec3d(0.3, -0.5, 0.8));
  checks.check("(R x)~ = R x~ R*",
               (soa::tilde<double>(R_any * x) - R_any * x_tilde * R_any.transpose()).norm(),
               tol(16, x.norm()));

  /// ## Accumulating positions and rotations (slides 11-15)
  ///
  /// The concrete motion, frozen at \f$t_0 = 0.7\f$. Positions accumulate once they are
  /// represented in the same frame (slides 12-13):
  /// \f[ {}^A l(A,C) = {}^A l(A,B) + {}^A R_B\; {}^B l(B,C), \qquad
  ///     \text{coordinate-free: } l(A,C) = l(A,B) + l(B,C), \f]
  /// and rotations accumulate with matching inner indices (slide 15),
  /// \f${}^A R_C = {}^A R_B\; {}^B R_C\f$. Adding the raw coordinates \f${}^A l(A,B) +
  /// {}^B l(B,C)\f$ mixes two frames (the "wrong sum" printed below). The homogeneous transform
  /// of slide 25 packages position and rotation, so its 4x4 product is an independent check.
  /// Two turns about one axis add their angles.
  checks.section("Accumulating positions and rotations (slides 11-15)");
  const RelativeMotion AB{
      Vec3d(0.3, -0.2, 0.5), Vec3d(0.1, 0.4, -0.3), soa::exp_so3(Vec3d(0.2, -0.1, 0.4)),
      Vec3d(1.0, 0.5, -0.2), Vec3d(0.2, -0.3, 0.1), Vec3d(0.05, 0.1, -0.08)};
  const RelativeMotion BC{
      Vec3d(-0.4, 0.2, 0.1), Vec3d(0.2, 0.3, 0.6),   soa::exp_so3(Vec3d(-0.3, 0.5, 0.2)),
      Vec3d(0.4, -0.6, 0.3), Vec3d(-0.1, 0.2, 0.25), Vec3d(0.07, -0.04, 0.03)};
  const double t0 = 0.7;
  const Mat3d R_AB = AB.R(t0), R_BC = BC.R(t0);
  const Vec3d l_AB = AB.l(t0), l_BC = BC.l(t0);
  const Vec3d l_AC = l_AB + R_AB * l_BC;
  const Mat3d R_AC = R_AB * R_BC;
  show("A l(A,C)", l_AC);
  show("wrong sum", Vec3d(l_AB + l_BC));
  const Eigen::Matrix4d T_AC_4x4 = AB.T(t0).matrix() * BC.T(t0).matrix();
  checks.check("A l(A,C) = A l(A,B) + A R_B B l(B,C)",
               (l_AC - T_AC_4x4.topRightCorner<3, 1>()).norm(), tol(8, l_AB.norm() + l_BC.norm()));
  checks.check("A R_C = A R_B B R_C is a rotation", soa::is_rotation(R_AC, tol(8)));
  const Vec3d n_axis = Vec3d(1.0, 2.0, 2.0) / 3.0;
  checks.check("exp(0.4 n~) exp(0.9 n~) = exp(1.3 n~)",
               (soa::exp_so3<double>(0.4 * n_axis) * soa::exp_so3<double>(0.9 * n_axis) -
                soa::exp_so3<double>(1.3 * n_axis))
                   .norm(),
               tol(16));

  /// ## Attitude representations and the convention (slides 16-20)
  ///
  /// Robotics and aerospace texts use opposite conventions (slides 16-17). The course, and
  /// the whole library (`soa/rotation/convention.hpp`), use the aerospace, passive one:
  /// \f${}^A R_B\f$ is the attitude of B relative to A; it maps B-coordinates of a vector to
  /// its A-coordinates, \f${}^A x = {}^A R_B\, {}^B x\f$, so its columns are B's axes seen in
  /// A. Turning B from A through \f$\theta\f$ about the unit axis \f$n\f$ gives (slide 19)
  /// \f[ {}^A R_B = \exp(\theta\,\tilde n) = \cos\theta\, I + (1 - \cos\theta)\, n n^* +
  ///     \sin\theta\, \tilde n . \f]
  /// A quarter turn about z puts B's x axis along A's y axis.
  checks.section("Attitude: the convention (slides 16-19)");
  const Mat3d R_quarter = soa::exp_so3<double>(M_PI / 2 * Vec3d::UnitZ());
  show("R(pi/2 about z)", R_quarter);
  checks.check("B's x axis seen in A is A's y axis", (R_quarter.col(0) - Vec3d::UnitY()).norm(),
               tol(4));
  const double theta = 2.0;
  const Mat3d n_tilde = soa::tilde(n_axis);
  const Mat3d R = soa::exp_so3<double>(theta * n_axis);
  const Mat3d R_rodrigues = std::cos(theta) * Mat3d::Identity() +
                            (1 - std::cos(theta)) * n_axis * n_axis.transpose() +
                            std::sin(theta) * n_tilde;
  checks.check("exp(theta n~) = cos I + (1-cos) n n* + sin n~", (R - R_rodrigues).norm(), tol(16));

  /// Minimal, three-number representations cannot be both global and non-singular
  /// (slide 18); the four-number unit quaternion is both (slides 19-20). Vector part first:
  /// \f[ \mathfrak q = \begin{pmatrix} q \\ q_0 \end{pmatrix} = \begin{pmatrix}
  ///     \sin(\theta/2)\, n \\ \cos(\theta/2) \end{pmatrix}, \qquad
  ///     R = (q_0^2 - q^* q)\, I + 2\, q q^* + 2\, q_0\, \tilde q . \f]
  /// Quaternions compose as the matrices do, \f$R(\mathfrak a \otimes \mathfrak b) =
  /// R(\mathfrak a)\, R(\mathfrak b)\f$; \f$\mathfrak q\f$ and \f$-\mathfrak q\f$ name the same
  /// rotation, and from_matrix() returns the one with \f$q_0 \ge 0\f$.
  ///
  /// *Now do exercise 1.4* (`soa::ex01::quaternion_from_axis_angle`): this quaternion from an
  /// axis of any length and an angle in radians, refusing an axis that names no rotation.
  checks.section("Attitude: unit quaternion, vector part first (slides 19-20)");
  const soa::UnitQuaternion q = soa::UnitQuaternion::exp(theta * n_axis);
  Eigen::Vector4d q_expected;
  q_expected << std::sin(theta / 2) * n_axis, std::cos(theta / 2);
  show("[q; q0]", q.coeffs());
  checks.check("[q; q0] = [sin(theta/2) n; cos(theta/2)]", (q.coeffs() - q_expected).norm(),
               tol(4));
  checks.check("R(q) = exp(theta n~)", (q.matrix() - R).norm(), tol(16));
  const soa::UnitQuaternion q2 = soa::UnitQuaternion::exp(Vec3d(-0.4, 0.9, 0.3));
  checks.check("R(q (x) q2) = R(q) R(q2)", ((q * q2).matrix() - q.matrix() * q2.matrix()).norm(),
               tol(16));
  checks.check("from_matrix(R(q)) = q",
               (soa::UnitQuaternion::from_matrix(R).coeffs() - q.coeffs()).norm(), tol(8));

  /// The Rodrigues (Gibbs) parameters \f$g = \tan(\theta/2)\, n = q / q_0\f$ (slide 20) are
  /// three numbers, good for integrating attitude rates, but singular at \f$\theta = \pi\f$,
  /// where \f$q_0 = 0\f$ (slide 18). The library refuses them there with soa::Error rather
  /// than return an infinite or NaN vector: re-centre the coordinates instead.
  checks.section("Attitude: Gibbs/Rodrigues parameters (slides 18-20)");
  const soa::Gibbs g = soa::Gibbs::from_matrix(R);
  show("g", g.g);
  checks.check("g = tan(theta/2) n = q / q0", (g.g - std::tan(theta / 2) * n_axis).norm(),
               tol(16, g.g.norm()));
  checks.check("R(g) = R", (g.matrix() - R).norm(), tol(16));
  const Mat3d R_pi = soa::exp_so3<double>(M_PI * n_axis);
  checks.check("Gibbs parameters at theta = pi: soa::Error",
               throws_soa_error([&] { (void)soa::Gibbs::from_matrix(R_pi); }));

  /// Euler angles, 3-2-1 (yaw \f$\psi\f$ about z, pitch \f$\vartheta\f$ about the new y, roll
  /// \f$\varphi\f$ about the new x): \f$R = \exp(\psi\tilde e_3) \exp(\vartheta\tilde e_2)
  /// \exp(\varphi\tilde e_1)\f$, global but singular (slide 18). At \f$\vartheta = \pi/2\f$
  /// (gimbal lock) \f$\exp(\tfrac\pi2\tilde e_2)\exp(\varphi\tilde e_1) =
  /// \exp(-\varphi\tilde e_3)\exp(\tfrac\pi2\tilde e_2)\f$: roll and yaw turn about the same
  /// axis and only \f$\psi - \varphi\f$ is defined. The documented fallback sets
  /// \f$\varphi = 0\f$ and gives the whole turn to \f$\psi\f$; the matrix is reproduced.
  checks.section("Attitude: Euler angles 3-2-1 and gimbal lock (slide 18)");
  const soa::EulerZYX e{0.7, -0.4, 1.1};
  const soa::EulerZYX e_back = soa::EulerZYX::from_matrix(e.matrix());
  checks.check("from_matrix(R(yaw, pitch, roll)) = (yaw, pitch, roll)",
               Vec3d(e_back.yaw - e.yaw, e_back.pitch - e.pitch, e_back.roll - e.roll).norm(),
               tol(16));
  const soa::EulerZYX locked{0.7, M_PI / 2, 0.2};
  const soa::EulerZYX locked_back = soa::EulerZYX::from_matrix(locked.matrix());
  std::printf("  gimbal lock: in (yaw, pitch, roll) = (%.6f, %.6f, %.6f)\n", locked.yaw,
              locked.pitch, locked.roll);
  std::printf("               out (yaw, pitch, roll) = (%.6f, %.6f, %.6f)\n", locked_back.yaw,
              locked_back.pitch, locked_back.roll);
  checks.check("gimbal lock: roll = 0, yaw = yaw - roll = 0.5",
               std::abs(locked_back.roll) + std::abs(locked_back.yaw - 0.5), tol(16));
  checks.check("gimbal lock: the angles still reproduce R",
               (locked_back.matrix() - locked.matrix()).norm(), tol(16));

  /// Axis-angle: the exponential \f$R = \exp(\tilde w)\f$ of the rotation vector
  /// \f$w = \theta n\f$ and its inverse, the logarithm with \f$\theta \in [0, \pi]\f$
  /// (slide 19). Both are written through \f$\sin(x)/x\f$ so that they keep full precision as
  /// \f$\theta \to 0\f$: the logarithm of \f$I\f$ is exactly \f$0\f$ (the axis is undefined
  /// there, the rotation vector is not), and at \f$\theta = \pi\f$, where \f$\sin\theta\f$
  /// vanishes, the axis is read from the symmetric part of \f$R\f$.
  checks.section("Attitude: axis-angle, exp and log (slide 19)");
  checks.check("log(exp(w)) = w at theta = 2", (soa::log_so3(R) - theta * n_axis).norm(),
               tol(16, theta));
  const Vec3d w_zero = soa::log_so3<double>(Mat3d::Identity());
  show("log(I)", w_zero);
  checks.check("log(I) = 0, finite (theta = 0)", w_zero.allFinite() && w_zero.norm() == 0.0);
  const Vec3d w_tiny = 1e-9 * n_axis;
  checks.check("log(exp(w)) = w at theta = 1e-9, relatively",
               (soa::log_so3(soa::exp_so3(w_tiny)) - w_tiny).norm(), tol(8, w_tiny.norm()));
  const Vec3d w_pi = soa::log_so3(R_pi);
  show("log(R(pi))", w_pi);
  checks.check("exp(log(R)) = R at theta = pi", (soa::exp_so3(w_pi) - R_pi).norm(), tol(16));

  /// The Cayley map \f$\mathrm{cay}(c) = (I - \tfrac12\tilde c)^{-1} (I + \tfrac12\tilde c)\f$
  /// is rational (no trigonometry), non-singular near the identity but not global
  /// (slide 18). It is exactly the rotation through \f$\theta\f$ about \f$n\f$ when
  /// \f$c = 2\tan(\theta/2)\, n\f$ (twice the Gibbs vector), so \f$\theta = \pi\f$ has no
  /// parameters (the error names the Gibbs parameters, which the inverse map goes through);
  /// and it agrees with \f$\exp(\tilde c)\f$ to second order: the series differ
  /// first in \f$\tilde c^3/12\f$, so halving \f$c\f$ divides the difference by 8.
  checks.section("Attitude: the Cayley map (slide 18)");
  const Vec3d c = 2.0 * std::tan(theta / 2) * n_axis;
  checks.check("cay(2 tan(theta/2) n) = exp(theta n~)", (soa::cayley(c) - R).norm(), tol(16));
  const Vec3d c_small = 1e-3 * Vec3d(0.3, -0.8, 0.5);
  const double d1 = (soa::cayley(c_small) - soa::exp_so3(c_small)).norm();
  const double d2 = (soa::cayley<double>(c_small / 2) - soa::exp_so3<double>(c_small / 2)).norm();
  std::printf("  |cay(c) - exp(c)| = %.3e, with c/2: %.3e, ratio %.4f\n", d1, d2, d1 / d2);
  checks.check("cay(c) - exp(c~) = O(|c|^3): ratio 8 on halving c", std::abs(d1 / d2 - 8.0), 1e-2);
  checks.check("Cayley parameters at theta = pi: soa::Error",
               throws_soa_error([&] { (void)soa::cayley_inverse(R_pi); }));

  {
    std::ofstream table(out_dir / "attitude.txt");
    const soa::EulerZYX eu = soa::EulerZYX::from_matrix(R);
    const soa::AxisAngle aa = soa::AxisAngle::from_matrix(R);
    const Eigen::IOFormat fmt(9, Eigen::DontAlignCols, " ", "\n               ");
    table << "# One rotation, theta = 2 rad about n = (1, 2, 2)/3, in every representation\n"
          << "# of lesson 1 (aerospace/passive convention, A R_B maps B- to A-coordinates).\n"
          << "matrix       : " << R.format(fmt) << "\n"
          << "quaternion   : " << q.coeffs().transpose().format(fmt) << "   [q; q0]\n"
          << "gibbs        : " << g.g.transpose().format(fmt) << "\n"
          << "euler zyx    : " << eu.yaw << " " << eu.pitch << " " << eu.roll
          << "   (yaw pitch roll)\n"
          << "axis-angle   : " << aa.n.transpose().format(fmt) << "   theta " << aa.theta << "\n"
          << "cayley       : " << soa::Cayley::from_matrix(R).c.transpose().format(fmt) << "\n";
  }

  /// ## Homogeneous transforms (slides 22-28)
  ///
  /// A pose, attitude and position together, is the 4x4 homogeneous transform (slide 23)
  /// \f[ {}^A T_B = \begin{pmatrix} {}^A R_B & {}^A l(A,B) \\ 0 & 1 \end{pmatrix} . \f]
  /// Its inverse is the pose of A in B (slide 24), \f${}^A T_B^{-1} = {}^B T_A =
  /// \begin{pmatrix} {}^A R_B^* & -{}^A R_B^*\, {}^A l(A,B) \\ 0 & 1 \end{pmatrix}\f$; poses
  /// compose with matching indices, \f${}^A T_C = {}^A T_B\, {}^B T_C\f$ (slides 25-27); and
  /// a point p given in C is found in A by \f$[{}^A p; 1] = {}^A T_C\, [{}^C p; 1]\f$
  /// (slide 28). The library stores \f$(R, l)\f$, never the 4x4.
  checks.section("Homogeneous transforms (slides 22-28)");
  const soa::Pose T_AB = AB.T(t0), T_BC = BC.T(t0);
  const soa::Pose T_AC = T_AB * T_BC;
  show("A T_C", T_AC.matrix());
  checks.check("A T_C = A T_B B T_C (4x4 product)", (T_AC.matrix() - T_AC_4x4).norm(),
               tol(16, T_AC_4x4.norm()));
  checks.check("B T_A = (A T_B)^-1 (4x4 inverse)",
               (T_AB.inverse().matrix() - T_AB.matrix().inverse()).norm(),
               tol(16, T_AB.matrix().norm()));
  const Vec3d p_C(0.25, -0.5, 1.5);
  Eigen::Vector4d p_C_h;
  p_C_h << p_C, 1.0;
  checks.check("A p = A T_C C p = A T_B (B T_C C p)",
               (T_AC.apply(p_C) - T_AB.apply(T_BC.apply(p_C))).norm() +
                   (T_AC.apply(p_C) - (T_AC_4x4 * p_C_h).head<3>()).norm(),
               tol(16, T_AC_4x4.norm() * p_C.norm()));

  /// ## Time derivatives in different frames and angular velocity (slides 30-33)
  ///
  /// Only coordinates can be differentiated, so a time derivative names the frame F it is
  /// taken in: \f${}^F\frac{d}{dt} x\f$ is the vector whose F-coordinates are
  /// \f$\frac{d}{dt}\big({}^F x\big)\f$. It is itself a vector, and can then be represented in
  /// any frame (slides 30-31). The angular velocity of G
  /// relative to F is defined by the derivative of the rotation (slide 32),
  /// \f[ {}^F\frac{d}{dt}\, {}^F R_G = {}^F\tilde\omega(F,G)\; {}^F R_G
  ///     = {}^F R_G\; {}^G\tilde\omega(F,G), \f]
  /// and derivatives in two frames differ by the cross product with it (slide 33):
  /// \f[ {}^F\frac{d}{dt}\, x = {}^G\frac{d}{dt}\, x + \omega(F,G) \times x . \f]
  /// Checked by finite differences on the motion of B in A, with \f$x = l(B,C)\f$.
  checks.section("Time derivatives and angular velocity (slides 30-33)");
  const Mat3d R_AB_dot = derivative([&](double t) { return AB.R(t); }, t0);
  const soa::Velocity V_AB_B = AB.V(t0);  // B V(A,B)
  const Vec3d w_AB_A = R_AB * V_AB_B.angular();
  checks.check("A d/dt A R_B = A w~(A,B) A R_B", (R_AB_dot - soa::tilde(w_AB_A) * R_AB).norm(),
               fd_tol(w_AB_A.norm()));
  checks.check("A d/dt A R_B = A R_B B w~(A,B)",
               (R_AB_dot - R_AB * soa::tilde<double>(V_AB_B.angular())).norm(),
               fd_tol(w_AB_A.norm()));
  const Vec3d dx_A = derivative([&](double t) -> Vec3d { return AB.R(t) * BC.l(t); }, t0);
  const Vec3d dx_B = R_AB * derivative([&](double t) { return BC.l(t); }, t0);
  checks.check("A d/dt x = B d/dt x + w(A,B) x x  (x = l(B,C), in A)",
               (dx_A - (dx_B + w_AB_A.cross(R_AB * l_BC))).norm(), fd_tol(dx_A.norm()));

  /// ## Linear and spatial velocities (slides 35-41)
  ///
  /// The linear velocity of G relative to F is the derivative of the position in the "from"
  /// frame, \f$v(F,G) = {}^F\frac{d}{dt}\, l(F,G)\f$ (slide 35). Differentiating
  /// \f$l(A,C) = l(A,B) + l(B,C)\f$ in A, with slide 33 for the second term, gives
  /// (slides 36-38)
  /// \f[ \omega(A,C) = \omega(A,B) + \omega(B,C), \qquad
  ///     v(A,C) = v(A,B) + \omega(A,B) \times l(B,C) + v(B,C) . \f]
  /// With the spatial velocity \f$V = [\omega; v]\f$ and the rigid body transformation
  /// \f$\phi(B,C) = \begin{pmatrix} I & \tilde l(B,C) \\ 0 & I \end{pmatrix}\f$ the two lines
  /// are one (slides 39-40):
  /// \f[ V(A,C) = \phi^*(B,C)\, V(A,B) + V(B,C), \qquad
  ///     \phi^*(B,C) = \begin{pmatrix} I & 0 \\ -\tilde l(B,C) & I \end{pmatrix}, \f]
  /// since \f$-\tilde l\, \omega = \omega \times l\f$. With coordinates, Phi(\f${}^B R_C\f$,
  /// \f${}^B l(B,C)\f$).transpose_apply() takes \f${}^B V(A,B)\f$ to C-coordinates. Checked
  /// against finite differences of the composed pose \f${}^A T_C(t)\f$.
  checks.section("Linear and spatial velocities (slides 35-41)");
  const soa::Velocity V_BC_C = BC.V(t0);  // C V(B,C)
  const Vec3d v_AC_A = derivative([&](double t) -> Vec3d { return (AB.T(t) * BC.T(t)).l(); }, t0);
  const Mat3d R_AC_dot = derivative([&](double t) -> Mat3d { return (AB.T(t) * BC.T(t)).R(); }, t0);
  const Vec3d w_AC_A = soa::vee<double>(R_AC_dot * R_AC.transpose());
  const Vec3d v_AC_formula =
      R_AB * V_AB_B.linear() + w_AB_A.cross(R_AB * l_BC) + R_AC * V_BC_C.linear();
  checks.check("v(A,C) = v(A,B) + w(A,B) x l(B,C) + v(B,C)", (v_AC_formula - v_AC_A).norm(),
               fd_tol(v_AC_A.norm()));
  checks.check("w(A,C) = w(A,B) + w(B,C)", (w_AB_A + R_AC * V_BC_C.angular() - w_AC_A).norm(),
               fd_tol(w_AC_A.norm()));
  const soa::Phi phi_BC(R_BC, l_BC);
  const soa::Velocity V_AC_C = phi_BC.transpose_apply(V_AB_B) + V_BC_C;
  const soa::Velocity V_AC_fd(R_AC.transpose() * w_AC_A, R_AC.transpose() * v_AC_A);
  show("C V(A,C)", V_AC_C.vector());
  checks.check("V(A,C) = phi*(B,C) V(A,B) + V(B,C)", (V_AC_C - V_AC_fd).vector().norm(),
               fd_tol(V_AC_fd.vector().norm()));

  /// For two points x, y of one rigid body nothing moves between them, \f$V(x, y) = 0\f$, and
  /// the propagation becomes the transformation of spatial velocities across a rigid body
  /// (slide 41): \f$V(y) = \phi^*(x,y)\, V(x)\f$. Frame D below is fixed in B.
  const RelativeMotion BD{Vec3d::Zero(),         Vec3d::Zero(), soa::exp_so3(Vec3d(0.5, 0.1, -0.7)),
                          Vec3d(-0.3, 0.8, 0.2), Vec3d::Zero(), Vec3d::Zero()};
  const soa::Phi phi_BD(BD.R(t0), BD.l(t0));
  const Mat3d R_AD = R_AB * BD.R(t0);
  const Vec3d w_AD = soa::vee<double>(
      derivative([&](double t) -> Mat3d { return AB.R(t) * BD.R(t); }, t0) * R_AD.transpose());
  const Vec3d v_AD = derivative([&](double t) -> Vec3d { return (AB.T(t) * BD.T(t)).l(); }, t0);
  const soa::Velocity V_AD_fd(R_AD.transpose() * w_AD, R_AD.transpose() * v_AD);
  checks.check("rigid body: V(D) = phi*(B,D) V(B)",
               (phi_BD.transpose_apply(V_AB_B) - V_AD_fd).vector().norm(),
               fd_tol(V_AD_fd.vector().norm()));

  /// ## The structure and properties of \f$\phi\f$ (slides 43-45)
  ///
  /// With the rotations shown (slide 43), for \f$R = {}^x R_y\f$ and \f$l = {}^x l(x,y)\f$,
  /// \f[ \phi(x,y) = \begin{pmatrix} I & \tilde l \\ 0 & I \end{pmatrix}
  ///     \begin{pmatrix} R & 0 \\ 0 & R \end{pmatrix}
  ///     = \begin{pmatrix} R & \tilde l R \\ 0 & R \end{pmatrix} . \f]
  /// Like rotations (slides 44-45): \f$\phi(x,x) = I\f$, \f$\phi(x,z) = \phi(x,y)\,
  /// \phi(y,z)\f$ and \f$\phi^{-1}(x,y) = \phi(y,x)\f$. Without rotations the product is the
  /// sum of the offsets: \f$\tilde l(x,y) + \tilde l(y,z) = \tilde l(x,z)\f$.
  checks.section("Structure and properties of phi (slides 43-45)");
  Mat6d phi_by_hand = Mat6d::Zero();
  phi_by_hand.topLeftCorner<3, 3>() = R_BC;
  phi_by_hand.bottomRightCorner<3, 3>() = R_BC;
  phi_by_hand.topRightCorner<3, 3>() = soa::tilde(l_BC) * R_BC;
  checks.check("phi(x,y) = [I l~; 0 I] diag(R, R)", (phi_BC.matrix() - phi_by_hand).norm(), 0.0);
  checks.check("phi(x,x) = I", soa::Phi().matrix().isIdentity(0.0));
  const soa::Phi phi_AB(R_AB, l_AB);
  checks.check("phi(A,C) = phi(A,B) phi(B,C)",
               ((phi_AB * phi_BC).matrix() - phi_AB.matrix() * phi_BC.matrix()).norm(),
               tol(16, phi_AB.matrix().norm() * phi_BC.matrix().norm()));
  checks.check("phi^-1(B,C) = phi(C,B)",
               (phi_BC.inverse().matrix() * phi_BC.matrix() - Mat6d::Identity()).norm(),
               tol(16, phi_BC.matrix().squaredNorm()));
  checks.check("coordinate-free: phi(l1) phi(l2) = phi(l1 + l2)",
               ((soa::Phi::translation(l_AB) * soa::Phi::translation(l_BC)).matrix() -
                soa::Phi::translation(Vec3d(l_AB + l_BC)).matrix())
                   .norm(),
               tol(4, l_AB.norm() + l_BC.norm()));

  /// ## Reversing a spatial velocity (slide 46)
  ///
  /// Seen from the other frame, \f$\omega(y,x) = -\omega(x,y)\f$ and, differentiating
  /// \f$l(y,x) = -l(x,y)\f$ in y with slide 33,
  /// \f$v(y,x) = -v(x,y) + \omega(x,y) \times l(x,y)\f$: the linear velocity reverses only
  /// when there is no relative rotation. In spatial form
  /// \f[ V(y,x) = -\phi^*(y,x)\, V(x,y) . \f]
  /// Checked on A and B: \f$V(B,A)\f$ from finite differences of \f${}^B T_A(t) =
  /// {}^A T_B(t)^{-1}\f$.
  ///
  /// *Now do exercise 1.6* (`soa::ex01::reverse_velocity`): the reversal with the rotation
  /// shown, from \f$V(x,y)\f$ in y-coordinates to \f$V(y,x)\f$ in x-coordinates.
  checks.section("Velocity reversal (slide 46)");
  const soa::Phi phi_BA = phi_AB.inverse();
  const soa::Velocity V_BA_A = -phi_BA.transpose_apply(V_AB_B);  // A V(B,A)
  const Mat3d R_BA_dot = derivative([&](double t) -> Mat3d { return AB.T(t).inverse().R(); }, t0);
  const Vec3d w_BA_B = soa::vee<double>(R_BA_dot * R_AB);
  const Vec3d v_BA_B = derivative([&](double t) -> Vec3d { return AB.T(t).inverse().l(); }, t0);
  const soa::Velocity V_BA_fd(R_AB * w_BA_B, R_AB * v_BA_B);
  show("A V(B,A)", V_BA_A.vector());
  checks.check("V(B,A) = -phi*(B,A) V(A,B)", (V_BA_A - V_BA_fd).vector().norm(),
               fd_tol(V_BA_fd.vector().norm()));

  /// ## Spatial forces and the dual relationships (slides 48-51)
  ///
  /// A force \f$F\f$ at B is, at A, the same force plus the moment of its offset (slide 48):
  /// \f$N(A) = N(B) + l(A,B) \times F(B)\f$, \f$F(A) = F(B)\f$. With the spatial force
  /// \f$f = [N; F]\f$ (moment first) this is \f$\phi\f$ itself (slide 49):
  /// \f[ f(A) = \phi(A,B)\, f(B) . \f]
  /// Forces move with \f$\phi\f$, velocities with \f$\phi^*\f$, in opposite directions
  /// (slide 50): \f$V(B) = \phi^*(A,B)\, V(A)\f$ and \f$f(A) = \phi(A,B)\, f(B)\f$. The pairing
  /// is the power, and it does not depend on the point:
  /// \f[ f^*(A)\, V(A) = f^*(B)\, \phi^*(A,B)\, V(A) = f^*(B)\, V(B) . \f]
  /// Below, A and B are two frames fixed in one body, with the pose \f${}^A T_B\f$ of the
  /// motion at \f$t_0\f$ between them (a rotation as well as an offset).
  ///
  /// *Now do exercise 1.1* (`soa::ex01::apply_phi`): \f$f(x) = \phi(x,y)\, f(y)\f$ written
  /// from \f$R\f$ and \f$l\f$, the two factors of slide 43.
  checks.section("Spatial forces, duality and power (slides 48-51)");
  const soa::Force f_B(Vec3d(0.3, -1.2, 0.5), Vec3d(2.0, 0.4, -1.5));
  const soa::Force f_A_free = soa::Phi::translation(l_AB).apply(f_B);
  checks.check("N(A) = N(B) + l(A,B) x F(B), F(A) = F(B)",
               (f_A_free.angular() - (f_B.angular() + l_AB.cross(f_B.linear()))).norm() +
                   (f_A_free.linear() - f_B.linear()).norm(),
               tol(8, l_AB.norm() * f_B.vector().norm()));
  const soa::Force f_A = phi_AB.apply(f_B);
  checks.check("f(A) = phi(A,B) f(B), as the 6x6 matrix",
               (f_A.vector() - phi_AB.matrix() * f_B.vector()).norm(),
               tol(16, phi_AB.matrix().norm() * f_B.vector().norm()));
  const soa::Velocity V_A(Vec3d(0.4, -0.1, 0.7), Vec3d(-0.5, 1.0, 0.2));
  const soa::Velocity V_B = phi_AB.transpose_apply(V_A);
  std::printf("  power at A %.15f, at B %.15f\n", soa::dot(f_A, V_A), soa::dot(f_B, V_B));
  checks.check("power f*(A) V(A) = f*(B) V(B)", std::abs(soa::dot(f_A, V_A) - soa::dot(f_B, V_B)),
               tol(32, f_A.vector().norm() * V_A.vector().norm()));

  /// Forces acting at several points of a body add once they are moved to one point
  /// (slide 51): \f$f(B) = \sum_i \phi(B, i)\, f(i)\f$. Two thrusters at frames 1 and 2 of
  /// body B: the total moved on to a third point E equals the thrusts moved to E directly,
  /// and the total's power is the sum of the thrusters' powers.
  const soa::Phi phi_B1(soa::exp_so3(Vec3d(0.0, 0.3, 0.0)), Vec3d(1.0, 0.0, 0.2));
  const soa::Phi phi_B2(soa::exp_so3(Vec3d(0.0, -0.3, 0.0)), Vec3d(-1.0, 0.0, 0.2));
  const soa::Phi phi_EB(Mat3d::Identity(), Vec3d(0.0, 0.5, -0.8));
  const soa::Force thrust(Vec3d::Zero(), Vec3d(0.0, 0.0, 10.0));  // along each thruster's z
  const soa::Force f_total = phi_B1.apply(thrust) + phi_B2.apply(thrust);
  show("f(B) total", f_total.vector());
  checks.check(
      "phi(E,B) sum phi(B,i) f(i) = sum phi(E,i) f(i)",
      (phi_EB.apply(f_total) - ((phi_EB * phi_B1).apply(thrust) + (phi_EB * phi_B2).apply(thrust)))
          .vector()
          .norm(),
      tol(32, f_total.vector().norm()));
  const soa::Velocity V_Bbody(Vec3d(0.1, 0.2, -0.3), Vec3d(1.0, -0.5, 0.3));
  const double power_total = soa::dot(f_total, V_Bbody);
  const double power_sum = soa::dot(thrust, phi_B1.transpose_apply(V_Bbody)) +
                           soa::dot(thrust, phi_B2.transpose_apply(V_Bbody));
  checks.check("power of the total = sum of the thrusters' powers",
               std::abs(power_total - power_sum), tol(32, 20.0 * V_Bbody.vector().norm()));

  /// ## Spatial cross products (slides 53-57)
  ///
  /// For a spatial vector \f$X = [x; y]\f$ (slide 53) the spatial cross product, acting on
  /// motion vectors, and its companion acting on forces (slide 55):
  /// \f[ \tilde X = \begin{pmatrix} \tilde x & 0 \\ \tilde y & \tilde x \end{pmatrix},
  ///     \qquad \bar X = -\tilde X^* = \begin{pmatrix} \tilde x & \tilde y \\ 0 & \tilde x
  ///     \end{pmatrix} . \f]
  /// Unlike the 3D case \f$\tilde X\f$ is not skew-symmetric (slide 55), but it keeps the
  /// identities of slide 54: \f$\tilde X X = 0\f$, \f$\tilde X Y = -\tilde Y X\f$, Jacobi
  /// \f$\tilde X \tilde Y Z + \tilde Y \tilde Z X + \tilde Z \tilde X Y = 0\f$, and the
  /// commutator \f$(\tilde X Y)^\sim = \tilde X \tilde Y - \tilde Y \tilde X\f$ (it is the Lie
  /// bracket, slide 63). Because \f$\bar X = -\tilde X^*\f$, the two are dual:
  /// \f$f^* (\tilde X Y) = -(\bar X f)^* Y\f$.
  ///
  /// *Now do exercise 1.2* (`soa::ex01::spatial_cross`): \f$\tilde X Y\f$ from the blocks;
  /// then the two that ask you to work it out: *exercise 1.8* (`soa::ex01::force_cross`)
  /// derives \f$\bar X\f$ from the power pairing alone, and *exercise 1.9*
  /// (`soa::ex01::spatial_cross_rank`) predicts the rank of \f$\tilde X\f$.
  checks.section("Spatial cross products (slides 53-57)");
  const soa::Velocity X(Vec3d(0.5, -1.0, 0.25), Vec3d(1.5, 0.3, -0.7));
  const soa::Velocity Y(Vec3d(-0.2, 0.8, 1.1), Vec3d(0.4, -0.9, 0.6));
  const soa::Velocity Z(Vec3d(1.0, 0.1, -0.6), Vec3d(-0.3, 0.2, 0.9));
  const Mat6d Xt = soa::tilde(X), Yt = soa::tilde(Y), Zt = soa::tilde(Z);
  const double s6 = X.vector().norm() * Y.vector().norm();
  checks.check("X~ Y = cross(X, Y)", (Xt * Y.vector() - soa::cross(X, Y).vector()).norm(),
               tol(8, s6));
  checks.check("X~ X = 0", (Xt * X.vector()).norm(), tol(8, X.vector().squaredNorm()));
  checks.check("X~ Y = -Y~ X", (Xt * Y.vector() + Yt * X.vector()).norm(), tol(8, s6));
  checks.check("Jacobi: X~Y~Z + Y~Z~X + Z~X~Y = 0",
               (Xt * Yt * Z.vector() + Yt * Zt * X.vector() + Zt * Xt * Y.vector()).norm(),
               tol(32, s6 * Z.vector().norm()));
  checks.check("commutator: (X~Y)~ = X~Y~ - Y~X~",
               (soa::tilde(soa::cross(X, Y)) - (Xt * Yt - Yt * Xt)).norm(), tol(32, s6));
  Mat6d X_bar_by_hand = Mat6d::Zero();
  X_bar_by_hand.topLeftCorner<3, 3>() = soa::tilde<double>(X.angular());
  X_bar_by_hand.bottomRightCorner<3, 3>() = soa::tilde<double>(X.angular());
  X_bar_by_hand.topRightCorner<3, 3>() = soa::tilde<double>(X.linear());
  checks.check("X_bar = -X~* = [x~ y~; 0 x~]", (soa::bar(X) - X_bar_by_hand).norm(), 0.0);
  checks.check("duality: f*(X~ Y) = -(X_bar f)* Y",
               std::abs(soa::dot(f_B, soa::cross(X, Y)) + soa::dot(soa::cross_bar(X, f_B), Y)),
               tol(32, s6 * f_B.vector().norm()));

  /// For points x, y of one rigid body, with \f$V(y) = \phi^*(x,y)\, V(x)\f$ (slide 56):
  /// \f[ \phi^*(x,y)\, \tilde V(x) = \tilde V(y)\, \phi^*(x,y), \qquad
  ///     \bar V(x)\, \phi(x,y) = \phi(x,y)\, \bar V(y), \f]
  /// that is \f$[\phi^*(x,y) X]^\sim = \phi^*(x,y)\, \tilde X\, \phi^{-*}(x,y)\f$ for any
  /// \f$X\f$ (slide 57): moving the vector moves its cross product. (\f$\phi^*\f$ is the
  /// adjoint map of the Lie group SE(3), slide 63.) Checked with the rotations shown, for
  /// x = A and y = B.
  const Mat6d phi = phi_AB.matrix();
  const soa::Velocity V_y = phi_AB.transpose_apply(V_A);
  checks.check("phi*(x,y) V~(x) = V~(y) phi*(x,y)",
               (phi.transpose() * soa::tilde(V_A) - soa::tilde(V_y) * phi.transpose()).norm(),
               tol(32, phi.squaredNorm() * V_A.vector().norm()));
  checks.check("V_bar(x) phi(x,y) = phi(x,y) V_bar(y)",
               (soa::bar(V_A) * phi - phi * soa::bar(V_y)).norm(),
               tol(32, phi.squaredNorm() * V_A.vector().norm()));

  /// ## Spatial accelerations and the Coriolis terms (slides 59-61)
  ///
  /// The spatial acceleration is the derivative of a spatial velocity in a chosen frame H
  /// (slide 59): \f$\alpha_H(F,G) = {}^H\frac{d}{dt}\, V(F,G)\f$, usually H = the inertial
  /// frame, the "from" frame F or the "to" frame G. Differentiating the propagation
  /// \f$V(A,C) = \phi^*(B,C)\, V(A,B) + V(B,C)\f$ in H (slide 61):
  /// \f[ \alpha_H(A,C) = \phi^*(B,C)\, \alpha_H(A,B) + \alpha_H(B,C) + a_H, \qquad
  ///     a_H = \Big({}^H\frac{d}{dt}\, \phi^*(B,C)\Big)\, V(A,B) . \f]
  /// Only \f$l = l(B,C)\f$ varies in \f$\phi^*(B,C) = \begin{pmatrix} I & 0 \\ -\tilde l & I
  /// \end{pmatrix}\f$, so with \f$V(A,B) = [\omega_1; v_1]\f$, \f$V(B,C) = [\omega_2; v_2]\f$
  /// the Coriolis term has only a linear part:
  /// \f[ a_H = \begin{pmatrix} 0 \\ -\big({}^H\dot l\big)^\sim \omega_1 \end{pmatrix}
  ///     = \begin{pmatrix} 0 \\ \omega_1 \times {}^H\dot l \end{pmatrix},
  ///     \qquad {}^H\dot l = {}^H\frac{d}{dt}\, l(B,C) . \f]
  /// The derivative of \f$l(B,C)\f$ in each frame follows from slides 33 and 35:
  /// - H = B: \f${}^B\dot l = v(B,C) = v_2\f$ by definition, so \f$a_B = [0;\ \omega_1 \times
  ///   v_2]\f$;
  /// - H = A: \f${}^A\dot l = {}^B\dot l + \omega(A,B) \times l = v_2 + \omega_1 \times l =
  ///   v(A,C) - v(A,B)\f$ (slide 36), so \f$a_A = [0;\ \omega_1 \times (\omega_1 \times l +
  ///   v_2)]\f$;
  /// - H = C: \f${}^C\dot l = {}^B\dot l + \omega(C,B) \times l = v_2 - \omega_2 \times l\f$,
  ///   so \f$a_C = [0;\ \omega_1 \times (v_2 - \omega_2 \times l)]\f$.
  ///
  /// Different choices of H change only the Coriolis term (slide 60). The library has these
  /// results as soa::coriolis(H, V(A,B), V(B,C), l(B,C)), all vectors in one frame. Each is
  /// checked against finite differences: every velocity of the motion is expressed in
  /// H-coordinates as a function of time, differentiated, and brought back to C-coordinates.
  checks.section("Spatial accelerations and Coriolis terms (slides 59-61)");
  const auto R_HC = [&](DerivativeFrame H, double t) -> Mat3d {
    switch (H) {
      case DerivativeFrame::A:
        return AB.R(t) * BC.R(t);
      case DerivativeFrame::B:
        return BC.R(t);
      default:
        return Mat3d::Identity();
    }
  };
  // The three velocities in C-coordinates, as functions of time.
  const auto V_AB_at = [&](double t) { return rotated(BC.R(t).transpose(), AB.V(t)); };
  const auto V_BC_at = [&](double t) { return BC.V(t); };
  const auto V_AC_at = [&](double t) {
    return soa::Phi(BC.T(t)).transpose_apply(AB.V(t)) + BC.V(t);
  };
  // C-coordinates of H d/dt V, for V given in C-coordinates.
  const auto alpha = [&](DerivativeFrame H, const auto& V_at) -> soa::Acceleration {
    const Vec6d d =
        derivative([&](double t) -> Vec6d { return rotated(R_HC(H, t), V_at(t)).vector(); }, t0);
    return rotated(R_HC(H, t0).transpose(), soa::Acceleration(d));
  };
  const soa::Velocity V1 = V_AB_at(t0), V2 = V_BC_at(t0);
  const Vec3d l_BC_C = R_BC.transpose() * l_BC;
  const soa::Phi phi_BC_free = soa::Phi::translation(l_BC_C);  // coordinate-free, in C
  const char* names[] = {"A", "B", "C"};
  for (const DerivativeFrame H : {DerivativeFrame::A, DerivativeFrame::B, DerivativeFrame::C}) {
    const soa::Acceleration a_H = soa::coriolis(H, V1, V2, l_BC_C);
    const soa::Acceleration a_fd =
        alpha(H, V_AC_at) - phi_BC_free.transpose_apply(alpha(H, V_AB_at)) - alpha(H, V_BC_at);
    show(std::string("a_") + names[int(H)], a_H.vector());
    checks.check(std::string("a_") + names[int(H)] +
                     ": alpha_H(A,C) - phi* alpha_H(A,B) - alpha_H(B,C), finite differences",
                 (a_H - a_fd).vector().norm(), fd_tol(V_AC_C.vector().squaredNorm()));
  }

  /// ## The Lie group connection: SE(3) (slide 63)
  ///
  /// Rotations form the Lie group SO(3) and poses \f${}^x T_y = (R, l)\f$, the homogeneous
  /// transforms of slide 23, the Lie group SE(3); the slide says how the spatial notation
  /// sits in it. A twist \f$\xi = [\omega; v]\f$ (a motion vector, angular part first) is an
  /// element of its Lie algebra se(3) through the 4x4
  /// \f[ \hat\xi = \begin{pmatrix} \tilde\omega & v \\ 0 & 0 \end{pmatrix} . \f]
  ///
  /// **Ad is \f$\phi^*\f$.** The adjoint of SE(3) is defined by
  /// \f$T\hat\xi T^{-1} = (\mathrm{Ad}(T)\,\xi)^\wedge\f$. Multiplying the blocks with
  /// \f$T^{-1} = (R^*, -R^* l)\f$:
  /// \f$T\hat\xi T^{-1} = \begin{pmatrix} R\tilde\omega R^* & Rv - R\tilde\omega R^* l \\ 0 & 0
  /// \end{pmatrix}\f$, and \f$R\tilde\omega R^* = (R\omega)^\sim\f$ (slide 8), so
  /// \f[ \mathrm{Ad}({}^x T_y) = \begin{pmatrix} R & 0 \\ \tilde l R & R \end{pmatrix}
  ///     = \phi^*(y,x) \f]
  /// with the rotations shown (slide 43): \f$\phi(y,x) = \phi^{-1}(x,y)\f$ is the pair
  /// \f$(R^*, -R^* l)\f$, and its transpose is the matrix above. Ad takes a motion at y in
  /// y-coordinates to the same rigid motion referred to x, in x-coordinates, which is slide
  /// 41's \f$V(x) = \phi^*(y,x)\,V(y)\f$. Ad is a homomorphism,
  /// \f$\mathrm{Ad}(T_1T_2) = \mathrm{Ad}(T_1)\mathrm{Ad}(T_2)\f$ (from the definition), which
  /// is \f$\phi(x,z) = \phi(x,y)\phi(y,z)\f$ of slide 44 again.
  ///
  /// **ad is the spatial cross product.** The Lie bracket of se(3) is the matrix commutator,
  /// \f$(\mathrm{ad}(X)\,Y)^\wedge = [\hat X, \hat Y] = \hat X\hat Y - \hat Y\hat X\f$. For
  /// \f$X = [\omega_1; v_1]\f$, \f$Y = [\omega_2; v_2]\f$ the blocks give
  /// \f[ [\hat X, \hat Y] = \begin{pmatrix} \tilde\omega_1\tilde\omega_2 -
  ///     \tilde\omega_2\tilde\omega_1 & \omega_1 \times v_2 - \omega_2 \times v_1 \\ 0 & 0
  ///     \end{pmatrix} = \begin{pmatrix} (\omega_1 \times \omega_2)^\sim & \omega_1 \times v_2
  ///     + v_1 \times \omega_2 \\ 0 & 0 \end{pmatrix} = (\tilde X Y)^\wedge \f]
  /// (the 3D commutator \f$\tilde a\tilde b - \tilde b\tilde a = (a \times b)^\sim\f$ of slide
  /// 8), so \f$\mathrm{ad}(X) = \tilde X\f$, slide 53's spatial cross product. It is also the
  /// derivative of Ad at the identity: with \f$T(s) = \exp(s\hat X)\f$,
  /// \f$R(s) = I + s\tilde\omega_1 + O(s^2)\f$ and \f$l(s) = s v_1 + O(s^2)\f$, so
  /// \f$\frac{d}{ds}\mathrm{Ad}(T(s))|_{s=0} = \begin{pmatrix} \tilde\omega_1 & 0
  /// \\ \tilde v_1 & \tilde\omega_1 \end{pmatrix} = \tilde X\f$.
  ///
  /// **The identities of slide 54, proved.** Because \f$\hat{\ }\f$ is linear and one-to-one
  /// and turns \f$\tilde X Y\f$ into \f$[\hat X, \hat Y]\f$, every identity of commutators of
  /// matrices holds for the spatial cross product:
  /// - \f$\tilde X X = 0\f$ and \f$\tilde X Y = -\tilde Y X\f$: \f$[A, A] = 0\f$,
  ///   \f$[A, B] = -[B, A]\f$.
  /// - Jacobi: expanding the twelve products,
  ///   \f$[A,[B,C]] + [B,[C,A]] + [C,[A,B]] = ABC - ACB - BCA + CBA + BCA - BAC - CAB + ACB +
  ///   CAB - CBA - ABC + BAC = 0\f$, so
  ///   \f$\tilde X\tilde Y Z + \tilde Y\tilde Z X + \tilde Z\tilde X Y = 0\f$.
  /// - The commutator identity: by Jacobi and antisymmetry,
  ///   \f$[[A,B],C] = -[C,[A,B]] = [A,[B,C]] + [B,[C,A]] = [A,[B,C]] - [B,[A,C]]\f$, that is
  ///   \f$(\tilde X Y)^\sim Z = \tilde X\tilde Y Z - \tilde Y\tilde X Z\f$ for every Z:
  ///   \f$(\tilde X Y)^\sim = \tilde X\tilde Y - \tilde Y\tilde X\f$.
  /// - Slide 57, \f$(\phi^*(y,x) X)^\sim = \phi^*(y,x)\,\tilde X\,\phi^{-*}(y,x)\f$: conjugating
  ///   a commutator by T, \f$T[\hat X, \hat Y]T^{-1} = [T\hat XT^{-1}, T\hat YT^{-1}]\f$, so
  ///   \f$\mathrm{Ad}(T)\,\tilde X Y = (\mathrm{Ad}(T)X)^\sim\,\mathrm{Ad}(T)\,Y\f$ for every Y.
  ///
  /// The numbers below check each on the vectors X, Y, Z of the cross products section
  /// (soa::Ad(), soa::ad(), soa::hat(), soa::vee_se3()).
  checks.section("SE(3): Ad, ad and the bracket (slide 63)");
  const soa::Pose T_xy = T_AB;
  const Mat6d Ad_T = soa::Ad(T_xy);
  const Mat6d phi_star_yx = soa::Phi(T_xy.inverse()).matrix().transpose();
  show("Ad(T_AB)", Ad_T);
  checks.check("Ad(T) = phi*(y,x) = [R 0; l~R R]", (Ad_T - phi_star_yx).norm(),
               tol(8, phi_star_yx.norm()));
  const Eigen::Matrix4d Tm = T_xy.matrix();
  const Eigen::Matrix4d conj = Tm * soa::hat(X) * T_xy.inverse().matrix();
  checks.check("T X^ T^-1 = (Ad(T) X)^", (conj - soa::hat(soa::Velocity(Ad_T * X.vector()))).norm(),
               tol(16, Tm.squaredNorm() * X.vector().norm()));
  checks.check("Ad(T1 T2) = Ad(T1) Ad(T2)",
               (soa::Ad(T_AB * T_BC) - soa::Ad(T_AB) * soa::Ad(T_BC)).norm(),
               tol(16, soa::Ad(T_AB).norm() * soa::Ad(T_BC).norm()));
  const Eigen::Matrix4d bracket = soa::hat(X) * soa::hat(Y) - soa::hat(Y) * soa::hat(X);
  checks.check("ad(X) = X~ (the spatial cross product)", (soa::ad(X) - Xt).norm(), 0.0);
  checks.check("[X^, Y^] = (X~ Y)^ (ad is the Lie bracket)",
               (bracket - soa::hat(soa::cross(X, Y))).norm(), tol(8, s6));
  {
    // d/ds Ad(exp(s X)) at s = 0, by the central difference of the lesson.
    const Mat6d dAd = derivative(
        [&](double s) -> Mat6d { return soa::Ad(soa::exp_se3(soa::Velocity(s * X.vector()))); },
        0.0);
    checks.check("d/ds Ad(exp(s X)) at s = 0 is X~, finite differences", (dAd - Xt).norm(),
                 fd_tol(X.vector().squaredNorm()));
  }
  checks.check("slide 57 from the bracket: Ad(T) X~ Y = (Ad(T) X)~ Ad(T) Y",
               (Ad_T * soa::cross(X, Y).vector() -
                soa::tilde(soa::Velocity(Ad_T * X.vector())) * (Ad_T * Y.vector()))
                   .norm(),
               tol(32, Ad_T.squaredNorm() * s6));

  /// **The exponential and the logarithm.** The series of \f$\exp(\hat\xi)\f$ sums in closed
  /// form because \f$\tilde\omega^3 = -\theta^2\tilde\omega\f$ (\f$\theta = |\omega|\f$):
  /// \f[ \exp(\hat\xi) = \big(\exp(\tilde\omega),\ J(\omega)\,v\big), \qquad
  ///     J(\omega) = \sum_{k \ge 0} \frac{\tilde\omega^k}{(k+1)!} = I + g_2\,\tilde\omega +
  ///     g_3\,\tilde\omega^2, \f]
  /// \f[ g_2 = \frac{1 - \cos\theta}{\theta^2}, \qquad g_3 = \frac{\theta - \sin\theta}
  ///     {\theta^3}, \f]
  /// and \f$\exp(\tilde\omega) = I + g_1\tilde\omega + g_2\tilde\omega^2\f$ is Rodrigues'
  /// formula of slide 19. \f$J\f$ is the left Jacobian of SO(3). The logarithm inverts it:
  /// \f$\omega = \log(R)\f$ (soa::log_so3(), \f$\theta \in [0, \pi]\f$) and
  /// \f$v = J^{-1}(\omega)\, l\f$ with
  /// \f[ J^{-1} = I - \tfrac12\tilde\omega + \frac{1}{\theta^2}\Big(1 - \frac{\theta\sin\theta}
  ///     {2(1 - \cos\theta)}\Big)\tilde\omega^2 , \f]
  /// regular on \f$[0, \pi]\f$. As \f$\theta \to 0\f$ the quotients \f$g_2, g_3\f$ of the
  /// closed forms cancel catastrophically (\f$\theta - \sin\theta\f$ loses all digits below
  /// \f$\theta \approx 10^{-5}\f$), exactly like the SO(3) ones: soa::g_series() sums their
  /// series for \f$\theta < 2\f$, where its terms fall fast, and uses the recurrence
  /// \f$g_{n+2} = (1/n! - g_n)/\theta^2\f$ above. Near \f$\theta = \pi\f$ the logarithm
  /// inherits soa::log_so3()'s branch for the axis. Finally \f$\mathrm{Ad}\f$ and
  /// \f$\exp\f$ commute with ad: \f$\mathrm{Ad}(\exp(\hat\xi)) = \exp(\mathrm{ad}(\xi)) =
  /// \exp(\tilde\xi)\f$, the 6x6 exponential, since both sides solve
  /// \f$\frac{d}{ds}M(s) = \tilde\xi M(s)\f$, \f$M(0) = I\f$ (the derivative of
  /// \f$\mathrm{Ad}(\exp(s\hat\xi))\f$ is \f$\mathrm{ad}\f$ at the identity, carried along by
  /// the homomorphism). API: soa::exp_se3(), soa::log_se3(), soa::dexp_so3().
  ///
  /// *Now do exercise 1.7* (`soa::ex01::exp_twist`): the closed form of \f$\exp(\hat\xi)\f$,
  /// accurate at every angle down to \f$\theta = 0\f$.
  checks.section("SE(3): exponential and logarithm (slide 63)");
  const soa::Velocity xi(Vec3d(0.3, -1.2, 0.8), Vec3d(0.5, 0.4, -1.1));
  const soa::Pose E = soa::exp_se3(xi);
  const Eigen::Matrix4d E_dense = soa::hat(xi).exp();
  show("exp(xi)", E.matrix());
  checks.check("exp(xi^) = the 4x4 matrix exponential", (E.matrix() - E_dense).norm(),
               tol(32, E_dense.norm()));
  checks.check("log(exp(xi)) = xi", (soa::log_se3(E).vector() - xi.vector()).norm(),
               tol(32, xi.vector().norm()));
  checks.check("exp(log(T_AB)) = T_AB", (soa::exp_se3(soa::log_se3(T_AB)).matrix() - Tm).norm(),
               tol(64, Tm.norm()));
  checks.check("Ad(exp(xi)) = exp(ad(xi)), the 6x6 matrix exponential",
               (soa::Ad(E) - Mat6d(soa::ad(xi).exp())).norm(), tol(64, soa::Ad(E).norm()));
  {
    // Small angles: theta = 1e-6. The closed form of g3 has no correct digit there; the
    // library's series has them all (g3 -> 1/6).
    const double th = 1e-6;
    const double g3_closed = (th - std::sin(th)) / (th * th * th);
    const double g3_lib = soa::g_series(3, th);
    const double g3_exact = 1.0 / 6.0 - th * th / 120.0;
    std::printf("  theta = 1e-6: g3 closed form %.17g, series %.17g, 1/6 - theta^2/120 %.17g\n",
                g3_closed, g3_lib, g3_exact);
    checks.check("small angle: g3(1e-6) by the series, relative error",
                 std::abs(g3_lib - g3_exact) / g3_exact, tol(4));
    checks.check("small angle: the closed form (theta - sin theta)/theta^3 has lost >= 6 digits",
                 std::abs(g3_closed - g3_exact) / g3_exact > 1e-10);
    const soa::Velocity small(Vec3d(th, -2 * th, 0.5 * th), Vec3d(0.7, -0.2, 0.4));
    const soa::Pose Es = soa::exp_se3(small);
    checks.check("small angle: log(exp(xi)) = xi",
                 (soa::log_se3(Es).vector() - small.vector()).norm(),
                 tol(16, small.vector().norm()));
    // Near pi: theta = pi - 1e-7. The axis comes from the symmetric part of R, its sign from
    // vee(R) = sin(theta) n, of size 1e-7, far above the rounding of R: full precision.
    const Vec3d n = Vec3d(1, 2, -2).normalized();
    const soa::Velocity big(((M_PI - 1e-7) * n).eval(), Vec3d(0.3, 0.1, -0.5));
    checks.check("near pi: log(exp(xi)) = xi (theta = pi - 1e-7)",
                 (soa::log_se3(soa::exp_se3(big)).vector() - big.vector()).norm(),
                 tol(32, big.vector().norm()));
  }

  /// **The derivative of exp.** Differentiating \f$T(t) = \exp(\hat\xi(t))\f$ gives the
  /// right-trivialized rate
  /// \f$\dot T T^{-1} = (\mathrm{dexp}(\xi)\,\dot\xi)^\wedge\f$ with
  /// \f$\mathrm{dexp}(\xi) = \sum_k \tilde\xi^k/(k+1)!\f$ (the 6x6 left Jacobian of SE(3),
  /// soa::dexp_se3(), closed form in its documentation), and the left-trivialized rate
  /// \f$T^{-1}\dot T = (\mathrm{dexp}(-\xi)\,\dot\xi)^\wedge\f$; the two are related by
  /// \f$\mathrm{dexp}(\xi) = \mathrm{Ad}(\exp\hat\xi)\,\mathrm{dexp}(-\xi)\f$.
  ///
  /// **Twists and the course's spatial velocity.** For the moving frame B of the concrete
  /// motion, \f$T(t) = {}^A T_B(t) = (R, l)\f$:
  /// \f[ T^{-1}\dot T = \begin{pmatrix} R^*\dot R & R^*\dot l \\ 0 & 0 \end{pmatrix}
  ///     = \big({}^B V(A,B)\big)^\wedge, \qquad
  ///     \dot T T^{-1} = \begin{pmatrix} \dot R R^* & \dot l - \dot R R^* l \\ 0 & 0
  ///     \end{pmatrix} = \big(\mathrm{Ad}(T)\,{}^B V(A,B)\big)^\wedge . \f]
  /// The left-trivialized ("body") twist is the course's spatial velocity
  /// \f$V(A,B) = [\omega; v]\f$ of B's origin, in B-coordinates. The right-trivialized
  /// ("spatial") twist of the robotics literature is \f$\phi^*(B,A)\,V(A,B)\f$: the same
  /// rigid motion referred to the body point at A's origin, whose linear part
  /// \f$\dot l + l \times \omega\f$ is not the course's \f${}^A v(A,B) = \dot l\f$. The course
  /// always refers a velocity to the point it is the velocity of and writes it in any frame
  /// (a coordinate-free vector); the twists fix the point and the frame together, which is
  /// why the slide calls them "closely related to (but not the same as)" the spatial
  /// velocities.
  checks.section("SE(3): derivative of exp, twists and spatial velocities (slide 63)");
  {
    const soa::Velocity xi_dot(Vec3d(-0.4, 0.9, 0.2), Vec3d(1.0, -0.3, 0.6));
    const auto T_of = [&](double s) -> Eigen::Matrix4d {
      return soa::exp_se3(soa::Velocity(xi.vector() + s * xi_dot.vector())).matrix();
    };
    const Eigen::Matrix4d dT = derivative(T_of, 0.0);
    const Vec6d right = soa::vee_se3<double>(Eigen::Matrix4d(dT * E.inverse().matrix())).vector();
    const Vec6d left = soa::vee_se3<double>(Eigen::Matrix4d(E.inverse().matrix() * dT)).vector();
    checks.check("dT T^-1 = (dexp(xi) xi_dot)^, finite differences",
                 (right - soa::dexp_se3(xi) * xi_dot.vector()).norm(),
                 fd_tol(xi_dot.vector().norm() * E_dense.squaredNorm()));
    checks.check("T^-1 dT = (dexp(-xi) xi_dot)^, finite differences",
                 (left - soa::dexp_se3(soa::Velocity(-xi.vector())) * xi_dot.vector()).norm(),
                 fd_tol(xi_dot.vector().norm() * E_dense.squaredNorm()));
    checks.check(
        "dexp(xi) = Ad(exp xi) dexp(-xi)",
        (soa::dexp_se3(xi) - soa::Ad(E) * soa::dexp_se3(soa::Velocity(-xi.vector()))).norm(),
        tol(64, soa::Ad(E).norm() * soa::dexp_se3(xi).norm()));

    const Eigen::Matrix4d dT_AB =
        derivative([&](double t) -> Eigen::Matrix4d { return AB.T(t).matrix(); }, t0);
    const soa::Velocity V_AB_B = AB.V(t0);  // the course's V(A,B), B-coordinates
    const soa::Velocity body = soa::vee_se3<double>(Eigen::Matrix4d(Tm.inverse() * dT_AB));
    const soa::Velocity spatial = soa::vee_se3<double>(Eigen::Matrix4d(dT_AB * Tm.inverse()));
    const double s_v = V_AB_B.vector().norm() * (1 + l_AB.norm());
    show("^B V(A,B)", V_AB_B.vector());
    show("spatial twist", spatial.vector());
    checks.check("T^-1 dT = ^B V(A,B): the body twist is the course's velocity",
                 (body.vector() - V_AB_B.vector()).norm(), fd_tol(s_v));
    checks.check(
        "dT T^-1 = phi*(B,A) V(A,B): the spatial twist",
        (spatial.vector() - soa::Phi(T_AB.inverse()).transpose_apply(V_AB_B).vector()).norm(),
        fd_tol(s_v));
    const Vec3d l_dot = AB.p1 + 2.0 * t0 * AB.p2, w_A = R_AB * V_AB_B.angular();
    checks.check("its linear part is l_dot + l x w, not the course's ^A v(A,B) = l_dot",
                 (Vec3d(spatial.linear()) - (l_dot + l_AB.cross(w_A))).norm(), fd_tol(s_v));
  }

  /// ## Spatial inertia (slides 64-69)
  ///
  /// A body has a mass \f$m\f$, a first moment \f$m\,p(x)\f$ with \f$p(x) = l(x, C)\f$ from
  /// the reference point x to the centre of mass C, and an inertia \f$J(x)\f$. The parallel
  /// axis theorem moves the 3x3 inertia from the centre of mass (slide 66):
  /// \f[ J(x) = J(C) - m\, \tilde p(x)\, \tilde p(x) = J(C) + m\,(p^* p\, I - p\, p^*) . \f]
  /// At C the kinetic energy separates into angular and linear parts (slide 67),
  /// \f$\tfrac12 \omega^* J(C)\, \omega + \tfrac12 m\, v^*(C)\, v(C) = \tfrac12 V^*(C)\, M(C)\,
  /// V(C)\f$ with \f$M(C) = \mathrm{diag}(J(C), m I)\f$. Moving \f$V(C) = \phi^*(x,C)\,
  /// V(x)\f$ gives the spatial inertia about any point (slides 68-69):
  /// \f[ M(x) = \phi(x,C)\, M(C)\, \phi^*(x,C) = \begin{pmatrix} J(x) & m\,\tilde p(x)
  ///     \\ -m\,\tilde p(x) & m I \end{pmatrix}, \f]
  /// symmetric and positive definite for a real body. The body below has its frame x
  /// parallel to its centre-of-mass frame C (no rotation between them).
  checks.section("Spatial inertia (slides 64-69)");
  const double m = 2.5;
  const Vec3d p(0.3, -0.2, 0.45);  // p(x) = l(x, C)
  const Mat3d Q = soa::exp_so3(Vec3d(0.4, 0.2, -0.5));
  const Mat3d J_principal = Q * Vec3d(0.8, 1.1, 1.5).asDiagonal() * Q.transpose();
  const Mat3d J_C = (J_principal + J_principal.transpose()) / 2;  // symmetric to the last bit
  const soa::SpatialInertia M_x = soa::SpatialInertia::from_cm(m, p, J_C);
  const soa::SpatialInertia M_C(m, Vec3d::Zero(), J_C);
  const soa::Phi phi_xC = soa::Phi::translation(p);
  checks.check(
      "J(x) = J(C) - m p~ p~ = J(C) + m (p*p I - p p*)",
      (M_x.J() - (J_C + m * (p.squaredNorm() * Mat3d::Identity() - p * p.transpose()))).norm(),
      tol(16, J_C.norm() + m * p.squaredNorm()));
  const soa::Velocity V_x(Vec3d(0.6, -0.3, 0.9), Vec3d(0.2, 1.1, -0.4));
  const soa::Velocity V_C = phi_xC.transpose_apply(V_x);
  const Vec3d w = V_x.angular();
  const double ke_split = 0.5 * w.dot(J_C * w) + 0.5 * m * Vec3d(V_C.linear()).squaredNorm();
  checks.check("1/2 w* J(C) w + 1/2 m v(C)^2 = 1/2 V*(C) M(C) V(C)",
               std::abs(ke_split - 0.5 * V_C.vector().dot(M_C.matrix() * V_C.vector())),
               tol(16, ke_split));
  const Mat6d M_x_6x6 = phi_xC.matrix() * M_C.matrix() * phi_xC.matrix().transpose();
  show("M(x)", M_x_6x6);
  checks.check("M(x) = phi(x,C) M(C) phi*(x,C) = [J m p~; -m p~ m I]",
               (M_x.matrix() - M_x_6x6).norm(), tol(16, M_x_6x6.norm()));
  const Eigen::SelfAdjointEigenSolver<Mat6d> eig(M_x.matrix());
  show("eig M(x)", eig.eigenvalues());
  checks.check("M(x) = M*(x)", (M_x.matrix() - M_x.matrix().transpose()).norm(),
               tol(4, M_x_6x6.norm()));
  checks.check("M(x) positive definite: smallest eigenvalue > 0", eig.eigenvalues().minCoeff() > 0);

  /// ## The parallel axis theorem for spatial inertias and kinetic energy (slides 70-73)
  ///
  /// The spatial parallel axis theorem moves the spatial inertia between any two points
  /// (slide 70); neither needs to be the centre of mass (slide 71):
  /// \f[ M(y) = \phi(y,x)\, M(x)\, \phi^*(y,x) . \f]
  /// Its verification on slide 70 is \f$\phi(y,C) = \phi(y,x)\, \phi(x,C)\f$: moving
  /// \f$M(C)\f$ to y directly or by way of x gives the same inertia. soa::transform() does it
  /// on the ten numbers \f$(m, m p, J)\f$. The kinetic energy is
  /// the same about every point of the body (slides 72-73):
  /// \f$\tfrac12 V^*(x) M(x) V(x) = \tfrac12 V^*(x)\phi(x,y) M(y) \phi^*(x,y) V(x) =
  /// \tfrac12 V^*(y) M(y) V(y)\f$.
  ///
  /// *Now do exercise 1.3* (`soa::ex01::parallel_axis`): the theorem on the ten numbers
  /// \f$(m, m p, J)\f$, through the centre of mass; and *exercise 1.5*
  /// (`soa::ex01::kinetic_energy`): the kinetic energy about x from the same ten numbers,
  /// without the 6x6.
  checks.section("Parallel axis theorem and kinetic energy (slides 70-73)");
  const soa::Phi phi_yx(soa::exp_so3(Vec3d(-0.6, 0.3, 0.2)), Vec3d(0.7, 0.1, -0.5));
  const soa::SpatialInertia M_y = soa::transform(phi_yx, M_x);
  checks.check("M(y) = phi(y,x) M(x) phi*(y,x), 6x6",
               (M_y.matrix() - phi_yx.matrix() * M_x.matrix() * phi_yx.matrix().transpose()).norm(),
               tol(32, M_y.matrix().norm()));
  checks.check("M(y) = phi(y,C) M(C) phi*(y,C): C -> y = C -> x -> y",
               (M_y.matrix() - soa::transform(phi_yx * phi_xC, M_C).matrix()).norm(),
               tol(32, M_y.matrix().norm()));
  const soa::Velocity V_y_body = phi_yx.inverse().transpose_apply(V_x);
  const double ke_x = M_x.kinetic_energy(V_x), ke_y = M_y.kinetic_energy(V_y_body),
               ke_C = M_C.kinetic_energy(V_C);
  std::printf("  kinetic energy about x %.15f, y %.15f, C %.15f\n", ke_x, ke_y, ke_C);
  checks.check("kinetic energy about x = about y", std::abs(ke_x - ke_y), tol(32, ke_x));
  checks.check("kinetic energy about x = about C", std::abs(ke_x - ke_C), tol(32, ke_x));

  /// The inertia of a collection of bodies about a point B is the sum of their inertias
  /// moved to B (slide 74): \f$M(B) = \sum_i \phi(B, i)\, M(i)\, \phi^*(B, i)\f$. Its mass is
  /// the total mass and its first moment puts the centre of mass at the mass-weighted mean.
  const soa::Phi phi_B2body(soa::exp_so3(Vec3d(0.1, 0.9, -0.2)), Vec3d(1.2, -0.4, 0.3));
  const soa::SpatialInertia M2 = soa::SpatialInertia::from_cm(
      1.5, Vec3d(0.1, 0.1, -0.2), Mat3d(Vec3d(0.3, 0.4, 0.5).asDiagonal()));
  const soa::SpatialInertia M_total = M_x + soa::transform(phi_B2body, M2);
  const Vec3d cm_expected = (m * p + 1.5 * (phi_B2body.l() + phi_B2body.R() * M2.p())) / (m + 1.5);
  checks.check("composite: mass m1 + m2, centre of mass at the weighted mean",
               std::abs(M_total.mass() - (m + 1.5)) + (M_total.p() - cm_expected).norm(),
               tol(16, cm_expected.norm() + m));

  /// ## Spatial momentum (slides 76-77)
  ///
  /// About the centre of mass the spatial momentum has the familiar parts (slide 76),
  /// \f$h(C) = [J(C)\, \omega;\ m\, v(C)] = M(C)\, V(C)\f$; about any point
  /// \f$h(x) = M(x)\, V(x)\f$. Momentum is a force-like vector: it moves with \f$\phi\f$
  /// (slides 76-77),
  /// \f[ h(x) = \phi(x,C)\, h(C), \qquad h(y) = \phi(y,x)\, h(x), \f]
  /// because \f$M(x) V(x) = \phi(x,C) M(C) \phi^*(x,C) V(x) = \phi(x,C) M(C) V(C)\f$. Paired
  /// with the velocity it gives twice the kinetic energy, \f$h^*(x)\, V(x) = 2 T\f$.
  checks.section("Spatial momentum (slides 76-77)");
  const soa::Momentum h_C = M_C * V_C;
  const soa::Momentum h_x = M_x * V_x;
  show("h(x)", h_x.vector());
  checks.check("h(C) = [J(C) w; m v(C)]",
               (h_C.vector() - (Vec6d() << J_C * w, m * V_C.linear()).finished()).norm(),
               tol(16, h_C.vector().norm()));
  checks.check("h(x) = phi(x,C) h(C)", (h_x - phi_xC.apply(h_C)).vector().norm(),
               tol(16, h_x.vector().norm()));
  checks.check("h(y) = phi(y,x) h(x)", ((M_y * V_y_body) - phi_yx.apply(h_x)).vector().norm(),
               tol(32, h_x.vector().norm()));
  checks.check("h*(x) V(x) = 2 T", std::abs(soa::dot(h_x, V_x) - 2 * ke_x), tol(16, ke_x));

  /// ## What comes next
  ///
  /// Lesson 2 writes Newton's and Euler's equations for one rigid body about an arbitrary
  /// point with these tools: \f$f(x) = M(x)\, \alpha(x) + b(x)\f$.
  return checks.finish();
}
