/// \file
/// Flop counts of the chain algorithms, from the code as it runs: each algorithm called on
/// chains of the scalar soa::test::Counted, with the benchmarks' set-up, the operations counted
/// per call. Per body: the difference between chains of n and 2n bodies, so that what a call
/// does once drops out. Used by the flop-count test (tests/dynamics/flop_count_test.cpp) and
/// the work lab (lessons/labs/work/).
#pragma once

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "counted_scalar.hpp"
#include "soa/chain.hpp"

namespace soa::test {

/// Hinge axes of a counting chain: about coordinate axes with placements that do not
/// rotate, offset along x (the fast paths apply), or general unit axes and rotated
/// placements with general offsets.
enum class Axes { Coordinate, General };

/// A chain of \p n bodies with one hinge type, its state, accelerations and hinge forces:
/// the benchmark chain (benchmark_chain.hpp: links of 0.3 m, masses 1, 1.1, 1.2,
/// gravity, a random state from a fixed seed) with any hinge type. Coordinate axes
/// alternate z and y as the benchmark's (a universal hinge's second axis is the other one);
/// general axes alternate two fixed oblique unit vectors. The numbers are drawn in double
/// and rounded once to S, so that every S gets the same problem.
template <class S>
struct CountChain {
  ModelT<S> m;
  StateT<S> x;
  VecX<S> beta_dot, T;

  CountChain(HingeType type, int n, Axes axes) {
    const auto v3 = [](double a, double b, double c) { return Vec3<S>(S(a), S(b), S(c)); };
    const Eigen::Vector3d oblique[2] = {Eigen::Vector3d(1, 2, 3).normalized(),
                                        Eigen::Vector3d(-2, 1, 0.5).normalized()};
    const Eigen::Matrix3d R_place =
        Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.3, -1, 2).normalized()).toRotationMatrix();
    std::vector<BodyT<S>> bodies(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      BodyT<S>& b = bodies[std::size_t(i)];
      b.name = "link" + std::to_string(i);
      b.M = SpatialInertiaT<S>::from_cm(S(1.0 + 0.1 * (i % 3)), v3(0.15, 0, 0.01),
                                        Mat3<S>(v3(0.01, 0.02, 0.02).asDiagonal()));
      b.hinge.type = type;
      b.hinge.pitch = S(0.05);
      if (axes == Axes::Coordinate) {
        b.placement = PoseT<S>(Mat3<S>::Identity(), v3(i == 0 ? 0 : 0.3, 0, 0));
        b.hinge.axis = i % 2 ? Vec3<S>::UnitY() : Vec3<S>::UnitZ();
        b.hinge.axis2 = i % 2 ? Vec3<S>::UnitZ() : Vec3<S>::UnitY();
      } else {
        b.placement = PoseT<S>(R_place.cast<S>(), v3(i == 0 ? 0 : 0.3, 0.05, -0.02));
        b.hinge.axis = oblique[i % 2].cast<S>();
        b.hinge.axis2 = oblique[(i + 1) % 2].cast<S>();
      }
    }
    m = ModelT<S>::from_base_first(std::move(bodies));
    m.gravity = v3(0, 0, -9.81);
    x = StateT<S>::rest(m);
    std::mt19937 g(11);
    std::normal_distribution<double> N;
    Eigen::VectorXd theta(m.nq());
    for (int i = 0; i < m.nq(); ++i) theta[i] = N(g);
    for (int k = 1; k <= m.n(); ++k) {
      const BodyT<S>& B = m.body(k);
      if (B.hinge.type == HingeType::Spherical || B.hinge.type == HingeType::Free)
        theta.segment(B.q_offset, 4).normalize();
    }
    x.theta = theta.cast<S>();
    beta_dot.resize(m.nv());
    T.resize(m.nv());
    for (int i = 0; i < m.nv(); ++i) x.beta[i] = S(N(g)), beta_dot[i] = S(N(g)), T[i] = S(N(g));
  }
};

/// The algorithms counted, each called as the benchmarks call it (tests/bench/): inverse
/// dynamics and the articulated body forward dynamics from the state (kinematics included);
/// the mass matrix by carried columns (soa::mass_matrix_crb()) and with the products
/// hoisted (soa::mass_matrix_inertial()) after soa::update_phi(), which is not counted; the
/// O(N^2) inverse soa::mass_matrix_inverse() with soa::update_phi().
enum class Algorithm {
  InverseDynamics,
  ForwardDynamics,
  MassMatrixCRB,
  MassMatrixInertial,
  MassMatrixInverse
};

inline const char* algorithm_name(Algorithm a) {
  switch (a) {
    case Algorithm::InverseDynamics:
      return "inverse dynamics";
    case Algorithm::ForwardDynamics:
      return "forward dynamics (articulated body)";
    case Algorithm::MassMatrixCRB:
      return "mass matrix (carried columns)";
    case Algorithm::MassMatrixInertial:
      return "mass matrix (products hoisted)";
    case Algorithm::MassMatrixInverse:
      return "mass matrix inverse";
  }
  return "?";
}

/// The operations of \p f.
template <class F>
OpCounts count_ops(F&& f) {
  reset_counts();
  f();
  return counts();
}

