/// \file
/// One step of each integrator of the simulation, on the chain's configuration manifold.
#pragma once

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <array>
#include <cmath>
#include <complex>
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
  /// ESDIRK4(3)6L[2]SA, adaptive step, order 4 (embedded 3), L-stable: for stiff springs
  Esdirk,
  /// Radau IIA (three stages), adaptive step, order 5 (embedded 3), L-stable: stiff springs
  /// at tight tolerances
  Radau5,
  /// implicit midpoint in the canonical variables \f$(\theta, p = \mathcal M\beta)\f$, order 2,
  /// symplectic and symmetric (hinges whose coordinates add)
  Variational,
};

/// The methods that choose their own step from a tolerance (`--tol`).
inline bool is_adaptive(Integrator i) {
  return i == Integrator::DormandPrince || i == Integrator::Esdirk || i == Integrator::Radau5;
}

/// The adaptive implicit methods (esdirk4, radau5): Newton with a kept Jacobian, a step
/// retried smaller when Newton fails.
inline bool is_adaptive_implicit(Integrator i) {
  return i == Integrator::Esdirk || i == Integrator::Radau5;
}

/// "euler", "symplectic-euler", "rk4", "dopri5", "implicit-midpoint", "esdirk4", "radau5",
/// "variational".
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
    case Integrator::Esdirk:
      return "esdirk4";
    case Integrator::Radau5:
      return "radau5";
    case Integrator::Variational:
      return "variational";
  }
  return "?";
}

/// The integrator called \p name; throws soa::Error listing the names.
inline Integrator integrator_from_name(const std::string& name) {
  for (Integrator i : {Integrator::Euler, Integrator::SymplecticEuler, Integrator::RK4,
                       Integrator::DormandPrince, Integrator::ImplicitMidpoint, Integrator::Esdirk,
                       Integrator::Radau5, Integrator::Variational})
    if (name == integrator_name(i)) return i;
  throw Error("unknown integrator \"" + name +
              "\" (euler, symplectic-euler, rk4, dopri5, implicit-midpoint, esdirk4, radau5, "
              "variational)");
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
    case Integrator::Radau5:
      return 5;
    case Integrator::ImplicitMidpoint:
    case Integrator::Variational:
      return 2;
    case Integrator::Esdirk:
      return 4;
  }
  return 0;
}

/// The order of an adaptive method's embedded error estimate (0 for fixed-step methods): the
/// local error estimate is \f$O(h^{q+1})\f$, and the step control uses \f$e^{-1/(q+1)}\f$.
inline int embedded_order(Integrator i) {
  return i == Integrator::DormandPrince                       ? 4
         : i == Integrator::Esdirk || i == Integrator::Radau5 ? 3
                                                              : 0;
}

/// The Butcher tableau of ESDIRK4(3)6L[2]SA (Kennedy and Carpenter, Appl. Numer. Math. 44,
/// 2003: the implicit part of ARK4(3)6L[2]SA; SUNDIALS ARKODE's ARK436L2SA_DIRK_6_3_4):
/// \f$a_{11} = 0\f$ (the first stage explicit), \f$a_{ii} = \gamma = 1/4\f$, the last row is
/// \f$b\f$ (stiffly accurate), and \f$e = b - \hat b\f$ against the embedded third order.
struct Esdirk436 {
  static constexpr int s = 6;
  static constexpr double gamma = 0.25;
  static constexpr std::array<std::array<double, 6>, 6> a{
      {{0, 0, 0, 0, 0, 0},
       {0.25, 0.25, 0, 0, 0, 0},
       {8611.0 / 62500, -1743.0 / 31250, 0.25, 0, 0, 0},
       {5012029.0 / 34652500, -654441.0 / 2922500, 174375.0 / 388108, 0.25, 0, 0},
       {15267082809.0 / 155376265600, -71443401.0 / 120774400, 730878875.0 / 902184768,
        2285395.0 / 8070912, 0.25, 0},
       {82889.0 / 524892, 0, 15625.0 / 83664, 69875.0 / 102672, -2260.0 / 8211, 0.25}}};
  static constexpr std::array<double, 6> c{0, 0.5, 83.0 / 250, 31.0 / 50, 17.0 / 20, 1};
  static constexpr std::array<double, 6> e{31666707.0 / 9881966720, 0,
                                           -256875.0 / 105007616,   -2768025.0 / 128864768,
                                           169839.0 / 3864644,      -5247.0 / 225920};
};

/// Radau IIA with three stages (Hairer and Wanner, Solving ODEs II, IV.5 and IV.8), derived
/// here rather than copied: the nodes \f$c_{1,2} = (4 \mp \sqrt6)/10\f$, \f$c_3 = 1\f$; the
/// matrix \f$A\f$ from the collocation conditions \f$\sum_j a_{ij} c_j^{k-1} = c_i^k/k\f$,
/// k = 1, 2, 3; a real \f$T\f$ with \f$T^{-1}A^{-1}T = \begin{pmatrix}\gamma & 0 & 0\\ 0 &
/// \alpha & \beta\\ 0 & -\beta & \alpha\end{pmatrix}\f$ (the eigenvalues of \f$A^{-1}\f$,
/// \f$\gamma\f$ real and \f$\alpha \pm i\beta\f$), which splits the simplified Newton system
/// of the \f$3n\f$ stage unknowns into one real and one complex system of size n; and the
/// embedded order-3 error weights: \f$\hat y_1 - y_1 = \gamma_0 h f(y_0) + \sum_k e_k Z_k\f$,
/// \f$\gamma_0 = 1/\gamma\f$, \f$e = (\hat b - b)^* A^{-1}\f$ with \f$\hat b\f$ from the
/// order conditions \f$\gamma_0 + \sum_i \hat b_i c_i^{k-1} = 1/k\f$ (k = 1: \f$\gamma_0 +
/// \sum\hat b_i = 1\f$). Tested against the order conditions and the block form.
template <class S>
struct RadauIIA {
  static constexpr int s = 3;
  Eigen::Matrix<S, 3, 3> A, T, T_inv, Lambda;
  Eigen::Matrix<S, 3, 1> c, b, e;
  S gamma, alpha, beta;  ///< the eigenvalues of \f$A^{-1}\f$: \f$\gamma\f$, \f$\alpha \pm i\beta\f$

