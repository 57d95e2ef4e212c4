/// \file
/// The sines and cosines of many angles in one call: the revolute hinge angles of a chain,
/// before the recursions that build \f$\phi(k+1,k)\f$ from them (hinge_sin_cos()).
#pragma once

#include <cmath>
#include <type_traits>

namespace soa::detail {

/// \f$s_i = \sin\theta_i\f$ and \f$c_i = \cos\theta_i\f$ for \f$i < n\f$, in double with
/// SLEEF's vector sincos (Sleef_sincosd4_u10avx2 under AVX2, else Sleef_sincosd2_u10sse2),
/// within 1.0 ulp of the exact values (lib/src/sin_cos.cpp). One glibc std::sin and std::cos
/// per joint were a large share of a recursion's time per body; the batch takes a fraction of
/// that (`make bench`'s HingeSinCosBatch against HingeSinCosStd; README "Speed" gives the
/// times). Each lane is computed on its own (the last few angles in a zero-padded vector), so
/// an angle's sine does not depend on where it stands. It is not glibc's std::sin and std::cos,
/// which are closer to exact (0.56 ulp at worst in tests/chain/sin_cos_test.cpp against SLEEF's
/// 0.83): the two may differ in the last bit. \p c may be \p theta (in place).
void sin_cos(const double* theta, int n, double* s, double* c);

/// Whether sin_cos() of \p S is the vector one (double); other scalars take std::sin and
/// std::cos angle by angle, where the batch would gain nothing (and the counting scalar of
/// the tests counts each).
template <class S>
inline constexpr bool batched_sin_cos = std::is_same_v<S, double>;

}  // namespace soa::detail
