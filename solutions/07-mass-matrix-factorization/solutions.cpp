// Lesson 7 reference solutions (statements in exercises/07-mass-matrix-factorization).
#include <cmath>

#include "exercises.hpp"

namespace soa::ex07 {

namespace {

// The Riccati quantities of lesson 6 at state x, with phi(k+1,k) in ws.phi.
struct Riccati {
  Workspace ws;
  Articulated art;
  Riccati(const Model& m, const State& x) : ws(m), art(m) {
    update_phi(m, x.theta, ws);
    articulated_inertias(m, x, ws, art);
  }
};

MatX H_star(const Model& m, const State& x, int k) {
  const Body& B = m.body(k);
  return B.hinge.H_star(x.theta.data() + B.q_offset);
}

}  // namespace

// Lesson 7, section 1: K = E_phi G (phi(k+1,k) G(k) at block (k+1, k)), psi = (I - E_psi)^-1
// with E_psi = E_phi tau_bar (phi(k+1,k) tau_bar(k) at block (k+1, k)).
KAndPsi k_and_psi(const Model& m, const State& x) {
  const Riccati r(m, x);
  const int n = m.n(), N = 6 * n;
  KAndPsi out;
  out.K = MatX::Zero(N, m.nv());
  MatX E_psi = MatX::Zero(N, N);
  for (int k = 1; k < n; ++k) {
    const Body& B = m.body(k);
    const std::size_t j = std::size_t(k - 1);
    const Mat6<double> phi = r.ws.phi[j].matrix();  // phi(k+1,k)
    out.K.block(6 * k, B.v_offset, 6, B.hinge.nv()) = phi * r.art.G[j];
    E_psi.block(6 * k, 6 * (k - 1), 6, 6) = phi * r.art.tau_bar(m, x.theta, k);
  }
  const MatX I = MatX::Identity(N, N);
  out.psi = (I - E_psi).triangularView<Eigen::UnitLower>().solve(I);
  return out;
}

// Lesson 7, sections 3-4: L = I + H phi K, L^-1 = I - H psi K, D (K and psi as in 7.1).
InnovationsFactor innovations_factor(const Model& m, const State& x) {
  const Operators op = Operators::build(m, x);
  const Riccati r(m, x);
  const int n = m.n(), N = 6 * n, nv = m.nv();
  MatX G = MatX::Zero(N, nv), tau_bar = MatX::Zero(N, N);
  InnovationsFactor f;
  f.D = MatX::Zero(nv, nv);
  for (int k = 1; k <= n; ++k) {
    const Body& B = m.body(k);
    const int o = B.v_offset, nk = B.hinge.nv();
    G.block(6 * (k - 1), o, 6, nk) = r.art.G[std::size_t(k - 1)];
    tau_bar.block(6 * (k - 1), 6 * (k - 1), 6, 6) = r.art.tau_bar(m, x.theta, k);
    f.D.block(o, o, nk, nk) = r.art.D[std::size_t(k - 1)];
  }
  const MatX K = op.E_phi * G, IN = MatX::Identity(N, N), I = MatX::Identity(nv, nv);
  const MatX psi = (IN - op.E_phi * tau_bar).triangularView<Eigen::UnitLower>().solve(IN);
  f.L = I + op.H * op.phi * K;
  f.L_inv = I - op.H * psi * K;
  return f;
}

// Exercise 7.3: Upsilon(k) = psi*(k+1,k) Upsilon(k+1) psi(k+1,k) + H*(k) D^-1(k) H(k), base to
// tip; Minv(k,k) = D^-1(k) + G*(k) phi*(k+1,k) Upsilon(k+1) phi(k+1,k) G(k).
std::vector<MatX> minv_diagonal(const Model& m, const State& x) {
  const Riccati r(m, x);
  const int n = m.n();
  std::vector<MatX> out(static_cast<std::size_t>(n));
  Mat6<double> Upsilon = Mat6<double>::Zero();  // Upsilon(k+1)
  for (int k = n; k >= 1; --k) {
    const std::size_t j = std::size_t(k - 1);
    const MatX D_inv = r.art.D_inv[j];
    const MatX G = r.art.G[j];
    const MatX Hs = H_star(m, x, k);
    if (k == n) {
      out[j] = D_inv;
      Upsilon = Hs * D_inv * Hs.transpose();
      continue;
    }
    const Mat6<double> phi = r.ws.phi[j].matrix();  // phi(k+1,k)
    const Mat6<double> U = phi.transpose() * Upsilon * phi;
    out[j] = D_inv + G.transpose() * U * G;
    const Mat6<double> tau = r.art.tau_bar(m, x.theta, k);
    Upsilon = tau.transpose() * U * tau + Hs * D_inv * Hs.transpose();
  }
  return out;
}

// Lesson 7, section 4: the tip-to-base and base-to-tip recursions of M^-1 b.
VecX solve(const Model& m, const State& x, const VecX& b) {
  const Riccati r(m, x);
  const int n = m.n();
  std::vector<VecX> nu(static_cast<std::size_t>(n));
  Force z_plus = Force::Zero();
  for (int k = 1; k <= n; ++k) {
    const Body& B = m.body(k);
    const std::size_t j = std::size_t(k - 1);
    const Force z = k > 1 ? r.ws.phi[j - 1].apply(z_plus) : Force::Zero();
    const VecX eps = b.segment(B.v_offset, B.hinge.nv()) - H_star(m, x, k).transpose() * z.vector();
    nu[j] = r.art.D_inv[j] * eps;
    z_plus = Force(Vec6<double>(z.vector() + r.art.G[j] * eps));
  }
  VecX y(m.nv());
  Acceleration alpha = Acceleration::Zero();  // alpha(k+1)
  for (int k = n; k >= 1; --k) {
    const Body& B = m.body(k);
    const std::size_t j = std::size_t(k - 1);
    const Acceleration alpha_plus =
        k < n ? r.ws.phi[j].transpose_apply(alpha) : Acceleration::Zero();
    const VecX yk = nu[j] - r.art.G[j].transpose() * alpha_plus.vector();
    y.segment(B.v_offset, B.hinge.nv()) = yk;
    alpha = Acceleration(Vec6<double>(alpha_plus.vector() + H_star(m, x, k) * yk));
  }
  return y;
}

// Lesson 7, section 3: log det M = sum_k log det D(k).
double log_det_mass_matrix(const Model& m, const State& x) {
  const Riccati r(m, x);
  double s = 0;
  for (const auto& D : r.art.D) s += std::log(MatX(D).determinant());
  return s;
}

}  // namespace soa::ex07

