// Lesson 5 exercises, solved from the formulas of the statements (exercises.hpp).
#include "exercises.hpp"

namespace soa::ex05 {

// 5.1: tip to base, R(k) = phi(k,k-1) R(k-1) phi*(k,k-1) + M(k).
std::vector<SpatialInertia> composite_inertias(const Model& m, const std::vector<Phi>& phi) {
  std::vector<SpatialInertia> R;
  for (int k = 1; k <= m.n(); ++k) {
    const auto i = std::size_t(k - 1);
    R.push_back(k == 1 ? m.body(1).M : transform(phi[i - 1], R[i - 1]) + m.body(k).M);
  }
  return R;
}

// 5.2: M(k,k) = H(k) R(k) H*(k).
MatX<double> mass_matrix_diagonal(const Model& m, const VecX<double>& theta,
                                  const std::vector<SpatialInertia>& R, int k) {
  const Body& B = m.body(k);
  const MatX<double> Hs = B.hinge.H_star(theta.data() + B.q_offset);
  return Hs.transpose() * R[std::size_t(k - 1)].matrix() * Hs;
}

// 5.3: M(i,j) = H(i) phi(i,j) R(j) H*(j), carrying R(j) H*(j) inboard.
MatX<double> crb_mass_matrix_revolute(const Model& m, const VecX<double>& theta) {
  const int n = m.n();
  std::vector<Phi> phi;
  for (int k = 1; k <= n; ++k) {
    const Body& B = m.body(k);
    phi.push_back(Phi(B.placement * Pose(exp_so3(theta[B.q_offset] * B.hinge.axis))));
  }
  const std::vector<SpatialInertia> R = composite_inertias(m, phi);
  MatX<double> M(n, n);
  for (int j = 1; j <= n; ++j) {
    Vec6<double> h_star;
    h_star << m.body(j).hinge.axis, Vec3<double>::Zero();
    Force F(Vec6<double>(R[std::size_t(j - 1)].matrix() * h_star));
    for (int i = j; i <= n; ++i) {
      if (i > j) F = phi[std::size_t(i - 2)].apply(F);  // phi(i, i-1)
      M(i - 1, j - 1) = M(j - 1, i - 1) = m.body(i).hinge.axis.dot(Vec3<double>(F.angular()));
    }
  }
  return M;
}

// 5.4: R(k) = phi(k,k-1) R(k-1) phi*(k,k-1) + M(k) on the blocks, then R + phi~ R + R phi~*.
MatX<double> decomposition(const Operators& op) {
  const Eigen::Index N = op.M.rows();
  MatX<double> R = MatX<double>::Zero(N, N);
  for (Eigen::Index r = 0; r < N; r += 6) {
    R.block(r, r, 6, 6) = op.M.block(r, r, 6, 6);
    if (r > 0) {
      const MatX<double> E = op.E_phi.block(r, r - 6, 6, 6);
      R.block(r, r, 6, 6) += E * R.block(r - 6, r - 6, 6, 6) * E.transpose();
    }
  }
  const MatX<double> phi_t = op.phi - MatX<double>::Identity(N, N);
  return R + phi_t * R + R * phi_t.transpose();
}

}  // namespace soa::ex05
