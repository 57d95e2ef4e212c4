// The library's templates instantiated in float (see instantiate.hpp).

// GCC 12 with AVX-512 (SOA_NATIVE on such a CPU) reports two false positives here, both in
// its own intrinsics header (avx512fintrin.h) once inlined into Eigen's float code:
// - -Wmaybe-uninitialized: several intrinsics start from a self-initialized "undefined"
//   vector (GCC bug 105593, fixed in GCC 13);
// - -Warray-bounds: a 16-float packet load or store in Eigen's loops over the hinge-sized
//   vectors (at most 6 floats, HingeVector, Vec6), a path the loop takes only when the
//   runtime size allows it, which GCC 12's bounds check does not follow.
// Nothing is read out of bounds or uninitialized (ASan and UBSan runs agree); the two
// warnings are silenced for this one translation unit, this compiler and this instruction
// set only.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ == 12 && defined(__AVX512F__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Warray-bounds"
#endif

#include "instantiate.hpp"

namespace soa {
SOA_TEMPLATES(, float)
}  // namespace soa
