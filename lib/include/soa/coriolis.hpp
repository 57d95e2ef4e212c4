/// \file
/// Spatial accelerations and their Coriolis terms (slides 59-61).
#pragma once

#include "soa/spatial_vector.hpp"

namespace soa {

/// Which frame H the spatial acceleration \f$\alpha_H(F,G) = {}^H\!\frac{d}{dt} V(F,G)\f$ is
/// differentiated in (slide 59), for the three frames A, B, C of the propagation
/// \f$V(A,C) = \phi^*(B,C)\, V(A,B) + V(B,C)\f$ (slide 61).
enum class DerivativeFrame { A, B, C };

/// The Coriolis term \f$a\f$ of the acceleration propagation (slide 61)
/// \f[ \alpha_H(A,C) = \phi^*(B,C)\,\alpha_H(A,B) + \alpha_H(B,C) + a_H . \f]
/// Derived in lesson 1 (\f$\omega_1, v_1\f$ from \f$V(A,B)\f$, \f$\omega_2, v_2\f$ from
/// \f$V(B,C)\f$, \f$l = l(B,C)\f$, every vector in one common frame, coordinate-free
/// \f$\phi\f$); only the linear part is non-zero (slide 60):
/// \f[ a_A = \begin{pmatrix} 0 \\ \omega_1 \times (v(A,C) - v(A,B)) \end{pmatrix},\quad
///     a_B = \begin{pmatrix} 0 \\ \omega_1 \times v_2 \end{pmatrix},\quad
///     a_C = \begin{pmatrix} 0 \\ \omega_1 \times (v_2 - \omega_2\times l) \end{pmatrix}, \f]
/// with \f$v(A,C) - v(A,B) = \omega_1 \times l + v_2\f$. Checked against finite differences of
/// \f$V(A,C)\f$ in the tests.
template <class S>
AccelerationT<S> coriolis(DerivativeFrame H, const VelocityT<S>& V_AB, const VelocityT<S>& V_BC,
                          const Vec3<S>& l_BC) {
  const Vec3<S> w1 = V_AB.angular(), w2 = V_BC.angular(), v2 = V_BC.linear();
  Vec3<S> lin;
  switch (H) {
    case DerivativeFrame::A:
      lin = w1.cross(w1.cross(l_BC) + v2);
      break;
    case DerivativeFrame::B:
      lin = w1.cross(v2);
      break;
    case DerivativeFrame::C:
    default:
      lin = w1.cross(v2 - w2.cross(l_BC));
      break;
  }
  return AccelerationT<S>(Vec3<S>::Zero(), lin);
}

/// coriolis() with \p l_BC an Eigen expression: forwards to coriolis(..., const Vec3<S>&).
template <class S, class D>
AccelerationT<S> coriolis(DerivativeFrame H, const VelocityT<S>& V_AB, const VelocityT<S>& V_BC,
                          const Eigen::MatrixBase<D>& l_BC) {
  return coriolis(H, V_AB, V_BC, Vec3<S>(l_BC));
}

}  // namespace soa