  static const RadauIIA& get();

 private:
  RadauIIA() {
    using M3 = Eigen::Matrix<S, 3, 3>;
    const S r6 = std::sqrt(S(6));
    c << (S(4) - r6) / S(10), (S(4) + r6) / S(10), S(1);
    M3 V, C;  // V(j, k) = c_j^k, C(i, k) = c_i^(k+1) / (k+1)
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) {
        V(i, k) = std::pow(c[i], S(k));
        C(i, k) = std::pow(c[i], S(k + 1)) / S(k + 1);
      }
    A = C * V.inverse();  // A V = C
    b = A.row(2).transpose();
    const M3 A_inv = A.inverse();
    Eigen::EigenSolver<M3> es(A_inv);
    int ir = 0;  // the real eigenvalue
    for (int i = 1; i < 3; ++i)
      if (std::abs(es.eigenvalues()[i].imag()) < std::abs(es.eigenvalues()[ir].imag())) ir = i;
    const int ic = ir == 0 ? 1 : 0;
    const Eigen::Matrix<std::complex<S>, 3, 1> vc = es.eigenvectors().col(ic);
    T.col(0) = es.eigenvectors().col(ir).real();
    T.col(1) = vc.real();
    T.col(2) = vc.imag();
    T_inv = T.inverse();
    Lambda = T_inv * A_inv * T;
    gamma = Lambda(0, 0);
    alpha = Lambda(1, 1);
    beta = Lambda(1, 2);
    const S gamma0 = S(1) / gamma;
    Eigen::Matrix<S, 3, 1> rhs(S(1) - gamma0, S(1) / S(2), S(1) / S(3));
    const Eigen::Matrix<S, 3, 1> b_hat = V.transpose().inverse() * rhs;  // sum_i b_i c_i^k
    e = A_inv.transpose() * (b_hat - b);
  }
};

// The members are defined out of the class, not inline: the library compiles them once
// (soa/instantiations.hpp), and the programs, which declare them extern, do not compile them
// again.

template <class S>
const RadauIIA<S>& RadauIIA<S>::get() {
  static const RadauIIA r;
  return r;
}

