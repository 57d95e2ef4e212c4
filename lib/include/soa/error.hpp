/// \file
/// The one exception type of the library, and the finiteness checks at its boundaries.
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <string>

namespace soa {

/// Raised on input the library refuses (a zero quaternion, a non-positive mass, a NaN, a
/// representation used at its singularity without a documented fallback). The message
/// names what was wrong and where.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

/// Throws soa::Error("<where>: not finite") when any entry of \p x is NaN or infinite.
template <class Derived>
void require_finite(const Eigen::MatrixBase<Derived>& x, const char* where) {
  if (!x.allFinite()) throw Error(std::string(where) + ": not finite");
}

/// Scalar version of require_finite().
template <class S>
void require_finite_scalar(S x, const char* where) {
  if (!(x - x == x - x)) throw Error(std::string(where) + ": not finite");
}

}  // namespace soa