/// The operations of one call of \p a on \p c (a second call, after one that warms the
/// workspace up, as in a benchmark loop). \p result receives the call's output (T,
/// beta_dot, M or M^-1) when not null.
inline OpCounts count_call(Algorithm a, const CountChain<Counted>& c,
                           MatX<Counted>* result = nullptr) {
  using S = Counted;
  const ModelT<S>& m = c.m;
  WorkspaceT<S> ws(m);
  MatX<S> out;
  OpCounts n;
  switch (a) {
    case Algorithm::InverseDynamics: {
      VecX<S> T(m.nv());
      const auto call = [&] { inverse_dynamics(m, c.x, c.beta_dot, {}, ws, T); };
      call();
      n = count_ops(call);
      out = T;
      break;
    }
    case Algorithm::ForwardDynamics: {
      ForwardDynamicsT<S> fd(m);
      VecX<S> beta_dot(m.nv());
      const auto call = [&] { forward_dynamics(m, c.x, c.T, {}, ws, fd, beta_dot); };
      call();
      n = count_ops(call);
      out = beta_dot;
      break;
    }
    case Algorithm::MassMatrixCRB: {
      std::vector<SpatialInertiaT<S>> R(std::size_t(m.n()));
      MatX<S> M(m.nv(), m.nv());
      update_phi(m, c.x.theta, ws);
      const auto call = [&] { mass_matrix_crb(m, c.x, ws, R, M); };
      call();
      n = count_ops(call);
      out = M;
      break;
    }
    case Algorithm::MassMatrixInertial: {
      MassMatrixInertialT<S> w(m);
      MatX<S> M(m.nv(), m.nv());
      update_phi(m, c.x.theta, ws);
      const auto call = [&] { mass_matrix_inertial(m, c.x, ws, w, M); };
      call();
      n = count_ops(call);
      out = M;
      break;
    }
    case Algorithm::MassMatrixInverse: {
      MassMatrixInverseT<S> w(m);
      MatX<S> Minv(m.nv(), m.nv());
      const auto call = [&] {
        update_phi(m, c.x.theta, ws);
        mass_matrix_inverse(m, c.x, ws, w, Minv);
      };
      call();
      n = count_ops(call);
      out = Minv;
      break;
    }
  }
  if (result) *result = out;
  return n;
}

/// The count of \p a on the chain of \p n bodies of \p type, with \p fast_paths.
inline OpCounts count_chain(Algorithm a, HingeType type, int n, Axes axes, bool fast_paths) {
  CountChain<Counted> c(type, n, axes);
  c.m.fast_paths = fast_paths;
  return count_call(a, c);
}

/// Operations per body of an O(N) algorithm: the count on 2n bodies less the count on n,
/// over n. \p linear: whether the count on 3n bodies continues the line, as it must when no
/// branch depends on the values; \p spread: how far it misses, relative (a hinge of several
/// degrees of freedom iterates the eigenvalues of its n_k x n_k pivot in the singularity
/// guard, a number of steps that depends on the values).
struct PerBody {
  double flops = 0, sqrt = 0, trig = 0, other = 0, cmp = 0;
  bool linear = false;
  double spread = 0;
};
inline PerBody per_body(Algorithm a, HingeType type, Axes axes, bool fast_paths, int n = 8) {
  const OpCounts c1 = count_chain(a, type, n, axes, fast_paths);
  const OpCounts c2 = count_chain(a, type, 2 * n, axes, fast_paths);
  const OpCounts c3 = count_chain(a, type, 3 * n, axes, fast_paths);
  const OpCounts d = c2 - c1, e = c3 - c2;
  PerBody p;
  p.flops = double(d.flops()) / n;
  p.sqrt = double(d.sqrt) / n;
  p.trig = double(d.trig) / n;
  p.other = double(d.other) / n;
  p.cmp = double(d.cmp) / n;
  p.linear = d.flops() == e.flops() && d.sqrt == e.sqrt && d.trig == e.trig && d.other == e.other &&
             d.cmp == e.cmp;
  p.spread = std::abs(double(e.flops() - d.flops())) / double(d.flops());
  return p;
}

/// The flops of an O(N^2) algorithm as a N^2 + b N + c, from chains of n, 2n and 3n bodies.
/// \p exact: whether the count on 4n bodies is that polynomial's (as in PerBody, unless a
/// branch depends on the values); \p miss: how far it is, relative.
struct Quadratic {
  double a = 0, b = 0, c = 0;
  bool exact = false;
  double miss = 0;
};
inline Quadratic quadratic_flops(Algorithm a, HingeType type, Axes axes, bool fast_paths,
                                 int n = 8) {
  double f[4];
  for (int i = 0; i < 4; ++i)
    f[i] = double(count_chain(a, type, (i + 1) * n, axes, fast_paths).flops());
  Quadratic q;
  const double h = n;
  q.a = (f[2] - 2 * f[1] + f[0]) / (2 * h * h);
  q.b = (f[1] - f[0]) / h - 3 * q.a * h;
  q.c = f[0] - q.a * h * h - q.b * h;
  const double f4 = q.a * 16 * h * h + q.b * 4 * h + q.c;
  q.exact = f[3] == f4;
  q.miss = std::abs(f[3] - f4) / f[3];
  return q;
}

}  // namespace soa::test