/// Throws soa::Error (one line, naming the body and its hinge) unless every hinge of \p m
/// has coordinates that add (soa::hinge_coordinates_add()): the configuration space of
/// the variational integrator is a vector space.
template <class S>
void require_coordinates_add(const ModelT<S>& m) {
  for (const BodyT<S>& B : m.bodies())
    if (!hinge_coordinates_add(B.hinge.type))
      throw Error(std::string("variational: body '") + B.name + "' has a " +
                  hinge_type_name(B.hinge.type) +
                  " hinge; the variational integrator needs hinges whose coordinates add "
                  "(revolute, prismatic, helical, universal)");
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
        Kb_(7, VecX<S>(nv_)),
        ru_(nv_),
        rud_(nv_),
        rbd_(nv_),
        p0_(nv_),
        pc_(nv_) {}

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
  void euler(S t, S h, const StateT<S>& x0, StateT<S>& x1);

  /// Semi-implicit (symplectic) Euler: \f$\beta_1 = \beta_0 + h\dot\beta(x_0)\f$, then
  /// \f$\theta_1 = \theta_0 \oplus h\beta_1\f$.
  void symplectic_euler(S t, S h, const StateT<S>& x0, StateT<S>& x1);

  /// Classical RK4.
  void rk4(S t, S h, const StateT<S>& x0, StateT<S>& x1);

  /// Dormand-Prince 5(4) (Hairer, Norsett, Wanner, Solving ODEs I, table II.5.2): the fifth
  /// order solution, and in \p err the difference from the embedded fourth order one.
  void dopri5(S t, S h, const StateT<S>& x0, StateT<S>& x1, VecX<S>& err);

  /// Implicit midpoint: with \f$Z = (u, w)\f$ the step in local coordinates and velocity,
  /// \f$Z = h\,F(Z/2)\f$, \f$F\f$ the rate at \f$(\theta_0 \oplus u/2,\ \beta_0 + w/2)\f$;
  /// solved by Newton's method with the Jacobian of the dynamics by finite differences
  /// (frozen during the step); when that fails, by continuation in the step
  /// (continued_solve(): the same equation at h/m, 2h/m, ..., h, each from the last).
  /// Returns false when neither converges. Allocates nothing once the first call has sized
  /// the workspace (shared with esdirk()).
  bool implicit_midpoint(S t, S h, const StateT<S>& x0, StateT<S>& x1);

  /// The variational integrator: the implicit midpoint rule in the canonical variables
  /// \f$z = (\theta, p)\f$, \f$p = \mathcal M(\theta)\beta\f$, of \f$H = \tfrac12 p^*\mathcal
  /// M^{-1}(\theta) p + U(\theta)\f$ (Hairer, Lubich and Wanner, Geometric Numerical
  /// Integration, VI.3: a symplectic map, and symmetric):
  /// \f[ z_1 = z_0 + h\,F\big(\tfrac12(z_0 + z_1)\big), \qquad
  ///     F(\theta, p) = \big(\mathcal M^{-1}(\theta)\,p,\ \partial T/\partial\theta
  ///     + Q\big) \f]
  /// (canonical_rate()), solved as implicit_midpoint() does: \f$Z = z_1 - z_0 = hF(z_0 +
  /// Z/2)\f$ by simplified Newton with a finite-difference Jacobian, taken again when Newton
  /// diverges or contracts slowly (midpoint_solve() with refresh), and by continuation in the
  /// step when Newton from \f$Z = 0\f$ fails (continued_solve()). From \f$(\theta_0,
  /// \beta_0)\f$: \f$p_0 = \mathcal M(\theta_0)\beta_0\f$ (ChainSystemT::momentum()), and after
  /// the step \f$\beta_1 = \mathcal M^{-1}(\theta_1)p_1\f$ (ChainSystemT::velocity()), all
  /// O(N). Needs hinges whose coordinates add (require_coordinates_add() throws otherwise).
  /// Returns false when Newton does not converge; allocates nothing once sized.
  bool variational(S t, S h, const StateT<S>& x0, StateT<S>& x1);

  /// The canonical rate \f$F = (\dot\theta, \dot p) = (\beta,\ \partial T/\partial\theta
  /// (\theta, \beta) + Q(t, \theta, \beta))\f$ with \f$\beta = \mathcal M^{-1}(\theta)p\f$ at
  /// \f$(\theta, p) = (\theta_0 + u, p_0 + w)\f$, \p Zh = (u, w), \f$p_0\f$ that of the
  /// current variational() step (ChainSystemT::velocity(), ChainSystemT::momentum_rate()).
  void canonical_rate(S t, const VecX<S>& theta0, const VecX<S>& Zh, VecX<S>& F);

  /// The full rate \f$(\dot u, \dot\beta)\f$ at local coordinates \p Z = (u, w) around \p x0
  /// (state \f$(\theta_0 \oplus u, \beta_0 + w)\f$), for Newton and stiffness estimates.
  /// Allocates nothing once \p F has size \f$2n_v\f$.
  void rate_at(S t, const StateT<S>& x0, const VecX<S>& Z, VecX<S>& F);

  /// Sets the scales of the error and Newton norms of esdirk(): component i of
  /// \f$(u, \beta)\f$ counts as \f$e_i / w_i\f$, \f$w_i = \mathrm{tol}\f$ for the local
  /// coordinates, \f$\mathrm{tol}(1 + |\beta_i|)\f$ for velocities (as dopri5's control).
  void set_tolerance(S tol) { tol_ = tol; }

  /// What the last esdirk() or implicit_midpoint() call did when it returned false.
  struct NewtonFailure {
    int stage = 0;  ///< the stage whose Newton iteration failed (esdirk 2 ... 6, midpoint 1)
    /// The last Newton correction: esdirk in the tolerance's scaled norm, implicit midpoint
    /// \f$|\Delta Z|_2\f$ of \f$Z = (u, w)\f$
    S residual = S(0);
    bool diverged = false;  ///< the corrections grew (else: too slow)
    /// implicit midpoint and variational: the largest step whose equation
    /// continued_solve() solved on its way to h (0: none)
    S reached = S(0);
  };
  const NewtonFailure& newton_failure() const { return failure_; }
  /// Jacobians computed (each \f$2n_v\f$ forward dynamics calls) and LU factorizations.
  long jacobians() const { return jacobians_; }
  /// Subdivisions tried by implicit_midpoint() and variational() when Newton from the
  /// step's start failed (continued_solve()).
  long continuations() const { return continuations_; }
  long factorizations() const { return factorizations_; }

  /// ESDIRK4(3)6L[2]SA (Kennedy and Carpenter, Appl. Numer. Math. 44, 2003; the implicit
  /// table of ARK4(3)6L[2]SA, as SUNDIALS ARKODE has it): six stages, the first explicit,
  /// the others \f$Z_i = h\sum_{j<i} a_{ij} F_j + h\gamma F(Z_i)\f$ with \f$\gamma = 1/4\f$,
  /// stiffly accurate (\f$Z_6\f$ is the step), L-stable, order 4 with an embedded order 3.
  /// Each stage is solved by simplified Newton with the matrix \f$I - h\gamma J\f$, \f$J\f$
  /// the Jacobian of the rate by forward differences (\f$2n_v\f$ rate evaluations) kept from
  /// step to step and refreshed when Newton converges slowly or fails; the matrix is
  /// factorized again when h changes. \p err gets the embedded error estimate, filtered by
  /// \f$(I - h\gamma J)^{-1}\f$ (Hairer and Wanner, Solving ODEs II, IV.8) so that stiff
  /// components do not inflate it. Returns false when Newton fails with a fresh Jacobian
  /// (newton_failure() says how): the caller takes a smaller step. Allocates nothing once
  /// the first call has sized the workspace.
  bool esdirk(S t, S h, const StateT<S>& x0, StateT<S>& x1, VecX<S>& err);

  /// Radau IIA of order 5 (RadauIIA; Hairer and Wanner, Solving ODEs II, IV.8): the stages
  /// \f$Z_i = h\sum_j a_{ij} F(Z_j)\f$ at \f$c_i h\f$, solved together by simplified Newton
  /// with \f$I - hA\otimes J\f$, which \f$T\f$ splits into \f$\gamma/h - J\f$ (real) and
  /// \f$(\alpha - i\beta)/h - J\f$ (complex), each of size \f$2n_v\f$: three rate evaluations
  /// and two solves an iteration. Newton starts from the last step's collocation polynomial
  /// extrapolated, and stops when \f$\eta\,|\Delta W| \le \kappa\f$ in the tolerance's
  /// norm, \f$\eta = \theta/(1 - \theta)\f$ from this step's contraction \f$\theta\f$ (the
  /// last step's \f$\eta^{0.8}\f$ at the first iteration), \f$\kappa = 3\cdot10^{-5}\f$ (at
  /// least \f$10\varepsilon/\mathrm{tol}\f$): Newton's error enters \f$y_1\f$ unfiltered at
  /// every step, and RADAU5's 0.03 left the stiff chain's (k = 1e8) global error 120-2100
  /// times the tolerance, against 0.1-3 times at 3e-5 for 20-42 % more evaluations. \f$J\f$
  /// as in esdirk(), refreshed when \f$\theta > 0.1\f$ or Newton fails; the matrices
  /// factorized again when h changes. Stiffly accurate: \f$y_1 = y_0 + Z_3\f$. \p err gets
  /// the embedded order-3 estimate filtered by \f$(\gamma/h - J)^{-1}\f$, and on a first or
  /// retried step whose estimate exceeds the tolerance, the same evaluated once more at
  /// \f$y_0 + \mathrm{err}\f$ (ibid., (8.20)). Returns false when Newton fails with a fresh
  /// Jacobian (newton_failure()): the caller takes a smaller step. Allocates nothing once
  /// sized.
  bool radau5(S t, S h, const StateT<S>& x0, StateT<S>& x1, VecX<S>& err);

 private:
  // The scales of the error and Newton norms at the step's start (set_tolerance()).
  void set_scale(const StateT<S>& x0) {
    for (int i = 0; i < nv_; ++i) {
      scale_[i] = tol_;
      scale_[nv_ + i] = tol_ * (S(1) + std::abs(x0.beta[i]));
    }
  }
  // LU of gamma/h - J (real, lu_) and (alpha - i beta)/h - J (complex, clu_).
  void factorize_radau(S h) {
    const RadauIIA<S>& R = RadauIIA<S>::get();
    A_ = -J_;
    A_.diagonal().array() += R.gamma / h;
    lu_.compute(A_);
    CA_ = -J_.template cast<std::complex<S>>();
    CA_.diagonal().array() += std::complex<S>(R.alpha, -R.beta) / h;
    clu_.compute(CA_);
    rlu_h_ = h;
    lu_hg_ = S(0);  // lu_ is not esdirk()'s matrix
    fresh_lu_needed_ = false;
    ++factorizations_;
  }
  // Z_i (Zs_[3 + i]) from the last step's collocation polynomial P through (0, 0), (c_k, Z_k)
  // in units of its step, at 1 + c_i h / h_prev, less P(1); zero on a first step.
  void radau_start(S h) {
    const RadauIIA<S>& R = RadauIIA<S>::get();
    const bool have = rt_prev_ == rt_prev_;  // not NaN
    for (int i = 0; i < 3; ++i) {
      VecX<S>& Z = Zs_[std::size_t(3 + i)];
      Z.setZero();
      if (!have) continue;
      const S x = S(1) + R.c[i] * h / rh_prev_;
      for (int k = 0; k < 3; ++k) {
        S w = x / R.c[k];  // node 0 (value 0) and the other two
        for (int m = 0; m < 3; ++m)
          if (m != k) w *= (x - R.c[m]) / (R.c[k] - R.c[m]);
        if (k == 2) w -= S(1);
        Z += w * Zprev_[std::size_t(k)];
      }
    }
  }
  // Simplified Newton on the transformed stages W = T^{-1} Z (Zs_[3..5] hold Z).
  bool radau_newton(S t, S h, const StateT<S>& x0) {
    const RadauIIA<S>& R = RadauIIA<S>::get();
    // Newton's error enters y_1 unfiltered, step after step: kappa = 3e-5 keeps the global
    // error near the tolerance (0.03, Hairer's RADAU5, left it 120-2100 x tol on the stiff
    // chain, k = 1e8), and above rounding (10 eps / tol)
    const S kappa = std::max(S(3e-5), S(10) * eps<S>() / tol_);
    for (int i = 0; i < 3; ++i) {
      Ws_[std::size_t(i)].setZero();
      for (int k = 0; k < 3; ++k) Ws_[std::size_t(i)] += R.T_inv(i, k) * Zs_[std::size_t(3 + k)];
    }
    S last = S(0), theta = S(0);
    S eta = std::pow(std::max(eta_, eps<S>()), S(0.8));
    for (int it = 0; it < 7; ++it) {
      for (int i = 0; i < 3; ++i)
        rate_at(t + R.c[i] * h, x0, Zs_[std::size_t(3 + i)], Fs_[std::size_t(1 + i)]);
      // G = T^{-1} F, then the right-hand sides of the two systems
      for (int i = 0; i < 3; ++i) {
        VecX<S>& G = Gs_[std::size_t(i)];
        G = R.T_inv(i, 0) * Fs_[1] + R.T_inv(i, 1) * Fs_[2] + R.T_inv(i, 2) * Fs_[3];
      }
      r_ = Gs_[0] - (R.gamma / h) * Ws_[0];
      dZ_ = lu_.solve(r_);
      cr_.real() = Gs_[1] - (R.alpha * Ws_[1] + R.beta * Ws_[2]) / h;
      cr_.imag() = Gs_[2] - (R.alpha * Ws_[2] - R.beta * Ws_[1]) / h;
      cu_ = clu_.solve(cr_);
      const S size = std::sqrt(((dZ_.array() / scale_.array()).square().sum() +
                                (cu_.real().array() / scale_.array()).square().sum() +
                                (cu_.imag().array() / scale_.array()).square().sum()) /
                               S(3 * 2 * nv_));
      if (!std::isfinite(double(size))) {
        failure_ = {1, size, true, S(0)};
        refresh_ = true;
        return false;
      }
      if (it > 0) {
        theta = size / last;
        if (theta >= S(0.99)) {
          failure_ = {1, size, true, S(0)};
          refresh_ = true;
          return false;
        }
        eta = theta / (S(1) - theta);
        // the distance left after the remaining iterations: too far, give up now
        if (eta * size * std::pow(theta, S(6 - it)) > kappa) {
          failure_ = {1, size, false, S(0)};
          refresh_ = true;
          return false;
        }
      }
      Ws_[0] += dZ_;
      Ws_[1] += cu_.real();
      Ws_[2] += cu_.imag();
      for (int i = 0; i < 3; ++i)
        Zs_[std::size_t(3 + i)] = R.T(i, 0) * Ws_[0] + R.T(i, 1) * Ws_[1] + R.T(i, 2) * Ws_[2];
      if (eta * size <= kappa) {
        eta_ = eta;
        if (theta > S(0.1)) refresh_ = true;  // slow: a new Jacobian next step
        return true;
      }
      last = std::max(size, eps<S>());
    }
    failure_ = {1, last, false, S(0)};
    refresh_ = true;
    return false;
  }

  // The midpoint equation Z = h F(Z/2) for the rate(offset, F) of an offset from the step's
  // start: J = I - (h/2) dF/dZ at Z = 0 by forward differences, then simplified Newton,
  // stopped when the estimated distance to the solution, theta/(1 - theta) |dZ| with theta
  // the contraction rate, is at rounding level (Hairer and Wanner, Solving ODEs II, IV.8).
  // The solution in Zs_[0]; false when Newton diverges or does not converge in 50
  // iterations. With refresh (variational()), a diverging or slow (theta > 1/2) iteration
  // takes the Jacobian again at the last iterate that contracted (at most kRefreshes times),
  // unless the corrections are below sqrt(eps)/100 (1 + |Z|): then it is rounding noise
  // that does not contract (the rate's evaluation is exact to about eps cond(M) |F|, above
  // 16 eps |Z| on an ill-conditioned mass matrix), and the iteration has converged.
  template <class Rate>
  bool midpoint_solve(S h, bool refresh, Rate&& rate, bool warm = false) {
    const int n2 = 2 * nv_;
    size_workspace();
    jac_valid_ = false;  // J_ and lu_ hold this method's matrix now, not esdirk()'s
    fresh_lu_needed_ = true;
    VecX<S>& Z = Zs_[0];
    VecX<S>& F = Fs_[0];
    if (warm) {  // from the Z given in Zs_[0] (continued_solve())
      jacobian_at(h, Z, F, rate);
    } else {
      Z.setZero();
      rate(Z, F);
      r_.setZero();
      for (int i = 0; i < n2; ++i) {
        const S d = std::sqrt(eps<S>());
        r_[i] = d;
        rate(r_, Fp_);
        r_[i] = S(0);
        A_.col(i) = -(h / S(2)) * (Fp_ - F) / d;
        A_(i, i) += S(1);
      }
      lu_.compute(A_);
    }
    S last = S(0);
    int refreshes = 0;
    // k counts the iterations since the last Jacobian.
    for (int it = 0, k = 0; it < 50; ++it, ++k) {
      if (it > 0) {
        base_ = Z / S(2);
        rate(base_, F);
      }
      r_ = Z - h * F;
      dZ_ = lu_.solve(r_);
      Z -= dZ_;
      const S size = dZ_.norm(), tol = S(16) * eps<S>() * (S(1) + Z.norm());
      failure_ = NewtonFailure{1, size, !Z.allFinite(), S(0)};
      if (!Z.allFinite() && !refresh) return false;
      if (size <= tol) break;
      const S theta = k > 0 ? size / last : S(0);
      const bool diverging = !Z.allFinite() || theta >= S(1);
      // implicit midpoint (no refresh): corrections that stopped contracting below
      // sqrt(eps) (1 + |Z|) have reached the rounding of F, eps cond(M) on an ill-conditioned
      // chain, far below the step's truncation error: converged as far as it can
      const S stalled = std::sqrt(eps<S>()) * (S(1) + Z.norm());
      if (!refresh && diverging && Z.allFinite() && size <= stalled) break;
      failure_.diverged = diverging;
      if (!refresh && diverging) return false;
      // no contraction at the level of rounding noise
      if (refresh && (diverging || theta > S(0.5)) && Z.allFinite() &&
          size <= S(1e-2) * std::sqrt(eps<S>()) * (S(1) + Z.norm()))
        break;
      if (k > 0 && !diverging && theta / (S(1) - theta) * size <= tol) break;
      // diverging or slow: the Jacobian again, at the last iterate that contracted
      if (refresh && (diverging || theta > S(0.5) || it == 49)) {
        if (refreshes == kRefreshes || it == 49) return false;
        if (diverging) Z += dZ_;
        jacobian_at(h, Z, F, rate);
        ++refreshes;
        k = -1;
        continue;
      }
      last = size;
      if (it == 49 && !(!refresh && size <= stalled)) return false;
    }
    return true;
  }
  // The most Jacobians midpoint_solve() takes again in one variational() step.
  static constexpr int kRefreshes = 4;
  // Continuation in the step (a globalized Newton; Allgower and Georg, Numerical
  // Continuation Methods, ch. 1): when Newton from Z = 0 fails at h, the solutions Z(h_j)
  // of the same equation at h_j = j h / m, j = 1 ... m, each from the predictor
  // Z(h_{j-1}) h_j / h_{j-1}, for m = 2, 4, ..., kSubdivisions. The last one is the step at
  // h itself, on the branch of solutions that starts at Z(0) = 0: the same map, found from
  // closer starts. \p hk is the step \p rate reads.
  static constexpr int kSubdivisions = 16;
  template <class Rate>
  bool continued_solve(S h, S& hk, Rate& rate) {
    S reached = S(0);
    for (int m = 2; m <= kSubdivisions; m *= 2) {
      bool ok = true;
      for (int j = 1; j <= m && ok; ++j) {
        hk = h * S(j) / S(m);
        if (j > 1) Zs_[0] *= S(j) / S(j - 1);
        ok = midpoint_solve(hk, true, rate, j > 1);
        if (ok) reached = std::max(reached, hk);
      }
      ++continuations_;
      if (ok) return true;
    }
    failure_.reached = reached;
    return false;
  }
  // A_ = I - (h/2) dF/dZ at the midpoint offset Z/2 by forward differences, factorized; F
  // gets the rate there.
  template <class Rate>
  void jacobian_at(S h, const VecX<S>& Z, VecX<S>& F, Rate& rate) {
    base_ = Z / S(2);
    rate(base_, F);
    for (int i = 0; i < 2 * nv_; ++i) {
      const S d = std::sqrt(eps<S>()) * (S(1) + std::abs(base_[i]));
      r_ = base_;
      r_[i] += d;
      rate(r_, Fp_);
      A_.col(i) = -(h / S(2)) * (Fp_ - F) / d;
      A_(i, i) += S(1);
    }
    lu_.compute(A_);
  }

  // The implicit methods' workspace, sized once.
  void size_workspace() {
    const int n2 = 2 * nv_;
    if (Zs_.size() == std::size_t(Esdirk436::s) && Zs_[0].size() == n2) return;
    Zs_.assign(Esdirk436::s, VecX<S>::Zero(n2));
    Fs_.assign(Esdirk436::s, VecX<S>::Zero(n2));
    base_.setZero(n2);
    r_.setZero(n2);
    dZ_.setZero(n2);
    Fp_.setZero(n2);
    scale_.setZero(n2);
    J_.setZero(n2, n2);
    A_.setZero(n2, n2);
    lu_ = Eigen::PartialPivLU<MatX<S>>(n2);
    Zprev_.assign(3, VecX<S>::Zero(n2));
    Zcand_.assign(3, VecX<S>::Zero(n2));
    Ws_.assign(3, VecX<S>::Zero(n2));
    Gs_.assign(3, VecX<S>::Zero(n2));
    CA_.setZero(n2, n2);
    clu_ = Eigen::PartialPivLU<MatX<std::complex<S>>>(n2);
    cr_.setZero(n2);
    cu_.setZero(n2);
    jac_valid_ = false;
  }
  // J = dF/dZ at Z = 0 around x0 by forward differences, column by column (2 n_v rates).
  void jacobian(S t, const StateT<S>& x0) {
    const int n2 = 2 * nv_;
    r_.setZero();
    for (int i = 0; i < n2; ++i) {
      const S d = std::sqrt(eps<S>()) * (i < nv_ ? S(1) : S(1) + std::abs(x0.beta[i - nv_]));
      r_[i] = d;
      rate_at(t, x0, r_, Fp_);
      J_.col(i) = (Fp_ - Fs_[0]) / d;
      r_[i] = S(0);
    }
    ++jacobians_;
    jac_valid_ = true;
    refresh_ = false;
    fresh_lu_needed_ = true;
  }
  // LU of I - h gamma J.
  void factorize(S hg) {
    A_ = -hg * J_;
    A_.diagonal().array() += S(1);
    lu_.compute(A_);
    lu_hg_ = hg;
    rlu_h_ = S(0);  // lu_ is not radau5()'s matrix
    fresh_lu_needed_ = false;
    ++factorizations_;
  }
  // The scaled RMS norm of a correction.
  S scaled_norm(const VecX<S>& v) const {
    return std::sqrt((v.array() / scale_.array()).square().mean());
  }
  // Simplified Newton for stage i: Z = base_ + hg F(Z). Converged when the estimated
  // distance to the solution, theta/(1 - theta) |dZ| (theta the contraction rate), is below
  // 0.05 in the tolerance's norm (Hairer and Wanner IV.8); at most 10 iterations.
  bool newton(S t, S hg, const StateT<S>& x0, int stage, VecX<S>& Z) {
    S last = S(0), theta = S(0);
    for (int it = 0; it < 10; ++it) {
      rate_at(t, x0, Z, Fp_);
      r_ = Z - base_ - hg * Fp_;
      dZ_ = lu_.solve(r_);
      Z -= dZ_;
      const S size = scaled_norm(dZ_);
      if (!std::isfinite(double(size)) || !Z.allFinite()) {
        failure_ = {stage, size, true, S(0)};
        return false;
      }
      if (it > 0) {
        theta = size / last;
        if (theta >= S(1)) {
          failure_ = {stage, size, true, S(0)};
          refresh_ = true;
          return false;
        }
        if (theta > S(0.5)) refresh_ = true;  // slow: a new Jacobian next step
        if (theta / (S(1) - theta) * size <= S(0.05)) return true;
      } else if (size <= S(0.05) * S(1e-2)) {
        return true;
      }
      last = size;
    }
    failure_ = {stage, last, false, S(0)};
    refresh_ = true;
    return false;
  }

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
  VecX<S> ru_, rud_, rbd_;  // rate_at()
  VecX<S> p0_, pc_;         // variational(): p at the start, p at the evaluation
  // esdirk(): stages, Newton, Jacobian and its factorization.
  std::vector<VecX<S>> Zs_, Fs_;
  VecX<S> base_, r_, dZ_, Fp_, scale_;
  MatX<S> J_, A_;
  Eigen::PartialPivLU<MatX<S>> lu_;
  S lu_hg_ = S(0), tol_ = S(1e-6);  // the h gamma of lu_
  bool jac_valid_ = false, refresh_ = false, fresh_lu_needed_ = true;
  // radau5(): transformed stages, the last steps' stages, complex factorization
  std::vector<VecX<S>> Ws_, Gs_, Zprev_, Zcand_;
  MatX<std::complex<S>> CA_;
  Eigen::PartialPivLU<MatX<std::complex<S>>> clu_;
  Eigen::Matrix<std::complex<S>, Eigen::Dynamic, 1> cr_, cu_;
  S rlu_h_ = S(0), eta_ = S(1);
  S rt_prev_ = std::numeric_limits<S>::quiet_NaN(), rh_prev_ = S(0);
  S rt_cand_ = std::numeric_limits<S>::quiet_NaN(), rh_cand_ = S(0);
  S rt_call_ = std::numeric_limits<S>::quiet_NaN();
  long jacobians_ = 0, factorizations_ = 0, continuations_ = 0;
  NewtonFailure failure_;
};

