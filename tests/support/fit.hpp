// Fits of convergence tests: the order of a method from errors against steps.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

namespace soa::test {

/// The least-squares slope of \f$\log e\f$ against \f$\log x\f$: a method of order q has
/// errors \f$e \approx C h^q\f$, a straight line of slope q in log-log.
inline double slope(const std::vector<double>& x, const std::vector<double>& err) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]), ly = std::log(err[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace soa::test
