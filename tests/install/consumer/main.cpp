// Uses the installed library: power is the same at two points of a body (slide 50).
#include <soa/phi.hpp>

#include <cmath>
#include <cstdio>

int main() {
  const soa::Phi phi(soa::Mat3<double>::Identity(), soa::Vec3<double>(1, 2, 3));
  const soa::Force f_y(soa::Vec3<double>(1, 0, 0), soa::Vec3<double>(0, 1, 0));
  const soa::Velocity V_x(soa::Vec3<double>(0, 0, 1), soa::Vec3<double>(1, 1, 0));
  const double p_x = soa::dot(phi.apply(f_y), V_x), p_y = soa::dot(f_y, phi.transpose_apply(V_x));
  std::printf("power at x %g, at y %g\n", p_x, p_y);
  return std::abs(p_x - p_y) < 1e-12 ? 0 : 1;
}