// The members are defined out of the class, not inline: the library compiles them once
// (soa/instantiations.hpp), and the programs, which declare them extern, do not compile them
// again.

template <class S>
void StepperT<S>::euler(S t, S h, const StateT<S>& x0, StateT<S>& x1) {
  static constexpr std::array<std::array<double, 1>, 1> a{{{0}}};
  static constexpr std::array<double, 1> b{1}, c{0};
  explicit_rk<1>(a, b, c, nullptr, t, h, x0, x1, nullptr);
}

template <class S>
void StepperT<S>::symplectic_euler(S t, S h, const StateT<S>& x0, StateT<S>& x1) {
  sys_.acceleration(t, x0, Kb_[0]);
  x1.beta = x0.beta + h * Kb_[0];
  u_.setZero();
  local_rate(sys_.model(), x0.theta, u_, x1.beta, Ku_[0]);
  u_ = h * Ku_[0];
  finish(x0.theta, x1);
}

template <class S>
void StepperT<S>::rk4(S t, S h, const StateT<S>& x0, StateT<S>& x1) {
  static constexpr std::array<std::array<double, 4>, 4> a{
      {{0, 0, 0, 0}, {0.5, 0, 0, 0}, {0, 0.5, 0, 0}, {0, 0, 1, 0}}};
  static constexpr std::array<double, 4> b{1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6}, c{0, 0.5, 0.5, 1};
  explicit_rk<4>(a, b, c, nullptr, t, h, x0, x1, nullptr);
}

