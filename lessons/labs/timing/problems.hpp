/// \file
/// The problems of the timing lab, error against run time of lesson 8's forward dynamics: the
/// benchmark chain of `make bench` and the extreme chains of lesson 6 with joint rates, built
/// in double and cast to float and long double; the four ways to solve \f$\mathcal M\dot\beta = T - \mathcal C\f$ and
/// the errors of their results.
#pragma once

#include <Eigen/Cholesky>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "benchmark_chain.hpp"
#include "report.hpp"
#include "soa/chain.hpp"
#include "soa/chain/mass_matrix_inverse_upsilon.hpp"
#include "soa/soa.hpp"

namespace soa::lesson::timing {

/// A forward dynamics problem: the chain, its state and the hinge forces \f$T\f$.
template <class S>
struct Problem {
  soa::ModelT<S> m;
  soa::StateT<S> x;
  soa::VecX<S> T;
};

/// \p p in precision S: every number of the double problem rounded once (so that float,
/// double and long double solve the same problem, the one written in double).
template <class S>
Problem<S> cast(const Problem<double>& p) {
  std::vector<soa::BodyT<S>> bodies;
  for (int k = p.m.n(); k >= 1; --k) {
    const soa::Body& B = p.m.body(k);
    soa::BodyT<S> b;
    b.name = B.name;
    b.M = B.M.template cast<S>();
    b.placement = B.placement.template cast<S>();
    b.hinge = B.hinge.template cast<S>();
    bodies.push_back(b);
  }
  Problem<S> q{soa::ModelT<S>::from_base_first(std::move(bodies)), {}, p.T.template cast<S>()};
  q.m.gravity = p.m.gravity.template cast<S>();
  q.x = soa::StateT<S>{p.x.theta.template cast<S>(), p.x.beta.template cast<S>()};
  return q;
}

/// The benchmark chain of `make bench` (soa::bench::Chain): n revolute links of 0.3 m with
/// axes alternating z and y, masses 1, 1.1, 1.2, gravity, a random pose, random rates and
/// random hinge forces.
inline Problem<double> benchmark_chain(int n) {
  soa::bench::Chain c(n, true);
  return Problem<double>{std::move(c.model), std::move(c.x), std::move(c.T)};
}

/// One extreme chain (lesson 6, section 7, with rates): n revolute hinges, every axis along
/// z, links of 1 m, point-like bodies (centre of mass 0.5 m out, rotational inertia J about
/// it), masses alternating heavy (1) and light from the base out (\p ratio = the second
/// body's mass over the first's), straight (\f$\theta = 0\f$, all axes parallel) or a random
/// pose (\p pose_seed > 0), joint rates uniform in [-\p rate, \p rate] rad/s, gravity in
/// the plane of motion, random hinge forces; \p tip_mass >= 0 replaces the tip's mass (a
/// point mass).
struct Spec {
  std::string name;
  int n = 10;
  double ratio = 1;
  double J = 1e-3;
  unsigned pose_seed = 0;
  double rate = 0;
  double tip_mass = -1;
};

/// The short name of a case, for tables and figure axes: "r1e-08 J1e-09 bent w1e+02 n10".
inline std::string short_name(const Spec& s) {
  std::string t = s.ratio != 1 ? "r" + soa::lesson::num(s.ratio, "%.0e") : "r1";
  t += " J" + soa::lesson::num(s.J, "%.0e");
  if (s.pose_seed) t += " bent";
  if (s.rate > 0) t += " w" + soa::lesson::num(s.rate, "%.0e");
  if (s.tip_mass >= 0) t += " tip0";
  return t + " n" + std::to_string(s.n);
}

/// The chain and the problem of \p s, bodies named by their course number (`b1` is the tip).
inline Problem<double> extreme_chain(const Spec& s) {
  const double light = 1 / std::max(s.ratio, 1 / s.ratio);
  std::vector<soa::Body> bodies(static_cast<std::size_t>(s.n));
  for (int i = 0; i < s.n; ++i) {  // i = 0 next to the base: course number k = n - i
    const bool first = i % 2 == 0;
    double m = (first == (s.ratio < 1)) ? 1.0 : light, J = s.J;
    if (i == s.n - 1 && s.tip_mass >= 0) m = s.tip_mass, J = 0;
    soa::Body& b = bodies[std::size_t(i)];
    b.name = "b" + std::to_string(s.n - i);
    b.M = m > 0 ? soa::SpatialInertia::from_cm(m, soa::Vec3<double>(0.5, 0, 0),
                                               J * soa::Mat3<double>::Identity())
                : soa::SpatialInertia();
    b.placement = soa::Pose(soa::Mat3<double>::Identity(),
                            i == 0 ? soa::Vec3<double>::Zero() : soa::Vec3<double>(1, 0, 0));
    b.hinge.type = soa::HingeType::Revolute;
    b.hinge.axis = soa::Vec3<double>::UnitZ();
  }
  Problem<double> p{soa::Model::from_base_first(std::move(bodies)), {}, {}};
  p.m.gravity = soa::Vec3<double>(0, -9.81, 0);
  p.x = soa::State::rest(p.m);
  std::mt19937_64 gen(1000 + unsigned(s.n));
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), unit(-1, 1);
  std::normal_distribution<double> normal;
  if (s.pose_seed > 0) {
    std::mt19937_64 pose(s.pose_seed);
    for (int i = 0; i < p.m.nq(); ++i) p.x.theta[i] = angle(pose);
  }
  p.T.resize(p.m.nv());
  for (int i = 0; i < p.m.nv(); ++i) {
    p.x.beta[i] = s.rate * unit(gen);
    p.T[i] = normal(gen);
  }
  return p;
}

