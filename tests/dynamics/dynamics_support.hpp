// Shared set-up of the dynamics tests: a random chain with its state, hinge forces and
// (sometimes) external forces, and the reference solution by the composite bodies.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <random>
#include <utility>
#include <vector>

#include "property.hpp"
#include "random_chain.hpp"
#include "soa/chain.hpp"

namespace soa::test {

/// Random case \p i: 1..12 bodies of every hinge type; gravity on odd cases, springs and
/// dampers on every third, external forces on every fourth, at rest on every fifth.
template <class S>
struct DynamicsCase {
  ModelT<S> m;
  StateT<S> x;
  VecX<S> T;
  ExternalForces<S> f_ext;
  DynamicsCase(Random<S>& rnd, int i) {
    ChainOptions opt;
    opt.gravity = i % 2 == 1;
    opt.springs = i % 3 == 0;
    m = random_chain(rnd, 1 + i % 12, opt);
    x = random_state(rnd, m);
    if (i % 5 == 0) x.beta.setZero();
    T = random_vector(rnd, m.nv());
    if (i % 4 == 0) f_ext = random_forces(rnd, m);
  }
};

/// The mass matrix (composite bodies, lesson 5) and the bias \f$\mathcal C\f$ (inverse
/// dynamics at \f$\dot\beta = 0\f$, springs included) of a case.
template <class S>
struct MassAndBias {
  MatX<S> M;
  VecX<S> C;
  template <class Case>
  explicit MassAndBias(const Case& c) {
    WorkspaceT<S> ws(c.m);
    C.resize(c.m.nv());
    inverse_dynamics(c.m, c.x, VecX<S>::Zero(c.m.nv()).eval(), c.f_ext, ws, C);
    std::vector<SpatialInertiaT<S>> R(std::size_t(c.m.n()));
    mass_matrix_crb(c.m, c.x, ws, R, M);
  }
  /// The 2-norm condition number of M.
  double cond() const {
    const VecX<S> ev =
        Eigen::SelfAdjointEigenSolver<MatX<S>>(M, Eigen::EigenvaluesOnly).eigenvalues();
    return double(ev.maxCoeff() / ev.minCoeff());
  }
};

/// Turns \p c into a chain where the fast paths apply (Model::fast_paths): every one-dof
/// hinge about a random \f$\pm e_i\f$, half of the placements not rotating and half of the
/// offsets along a coordinate axis (of the same length), drawn from \p g. Returns how many
/// bodies past the tip have a placement that does not rotate (first) and an offset along an
/// axis (second): a test checks that the paths were taken.
inline std::pair<int, int> coordinate_axis_chain(DynamicsCase<double>& c, std::mt19937& g) {
  std::pair<int, int> taken{0, 0};
  for (int k = 1; k <= c.m.n(); ++k) {
    soa::Body& B = c.m.body(k);
    if (B.hinge.nv() != 1) continue;
    B.hinge.axis = soa::Vec3<double>::Zero();
    B.hinge.axis[int(g() % 3)] = g() % 2 ? 1.0 : -1.0;
    if (g() % 2) B.placement = soa::Pose(soa::Mat3<double>::Identity(), B.placement.l());
    if (g() % 2) {
      soa::Vec3<double> l = soa::Vec3<double>::Zero();
      l[int(g() % 3)] = (g() % 2 ? 1.0 : -1.0) * B.placement.l().norm();
      B.placement = soa::Pose(B.placement.R(), l);
    }
    if (k > 1 && B.placement.R().isIdentity(0)) ++taken.first;
    if (k > 1 && soa::detail::coordinate_offset(B.placement.l()) >= 0) ++taken.second;
  }
  return taken;
}

/// Calls \p f(c, i) on the kCases random cases of \p rnd, each made a coordinate_axis_chain()
/// with one generator seeded kSeed. Returns the summed counts of coordinate_axis_chain().
template <class F>
std::pair<int, int> for_each_coordinate_axis_case(Random<double>& rnd, F&& f) {
  std::mt19937 g(kSeed);
  std::pair<int, int> taken{0, 0};
  for (int i = 0; i < kCases; ++i) {
    DynamicsCase<double> c(rnd, i);
    const std::pair<int, int> t = coordinate_axis_chain(c, g);
    taken.first += t.first, taken.second += t.second;
    f(c, i);
  }
  return taken;
}

}  // namespace soa::test