template <class S>
void StepperT<S>::dopri5(S t, S h, const StateT<S>& x0, StateT<S>& x1, VecX<S>& err) {
  static constexpr std::array<std::array<double, 7>, 7> a{
      {{0, 0, 0, 0, 0, 0, 0},
       {1.0 / 5, 0, 0, 0, 0, 0, 0},
       {3.0 / 40, 9.0 / 40, 0, 0, 0, 0, 0},
       {44.0 / 45, -56.0 / 15, 32.0 / 9, 0, 0, 0, 0},
       {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729, 0, 0, 0},
       {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656, 0, 0},
       {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0}}};
  static constexpr std::array<double, 7> b{35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784,
                                           11.0 / 84,  0};
  static constexpr std::array<double, 7> b4{
      5179.0 / 57600, 0, 7571.0 / 16695, 393.0 / 640, -92097.0 / 339200, 187.0 / 2100, 1.0 / 40};
  static constexpr std::array<double, 7> c{0, 0.2, 0.3, 0.8, 8.0 / 9, 1, 1};
  std::array<double, 7> e{};
  for (int i = 0; i < 7; ++i) e[std::size_t(i)] = b[std::size_t(i)] - b4[std::size_t(i)];
  explicit_rk<7>(a, b, c, &e, t, h, x0, x1, &err);
}

