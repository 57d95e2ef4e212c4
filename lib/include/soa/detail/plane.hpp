/// \file
/// Rotations about a coordinate axis: the fast paths of the recursions. A joint about
/// \f$\pm e_i\f$ with an unrotated placement gives \f$\phi(k,k-1)\f$ a rotation about
/// \f$e_i\f$: only the plane \f$(e_u, e_w)\f$ of it mixes, so products with it drop the exact
/// zeros and ones of \f$R\f$, and each remaining sum keeps its terms in the general order.
///
/// Index names: `Axis` (a template parameter) or `i` is the axis of the rotation; `U`, `W`
/// (or `u`, `w`) are the two others, with (Axis, U, W) a cyclic order of (0, 1, 2), so that
/// \f$e_U \times e_W = e_{Axis}\f$.
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
    const int u = i == 2 ? 0 : i + 1, w = u == 2 ? 0 : u + 1;
    if (R(i, i) == S(1) && R(u, i) == S(0) && R(w, i) == S(0) && R(i, u) == S(0) && R(i, w) == S(0))
      return i;
  }
  return -1;
}

/// The \f$i\f$ of an offset \f$l = \lambda e_i\f$ (\f$\lambda \ne 0\f$, the other two
/// components exactly zero: a placement along a coordinate axis); -1 otherwise.
template <class S>
EIGEN_ALWAYS_INLINE int coordinate_offset(const Vec3<S>& l) {
  const int i = l[0] != S(0) ? 0 : l[1] != S(0) ? 1 : 2;  // the first non-zero component
  const int u = i == 2 ? 0 : i + 1, w = u == 2 ? 0 : u + 1;
  return l[i] != S(0) && l[u] == S(0) && l[w] == S(0) ? i : -1;
}

/// The \f$i\f$ of an axis that is exactly \f$\pm e_i\f$; -1 otherwise.
template <class S>
EIGEN_ALWAYS_INLINE int coordinate_axis(const Vec3<S>& a) {
  const int i = coordinate_offset(a);
  return i >= 0 && (a[i] == S(1) || a[i] == S(-1)) ? i : -1;
}

/// Component \p i (\f$\ne\f$ Axis) of \f$\lambda e_{Axis} \times v\f$ from \f$v_U, v_W\f$:
/// \f$-\lambda v_W\f$ for \f$i = U\f$, \f$\lambda v_U\f$ for \f$i = W\f$ (component
/// Axis is zero); the general cross product's value, its product with an exact zero of
/// \f$l\f$ dropped.
template <int Axis, class S>
EIGEN_ALWAYS_INLINE S axis_cross(int i, S lambda, S vU, S vW) {
  constexpr int U = Axis == 2 ? 0 : Axis + 1;
  return i == U ? -(lambda * vW) : lambda * vU;
}

/// Calls \p f with std::integral_constant<int, Axis> for \p axis = Axis in {0, 1, 2} and
/// returns true; false (f not called) for -1. The axis becomes a compile-time index, so that
/// the kernels templated on it unroll to the entries of their plane.
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
/// Axis: only rows and columns \f$U, W\f$ (the plane of the rotation) mix; \f$Y = RX\f$,
/// then \f$Z = Y R^*\f$, with \f$R\f$'s four plane entries. \p symmetric: \f$X\f$ is (up to
/// rounding), and \f$Z\f$ is made so (its lower triangle formed and mirrored): 27 flops
/// instead of 75; a general block 36 instead of 90. Each entry is the general
/// \f$(RX)_{i\cdot}\,R_{j\cdot}^*\f$ (lower triangle \f$i \ge j\f$ when symmetric, the upper
/// mirrored) less the products with an exact 0 or 1 of \f$R\f$: at most two products remain
/// in each sum, and a sum with one exact zero term rounds alike in any order: the general
/// result bit for bit where the general product rounds every term (Eigen's packet products
/// fuse multiply-adds on FMA targets, rounding such a sum once: then within an ulp of each
/// term).
template <int Axis, class S>
EIGEN_ALWAYS_INLINE Mat3<S> plane_rotate(const Mat3<S>& R, const Mat3<S>& X, bool symmetric) {
  constexpr int U = Axis == 2 ? 0 : Axis + 1, W = U == 2 ? 0 : U + 1;
  const S RUU = R(U, U), RUW = R(U, W), RWU = R(W, U), RWW = R(W, W);
  Mat3<S> Z;
  // Y = R X, rows U and W
  const S yU_axis = RUU * X(U, Axis) + RUW * X(W, Axis),
          yW_axis = RWU * X(U, Axis) + RWW * X(W, Axis);
  const S yUU = RUU * X(U, U) + RUW * X(W, U), yWU = RWU * X(U, U) + RWW * X(W, U);
  const S yUW = RUU * X(U, W) + RUW * X(W, W), yWW = RWU * X(U, W) + RWW * X(W, W);
  Z(Axis, Axis) = X(Axis, Axis);
  Z(U, U) = RUU * yUU + RUW * yUW;
  Z(W, W) = RWU * yWU + RWW * yWW;
  if (symmetric) {
    // each pair's entry below the diagonal, as the general lower triangle forms it
    Z(W, U) = W > U ? RUU * yWU + RUW * yWW : RWU * yUU + RWW * yUW;
    Z(U, Axis) = U > Axis ? yU_axis : RUU * X(Axis, U) + RUW * X(Axis, W);
    Z(W, Axis) = W > Axis ? yW_axis : RWU * X(Axis, U) + RWW * X(Axis, W);
    Z(Axis, U) = Z(U, Axis), Z(Axis, W) = Z(W, Axis), Z(U, W) = Z(W, U);
  } else {
    Z(U, Axis) = yU_axis, Z(W, Axis) = yW_axis;
    Z(W, U) = RUU * yWU + RUW * yWW;
    Z(Axis, U) = RUU * X(Axis, U) + RUW * X(Axis, W);
    Z(Axis, W) = RWU * X(Axis, U) + RWW * X(Axis, W);
    Z(U, W) = RWU * yUU + RWW * yUW;
  }
  return Z;
}

/// \f$X\,R\f$ for a rotation \f$R\f$ about the coordinate axis Axis (a pose composed with
/// a joint's): column Axis of \f$X\f$ stays, columns \f$U, W\f$ mix (12 flops instead of
/// 45, each entry the general two-product sum).
template <int Axis, class S>
EIGEN_ALWAYS_INLINE Mat3<S> plane_times(const Mat3<S>& X, const Mat3<S>& R) {
  constexpr int U = Axis == 2 ? 0 : Axis + 1, W = U == 2 ? 0 : U + 1;
  Mat3<S> Z;
  Z.col(Axis) = X.col(Axis);
  Z.col(U) = X.col(U) * R(U, U) + X.col(W) * R(W, U);
  Z.col(W) = X.col(U) * R(U, W) + X.col(W) * R(W, W);
  return Z;
}

}  // namespace soa::detail
