/// \file
/// Shared by the serial-chain property tests (lessons 3-4): the kinds of random chains every
/// identity is checked on, stacking of per-body quantities into the operators' block
/// vectors, the fourth-order central difference, and the precisions of the typed tests.
#pragma once

#include <algorithm>
#include <ostream>
#include <string>
#include <type_traits>
#include <vector>

#include "precisions.hpp"
#include "random_chain.hpp"

namespace soa::test {

/// The chains of the tests: every hinge type in one chain (locked hinges merged), or all
/// hinges of one type.
enum class ChainKind { Mixed, Revolute, Prismatic, Helical, Universal, Spherical, Free };

inline const char* chain_kind_name(ChainKind k) {
  switch (k) {
    case ChainKind::Mixed:
      return "mixed";
    case ChainKind::Revolute:
      return "revolute";
    case ChainKind::Prismatic:
      return "prismatic";
    case ChainKind::Helical:
      return "helical";
    case ChainKind::Universal:
      return "universal";
    case ChainKind::Spherical:
      return "spherical";
    case ChainKind::Free:
      return "free";
  }
  return "?";
}

/// GoogleTest prints a kind by its name (in test lists and ctest names).
inline void PrintTo(ChainKind k, std::ostream* os) {
  *os << chain_kind_name(k);
}

/// Every kind, for INSTANTIATE_TEST_SUITE_P.
inline auto all_chain_kinds() {
  return ::testing::Values(ChainKind::Mixed, ChainKind::Revolute, ChainKind::Prismatic,
                           ChainKind::Helical, ChainKind::Universal, ChainKind::Spherical,
                           ChainKind::Free);
}

/// Test-name generator for the kinds: `chain_Operators/Operators.Velocity/mixed`.
struct ChainKindName {
  std::string operator()(const ::testing::TestParamInfo<ChainKind>& info) const {
    return chain_kind_name(info.param);
  }
};

/// A random chain of kind \p kind with \p n bodies before locked hinges merge.
template <class S>
ModelT<S> make_chain(Random<S>& rnd, ChainKind kind, int n, ChainOptions opt = {}) {
  if (kind == ChainKind::Mixed) {
    opt.all_hinge_types = true;
    return random_chain(rnd, n, opt);
  }
  const HingeType type = kind == ChainKind::Revolute    ? HingeType::Revolute
                         : kind == ChainKind::Prismatic ? HingeType::Prismatic
                         : kind == ChainKind::Helical   ? HingeType::Helical
                         : kind == ChainKind::Universal ? HingeType::Universal
                         : kind == ChainKind::Spherical ? HingeType::Spherical
                                                        : HingeType::Free;
  return random_chain_of_type(rnd, n, type, opt);
}

/// The number of bodies of case \p i: cycles through 1 ... \p n_max, so that every size is
/// drawn equally often.
inline int chain_size(int i, int n_max) {
  return 1 + i % n_max;
}

/// The per-body vectors of a workspace (entry k-1 = body k) stacked as the operators' block
/// vector: block k is rows 6(k-1) ... 6k-1.
template <class S, class K>
VecX<S> stack(const std::vector<SpatialVector<S, K>>& v) {
  VecX<S> s(6 * int(v.size()));
  for (std::size_t k = 0; k < v.size(); ++k) s.template segment<6>(6 * k) = v[k].vector();
  return s;
}

/// The fourth-order central difference of a vector function of time at t = 0:
/// \f[ \dot x(0) \approx \frac{8\,(x(h) - x(-h)) - (x(2h) - x(-2h))}{12\,h}, \f]
/// truncation \f$h^4 |x^{(5)}| / 30\f$, rounding about \f$1.5\,\varepsilon |x| / h\f$.
template <class F>
auto derivative(F x, double h) {
  using V = decltype(x(0.0));
  const V d = (8.0 * (x(h) - x(-h)) - (x(2 * h) - x(-2 * h))) / (12.0 * h);
  return d;
}

/// \f$\|a - b\| / s\f$ in double, for a residual relative to a bound \p s on the terms.
template <class A, class B>
double residual(const A& a, const B& b, double s) {
  return double((a - b).norm()) / std::max(s, 1e-300);
}

}  // namespace soa::test