template <class S>
bool StepperT<S>::implicit_midpoint(S t, S h, const StateT<S>& x0, StateT<S>& x1) {
  S hk = h;  // the step of the equation being solved
  const auto rate = [&](const VecX<S>& Zh, VecX<S>& F) { rate_at(t + hk / 2, x0, Zh, F); };
  if (!midpoint_solve(h, false, rate) && !continued_solve(h, hk, rate)) return false;
  u_ = Zs_[0].head(nv_);
  x1.beta = x0.beta + Zs_[0].tail(nv_);
  finish(x0.theta, x1);
  return true;
}

template <class S>
bool StepperT<S>::variational(S t, S h, const StateT<S>& x0, StateT<S>& x1) {
  require_coordinates_add(sys_.model());
  sys_.momentum(x0, p0_);
  S hk = h;  // the step of the equation being solved
  const auto rate = [&](const VecX<S>& Zh, VecX<S>& F) {
    canonical_rate(t + hk / 2, x0.theta, Zh, F);
  };
  if (!midpoint_solve(h, true, rate) && !continued_solve(h, hk, rate)) return false;
  u_ = Zs_[0].head(nv_);
  finish(x0.theta, x1);
  pc_ = p0_ + Zs_[0].tail(nv_);
  sys_.velocity(x1, pc_, x1.beta);
  return true;
}

