// Uses the installed library: power is the same at two points of a body (slide 50), and a
// joint transform of the chain, whose sine comes from SLEEF (a dependency the package finds).
#include <soa/chain.hpp>
#include <soa/phi.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

int main() {
  const soa::Phi phi(soa::Mat3<double>::Identity(), soa::Vec3<double>(1, 2, 3));
  const soa::Force f_y(soa::Vec3<double>(1, 0, 0), soa::Vec3<double>(0, 1, 0));
  const soa::Velocity V_x(soa::Vec3<double>(0, 0, 1), soa::Vec3<double>(1, 1, 0));
  const double p_x = soa::dot(phi.apply(f_y), V_x), p_y = soa::dot(f_y, phi.transpose_apply(V_x));
  std::printf("power at x %g, at y %g\n", p_x, p_y);
  // One revolute body about z turned by 0.5 rad: phi's R(1, 0) is sin 0.5.
  const soa::Model m = soa::Model::from_base_first(std::vector<soa::Body>(1));
  soa::Workspace ws(m);
  soa::update_phi(m, soa::VecX<double>::Constant(1, 0.5), ws);
  const double s = ws.phi[0].R()(1, 0);
  std::printf("sin 0.5 = %.17g (std::sin %.17g)\n", s, std::sin(0.5));
  return std::abs(p_x - p_y) < 1e-12 && std::abs(s - std::sin(0.5)) < 1e-15 ? 0 : 1;
}
