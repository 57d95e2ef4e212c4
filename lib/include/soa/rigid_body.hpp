/// \file
/// Equations of motion of one rigid body about an arbitrary body point (lesson 2).
#pragma once

#include <Eigen/Cholesky>

#include "soa/spatial_inertia.hpp"

namespace soa {

/// The gyroscopic term of the equations of motion about a body point x (lesson 2, derived
/// there from \f$f(x) = \phi(x,C)\,f(C)\f$ and the CM form):
/// \f[ b(x) = \begin{pmatrix} \tilde\omega\, J(x)\, \omega \\ m\,\tilde\omega\tilde\omega\,
///     p(x) \end{pmatrix}. \f]
template <class S>
ForceT<S> gyroscopic_force(const SpatialInertiaT<S>& M, const VelocityT<S>& V) {
  const Vec3<S> w = V.angular();
  return ForceT<S>(w.cross(M.J() * w), w.cross(w.cross(M.h())));
}

/// The spatial force needed at x for the acceleration \f$\alpha(x)\f$ (the inertial-frame
/// derivative of \f$V(x)\f$): \f$f(x) = M(x)\,\alpha(x) + b(x)\f$ (lesson 2).
template <class S>
ForceT<S> rigid_body_force(const SpatialInertiaT<S>& M, const VelocityT<S>& V,
                           const AccelerationT<S>& alpha) {
  return M * alpha + gyroscopic_force(M, V);
}

/// The acceleration under the force \f$f(x)\f$: \f$\alpha(x) = M^{-1}(x)\,(f(x) - b(x))\f$.
/// (A single body: the 6x6 Cholesky factor is the clearest way; the chains of later lessons
/// never form it.)
template <class S>
AccelerationT<S> rigid_body_acceleration(const SpatialInertiaT<S>& M, const VelocityT<S>& V,
                                         const ForceT<S>& f) {
  const Vec6<S> rhs = (f - gyroscopic_force(M, V)).vector();
  return AccelerationT<S>(Vec6<S>(M.matrix().llt().solve(rhs)));
}

}  // namespace soa
