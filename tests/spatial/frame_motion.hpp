/// \file
/// Smooth random motions of frames, with exact first derivatives by the product rule: the
/// explicit kinematics against which the velocity and acceleration propagation formulas of
/// lesson 1 (slides 40-46, 59-61) and the free-body equations of lesson 2 are tested.
///
/// Nothing here uses a spatial-vector formula: angular velocities come from
/// \f$\tilde\omega = \dot R R^*\f$ and linear velocities from differentiating positions.
#pragma once

#include <cmath>

#include "spatial_support.hpp"

namespace soa::test {

/// A smooth scalar function of time, \f$f(t) = a + b\,t + c \sin(w t + d)\f$, and its rate.
struct Wave {
  double a = 0, b = 0, c = 0, w = 1, d = 0;

  double operator()(double t) const { return a + b * t + c * std::sin(w * t + d); }
  double rate(double t) const { return b + c * w * std::cos(w * t + d); }
  static Wave random(Random<double>& r) {
    return {r.normal(), r.normal(), r.normal(), r.uniform(0.5, 2), r.uniform(-3, 3)};
  }
};

/// The motion of a frame G relative to a frame F, in F coordinates: attitude
/// \f${}^F R_G(t) = \exp(f_1 \tilde n_1) \exp(f_2 \tilde n_2) \exp(f_3 \tilde n_3)\f$ about
/// fixed random axes, and origin \f${}^F l(F, G)(t) = (g_1, g_2, g_3)\f$.
struct RelativeMotion {
  Vec3<double> n[3];
  Wave f[3], g[3];

  static RelativeMotion random(Random<double>& r) {
    RelativeMotion m;
    for (int i = 0; i < 3; ++i) {
      m.n[i] = r.unit3();
      m.f[i] = Wave::random(r);
      m.g[i] = Wave::random(r);
    }
    return m;
  }
  /// \f${}^F R_G(t)\f$.
  Mat3<double> R(double t) const {
    Mat3<double> R = Mat3<double>::Identity();
    for (int i = 0; i < 3; ++i) R = R * exp_so3<double>(f[i](t) * n[i]);
    return R;
  }
  /// \f$\frac{d}{dt}{}^F R_G\f$: the product rule over the three factors, with
  /// \f$\frac{d}{dt}\exp(f \tilde n) = \dot f\, \tilde n \exp(f\tilde n)\f$.
  Mat3<double> R_dot(double t) const {
    Mat3<double> sum = Mat3<double>::Zero();
    for (int k = 0; k < 3; ++k) {
      Mat3<double> P = Mat3<double>::Identity();
      for (int i = 0; i < 3; ++i) {
        const Mat3<double> E = exp_so3<double>(f[i](t) * n[i]);
        P = P * (i == k ? Mat3<double>(f[i].rate(t) * tilde<double>(n[i]) * E) : E);
      }
      sum += P;
    }
    return sum;
  }
  /// \f${}^F l(F, G)(t)\f$.
  Vec3<double> l(double t) const { return Vec3<double>(g[0](t), g[1](t), g[2](t)); }
  /// \f$\frac{d}{dt}{}^F l(F, G)\f$, the velocity of G's origin seen from F.
  Vec3<double> l_dot(double t) const {
    return Vec3<double>(g[0].rate(t), g[1].rate(t), g[2].rate(t));
  }
};

/// The step of derivative(): with the fourth-order stencil, truncation
/// \f$h^4 |x^{(5)}| / 30 \approx 3\cdot10^{-16} |x^{(5)}|\f$ (about \f$10^{-12}\f$ for these
/// motions: rates of order 1-10) and rounding \f$\approx 1.5\,\varepsilon |x| / h \approx
/// 10^{-11}\f$.
constexpr double kFdStep = 3e-4;
/// Tolerance of the finite-difference tests, relative to the size of the derivatives:
/// a margin of about 300 over the error of derivative(), and far below the O(1) residual of
/// any wrong term.
constexpr double kFdTolerance = 1e-8;

/// \f$\dot x(t)\f$ by fourth-order central differences of the Eigen-valued function \p x:
/// \f$(8(x(t+h) - x(t-h)) - (x(t+2h) - x(t-2h))) / (12 h)\f$.
template <class F>
auto derivative(F x, double t) {
  const double h = kFdStep;
  return ((8 * (x(t + h) - x(t - h)) - (x(t + 2 * h) - x(t - 2 * h))) / (12 * h)).eval();
}

/// The spatial velocity \f$[\omega; v]\f$ of a frame with attitude \p R, attitude rate
/// \p R_dot and origin velocity \p l_dot, all in the observer's coordinates:
/// \f$\tilde\omega = \dot R R^*\f$ (vee() of it).
inline Velocity velocity_of(const Mat3<double>& R, const Mat3<double>& R_dot,
                            const Vec3<double>& l_dot) {
  return Velocity(vee<double>(R_dot * R.transpose()), l_dot);
}

/// Three frames: B moves relative to the inertial frame A, C moves relative to B. Every
/// vector of a snapshot is written in A coordinates (coordinate-free vectors, one frame).
struct ThreeFrames {
  RelativeMotion AB, BC;

  struct Snapshot {
    Mat3<double> R_AB, R_BC;  ///< \f${}^A R_B\f$, \f${}^B R_C\f$
    Vec3<double> l_AB, l_BC;  ///< \f$l(A,B)\f$, \f$l(B,C)\f$
    Velocity V_AB, V_BC, V_AC, V_BA;
  };

  static ThreeFrames random(Random<double>& r) {
    return {RelativeMotion::random(r), RelativeMotion::random(r)};
  }

  Snapshot at(double t) const {
    Snapshot s;
    const Mat3<double> R1 = AB.R(t), R1_dot = AB.R_dot(t), R2 = BC.R(t), R2_dot = BC.R_dot(t);
    const Vec3<double> l1 = AB.l(t), l1_dot = AB.l_dot(t), l2 = BC.l(t), l2_dot = BC.l_dot(t);
    s.R_AB = R1;
    s.R_BC = R2;
    s.l_AB = l1;
    s.l_BC = R1 * l2;
    // V(A,B): B's attitude and origin differentiated in A.
    s.V_AB = velocity_of(R1, R1_dot, l1_dot);
    // V(B,C): C's attitude and origin differentiated in B (B coordinates), then written in A.
    s.V_BC = rotated(R1, velocity_of(R2, R2_dot, l2_dot));
    // V(A,C): C's attitude R1 R2 and origin l1 + R1 l2, differentiated in A.
    s.V_AC = velocity_of(R1 * R2, R1_dot * R2 + R1 * R2_dot, l1_dot + R1_dot * l2 + R1 * l2_dot);
    // V(B,A): A's attitude R1* and origin l(B,A) = -R1* l1 (B coordinates), differentiated in
    // B, then written in A.
    const Mat3<double> R1t_dot = R1_dot.transpose();
    s.V_BA = rotated(R1, velocity_of(R1.transpose(), R1t_dot,
                                     Vec3<double>(-R1t_dot * l1 - R1.transpose() * l1_dot)));
    return s;
  }
};

}  // namespace soa::test
