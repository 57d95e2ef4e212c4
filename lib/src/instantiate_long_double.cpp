// The library's templates instantiated in long double (see instantiate.hpp).
#include "instantiate.hpp"

namespace soa {
SOA_TEMPLATES(, long double)
}  // namespace soa
