/// \file
/// Rotations about a coordinate axis: the fast paths of the recursions. A joint about
/// \f$\pm e_i\f$ with an unrotated placement gives \f$\phi(k,k-1)\f$ a rotation about
/// \f$e_i\f$: only the plane \f$(e_j, e_k)\f$ of it mixes, so products with it drop the exact
/// zeros and ones of \f$R\f$.
#pragma once

#include <type_traits>

#include "soa/types.hpp"

namespace soa::detail {

/// The coordinate axis \f$i\f$ a rotation \f$R\f$ turns about, when it is exactly one (row
/// and column \f$i\f$ of \f$R\f$ are \f$e_i\f$, as joint_phi() makes them for a revolute
/// hinge about a coordinate axis with an identity placement rotation); -1 otherwise.
template <class S>
EIGEN_ALWAYS_INLINE int plane_rotation_axis(const Mat3<S>& R) {
  for (int i = 0; i < 3; ++i) {
    const int j = i == 2 ? 0 : i + 1, m = j == 2 ? 0 : j + 1;
    if (R(i, i) == S(1) && R(j, i) == S(0) && R(m, i) == S(0) && R(i, j) == S(0) && R(i, m) == S(0))
      return i;
  }
  return -1;
}

/// The \f$i\f$ of an offset \f$l = \lambda e_i\f$ (\f$\lambda \ne 0\f$, the other two
/// components exactly zero: a placement along a coordinate axis); -1 otherwise.
template <class S>
EIGEN_ALWAYS_INLINE int coordinate_offset(const Vec3<S>& l) {
  const int i = l[0] != S(0) ? 0 : l[1] != S(0) ? 1 : 2;  // the first non-zero component
  const int j = i == 2 ? 0 : i + 1, m = j == 2 ? 0 : j + 1;
  return l[i] != S(0) && l[j] == S(0) && l[m] == S(0) ? i : -1;
}

/// The \f$i\f$ of an axis that is exactly \f$\pm e_i\f$; -1 otherwise.
template <class S>
EIGEN_ALWAYS_INLINE int coordinate_axis(const Vec3<S>& a) {
  const int i = coordinate_offset(a);
  return i >= 0 && (a[i] == S(1) || a[i] == S(-1)) ? i : -1;
}

/// Component \p i (\f$\ne I\f$) of \f$\lambda e_I \times v\f$ from \f$v_J, v_K\f$:
/// \f$-\lambda v_K\f$ for \f$i = J\f$, \f$\lambda v_J\f$ for \f$i = K\f$ (component
/// \f$I\f$ is zero); the general cross product's value, its product with an exact zero of
/// \f$l\f$ dropped.
template <int I, class S>
EIGEN_ALWAYS_INLINE S axis_cross(int i, S lambda, S vJ, S vK) {
  constexpr int J = I == 2 ? 0 : I + 1;
  return i == J ? -(lambda * vK) : lambda * vJ;
}

/// Calls \p f with std::integral_constant<int, I> for \p axis = I in {0, 1, 2} and returns
/// true; false (f not called) for -1.
template <class F>
EIGEN_ALWAYS_INLINE bool with_plane_axis(int axis, F&& f) {
  switch (axis) {
    case 0:
      f(std::integral_constant<int, 0>());
      return true;
    case 1:
      f(std::integral_constant<int, 1>());
      return true;
    case 2:
      f(std::integral_constant<int, 2>());
      return true;
    default:
      return false;
  }
}

/// \f$R\, X\, R^*\f$ for a 3x3 block \p X and a rotation \f$R\f$ about the coordinate axis
/// \f$I\f$: only rows and columns \f$J, K\f$ (the plane of the rotation) mix; \f$Y = RX\f$,
/// then \f$Z = Y R^*\f$, with \f$R\f$'s four plane entries. \p symmetric: \f$X\f$ is (up to
/// rounding), and \f$Z\f$ is made so (its lower triangle formed and mirrored): 27 flops instead of 75; a general
/// block 36 instead of 90. Each entry is the general \f$(RX)_{i\cdot}\,R_{j\cdot}^*\f$
/// (lower triangle \f$i \ge j\f$ when symmetric, the upper mirrored) less the products with
/// an exact 0 or 1 of \f$R\f$: at most two products remain in each sum, and a sum with one
/// exact zero term rounds alike in any order: the general result bit for bit where the
/// general product rounds every term (Eigen's packet products fuse multiply-adds on FMA
/// targets, rounding such a sum once: then within an ulp of each term).
template <int I, class S>
EIGEN_ALWAYS_INLINE Mat3<S> plane_rotate(const Mat3<S>& R, const Mat3<S>& X, bool symmetric) {
  constexpr int J = I == 2 ? 0 : I + 1, K = J == 2 ? 0 : J + 1;
  const S a = R(J, J), b = R(J, K), c = R(K, J), d = R(K, K);
  Mat3<S> Z;
  // Y = R X, rows J and K
  const S yJI = a * X(J, I) + b * X(K, I), yKI = c * X(J, I) + d * X(K, I);
  const S yJJ = a * X(J, J) + b * X(K, J), yKJ = c * X(J, J) + d * X(K, J);
  const S yJK = a * X(J, K) + b * X(K, K), yKK = c * X(J, K) + d * X(K, K);
  Z(I, I) = X(I, I);
  Z(J, J) = a * yJJ + b * yJK;
  Z(K, K) = c * yKJ + d * yKK;
  if (symmetric) {
    // each pair's entry below the diagonal, as the general lower triangle forms it
    Z(K, J) = K > J ? a * yKJ + b * yKK : c * yJJ + d * yJK;
    Z(J, I) = J > I ? yJI : a * X(I, J) + b * X(I, K);
    Z(K, I) = K > I ? yKI : c * X(I, J) + d * X(I, K);
    Z(I, J) = Z(J, I), Z(I, K) = Z(K, I), Z(J, K) = Z(K, J);
  } else {
    Z(J, I) = yJI, Z(K, I) = yKI;
    Z(K, J) = a * yKJ + b * yKK;
    Z(I, J) = a * X(I, J) + b * X(I, K);
    Z(I, K) = c * X(I, J) + d * X(I, K);
    Z(J, K) = c * yJJ + d * yJK;
  }
  return Z;
}

/// \f$A\,R\f$ for a rotation \f$R\f$ about the coordinate axis \f$I\f$ (a pose composed with
/// a joint's): column \f$I\f$ of \f$A\f$ stays, columns \f$J, K\f$ mix (12 flops instead of
/// 45, each entry the general two-product sum).
template <int I, class S>
EIGEN_ALWAYS_INLINE Mat3<S> plane_times(const Mat3<S>& A, const Mat3<S>& R) {
  constexpr int J = I == 2 ? 0 : I + 1, K = J == 2 ? 0 : J + 1;
  Mat3<S> Z;
  Z.col(I) = A.col(I);
  Z.col(J) = A.col(J) * R(J, J) + A.col(K) * R(K, J);
  Z.col(K) = A.col(J) * R(J, K) + A.col(K) * R(K, K);
  return Z;
}

}  // namespace soa::detail
