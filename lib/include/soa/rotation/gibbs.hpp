/// \file
/// Rodrigues (Gibbs) parameters (slides 18-20).
#pragma once

#include <cmath>
#include <string>

#include "soa/rotation/quaternion.hpp"

namespace soa {

/// Rodrigues/Gibbs parameters \f$g = \tan(\theta/2)\, n = q / q_0\f$ (slide 20): three
/// numbers, global but singular at \f$\theta = \pi\f$ (slide 18), where \f$|g| \to \infty\f$.
///
/// Singularity (documented): from_matrix() and from_quaternion() refuse, with soa::Error,
/// a rotation whose \f$|q_0| < \sqrt{\varepsilon}\f$ (\f$\pi - \theta \lesssim 2\sqrt
/// \varepsilon\f$, \f$|g| \gtrsim 1/\sqrt\varepsilon\f$): beyond that the parameters would
/// carry fewer than half the digits of the rotation. Re-centre the coordinates (slide 20).
template <class S>
struct GibbsT {
  Vec3<S> g = Vec3<S>::Zero();  ///< \f$\tan(\theta/2)\, n\f$

  /// \f${}^A R_B = I + \frac{2}{1 + g^* g} (\tilde g + \tilde g \tilde g)\f$.
  Mat3<S> matrix() const {
    const Mat3<S> G = tilde(g);
    return Mat3<S>::Identity() + (S(2) / (S(1) + g.squaredNorm())) * (G + G * G);
  }
  /// \f$[q; q_0] = [g; 1] / \sqrt{1 + g^* g}\f$.
  UnitQuaternionT<S> quaternion() const { return UnitQuaternionT<S>(g, S(1)); }

  static GibbsT from_quaternion(const UnitQuaternionT<S>& q) {
    if (std::abs(q.q0()) < std::sqrt(eps<S>()))
      throw Error("Gibbs parameters: undefined at theta = pi (|q0| = " +
                  std::to_string(double(std::abs(q.q0()))) + ")");
    return {q.q() / q.q0()};
  }
  static GibbsT from_matrix(const Mat3<S>& R) {
    return from_quaternion(UnitQuaternionT<S>::from_matrix(R));
  }
};
using Gibbs = GibbsT<double>;

}  // namespace soa