namespace soa::ex07 {

namespace {

// psi(k+1,k) = phi(k+1,k) tau_bar(k), 6x6 (k < n).
Mat6<double> psi_step(const Model& m, const State& x, const Workspace& ws, const Articulated& art,
                      int k) {
  return ws.phi[std::size_t(k - 1)].matrix() * art.tau_bar(m, x.theta, k);
}

}  // namespace

// Exercise 7.6: Omega(i,j) = Upsilon(i) psi(i,j) for i >= j, Omega(j,i) = Omega(i,j)*.
MatX omega_from_upsilon(const Model& m, const State& x) {
  const int n = m.n();
  Workspace ws(m);
  update_phi(m, x.theta, ws);
  Upsilon u(m);
  upsilons(m, x, ws, u);
  MatX Omega = MatX::Zero(6 * n, 6 * n);
  for (int j = 1; j <= n; ++j) {
    Mat6<double> psi_ij = Mat6<double>::Identity();  // psi(i,j), i = j first
    for (int i = j; i <= n; ++i) {
      if (i > j) psi_ij = psi_step(m, x, ws, u.art, i - 1) * psi_ij;
      const Mat6<double> block = u.Upsilon[std::size_t(i - 1)] * psi_ij;
      Omega.block(6 * (i - 1), 6 * (j - 1), 6, 6) = block;
      Omega.block(6 * (j - 1), 6 * (i - 1), 6, 6) = block.transpose();
    }
  }
  return Omega;
}

// Exercise 7.7: diagonal blocks from Upsilon+, off-diagonal ones by carrying z_i(k) tip to base.
MatX minv_from_upsilon(const Model& m, const State& x) {
  const int n = m.n();
  Workspace ws(m);
  update_phi(m, x.theta, ws);
  Upsilon u(m);
  upsilons(m, x, ws, u);
  const Articulated& art = u.art;
  MatX Minv = MatX::Zero(m.nv(), m.nv());
  std::vector<MatX> L(static_cast<std::size_t>(n)), Mkk(static_cast<std::size_t>(n));
  for (int k = 1; k <= n; ++k) {
    const std::size_t j = std::size_t(k - 1);
    const Mat6<double> Up =
        k < n ? Mat6<double>(ws.phi[j].matrix().transpose() * u.Upsilon[j + 1] * ws.phi[j].matrix())
              : Mat6<double>::Zero();
    const MatX G = art.G[j];
    Mkk[j] = MatX(art.D_inv[j]) + G.transpose() * Up * G;
    L[j] = G.transpose() * Up - Mkk[j] * H_star(m, x, k).transpose();
  }
  for (int i = 1; i <= n; ++i) {
    const Body& Bi = m.body(i);
    const int oi = Bi.v_offset, ni = Bi.hinge.nv();
    Minv.block(oi, oi, ni, ni) = Mkk[std::size_t(i - 1)];
    if (i == n) continue;
    MatX z = ws.phi[std::size_t(i - 1)].matrix() * MatX(art.G[std::size_t(i - 1)]);  // z_i(i+1)
    for (int k = i + 1; k <= n; ++k) {
      const Body& Bk = m.body(k);
      const MatX block = L[std::size_t(k - 1)] * z;
      Minv.block(Bk.v_offset, oi, Bk.hinge.nv(), ni) = block;
      Minv.block(oi, Bk.v_offset, ni, Bk.hinge.nv()) = block.transpose();
      if (k < n) {
        const MatX Hz = H_star(m, x, k).transpose() * z;
        z = ws.phi[std::size_t(k - 1)].matrix() * (z - MatX(art.G[std::size_t(k - 1)]) * Hz);
      }
    }
  }
  return Minv;
}

// Exercise 7.8: phi*(O_k,F) Upsilon(k) phi(O_k,F), Upsilon base to tip down to body k.
Mat6<double> operational_inverse_inertia(const Model& m, const State& x, int k, const Pose& frame) {
  const Riccati r(m, x);
  Mat6<double> U = Mat6<double>::Zero();  // Upsilon(j+1), then Upsilon(j)
  for (int j = m.n(); j >= k; --j) {
    const std::size_t i = std::size_t(j - 1);
    const MatX Hs = H_star(m, x, j);
    const Mat6<double> psi = j < m.n() ? psi_step(m, x, r.ws, r.art, j) : Mat6<double>::Zero();
    U = psi.transpose() * U * psi + Hs * MatX(r.art.D_inv[i]) * Hs.transpose();
  }
  const Mat6<double> phi = Phi(frame).matrix();
  return phi.transpose() * U * phi;
}

// Exercise 7.9: eta(k) = G*(k) V(k).
VecX innovations_coordinates(const Model& m, const State& x) {
  Riccati r(m, x);
  update_velocities(m, x, r.ws);
  VecX eta(m.nv());
  for (int k = 1; k <= m.n(); ++k) {
    const Body& B = m.body(k);
    eta.segment(B.v_offset, B.hinge.nv()) =
        r.art.G[std::size_t(k - 1)].transpose() * r.ws.V[std::size_t(k - 1)].vector();
  }
  return eta;
}

// Exercise 7.10: a free hinge f has an invertible 6 x 6 H(f), so G(f) = H(f)^-1 and
// tau_bar(f) = I - G(f) H(f) = 0: psi(k,j) = 0 whenever hinge f lies strictly between (j < f <
// k), and every term of M^-1(i,j) = sum_k L^-1(k,i)* D^-1(k) L^-1(k,j) over k >= max(i,j)
// carries such a psi. Everywhere else the blocks are generically non-zero. For the motion:
// a free hinge transmits no force, so a hinge force applied on one side of it (an internal
// force of the chain on that side, which floats freely) gives the hinges on the other side
// no acceleration from rest.
MatX minv_zero_pattern(const std::vector<HingeType>& hinges) {
  const int n = int(hinges.size());
  MatX pattern = MatX::Ones(n, n);
  for (int f = 1; f <= n; ++f) {
    if (hinges[std::size_t(f - 1)] != HingeType::Free) continue;
    for (int i = 1; i < f; ++i)  // outboard of hinge f
      for (int k = f + 1; k <= n; ++k) pattern(i - 1, k - 1) = pattern(k - 1, i - 1) = 0;
  }
  return pattern;
}

// Exercise 7.11: a force at hinge i alone gives eps(i) = b(i), z+(i) = G(i) b(i), z(i+1) =
// phi(i+1,i) G(i) b(i); each body k between passes z+(k) = z(k) - G(k) H(k) z(k) = tau_bar(k)
// z(k) on, and eps(k) = -H(k) z(k). So A(k,i) = -H(k) phi(k,k-1) tau_bar(k-1) ... tau_bar(i+1)
// phi(i+1,i) G(i) = -H(k) psi(k,i+1) phi(i+1,i) G(i): A = I - H psi K, the inverse of the
// innovations factor.
MatX sweep_operator(const Model& m, const State& x) {
  const Riccati r(m, x);
  MatX A = MatX::Identity(m.nv(), m.nv());
  for (int i = 1; i < m.n(); ++i) {
    const Body& Bi = m.body(i);
    MatX z = r.ws.phi[std::size_t(i - 1)].matrix() * MatX(r.art.G[std::size_t(i - 1)]);  // z(i+1)
    for (int k = i + 1; k <= m.n(); ++k) {
      const Body& Bk = m.body(k);
      A.block(Bk.v_offset, Bi.v_offset, Bk.hinge.nv(), Bi.hinge.nv()) =
          -H_star(m, x, k).transpose() * z;
      if (k < m.n()) z = r.ws.phi[std::size_t(k - 1)].matrix() * (r.art.tau_bar(m, x.theta, k) * z);
    }
  }
  return A;
}

// Exercise 7.12: the bug was V(k) = phi*(k+1,k) V(k+1) + H*(k) eta(k); the velocity
// recursion of lesson 3 adds the hinge velocity, H*(k) beta(k).
VecX beta_from_eta(const Model& m, const State& x, const VecX& eta) {
  const Riccati r(m, x);
  VecX beta(m.nv());
  Velocity V = Velocity::Zero();  // V(k+1), zero beyond the base
  for (int k = m.n(); k >= 1; --k) {
    const Body& B = m.body(k);
    const int o = B.v_offset, nk = B.hinge.nv();
    const MatX Hs = H_star(m, x, k);
    const Velocity V_plus =
        k < m.n() ? r.ws.phi[std::size_t(k - 1)].transpose_apply(V) : Velocity::Zero();
    const VecX eta_k = eta.segment(o, nk);
    const VecX beta_k = eta_k - MatX(r.art.G[std::size_t(k - 1)]).transpose() * V_plus.vector();
    beta.segment(o, nk) = beta_k;
    V = Velocity(Vec6<double>(V_plus.vector() + Hs * beta_k));
  }
  return beta;
}

}  // namespace soa::ex07
