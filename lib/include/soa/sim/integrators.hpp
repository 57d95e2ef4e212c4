/// \file
/// One step of each integrator of the simulation, on the chain's configuration manifold.
#pragma once

#include <Eigen/LU>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "soa/sim/chain_system.hpp"

namespace soa {

/// The integrators of `soa simulate`.
enum class Integrator {
  Euler,             ///< explicit Euler, order 1
  SymplecticEuler,   ///< semi-implicit Euler: velocity first, then position, order 1
  RK4,               ///< classical Runge-Kutta, order 4
  DormandPrince,     ///< Dormand-Prince 5(4), adaptive step, order 5
  ImplicitMidpoint,  ///< implicit midpoint (1-stage Gauss), order 2, A-stable, symmetric
};

/// "euler", "symplectic-euler", "rk4", "dopri5", "implicit-midpoint".
inline const char* integrator_name(Integrator i) {
  switch (i) {
    case Integrator::Euler:
      return "euler";
    case Integrator::SymplecticEuler:
      return "symplectic-euler";
    case Integrator::RK4:
      return "rk4";
    case Integrator::DormandPrince:
      return "dopri5";
    case Integrator::ImplicitMidpoint:
      return "implicit-midpoint";
  }
  return "?";
}

/// The integrator called \p name; throws soa::Error listing the names.
inline Integrator integrator_from_name(const std::string& name) {
  for (Integrator i : {Integrator::Euler, Integrator::SymplecticEuler, Integrator::RK4,
                       Integrator::DormandPrince, Integrator::ImplicitMidpoint})
    if (name == integrator_name(i)) return i;
  throw Error("unknown integrator \"" + name +
              "\" (euler, symplectic-euler, rk4, dopri5, implicit-midpoint)");
}

/// The order of convergence of each integrator.
inline int integrator_order(Integrator i) {
  switch (i) {
    case Integrator::Euler:
    case Integrator::SymplecticEuler:
      return 1;
    case Integrator::RK4:
      return 4;
    case Integrator::DormandPrince:
      return 5;
    case Integrator::ImplicitMidpoint:
      return 2;
  }
  return 0;
}

/// Steps a ChainSystemT. Every method works in local coordinates around the step's start,
/// \f$\theta = \theta_0 \oplus u\f$ (retract()), with \f$\dot u\f$ from local_rate(): a
/// Runge-Kutta-Munthe-Kaas scheme, so quaternion hinges stay on the unit sphere by
/// construction and each method keeps its order. Buffers are allocated once.
template <class S>
class StepperT {
 public:
  explicit StepperT(ChainSystemT<S>& sys)
      : sys_(sys),
        nv_(sys.model().nv()),
        x_{VecX<S>(sys.model().nq()), VecX<S>(nv_)},
        u_(nv_),
        Ku_(7, VecX<S>(nv_)),
        Kb_(7, VecX<S>(nv_)) {}

  /// One step of an explicit Runge-Kutta method with the Butcher tableau \p a (lower
  /// triangular, s x s), \p b and \p c from \p x0 to \p x1; with \p b_err, also the local
  /// error estimate \f$h\sum_j (b_j - \hat b_j) K_j\f$ (in \f$(u, \beta)\f$) into \p err.
  template <int s>
  void explicit_rk(const std::array<std::array<double, s>, s>& a, const std::array<double, s>& b,
                   const std::array<double, s>& c, const std::array<double, s>* b_err, S t, S h,
                   const StateT<S>& x0, StateT<S>& x1, VecX<S>* err) {
    for (int i = 0; i < s; ++i) {
      u_.setZero();
      x_.beta = x0.beta;
      for (int j = 0; j < i; ++j)
        if (a[i][j] != 0.0) {
          u_ += (h * S(a[i][j])) * Ku_[j];
          x_.beta += (h * S(a[i][j])) * Kb_[j];
        }
      stage(t + S(c[i]) * h, x0.theta, i);
    }
    u_.setZero();
    x1.beta = x0.beta;
    for (int j = 0; j < s; ++j) {
      u_ += (h * S(b[j])) * Ku_[j];
      x1.beta += (h * S(b[j])) * Kb_[j];
    }
    finish(x0.theta, x1);
    if (b_err) {
      err->resize(2 * nv_);
      err->setZero();
      for (int j = 0; j < s; ++j) {
        err->head(nv_) += (h * S((*b_err)[j])) * Ku_[j];
        err->tail(nv_) += (h * S((*b_err)[j])) * Kb_[j];
      }
    }
  }