template <class S>
void StepperT<S>::canonical_rate(S t, const VecX<S>& theta0, const VecX<S>& Zh, VecX<S>& F) {
  ru_ = Zh.head(nv_);
  retract(sys_.model(), theta0, ru_, x_.theta);
  pc_ = p0_ + Zh.tail(nv_);
  sys_.velocity(x_, pc_, x_.beta);
  sys_.momentum_rate(t, x_, rbd_);
  F.resize(2 * nv_);
  F.head(nv_) = x_.beta;
  F.tail(nv_) = rbd_;
}

template <class S>
void StepperT<S>::rate_at(S t, const StateT<S>& x0, const VecX<S>& Z, VecX<S>& F) {
  ru_ = Z.head(nv_);
  retract(sys_.model(), x0.theta, ru_, x_.theta);
  x_.beta = x0.beta + Z.tail(nv_);
  F.resize(2 * nv_);
  sys_.acceleration(t, x_, rbd_);
  local_rate(sys_.model(), x_.theta, ru_, x_.beta, rud_);
  F.head(nv_) = rud_;
  F.tail(nv_) = rbd_;
}

template <class S>
bool StepperT<S>::esdirk(S t, S h, const StateT<S>& x0, StateT<S>& x1, VecX<S>& err) {
  static constexpr int s = Esdirk436::s;
  static constexpr double g = Esdirk436::gamma;
  const auto& a = Esdirk436::a;
  const auto& c = Esdirk436::c;
  const auto& e = Esdirk436::e;
  size_workspace();
  set_scale(x0);
  Zs_[0].setZero();
  rate_at(t, x0, Zs_[0], Fs_[0]);
  bool fresh = false;
  if (!jac_valid_ || refresh_) {
    jacobian(t, x0);
    fresh = true;
  }
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (!(lu_hg_ == h * S(g)) || fresh_lu_needed_) factorize(h * S(g));
    bool converged = true;
    for (int i = 1; i < s && converged; ++i) {
      base_.setZero();
      for (int j = 0; j < i; ++j)
        if (a[std::size_t(i)][std::size_t(j)] != 0.0)
          base_ += (h * S(a[std::size_t(i)][std::size_t(j)])) * Fs_[std::size_t(j)];
      VecX<S>& Z = Zs_[std::size_t(i)];
      // predictor Z_i = base + h gamma F_i with F_i guessed on the line through the last
      // two stages' rates at their times c (F_1 = F_0): on the stiff chain (k = 1e8) 16-19 %
      // fewer evaluations at tolerances 1e-8 ... 1e-11 than F_i = F_{i-1}, same steps
      Z = base_ + (h * S(g)) * Fs_[std::size_t(i - 1)];
      if (i > 1)
        Z += (h * S(g) *
              S((c[std::size_t(i)] - c[std::size_t(i - 1)]) /
                (c[std::size_t(i - 1)] - c[std::size_t(i - 2)]))) *
             (Fs_[std::size_t(i - 1)] - Fs_[std::size_t(i - 2)]);
      converged = newton(t + S(c[std::size_t(i)]) * h, h * S(g), x0, i, Z);
      if (converged)  // F_i from the stage equation, not one more evaluation
        Fs_[std::size_t(i)] = (Z - base_) / (h * S(g));
    }
    if (converged) break;
    if (fresh) return false;  // a fresh Jacobian did not help: a smaller step
    jacobian(t, x0);
    fresh = true;
  }
  u_ = Zs_[s - 1].head(nv_);
  x1.beta = x0.beta + Zs_[s - 1].tail(nv_);
  finish(x0.theta, x1);
  r_.setZero();
  for (int j = 0; j < s; ++j)
    if (e[std::size_t(j)] != 0.0) r_ += (h * S(e[std::size_t(j)])) * Fs_[std::size_t(j)];
  err.resize(2 * nv_);
  err = lu_.solve(r_);
  return true;
}

