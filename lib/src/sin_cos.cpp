// soa::detail::sin_cos() in double: SLEEF's vector sincos with at most 1.0 ulp of error
// (u10), four angles a call under AVX2 (SOA_NATIVE on such a CPU), two with SSE2 (the
// portable x86-64 build). Here rather than in the header so that sleef.h, its macros and
// the intrinsics it includes stay out of the programs that use the library.
#include "soa/detail/sin_cos.hpp"

#include <sleef.h>

namespace soa::detail {

namespace {

#if defined(__AVX2__) && defined(__FMA__)
constexpr int kWidth = 4;
inline void sin_cos_vector(const double* theta, double* s, double* c) {
  const Sleef___m256d_2 sc = Sleef_sincosd4_u10avx2(_mm256_loadu_pd(theta));
  _mm256_storeu_pd(s, sc.x);
  _mm256_storeu_pd(c, sc.y);
}
#elif defined(__SSE2__)
constexpr int kWidth = 2;
inline void sin_cos_vector(const double* theta, double* s, double* c) {
  const Sleef___m128d_2 sc = Sleef_sincosd2_u10sse2(_mm_loadu_pd(theta));
  _mm_storeu_pd(s, sc.x);
  _mm_storeu_pd(c, sc.y);
}
#else
constexpr int kWidth = 1;
inline void sin_cos_vector(const double* theta, double* s, double* c) {
  const Sleef_double2 sc = Sleef_sincos_u10(*theta);
  *s = sc.x;
  *c = sc.y;
}
#endif

}  // namespace

void sin_cos(const double* theta, int n, double* s, double* c) {
  int i = 0;
  for (; i + kWidth <= n; i += kWidth) sin_cos_vector(theta + i, s + i, c + i);
  if (i == n) return;
  // The last n - i < kWidth angles in one vector padded with zeros.
  double t[kWidth] = {}, ts[kWidth], tc[kWidth];
  for (int j = 0; i + j < n; ++j) t[j] = theta[i + j];
  sin_cos_vector(t, ts, tc);
  for (int j = 0; i + j < n; ++j) s[i + j] = ts[j], c[i + j] = tc[j];
}

}  // namespace soa::detail
