/// \file
/// The Cayley map and its parameters (slide 18).
#pragma once

#include "soa/rotation/gibbs.hpp"

namespace soa {

/// \f$\mathrm{cay}(c) = (I - \tfrac12\tilde c)^{-1} (I + \tfrac12\tilde c)\f$, the Cayley map
/// from a 3-vector to a rotation. It agrees with \f$\exp(\tilde c)\f$ to second order in
/// \f$|c|\f$ (a cheap, rational stand-in for the exponential in integrators) and is exactly
/// the rotation by \f$\theta\f$ about \f$n\f$ when \f$c = 2\tan(\theta/2)\, n\f$, i.e.
/// twice the Gibbs vector. Written here in the equivalent closed form
/// \f$I + \frac{4}{4 + c^* c}(\tilde c + \tfrac12 \tilde c\tilde c)\f$.
template <class S>
Mat3<S> cayley(const Vec3<S>& c) {
  return GibbsT<S>{c / S(2)}.matrix();
}

/// cayley() of an Eigen expression: forwards to cayley(const Vec3<S>&).
template <class D>
Mat3<typename D::Scalar> cayley(const Eigen::MatrixBase<D>& c) {
  return cayley(Vec3<typename D::Scalar>(c));
}

/// The inverse Cayley map: \f$\tilde c = 2 (R - I)(R + I)^{-1}\f$, singular where \f$R + I\f$
/// is, at \f$\theta = \pi\f$ (soa::Error as for GibbsT).
template <class S>
Vec3<S> cayley_inverse(const Mat3<S>& R) {
  const UnitQuaternionT<S> q = UnitQuaternionT<S>::from_matrix(R);
  if (std::abs(q.q0()) < std::sqrt(eps<S>()))
    throw Error("Cayley parameters: undefined at theta = pi (|q0| = " +
                std::to_string(double(std::abs(q.q0()))) + ")");
  return S(2) * GibbsT<S>::from_quaternion(q).g;
}

/// cayley_inverse() of an Eigen expression: forwards to cayley_inverse(const Mat3<S>&).
template <class D>
Vec3<typename D::Scalar> cayley_inverse(const Eigen::MatrixBase<D>& R) {
  return cayley_inverse(Mat3<typename D::Scalar>(R));
}

/// Cayley parameters \f$c = 2\tan(\theta/2)\, n\f$: three numbers, non-singular near the
/// identity and not global (slide 18): \f$\theta = \pi\f$ has no parameters.
template <class S>
struct CayleyT {
  Vec3<S> c = Vec3<S>::Zero();

  Mat3<S> matrix() const { return cayley(c); }
  static CayleyT from_matrix(const Mat3<S>& R) { return {cayley_inverse(R)}; }
};
using Cayley = CayleyT<double>;

}  // namespace soa