  /// Explicit Euler: \f$\theta_1 = \theta_0 \oplus h\beta_0,\ \beta_1 = \beta_0 +
  /// h\dot\beta(x_0)\f$.
  void euler(S t, S h, const StateT<S>& x0, StateT<S>& x1) {
    static constexpr std::array<std::array<double, 1>, 1> a{{{0}}};
    static constexpr std::array<double, 1> b{1}, c{0};
    explicit_rk<1>(a, b, c, nullptr, t, h, x0, x1, nullptr);
  }

  /// Semi-implicit (symplectic) Euler: \f$\beta_1 = \beta_0 + h\dot\beta(x_0)\f$, then
  /// \f$\theta_1 = \theta_0 \oplus h\beta_1\f$.
  void symplectic_euler(S t, S h, const StateT<S>& x0, StateT<S>& x1) {
    sys_.acceleration(t, x0, Kb_[0]);
    x1.beta = x0.beta + h * Kb_[0];
    u_.setZero();
    local_rate(sys_.model(), x0.theta, u_, x1.beta, Ku_[0]);
    u_ = h * Ku_[0];
    finish(x0.theta, x1);
  }

  /// Classical RK4.
  void rk4(S t, S h, const StateT<S>& x0, StateT<S>& x1) {
    static constexpr std::array<std::array<double, 4>, 4> a{
        {{0, 0, 0, 0}, {0.5, 0, 0, 0}, {0, 0.5, 0, 0}, {0, 0, 1, 0}}};
    static constexpr std::array<double, 4> b{1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6}, c{0, 0.5, 0.5, 1};
    explicit_rk<4>(a, b, c, nullptr, t, h, x0, x1, nullptr);
  }

  /// Dormand-Prince 5(4) (Hairer, Norsett, Wanner, Solving ODEs I, table II.5.2): the fifth
  /// order solution, and in \p err the difference from the embedded fourth order one.
  void dopri5(S t, S h, const StateT<S>& x0, StateT<S>& x1, VecX<S>& err) {
    static constexpr std::array<std::array<double, 7>, 7> a{
        {{0, 0, 0, 0, 0, 0, 0},
         {1.0 / 5, 0, 0, 0, 0, 0, 0},
         {3.0 / 40, 9.0 / 40, 0, 0, 0, 0, 0},
         {44.0 / 45, -56.0 / 15, 32.0 / 9, 0, 0, 0, 0},
         {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729, 0, 0, 0},
         {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656, 0, 0},
         {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0}}};
    static constexpr std::array<double, 7> b{
        35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0};
    static constexpr std::array<double, 7> b4{
        5179.0 / 57600, 0, 7571.0 / 16695, 393.0 / 640, -92097.0 / 339200, 187.0 / 2100, 1.0 / 40};
    static constexpr std::array<double, 7> c{0, 0.2, 0.3, 0.8, 8.0 / 9, 1, 1};
    std::array<double, 7> e{};
    for (int i = 0; i < 7; ++i) e[std::size_t(i)] = b[std::size_t(i)] - b4[std::size_t(i)];
    explicit_rk<7>(a, b, c, &e, t, h, x0, x1, &err);
  }

