/// \file
/// Stiffness: the dominant eigenvalue \f$\lambda\f$ of the Jacobian of the rate by power
/// iteration, and whether a fixed step \f$h\f$ puts \f$h\lambda\f$ outside an explicit
/// method's stability region (the monitor of soa::simulate()).
#pragma once

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <random>

#include "soa/sim/integrators.hpp"

namespace soa {

/// What soa::simulate() does when the monitor finds an explicit fixed-step method beyond its
/// stability bound: stop with soa::Error (default), note it in
/// SimulationSummary::stiffness_warning and go on, or not look (no evaluations spent).
enum class StiffnessPolicy { Stop, Warn, Off };

/// The stability function \f$R(z)\f$ of an explicit Runge-Kutta method (\f$y_1 = R(h\lambda)
/// y_0\f$ on \f$\dot y = \lambda y\f$): explicit Euler \f$1 + z\f$, RK4 the Taylor polynomial
/// of \f$e^z\f$ of degree 4, Dormand-Prince \f$\sum_{j \le 5} z^j/j! + z^6/600\f$ (Hairer,
/// Norsett and Wanner, Solving ODEs I, IV.2). NaN for the other methods.
inline std::complex<double> explicit_stability_function(Integrator m, std::complex<double> z) {
  switch (m) {
    case Integrator::Euler:
      return 1.0 + z;
    case Integrator::RK4:
      return 1.0 + z * (1.0 + z / 2.0 * (1.0 + z / 3.0 * (1.0 + z / 4.0)));
    case Integrator::DormandPrince:
      return 1.0 + z * (1.0 + z / 2.0 * (1.0 + z / 3.0 * (1.0 + z / 4.0 * (1.0 + z / 5.0)))) +
             std::pow(z, 6) / 600.0;
    default:
      return std::complex<double>(NAN, NAN);
  }
}

/// Whether a fixed step puts \f$z = h\lambda\f$ beyond the method's stability bound: the step
/// does not resolve the mode (\f$|z| \ge 1\f$) and amplifies it more than the exact flow
/// does, \f$|R(z)| > \max(1, |e^z|)\f$, for a Runge-Kutta method (a mode that grows by
/// itself, as the falling arm's, is followed, not flagged: there \f$|R(z)| < e^z\f$); for
/// symplectic Euler, stable on \f$\ddot y = -\omega^2 y\f$ for \f$h\omega \le 2\f$,
/// \f$|z| > 2\f$, or a step that spans half an e-fold of a growing mode, \f$\mathrm{Re}\,z
/// \ge 1/2\f$, where its first-order step leaves a relative error of \f$z^2/2\f$ per step
/// (a chain whipping its light links has eigenvalues \f$\pm\lambda\f$). False for the
/// implicit methods (A-stable) and the adaptive ones (their step control holds
/// \f$h\lambda\f$ at the bound).
inline bool beyond_stability_bound(Integrator m, std::complex<double> z) {
  if (std::abs(z) < 1) return false;
  switch (m) {
    case Integrator::Euler:
    case Integrator::RK4: {
      const double R = std::abs(explicit_stability_function(m, z));
      return R > 1 && R > std::exp(z.real());
    }
    case Integrator::SymplecticEuler:
      return std::abs(z) > 2 || z.real() >= 0.5;
    default:
      return false;
  }
}

/// Where each method is stable on an undamped oscillation \f$\ddot x = -\omega^2 x\f$, for the
/// blow-up message.
inline const char* stability_note(Integrator i) {
  switch (i) {
    case Integrator::Euler:
      return "explicit Euler grows on undamped oscillations at every step, |1 + i h omega| > 1: "
             "use symplectic-euler, rk4 or implicit-midpoint";
    case Integrator::SymplecticEuler:
      return "symplectic Euler needs h omega < 2: take a smaller --dt or esdirk4";
    case Integrator::RK4:
      return "RK4 needs h omega < 2.83: take a smaller --dt or esdirk4";
    case Integrator::DormandPrince:
      return "dopri5 shrinks its steps to its stability limit (h lambda about 3.3 on decaying "
             "modes, 2.5 on lightly damped oscillations): a stiff scene is cheaper with "
             "esdirk4";
    case Integrator::ImplicitMidpoint:
      return "implicit midpoint is stable at any step; Newton's method needs a smaller --dt";
    case Integrator::Esdirk:
      return "esdirk4 is L-stable at any step and shrinks it when Newton fails: a blow-up here "
             "is in the motion itself, or the tolerance is too loose (--tol)";
    case Integrator::Radau5:
      return "radau5 is L-stable at any step and shrinks it when Newton fails: a blow-up here "
             "is in the motion itself, or the tolerance is too loose (--tol)";
    case Integrator::Variational:
      return "the variational integrator is implicit; Newton's method needs a smaller --dt";
  }
  return "";
}

/// The dominant eigenvalue of the Jacobian \f$J = \partial F/\partial z\f$ of the rate at a
/// state: the Ritz value of largest modulus of an Arnoldi process of \f$k\f$ steps on
/// Jacobian-vector products by forward differences, \f$J v \approx (F(x \oplus \delta v) -
/// F(x))/\delta\f$, \f$\delta = \sqrt\epsilon\f$, \f$|v| = 1\f$ (Saad, Numerical Methods
/// for Large Eigenvalue Problems, 2011, VI.2). Krylov vectors \f$V\f$ orthonormal by modified
/// Gram-Schmidt, \f$J V_k = V_{k+1} \bar H_k\f$; the Ritz values are the eigenvalues of the
/// \f$k \times k\f$ Hessenberg matrix \f$H_k\f$. Power iteration with the same evaluations
/// converges slowly where a chain's spectrum clusters (pairs \f$a \pm ib\f$, and
/// \f$\pm\lambda\f$ from the velocity terms); Arnoldi is exact once \f$k = 2n_v\f$.
///
/// The next call starts from the dominant Ritz vector \f$y\f$ of this one (\f$\mathrm{Re}\,y
/// + \mathrm{Im}\,y\f$, in the invariant plane of a complex pair): while \f$J\f$ changes
/// slowly along a run, a few steps suffice. Cost of a call: \f$k + 1\f$ rate evaluations.
/// Allocates nothing after construction (\f$k \le\f$ kMaxSteps).
template <class S>
class DominantEigenvalueT {
 public:
  static constexpr int kMaxSteps = 24;

