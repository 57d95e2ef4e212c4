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
  // The composite inertias, tip to base, as in 5.1 (inlined: a solution calls no other
  // exercise's function).
  std::vector<SpatialInertia> R;
  for (int k = 1; k <= n; ++k) {
    SpatialInertia Rk = m.body(k).M;
    if (k > 1) Rk = Rk + transform(phi[std::size_t(k - 2)], R.back());  // phi(k,k-1) R(k-1) ...
    R.push_back(Rk);
  }
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

// 5.5: phi~ = phi - I holds the blocks phi(i,j), i > j, and nothing else, so block (i,j) of
// R + phi~ R + R phi~* is R(i) for i = j, phi(i,j) R(j) for i > j (from phi~ R) and
// R(i) phi*(j,i) for i < j (from R phi~*): the transpose of block (j,i).
Mat6<double> phi_M_phi_star_block(const std::vector<Phi>& phi, const std::vector<SpatialInertia>& R,
                                  int i, int j) {
  if (i < j) return phi_M_phi_star_block(phi, R, j, i).transpose();
  Mat6<double> block = R[std::size_t(j - 1)].matrix();
  for (int k = j + 1; k <= i; ++k) block = phi[std::size_t(k - 2)].matrix() * block;  // phi(k,k-1)
  return block;
}

// 5.6: nothing turns, so every body moves with the sum of the sliding velocities inboard of
// it, sum_{i >= k} a_i beta_i, and the kinetic energy is 1/2 sum_k m_k |sum_{i >= k} a_i
// beta_i|^2: M(i,j) = (m_1 + ... + m_min(i,j)) a_i . a_j. (With the operators: H*(j) = [0; a_j]
// sees only the linear-linear block of R(j), the mass of bodies 1..j times I, and phi(i,j)
// turns a pure force [0; F] into [l x R F; R F]: H(i) takes its linear part.)
MatX<double> slider_mass_matrix(const std::vector<double>& mass,
                                const std::vector<Vec3<double>>& axis) {
  const int n = int(mass.size());
  MatX<double> M(n, n);
  double outboard = 0;  // m_1 + ... + m_j
  for (int j = 1; j <= n; ++j) {
    outboard += mass[std::size_t(j - 1)];
    for (int i = j; i <= n; ++i)
      M(i - 1, j - 1) = M(j - 1, i - 1) =
          outboard * axis[std::size_t(i - 1)].dot(axis[std::size_t(j - 1)]);
  }
  return M;
}

// 5.7: M(i,j) = H(i) phi(i,j) R(j) H*(j) for i >= j, forces carried inboard by
// phi(i,i-1); M(i,j) = H(i) R(i) phi*(j,i) H*(j) for i < j, motions carried outboard by
// phi*(i+1,i).
MatX<double> mass_matrix_column(const Model& m, const VecX<double>& theta,
                                const std::vector<Phi>& phi, const std::vector<SpatialInertia>& R,
                                int j) {
  auto H_star = [&](int k) {
    return MatX<double>(m.body(k).hinge.H_star(theta.data() + m.body(k).q_offset));
  };
  const MatX<double> Hj = H_star(j);
  MatX<double> column(m.nv(), Hj.cols());
  MatX<double> F = R[std::size_t(j - 1)].matrix() * Hj;  // R(j) H*(j)
  for (int i = j; i <= m.n(); ++i) {
    if (i > j) F = phi[std::size_t(i - 2)].matrix() * F;  // phi(i,i-1)
    column.middleRows(m.body(i).v_offset, m.body(i).hinge.nv()) = H_star(i).transpose() * F;
  }
  MatX<double> V = Hj;  // H*(j)
  for (int i = j - 1; i >= 1; --i) {
    V = phi[std::size_t(i - 1)].matrix().transpose() * V;  // phi*(i+1,i)
    column.middleRows(m.body(i).v_offset, m.body(i).hinge.nv()) =
        H_star(i).transpose() * R[std::size_t(i - 1)].matrix() * V;
  }
  return column;
}

}  // namespace soa::ex05