/// The three ways to solve \f$\mathcal M\dot\beta = T - \mathcal C\f$, and a fourth:
/// \f$\mathcal M^{-1}\f$ built on \f$\Upsilon\f$ (lesson 7, section 7).
enum class Method { ABA, CRB, Minv, MinvUpsilon };
inline const char* name(Method method) {
  return method == Method::ABA           ? "ABA"
         : method == Method::CRB         ? "CRB+LDLT"
         : method == Method::MinvUpsilon ? "MinvUpsilon"
                                         : "Minv";
}

/// A solver of one problem by one method, its workspace sized once (what the timing loop
/// calls): soa::forward_dynamics() (O(n)); soa::inverse_dynamics() at \f$\dot\beta = 0\f$ for
/// \f$\mathcal C\f$, soa::mass_matrix_crb() and Eigen's LDLT (O(n^3)); or \f$\mathcal C\f$,
/// soa::mass_matrix_inverse() and \f$\mathcal M^{-1}(T - \mathcal C)\f$ (O(n^2)); or the same
/// with soa::mass_matrix_inverse_upsilon() (O(n^2)).
template <class S>
class Solver {
 public:
  Solver(Method method, const Problem<S>& p)
      : method_(method),
        p_(p),
        ws_(p.m),
        fd_(method == Method::ABA ? p.m : soa::ModelT<S>()),
        w_(method == Method::Minv ? p.m : soa::ModelT<S>()),
        wu_(method == Method::MinvUpsilon ? p.m : soa::ModelT<S>()),
        R_(method == Method::CRB ? std::size_t(p.m.n()) : 0),
        A_(method == Method::ABA ? 0 : p.m.nv(), method == Method::ABA ? 0 : p.m.nv()),
        C_(p.m.nv()),
        zero_(soa::VecX<S>::Zero(p.m.nv())),
        ldlt_(method == Method::CRB ? p.m.nv() : 0) {}

  /// \f$\dot\beta\f$ into \p beta_dot (sized nv); throws soa::Error when the method refuses.
  void solve(soa::VecX<S>& beta_dot) {
    const Problem<S>& p = p_;
    switch (method_) {
      case Method::ABA:
        soa::forward_dynamics(p.m, p.x, p.T, {}, ws_, fd_, beta_dot);
        break;
      case Method::CRB:
        soa::inverse_dynamics(p.m, p.x, zero_, {}, ws_, C_);  // C, and phi for the CRB
        soa::mass_matrix_crb(p.m, p.x, ws_, R_, A_);
        ldlt_.compute(A_);
        beta_dot = p.T - C_;
        ldlt_.solveInPlace(beta_dot);
        break;
      case Method::Minv:
        soa::inverse_dynamics(p.m, p.x, zero_, {}, ws_, C_);  // C, and phi for M^-1
        soa::mass_matrix_inverse(p.m, p.x, ws_, w_, A_);
        C_ = p.T - C_;
        beta_dot.noalias() = A_ * C_;
        break;
      case Method::MinvUpsilon:
        soa::inverse_dynamics(p.m, p.x, zero_, {}, ws_, C_);  // C, and phi for M^-1
        soa::mass_matrix_inverse_upsilon(p.m, p.x, ws_, wu_, A_);
        C_ = p.T - C_;
        beta_dot.noalias() = A_ * C_;
        break;
    }
  }
  /// The matrix the method formed: \f$\mathcal M\f$ (CRB) or \f$\mathcal M^{-1}\f$ (Minv,
  /// MinvUpsilon).
  const soa::MatX<S>& matrix() const { return A_; }

 private:
  Method method_;
  const Problem<S>& p_;
  soa::WorkspaceT<S> ws_;
  soa::ForwardDynamicsT<S> fd_;
  soa::MassMatrixInverseT<S> w_;
  soa::MassMatrixInverseUpsilonT<S> wu_;
  std::vector<soa::SpatialInertiaT<S>> R_;
  soa::MatX<S> A_;
  soa::VecX<S> C_, zero_;
  Eigen::LDLT<soa::MatX<S>> ldlt_;
};

/// The forward error \f$\|\dot\beta - \dot\beta_{\rm ref}\| / \|\dot\beta_{\rm ref}\|\f$.
template <class S>
double forward_error(const soa::VecX<S>& beta_dot, const soa::VecX<long double>& ref) {
  return double((beta_dot.template cast<long double>() - ref).norm() / ref.norm());
}

/// The round trip \f$\|ID(\dot\beta) - T\| / \|T\|\f$, inverse dynamics in precision S (what
/// a user of that precision would check).
template <class S>
double round_trip(const Problem<S>& p, const soa::VecX<S>& beta_dot) {
  soa::WorkspaceT<S> ws(p.m);
  soa::VecX<S> T(p.m.nv());
  soa::inverse_dynamics(p.m, p.x, beta_dot, {}, ws, T);
  return double((T - p.T).template cast<long double>().norm() /
                p.T.template cast<long double>().norm());
}

}  // namespace soa::lesson::timing
