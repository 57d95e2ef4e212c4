/// \file
/// Euler angles, the aerospace 3-2-1 (yaw, pitch, roll) sequence (slide 18).
#pragma once

#include <cmath>

#include "soa/error.hpp"
#include "soa/rotation/axis_angle.hpp"

namespace soa {

/// Euler angles in the 3-2-1 sequence: yaw \f$\psi\f$ about z, then pitch \f$\vartheta\f$
/// about the new y, then roll \f$\varphi\f$ about the new x:
/// \f[ {}^A R_B = \exp(\psi\tilde e_3)\, \exp(\vartheta \tilde e_2)\, \exp(\varphi\tilde e_1).
/// \f]
/// Ranges returned by from_matrix(): \f$\psi, \varphi \in (-\pi, \pi]\f$, \f$\vartheta \in
/// [-\pi/2, \pi/2]\f$.
///
/// Gimbal lock (documented fallback): at \f$\vartheta = \pm\pi/2\f$ only \f$\psi \mp
/// \varphi\f$ is defined. When \f$|\cos\vartheta| < 4\varepsilon\f$ (the lock to rounding),
/// from_matrix() sets \f$\varphi = 0\f$ and gives the whole turn about the vertical to
/// \f$\psi\f$. The band is that narrow because setting \f$\varphi = 0\f$ changes \f$R\f$ by
/// about \f$|\cos\vartheta\,\sin\varphi|\f$ (a band of \f$\sqrt\varepsilon\f$ lost half the
/// digits of \f$R\f$ at \f$\vartheta = \pi/2 - 10^{-9}\f$). Everywhere, \f$\psi\f$ is solved
/// last from \f$\exp(\psi\tilde e_3) = R\,\exp(-\varphi\tilde e_1) \exp(-\vartheta\tilde
/// e_2)\f$, so the angles reproduce \f$R\f$ to rounding even near the lock, where
/// \f$\varphi\f$ from atan2 is ill-conditioned.
template <class S>
struct EulerZYXT {
  S yaw = S(0);    ///< \f$\psi\f$, about z
  S pitch = S(0);  ///< \f$\vartheta\f$, about the new y
  S roll = S(0);   ///< \f$\varphi\f$, about the new x

  Mat3<S> matrix() const {
    return exp_so3<S>(yaw * Vec3<S>::UnitZ()) * exp_so3<S>(pitch * Vec3<S>::UnitY()) *
           exp_so3<S>(roll * Vec3<S>::UnitX());
  }

  static EulerZYXT from_matrix(const Mat3<S>& R) {
    using std::atan2;
    require_finite(R, "EulerZYX::from_matrix: R");
    EulerZYXT e;
    const S cos_pitch = std::hypot(R(0, 0), R(1, 0));
    e.pitch = atan2(-R(2, 0), cos_pitch);
    e.roll = cos_pitch < S(4) * eps<S>() ? S(0) : atan2(R(2, 1), R(2, 2));
    const Mat3<S> Rz =
        R * exp_so3<S>(-e.roll * Vec3<S>::UnitX()) * exp_so3<S>(-e.pitch * Vec3<S>::UnitY());
    e.yaw = atan2(Rz(1, 0), Rz(0, 0));
    return e;
  }
};
using EulerZYX = EulerZYXT<double>;

}  // namespace soa
