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
  /// ESDIRK4(3)6L[2]SA, adaptive step, order 4 (embedded 3), L-stable: for stiff springs
  Esdirk,
  /// implicit midpoint in the canonical variables \f$(\theta, p = \mathcal M\beta)\f$, order 2,
  /// symplectic and symmetric (hinges whose coordinates add)
  Variational,
};

/// The methods that choose their own step from a tolerance (`--tol`).
inline bool is_adaptive(Integrator i) {
  return i == Integrator::DormandPrince || i == Integrator::Esdirk;
}

/// "euler", "symplectic-euler", "rk4", "dopri5", "implicit-midpoint", "esdirk4",
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
    case Integrator::Variational:
      return "variational";
  }
  return "?";
}

/// The integrator called \p name; throws soa::Error listing the names.
inline Integrator integrator_from_name(const std::string& name) {
  for (Integrator i :
       {Integrator::Euler, Integrator::SymplecticEuler, Integrator::RK4, Integrator::DormandPrince,
        Integrator::ImplicitMidpoint, Integrator::Esdirk, Integrator::Variational})
    if (name == integrator_name(i)) return i;
  throw Error("unknown integrator \"" + name +
              "\" (euler, symplectic-euler, rk4, dopri5, implicit-midpoint, esdirk4, variational)");
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
  return i == Integrator::DormandPrince ? 4 : i == Integrator::Esdirk ? 3 : 0;
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
  /// (frozen during the step); when that fails, by continuation in the step
  /// (continued_solve(): the same equation at h/m, 2h/m, ..., h, each from the last).
  /// Returns false when neither converges. Allocates nothing once the first call has sized
  /// the workspace (shared with esdirk()).
  bool implicit_midpoint(S t, S h, const StateT<S>& x0, StateT<S>& x1) {
    S hk = h;  // the step of the equation being solved
    const auto rate = [&](const VecX<S>& Zh, VecX<S>& F) { rate_at(t + hk / 2, x0, Zh, F); };
    if (!midpoint_solve(h, false, rate) && !continued_solve(h, hk, rate)) return false;
    u_ = Zs_[0].head(nv_);
    x1.beta = x0.beta + Zs_[0].tail(nv_);
    finish(x0.theta, x1);
    return true;
  }

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
  bool variational(S t, S h, const StateT<S>& x0, StateT<S>& x1) {
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

  /// The canonical rate \f$F = (\dot\theta, \dot p) = (\beta,\ \partial T/\partial\theta
  /// (\theta, \beta) + Q(t, \theta, \beta))\f$ with \f$\beta = \mathcal M^{-1}(\theta)p\f$ at
  /// \f$(\theta, p) = (\theta_0 + u, p_0 + w)\f$, \p Zh = (u, w), \f$p_0\f$ that of the
  /// current variational() step (ChainSystemT::velocity(), ChainSystemT::momentum_rate()).
  void canonical_rate(S t, const VecX<S>& theta0, const VecX<S>& Zh, VecX<S>& F) {
    ru_ = Zh.head(nv_);
    retract(sys_.model(), theta0, ru_, x_.theta);
    pc_ = p0_ + Zh.tail(nv_);
    sys_.velocity(x_, pc_, x_.beta);
    sys_.momentum_rate(t, x_, rbd_);
    F.resize(2 * nv_);
    F.head(nv_) = x_.beta;
    F.tail(nv_) = rbd_;
  }

  /// The full rate \f$(\dot u, \dot\beta)\f$ at local coordinates \p Z = (u, w) around \p x0
  /// (state \f$(\theta_0 \oplus u, \beta_0 + w)\f$), for Newton and stiffness estimates.
  /// Allocates nothing once \p F has size \f$2n_v\f$.
  void rate_at(S t, const StateT<S>& x0, const VecX<S>& Z, VecX<S>& F) {
    ru_ = Z.head(nv_);
    retract(sys_.model(), x0.theta, ru_, x_.theta);
    x_.beta = x0.beta + Z.tail(nv_);
    F.resize(2 * nv_);
    sys_.acceleration(t, x_, rbd_);
    local_rate(sys_.model(), x_.theta, ru_, x_.beta, rud_);
    F.head(nv_) = rud_;
    F.tail(nv_) = rbd_;
  }

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
  bool esdirk(S t, S h, const StateT<S>& x0, StateT<S>& x1, VecX<S>& err) {
    static constexpr int s = Esdirk436::s;
    static constexpr double g = Esdirk436::gamma;
    const auto& a = Esdirk436::a;
    const auto& c = Esdirk436::c;
    const auto& e = Esdirk436::e;
    size_workspace();
    for (int i = 0; i < nv_; ++i) {
      scale_[i] = tol_;
      scale_[nv_ + i] = tol_ * (S(1) + std::abs(x0.beta[i]));
    }
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

 private:
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
  long jacobians_ = 0, factorizations_ = 0, continuations_ = 0;
  NewtonFailure failure_;
};
using Stepper = StepperT<double>;

}  // namespace soa