template <class S>
bool StepperT<S>::radau5(S t, S h, const StateT<S>& x0, StateT<S>& x1, VecX<S>& err) {
  const RadauIIA<S>& R = RadauIIA<S>::get();
  const int n2 = 2 * nv_;
  size_workspace();
  set_scale(x0);
  // The collocation polynomial of the last accepted step: the last call's, when this step
  // starts where it ended; kept when this call retries the same start.
  const bool retry = t == rt_call_;
  if (t == rt_cand_ + rh_cand_) {
    std::swap(Zprev_, Zcand_);
    rt_prev_ = rt_cand_, rh_prev_ = rh_cand_;
    rt_cand_ = std::numeric_limits<S>::quiet_NaN();
  } else if (!(t == rt_prev_ + rh_prev_)) {
    rt_prev_ = std::numeric_limits<S>::quiet_NaN();
  }
  const bool first = !(t == rt_prev_ + rh_prev_) && !retry;
  rt_call_ = t;
  Zs_[0].setZero();
  rate_at(t, x0, Zs_[0], Fs_[0]);  // f(y0): the error estimate and the Jacobian
  bool fresh = false;
  if (!jac_valid_ || refresh_) {
    jacobian(t, x0);
    fresh = true;
  }
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (!(rlu_h_ == h) || fresh_lu_needed_) factorize_radau(h);
    radau_start(h);
    if (radau_newton(t, h, x0)) break;
    if (fresh) return false;  // a fresh Jacobian did not help: a smaller step
    jacobian(t, x0);
    fresh = true;
  }
  rt_cand_ = t, rh_cand_ = h;
  for (int i = 0; i < 3; ++i) Zcand_[std::size_t(i)] = Zs_[std::size_t(3 + i)];
  u_ = Zs_[5].head(nv_);
  x1.beta = x0.beta + Zs_[5].tail(nv_);
  finish(x0.theta, x1);
  // err = (gamma/h - J)^{-1} (f(y0) + (gamma/h) sum_k e_k Z_k)
  base_.setZero();
  for (int k = 0; k < 3; ++k) base_ += (R.gamma * R.e[k] / h) * Zs_[std::size_t(3 + k)];
  r_ = Fs_[0] + base_;
  err.resize(n2);
  err = lu_.solve(r_);
  if ((first || retry) && scaled_norm(err) > S(1)) {
    rate_at(t, x0, err, Fp_);
    r_ = Fp_ + base_;
    err = lu_.solve(r_);
  }
  return true;
}
using Stepper = StepperT<double>;

}  // namespace soa