  explicit DominantEigenvalueT(int nv)
      : n2_(2 * nv), V_(n2_, kMaxSteps + 1), d_(n2_), F0_(n2_), w_(n2_) {
    std::mt19937 g(5);
    std::normal_distribution<double> N;
    for (int i = 0; i < n2_; ++i) d_[i] = S(N(g));
    d_.normalize();
  }

  /// \f$\lambda\f$ at \p t, \p x by \p steps Arnoldi steps (at most kMaxSteps) from the
  /// kept vector (the constructor's random one at first).
  std::complex<double> operator()(StepperT<S>& stepper, S t, const StateT<S>& x, int steps);

 private:
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxSteps + 1, kMaxSteps>;
  using Square = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxSteps, kMaxSteps>;
  int n2_;
  MatX<S> V_;
  VecX<S> d_, F0_, w_;
  Small H_ = Small::Zero(kMaxSteps + 1, kMaxSteps);
  Square Hk_;
  Eigen::EigenSolver<Square> es_;
};

// The members are defined out of the class, not inline: the library compiles them once
// (soa/instantiations.hpp), and the programs, which declare them extern, do not compile them
// again.

template <class S>
std::complex<double> DominantEigenvalueT<S>::operator()(StepperT<S>& stepper, S t,
                                                        const StateT<S>& x, int steps) {
  if (n2_ == 0) return 0;
  const int k_max = std::min({steps, kMaxSteps, n2_});
  w_.setZero();
  stepper.rate_at(t, x, w_, F0_);
  H_.setZero();
  V_.col(0) = d_;
  int k = 0;
  const S delta = std::sqrt(eps<S>());
  while (k < k_max) {
    w_ = delta * V_.col(k);
    stepper.rate_at(t, x, w_, w_);
    w_ = (w_ - F0_) / delta;
    if (!w_.allFinite()) break;
    const double size = double(w_.norm());
    for (int i = 0; i <= k; ++i) {  // modified Gram-Schmidt
      H_(i, k) = double(V_.col(i).dot(w_));
      w_ -= S(H_(i, k)) * V_.col(i);
    }
    H_(k + 1, k) = double(w_.norm());
    ++k;
    // J maps the Krylov space into itself (to rounding): its eigenvalues are exact.
    if (!(H_(k, k - 1) > 1e-10 * size) || k == k_max) break;
    V_.col(k) = w_ / S(H_(k, k - 1));
  }
  if (k == 0) return 0;
  Hk_ = H_.topLeftCorner(k, k);
  es_.compute(Hk_, true);
  // The largest modulus; of values within 1 % of it (+-lambda of a growing mode, a pair),
  // the one of largest real part, the one a step amplifies most.
  const auto& ev = es_.eigenvalues();
  double largest = 0;
  for (int i = 0; i < k; ++i) largest = std::max(largest, std::abs(ev[i]));
  int top = -1;
  for (int i = 0; i < k; ++i)
    if (std::abs(ev[i]) >= 0.99 * largest && (top < 0 || ev[i].real() > ev[top].real())) top = i;
  // The next start: the dominant Ritz vector V_k s, real and imaginary parts summed.
  // A vector of its own: eigenvectors() returns a matrix by value, and a column of it (a
  // block, as `auto` would keep) would outlive it.
  const Eigen::Matrix<std::complex<double>, Eigen::Dynamic, 1, 0, kMaxSteps, 1> s =
      es_.eigenvectors().col(top);
  d_.setZero();
  for (int i = 0; i < k; ++i) d_ += S(s[i].real() + s[i].imag()) * V_.col(i);
  const S norm = d_.norm();
  if (norm > S(0) && d_.allFinite()) {
    d_ /= norm;
  } else {
    d_ = V_.col(0);
  }
  return ev[top];
}

/// An estimate of \f$\max|\lambda|\f$ of the Jacobian of the rate at \p x: 24 Arnoldi steps
/// of DominantEigenvalueT from a fixed random vector (25 rate evaluations). With the step h,
/// \f$h|\lambda|\f$ tells whether an explicit method can be stable (RK4: below about 2.8,
/// Euler: 2 on the real axis, 0 on the imaginary one).
template <class S>
S stiffness_estimate(StepperT<S>& stepper, int nv, S t, const StateT<S>& x) {
  DominantEigenvalueT<S> dominant(nv);
  return S(std::abs(dominant(stepper, t, x, DominantEigenvalueT<S>::kMaxSteps)));
}

}  // namespace soa
