// Shared set-up of the dynamics tests: a random chain with its state, hinge forces and
// (sometimes) external forces, and the reference solution by the composite bodies.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
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

}  // namespace soa::test