  /// Implicit midpoint: with \f$Z = (u, w)\f$ the step in local coordinates and velocity,
  /// \f$Z = h\,F(Z/2)\f$, \f$F\f$ the rate at \f$(\theta_0 \oplus u/2,\ \beta_0 + w/2)\f$;
  /// solved by Newton's method with the Jacobian of the dynamics by finite differences
  /// (frozen during the step). Returns false when Newton does not converge.
  bool implicit_midpoint(S t, S h, const StateT<S>& x0, StateT<S>& x1) {
    const int n2 = 2 * nv_;
    VecX<S> Z = VecX<S>::Zero(n2), F(n2), Fp(n2), dZ(n2);
    // J = I - (h/2) dF/dZ at the start of the step, by forward differences.
    MatX<S> J(n2, n2);
    rate_at(t + h / 2, x0, Z, F);
    for (int i = 0; i < n2; ++i) {
      VecX<S> Zi = Z;
      const S d = std::sqrt(eps<S>());
      Zi[i] += d;
      rate_at(t + h / 2, x0, Zi, Fp);
      J.col(i) = -(h / S(2)) * (Fp - F) / d;
      J(i, i) += S(1);
    }
    const Eigen::PartialPivLU<MatX<S>> lu(J);
    // Simplified Newton; stops when the estimated distance to the solution,
    // theta/(1 - theta) |dZ| with theta the contraction rate, is at rounding level
    // (Hairer and Wanner, Solving ODEs II, IV.8).
    S last = S(0);
    for (int it = 0; it < 50; ++it) {
      if (it > 0) rate_at(t + h / 2, x0, (Z / S(2)).eval(), F);
      dZ = lu.solve(Z - h * F);
      Z -= dZ;
      const S size = dZ.norm(), tol = S(16) * eps<S>() * (S(1) + Z.norm());
      if (!Z.allFinite()) return false;
      if (size <= tol) break;
      if (it > 0) {
        const S rate = size / last;
        if (rate >= S(1)) return false;  // diverging
        if (rate / (S(1) - rate) * size <= tol) break;
      }
      last = size;
      if (it == 49) return false;
    }
    u_ = Z.head(nv_);
    x1.beta = x0.beta + Z.tail(nv_);
    finish(x0.theta, x1);
    return true;
  }

  /// The full rate \f$(\dot u, \dot\beta)\f$ at local coordinates \p Z = (u, w) around \p x0
  /// (state \f$(\theta_0 \oplus u, \beta_0 + w)\f$), for Newton and stiffness estimates.
  void rate_at(S t, const StateT<S>& x0, const VecX<S>& Z, VecX<S>& F) {
    const VecX<S> u = Z.head(nv_);
    retract(sys_.model(), x0.theta, u, x_.theta);
    x_.beta = x0.beta + Z.tail(nv_);
    F.resize(2 * nv_);
    VecX<S> bd(nv_), ud(nv_);
    sys_.acceleration(t, x_, bd);
    local_rate(sys_.model(), x_.theta, u, x_.beta, ud);
    F.head(nv_) = ud;
    F.tail(nv_) = bd;
  }

 private:
  // Stage i at local coordinates u_ and velocity x_.beta: K_u[i], K_beta[i].
  void stage(S t, const VecX<S>& theta0, int i) {
    retract(sys_.model(), theta0, u_, x_.theta);
    sys_.acceleration(t, x_, Kb_[std::size_t(i)]);
    local_rate(sys_.model(), x_.theta, u_, x_.beta, Ku_[std::size_t(i)]);
  }
  // theta_1 = theta_0 (+) u_.
  void finish(const VecX<S>& theta0, StateT<S>& x1) {
    if (!u_.allFinite()) {  // leave the blow-up to the caller: a non-finite state
      x1.theta.setConstant(theta0.size(), std::numeric_limits<S>::quiet_NaN());
      return;
    }
    retract(sys_.model(), theta0, u_, x1.theta);
  }

  ChainSystemT<S>& sys_;
  int nv_;
  StateT<S> x_;
  VecX<S> u_;
  std::vector<VecX<S>> Ku_, Kb_;
};
using Stepper = StepperT<double>;

}  // namespace soa
