/// The second topic of the course (slide 80, topic 2; Jain 2011, chapter 2): the equations of
/// motion of **one rigid body about an arbitrary point x of it**, in spatial notation,
/// \f[ f(x) = M(x)\,\alpha(x) + b(x), \qquad
///     b(x) = \begin{pmatrix} \tilde\omega\, J(x)\,\omega
///     \\ m\,\tilde\omega\tilde\omega\, p(x) \end{pmatrix}, \f]
/// where \f$f(x) = [N; F]\f$ is the spatial force applied at x, \f$M(x)\f$ the spatial inertia
/// about x (slide 68), \f$V(x) = [\omega; v(x)]\f$ the spatial velocity of x,
/// \f$\alpha(x)\f$ its derivative in the inertial frame (slide 59), and
/// \f$p(x) = l(x, C)\f$ the vector from x to the centre of mass C.
///
/// We derive the gyroscopic term \f$b(x)\f$ from Newton's and Euler's equations at C, moved to
/// x with \f$\phi(x, C)\f$, and check every step on numbers. Then we simulate a free body with
/// its frame away from C: the Dzhanibekov (intermediate-axis) flip, the invariants that the
/// simulation must keep, and the order of the Lie-group Runge-Kutta method that integrates it.
///
/// Learning goals. After this lesson you can
/// - write Newton's and Euler's equations at the centre of mass C in spatial form,
///   \f$f(C) = M(C)\alpha(C) + b(C)\f$, and say why only C decouples them;
/// - move the velocity, the acceleration (with its centripetal term), the force and the
///   inertia from C to any body point x with \f$\phi(x, C)\f$;
/// - derive the gyroscopic term
///   \f$b(x) = [\tilde\omega J(x)\omega;\ m\tilde\omega\tilde\omega p(x)]\f$ and the
///   body-frame form \f$f = M\dot V + \bar V M V\f$;
/// - state the rates of a free body (quaternion, position, velocity) and integrate them with a
///   Lie-group Runge-Kutta method that keeps \f$|\mathfrak q| = 1\f$;
/// - check a simulation by what it must conserve (energy, momentum about O) and by its
///   measured order of convergence.
///
/// Run it as `lesson02 OUTDIR`: it prints each check and writes `OUTDIR/l2_energy_error.csv`,
/// `OUTDIR/l2_flip.csv`, the figures `l2_energy_error.png` and `l2_flip.png`, and the 3D viewer
/// of the flip, `OUTDIR/l2_flip_view/` (open its `index.html` in a browser).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "args.hpp"
#include "checklist.hpp"
#include "plot.hpp"
#include "report.hpp"
#include "soa/soa.hpp"
#include "soa/view.hpp"
#include "viewer.hpp"

using soa::Acceleration;
using soa::Force;
using soa::FreeBodyState;
using soa::Phi;
using soa::SpatialInertia;
using soa::UnitQuaternion;
using soa::Velocity;
using Vec3 = soa::Vec3<double>;
using Mat3 = soa::Mat3<double>;
using Vec4 = Eigen::Vector4d;

/// ## Helpers
///
/// The Hamilton product of two quaternions stored vector part first (slide 19), on raw
/// 4-vectors (no normalization), so that we can watch the norm:
/// \f$[a; a_0] \otimes [b; b_0] = [a_0 b + b_0 a + a \times b;\ a_0 b_0 - a^* b]\f$.
Vec4 hamilton(const Vec4& a, const Vec4& b) {
  const Vec3 av = a.head<3>(), bv = b.head<3>();
  Vec4 c;
  c.head<3>() = a[3] * bv + b[3] * av + av.cross(bv);
  c[3] = a[3] * b[3] - av.dot(bv);
  return c;
}

/// A simulated run: the state after every step of size h, from t = 0 to t = steps h.
struct Run {
  double h = 0;
  std::vector<FreeBodyState> x;
  double t(std::size_t k) const { return double(k) * h; }
};

/// Integrates the torque-free body with the library's Lie-group RK4 (soa::rk4_step).
Run simulate(const SpatialInertia& M, const FreeBodyState& x0, double h, int steps) {
  Run run;
  run.h = h;
  run.x.reserve(std::size_t(steps) + 1);
  run.x.push_back(x0);
  for (int k = 0; k < steps; ++k) run.x.push_back(soa::rk4_step(M, run.x.back(), h));
  return run;
}

/// The same body integrated the naive way: classical RK4 on the four quaternion coefficients
/// with \f$\dot{\mathfrak q} = \tfrac12\,\mathfrak q \otimes [\omega; 0]\f$, as if they lived in
/// \f$\mathbb{R}^4\f$. Returns the largest \f$\bigl|\,|\mathfrak q| - 1\bigr|\f$ met.
double naive_quaternion_drift(const SpatialInertia& M, const FreeBodyState& x0, double h,
                              int steps) {
  struct State {
    Vec4 q;
    soa::Vec6<double> V;
  };
  const auto rate = [&](const State& s) {
    FreeBodyState x;  // the attitude does not enter the torque-free body rates of V
    x.V = Velocity(s.V);
    const auto d = soa::free_body_rate(M, x, Force::Zero());
    Vec4 w4;
    w4 << d.omega, 0.0;
    return State{hamilton(s.q, w4) / 2, d.V_dot};
  };
  const auto add = [](const State& s, double c, const State& d) {
    return State{s.q + c * d.q, s.V + c * d.V};
  };
  State s{x0.q.coeffs(), x0.V.vector()};
  double drift = 0;
  for (int k = 0; k < steps; ++k) {
    const State k1 = rate(s), k2 = rate(add(s, h / 2, k1)), k3 = rate(add(s, h / 2, k2)),
                k4 = rate(add(s, h, k3));
    s.q += h / 6 * (k1.q + 2 * k2.q + 2 * k3.q + k4.q);
    s.V += h / 6 * (k1.V + 2 * k2.V + 2 * k3.V + k4.V);
    drift = std::max(drift, std::abs(s.q.norm() - 1));
  }
  return drift;
}

/// The 3D viewer of a run of the torque-free body (\ref viewer), one frame every \p every steps,
/// seen from the inertial frame that moves with the centre of mass C at its initial velocity \f$v_C
/// = {}^I v(C)(0)\f$ (torque-free, C moves uniformly, so in that frame C stands still; a Galilean
/// change of frame leaves \f$\omega\f$ and the angular momentum about C as they are): the position
/// \f$l(I,x) - t\,v_C\f$, the attitude \f$\mathfrak q\f$, \f$V(x) = [\omega; v(x) - v_C]\f$ in
/// world axes, and its kinetic energy \f$\tfrac12 V^* M(x) V\f$ (slide 72). The body (frame x,
/// \p M_x, principal axes along the body axes, \p J_C diagonal) is drawn with its inertia ellipsoid
/// and a rod from x through C to \f$2p(x)\f$ (a last body's segment). The fixed vector is the
/// angular momentum about C, \f$h(C) = R\,J(C)\,\omega\f$ in world axes (slides 76-77), at C. The
/// tip is \p tip_point (body frame x).
soa::view::View flip_view(const SpatialInertia& M_x, const Mat3& J_C, const Run& run,
                          std::size_t every, const Vec3& tip_point) {
  const Vec3 p = M_x.p();  // p(x) = l(x, C)
  const FreeBodyState& x0 = run.x.front();
  const Vec3 C0 = x0.r + x0.q.rotate(p);
  const Vec3 v_C = x0.q.rotate(Phi::translation(p).transpose_apply(x0.V).linear());
  soa::view::View v;
  v.title = "Dzhanibekov flip: a torque-free body spun about its intermediate axis";
  soa::view::Body b;
  b.name = "body";
  b.hinge = "free";
  b.com = p;
  b.segment = 2 * p;
  b.mass = M_x.mass();
  for (int i = 0, j = 1, k = 2; i < 3; ++i, j = (i + 1) % 3, k = (i + 2) % 3) {
    const double d = J_C(j, j) + J_C(k, k) - J_C(i, i);  // a_i = sqrt(5 d / (2m))
    b.radii[i] = std::sqrt(std::max(0.0, 5 * d / (2 * b.mass)));
  }
  v.bodies.push_back(b);
  v.tip_body = 0;
  v.tip_point = tip_point;
  const Vec3 h_C = x0.q.rotate(J_C * x0.V.angular());
  v.fixed.push_back({"angular momentum about C", C0, h_C});
  soa::view::Run r;
  char label[64];
  std::snprintf(label, sizeof label, "Lie-group RK4, h = %g s", run.h);
  r.label = label;
  for (std::size_t k = 0; k < run.x.size(); k += every) {
    const FreeBodyState& x = run.x[k];
    FreeBodyState rel = x;  // V(x) relative to the frame moving with C, body axes
    rel.V = Velocity(x.V.angular(), x.V.linear() - x.q.conjugate().rotate(v_C));
    soa::view::Frame f;
    f.t = run.t(k);
    f.energy = soa::kinetic_energy(M_x, rel);
    const Vec3 l = x.r - f.t * v_C;
    const Vec4 q = x.q.coeffs();
    f.pose = {l[0], l[1], l[2], q[0], q[1], q[2], q[3]};
    const Vec3 w = x.q.rotate(rel.V.angular()), vx = x.q.rotate(rel.V.linear());
    f.V = {w[0], w[1], w[2], vx[0], vx[1], vx[2]};
    f.tip = l + x.q.rotate(tip_point);
    r.frames.push_back(std::move(f));
  }
  v.note = soa::view::decimation_note(long(run.x.size()), r.frames.size(), every * run.h) +
           "; seen from the frame moving with the centre of mass";
  v.runs.push_back(std::move(r));
  return v;
}

/// The errors of one step size, as sections 7 and 8 measure them: the largest relative
/// changes of the energy and of \f$h(O)\f$ along the x run, the energy change at the end and
/// its excursion during the first flip (up to t1), the largest gap between the centres of
/// mass of the x and C runs (relative to the distance from O), and the relative error of
/// \f$V(x)\f$ at the end against a finer run.
struct Errors {
  double energy = 0, energy_flip = 0, energy_end = 0, momentum = 0, cm = 0, state = 0;
};

Errors errors(const SpatialInertia& M_x, const Vec3& p, const Run& x_run, const Run& C_run,
              const Run& fine, double t1) {
  Errors e;
  const double E0 = soa::kinetic_energy(M_x, x_run.x.front());
  const soa::Vec6<double> h0 = soa::inertial_momentum(M_x, x_run.x.front()).vector();
  double cm_scale = 0;
  for (std::size_t k = 0; k < x_run.x.size(); ++k) {
    const FreeBodyState& x = x_run.x[k];
    e.energy = std::max(e.energy, std::abs(soa::kinetic_energy(M_x, x) - E0) / E0);
    e.momentum =
        std::max(e.momentum, (soa::inertial_momentum(M_x, x).vector() - h0).norm() / h0.norm());
    e.cm = std::max(e.cm, (x.r + x.q.rotate(p) - C_run.x[k].r).norm());
    cm_scale = std::max(cm_scale, C_run.x[k].r.norm());
  }
  e.cm /= cm_scale;
  e.energy_end = std::abs(soa::kinetic_energy(M_x, x_run.x.back()) - E0) / E0;
  const auto k1 = std::size_t(std::lround(t1 / x_run.h));
  const double E1 = soa::kinetic_energy(M_x, x_run.x[k1]);
  for (std::size_t k = 0; k <= k1; ++k)
    e.energy_flip =
        std::max(e.energy_flip, std::abs(soa::kinetic_energy(M_x, x_run.x[k]) - E1) / E0);
  const soa::Vec6<double> V_end = fine.x.back().V.vector();
  e.state = (x_run.x.back().V.vector() - V_end).norm() / V_end.norm();
  return e;
}

/// The least-squares slope of \f$\log e\f$ against \f$\log h\f$: the observed order.
double fitted_order(const std::vector<double>& h, const std::vector<double>& e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double X = std::log(h[i]), Y = std::log(e[i]);
    sx += X, sy += Y, sxx += X * X, sxy += X * Y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

int main(int argc, char** argv) {
  const std::filesystem::path out = soa::lesson::output_dir(argc, argv);
  soa::lesson::Checklist checks;
  const double eps = soa::eps<double>();

  /// ## 1. Newton and Euler at the centre of mass
  ///
  /// At the centre of mass C the linear and angular equations decouple (slide 65). With
  /// \f$V(C) = [\omega; v(C)]\f$ and \f$\alpha(C) = [\dot\omega; \dot v(C)]\f$ its inertial
  /// derivative, Newton's law is \f$F = m\,\dot v(C)\f$, and Euler's law is the inertial
  /// derivative of the angular momentum \f$J(C)\,\omega\f$. In body axes \f$J(C)\f$ is
  /// constant, and the inertial derivative of a vector given in body axes is the rate of its
  /// components plus \f$\omega\,\times\f$ the vector, so
  /// \f$\tfrac{d}{dt}(J(C)\omega) = J(C)\dot\omega + \tilde\omega J(C)\omega\f$. Together:
  /// \f[ f(C) = M(C)\,\alpha(C) + b(C), \qquad M(C) = \begin{pmatrix} J(C) & 0 \\ 0 & m I
  ///     \end{pmatrix}, \qquad b(C) = \begin{pmatrix} \tilde\omega\, J(C)\,\omega \\ 0
  ///     \end{pmatrix}. \f]
  ///
  /// The numbers: a body of mass m with a non-diagonal \f$J(C)\f$, a body point x with
  /// \f$p = p(x) = l(x, C)\f$, and a motion whose attitude is
  /// \f$R(t) = \exp(t\tilde a)\exp(t\tilde b)\f$ (so \f$R(0) = I\f$: at t = 0 body and inertial
  /// coordinates coincide), while x moves with \f$v(x)(t) = v_0 + t\,a_0\f$. Then
  /// \f$\tilde\omega = \dot R R^*\f$ gives \f$\omega(t) = a + \exp(t\tilde a)\, b\f$, so at
  /// t = 0: \f$\omega = a + b\f$ and \f$\dot\omega = a \times b\f$.
  checks.section("1. Newton and Euler at the centre of mass");
  const double m = 2.0;
  const Mat3 Q = soa::exp_so3<double>(Vec3(0.3, -0.4, 0.5));
  const Mat3 J_C = Q * Vec3(0.5, 0.8, 1.1).asDiagonal() * Q.transpose();
  const Vec3 p(0.3, -0.2, 0.5);  // p(x) = l(x, C)
  const Vec3 a(0.3, -0.5, 0.2), b(0.1, -0.6, 0.5), v0(0.5, 0.2, -0.3), a0(-0.4, 0.1, 0.9);
  const Vec3 w = a + b, w_dot = a.cross(b);
  const Velocity V_x(w, v0);
  const Acceleration alpha_x(w_dot, a0);

  const SpatialInertia M_C = SpatialInertia::from_cm(m, Vec3::Zero(), J_C);
  const SpatialInertia M_x = SpatialInertia::from_cm(m, p, J_C);
  const Force b_C(w.cross(J_C * w), Vec3::Zero());
  checks.check(
      "M(C) = diag(J(C), m I)",
      (M_C.matrix() -
       (soa::Mat6<double>() << J_C, Mat3::Zero(), Mat3::Zero(), m * Mat3::Identity()).finished())
          .norm(),
      0.0);
  checks.check("the library's b at C is [w~ J(C) w; 0]",
               (soa::gyroscopic_force(M_C, Velocity(w, Vec3(1, 2, 3))) - b_C).vector().norm(),
               4 * eps * b_C.vector().norm());

  /// ## 2. Moving the velocity and the acceleration from x to C
  ///
  /// The velocity moves with \f$\phi^*\f$ (slide 41): \f$V(C) = \phi^*(x,C)\,V(x)\f$, i.e.
  /// \f$v(C) = v(x) + \omega \times p\f$. The acceleration does not simply follow, because
  /// \f$p\f$ is fixed in the body and so turns: \f$\dot p = \omega \times p\f$ in the inertial
  /// frame. Differentiating \f$v(C)\f$:
  /// \f$\dot v(C) = \dot v(x) + \dot\omega \times p + \omega \times (\omega \times p)\f$, that is
  /// \f[ \alpha(C) = \phi^*(x, C)\,\alpha(x) + \begin{pmatrix} 0 \\ \tilde\omega\tilde\omega\, p
  ///     \end{pmatrix}, \f]
  /// the centripetal term being the Coriolis term \f$a\f$ of slides 60-61 for two points of one
  /// body. We check it against a 4th-order central difference of \f$V(C)(t)\f$ on the motion
  /// above (step \f$\tau\f$: truncation \f$O(\tau^4)\f$, rounding \f$O(\epsilon/\tau)\f$).
  checks.section("2. Moving the velocity and the acceleration from x to C");
  const Phi phi_xC = Phi::translation(p);
  const Velocity V_C = phi_xC.transpose_apply(V_x);
  const Acceleration alpha_C =
      phi_xC.transpose_apply(alpha_x) + Acceleration(Vec3::Zero(), w.cross(w.cross(p)));
  const auto V_C_at = [&](double t) {
    const Vec3 w_t = a + soa::exp_so3<double>(t * a) * b;
    const Vec3 p_t = soa::exp_so3<double>(t * a) * soa::exp_so3<double>(t * b) * p;
    return soa::Vec6<double>((soa::Vec6<double>() << w_t, v0 + t * a0 + w_t.cross(p_t)).finished());
  };
  const double tau = 1e-3;
  const soa::Vec6<double> alpha_C_fd =
      (V_C_at(-2 * tau) - 8 * V_C_at(-tau) + 8 * V_C_at(tau) - V_C_at(2 * tau)) / (12 * tau);
  checks.check("V(C) = phi*(x,C) V(x): v(C) = v(x) + w x p", (V_C.vector() - V_C_at(0)).norm(),
               4 * eps * V_C.vector().norm());
  checks.check("alpha(C) = phi*(x,C) alpha(x) + [0; w~w~p] (finite differences)",
               (alpha_C.vector() - alpha_C_fd).norm() / alpha_C.vector().norm(), 100 * eps / tau);

  /// ## 3. The equations of motion about x
  ///
  /// Forces move with \f$\phi\f$ (slide 49): \f$f(x) = \phi(x,C)\,f(C)\f$. Insert the CM form
  /// and the acceleration of section 2, and use the parallel axis theorem
  /// \f$M(x) = \phi(x,C)\,M(C)\,\phi^*(x,C)\f$ (slide 70):
  /// \f[ f(x) = \underbrace{\phi(x,C) M(C) \phi^*(x,C)}_{M(x)}\,\alpha(x)
  ///     + \phi(x,C)\,M(C) \begin{pmatrix} 0 \\ \tilde\omega\tilde\omega p \end{pmatrix}
  ///     + \phi(x,C)\, b(C). \f]
  /// With \f$\phi(x,C) = \begin{pmatrix} I & \tilde p \\ 0 & I \end{pmatrix}\f$ the last two
  /// terms are
  /// \f[ b(x) = \begin{pmatrix} \tilde\omega J(C)\omega + m\,\tilde p\,\tilde\omega\tilde\omega p
  ///     \\ m\,\tilde\omega\tilde\omega p \end{pmatrix}. \f]
  /// The moment is \f$\tilde\omega J(x)\omega\f$ with \f$J(x) = J(C) - m\tilde p\tilde p\f$
  /// (slide 66) because
  /// \f$\tilde p\tilde\omega\tilde\omega p + \tilde\omega\tilde p\tilde p\omega = 0\f$: with
  /// \f$\tilde p\omega = -\tilde\omega p\f$ the sum is
  /// \f$(\tilde p\tilde\omega - \tilde\omega\tilde p)\,\tilde\omega p =
  /// \widetilde{(p\times\omega)}\,(\omega\times p) = 0\f$ by the commutator identity (the
  /// 3-vector case of slide 54). Hence
  /// \f[ f(x) = M(x)\,\alpha(x) + b(x), \qquad b(x) = \begin{pmatrix} \tilde\omega\, J(x)\,\omega
  ///     \\ m\,\tilde\omega\tilde\omega\, p(x) \end{pmatrix}. \f]
  /// At \f$x = C\f$ (\f$p = 0\f$) it is the CM form again. The library computes
  /// soa::gyroscopic_force and soa::rigid_body_force; we compare them with the route through C.
  ///
  /// *Now do exercise 2.1* (`soa::ex02::gyroscopic_term`): \f$b(x)\f$ from its two cross
  /// products; and *exercise 2.2* (`soa::ex02::spatial_force`): the force at x computed the
  /// long way, through C, as in sections 1-3.
  checks.section("3. The equations of motion about x");
  const Force f_C = M_C * alpha_C + b_C;
  const Force f_x_via_C = phi_xC.apply(f_C);
  const Mat3 P = soa::tilde(p), W = soa::tilde(w);
  const Force b_x_hand(W * (J_C - m * P * P) * w, m * W * W * p);
  const Vec3 commutator = P * W * W * p + W * P * P * w;
  checks.check("p~w~w~p + w~p~p~w = 0", commutator.norm(), 8 * eps * (P * W * W * p).norm());
  checks.check("J(x) = J(C) - m p~p~ (the inertia about x)", (M_x.J() - (J_C - m * P * P)).norm(),
               4 * eps * M_x.J().norm());
  checks.check("b(x) = [w~J(x)w; m w~w~p] = soa::gyroscopic_force",
               (soa::gyroscopic_force(M_x, V_x) - b_x_hand).vector().norm(),
               8 * eps * b_x_hand.vector().norm());
  const Force f_x = soa::rigid_body_force(M_x, V_x, alpha_x);
  checks.check("phi(x,C) (M(C) alpha(C) + b(C)) = M(x) alpha(x) + b(x)",
               (f_x - f_x_via_C).vector().norm(), 16 * eps * f_x.vector().norm());
  const Force b_x_via_C = phi_xC.apply(M_C * Acceleration(Vec3::Zero(), w.cross(w.cross(p))) + b_C);
  checks.check("b(x) = phi(x,C) (M(C) [0; w~w~p] + b(C))", (b_x_via_C - b_x_hand).vector().norm(),
               16 * eps * b_x_hand.vector().norm());

  /// The inverse problem, the acceleration produced by a force, solves the 6x6 system
  /// \f$M(x)\,\alpha(x) = f(x) - b(x)\f$ (soa::rigid_body_acceleration); \f$M(x)\f$ is symmetric
  /// positive definite (slide 69), so the solution is unique. Its accuracy is that of the
  /// solve: a few \f$\kappa(M)\,\epsilon\f$, \f$\kappa\f$ the condition number.
  const Eigen::SelfAdjointEigenSolver<soa::Mat6<double>> eig(M_x.matrix());
  const double kappa = eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
  std::printf("  M(x): eigenvalues in [%.3f, %.3f], condition number %.1f\n",
              eig.eigenvalues().minCoeff(), eig.eigenvalues().maxCoeff(), kappa);
  checks.check("M(x) is positive definite", eig.eigenvalues().minCoeff() > 0);
  checks.check("alpha(x) = M(x)^-1 (f(x) - b(x)) recovers alpha(x)",
               (soa::rigid_body_acceleration(M_x, V_x, f_x) - alpha_x).vector().norm() /
                   alpha_x.vector().norm(),
               16 * kappa * eps);

  /// ## 4. The same law in body coordinates
  ///
  /// A simulation stores the body-frame coordinates of \f$V(x) = [\omega; v]\f$ and integrates
  /// their component rates \f$[\dot\omega; \dot v]\f$ (the derivative in the body frame). The
  /// inertial derivative adds the turning of the body axes, \f$\omega \times\f$, to each part;
  /// for \f$\omega\f$ that is \f$\omega\times\omega = 0\f$, so
  /// \f[ \alpha(x) = \begin{pmatrix} \dot\omega \\ \dot v + \omega \times v \end{pmatrix}. \f]
  /// Substituted in \f$f = M\alpha + b\f$ this gives the body-frame form with the spatial cross
  /// product of slide 55, \f$f(x) = M(x)\,\dot V + \bar V(x)\,M(x)\,V(x)\f$, where
  /// \f$\bar V = -\tilde V^* = \begin{pmatrix} \tilde\omega & \tilde v \\ 0 & \tilde\omega
  /// \end{pmatrix}\f$ acts on the momentum \f$M(x)V(x)\f$. Here it is checked on numbers.
  ///
  /// *Now do exercise 2.5* (`soa::ex02::body_frame_force`): the body-frame form from the
  /// blocks of \f$\bar V\f$ (exercise 1.8 works those blocks out).
  checks.section("4. The same law in body coordinates");
  const Acceleration V_dot_body(alpha_x.angular(), Vec3(alpha_x.linear()) - w.cross(v0));
  const Force f_body = M_x * V_dot_body + soa::cross_bar(V_x, M_x * V_x);
  checks.check("M(x) V_dot + V-bar M(x) V = M(x) alpha + b(x)", (f_body - f_x).vector().norm(),
               16 * eps * f_x.vector().norm());

  /// ## 5. The free body: state and rates
  ///
  /// The state of a free body with its frame at x (soa::FreeBodyState) is the attitude
  /// \f${}^I R_B\f$ as a unit quaternion \f$\mathfrak q\f$, the position \f${}^I l(I, x)\f$, and
  /// the body-frame coordinates of \f$V(x)\f$. Its rates (soa::free_body_rate) are
  /// \f[ \dot{\mathfrak q} = \tfrac12\,\mathfrak q \otimes [\omega; 0], \qquad
  ///     {}^I\dot l(I,x) = {}^I R_B\, v, \qquad
  ///     \alpha = M^{-1}(f - b), \quad \dot\omega = \alpha_\omega, \quad
  ///     \dot v = \alpha_v - \omega \times v. \f]
  /// Check: with an applied force, the rates rebuild \f$\alpha\f$ by section 4, and
  /// \f$M\alpha + b\f$ gives the force back; the quaternion rate is the derivative of
  /// \f$\mathfrak q \otimes \exp(t\omega)\f$ at t = 0.
  ///
  /// *Now do exercise 2.3* (`soa::ex02::body_rates`): these rates; then *exercise 2.7*
  /// (`soa::ex02::lie_euler_step`), a Lie-group Euler step built on them, given with one bug
  /// for you to find.
  checks.section("5. The free body: state and rates");
  FreeBodyState s;
  s.q = UnitQuaternion::exp(Vec3(0.4, -0.7, 0.2));
  s.r = Vec3(1.0, -2.0, 0.5);
  s.V = V_x;
  const Force f_applied(Vec3(0.3, -1.2, 0.4), Vec3(2.0, 0.5, -1.0));
  const auto d = soa::free_body_rate(M_x, s, f_applied);
  const Acceleration alpha_rebuilt(d.V_dot.head<3>(),
                                   d.V_dot.tail<3>() + d.omega.cross(Vec3(s.V.linear())));
  checks.check("M(x) [w_dot; v_dot + w x v] + b(x) = f",
               (soa::rigid_body_force(M_x, s.V, alpha_rebuilt) - f_applied).vector().norm() /
                   f_applied.vector().norm(),
               16 * kappa * eps);
  checks.check("position rate = R v", (d.r_dot - s.q.matrix() * v0).norm(), 8 * eps * v0.norm());
  const auto q_at = [&](double t) { return (s.q * UnitQuaternion::exp(t * w)).coeffs(); };
  const Vec4 q_dot_fd =
      (q_at(-2 * tau) - 8 * q_at(-tau) + 8 * q_at(tau) - q_at(2 * tau)) / (12 * tau);
  checks.check("q_dot = q (x) [w; 0] / 2 (finite differences)",
               (s.q.rate(w) - q_dot_fd).norm() / w.norm(), 100 * eps / tau);

  /// ## 6. A Lie-group Runge-Kutta method
  ///
  /// Classical RK4 applied to the four quaternion coefficients leaves the unit sphere: each
  /// step moves \f$\mathfrak q\f$ off it by a little, and the drift accumulates. The
  /// Runge-Kutta-Munthe-Kaas method (soa::rk4_step) writes the attitude over one step as
  /// \f$R(t_n + s) = R_n \exp(\tilde\delta(s))\f$ with a rotation vector \f$\delta\f$ that
  /// starts at 0 and obeys
  /// \f[ \dot\delta = \mathrm{dexp}^{-1}_{-\delta}\,\omega = \omega + \tfrac12\,\delta\times\omega
  ///     + c(\theta)\,\delta\times(\delta\times\omega), \qquad
  ///     c(\theta) = \frac{1 - \frac\theta2\cot\frac\theta2}{\theta^2},\ \theta = |\delta|. \f]
  /// RK4 runs on \f$(\delta, l, V)\f$, all vectors, and the attitude is updated by
  /// \f$\mathfrak q_{n+1} = \mathfrak q_n \otimes \exp(\delta_{n+1})\f$: a product of unit
  /// quaternions, unit because \f$|a \otimes b| = |a|\,|b|\f$ (checked here on the raw product;
  /// section 7 runs the naive method for comparison).
  ///
  /// *Now do exercise 2.4* (`soa::ex02::rk4_torque_free`): one step of this method, stage by
  /// stage.
  checks.section("6. A Lie-group Runge-Kutta method");
  const Vec4 raw = hamilton(s.q.coeffs(), UnitQuaternion::exp(Vec3(0.9, 0.1, -1.3)).coeffs());
  checks.check("|a (x) b| = |a| |b| = 1 for unit a, b (no normalization)", std::abs(raw.norm() - 1),
               4 * eps);

  /// ## 7. The Dzhanibekov flip, simulated about a point away from C
  ///
  /// A torque-free body with principal moments \f$J(C) = 0.02\,\mathrm{diag}(1, 2, 3)\f$
  /// kg m², spun at \f$\Omega = 2\pi\f$ rad/s about its intermediate axis with a small
  /// perturbation about the others. Rotation about the intermediate axis is unstable: the
  /// perturbation grows like \f$e^{\lambda t}\f$,
  /// \f$\lambda = \Omega\sqrt{(J_2 - J_1)(J_3 - J_2)/(J_1 J_3)}\f$, and the body flips over
  /// again and again (the Dzhanibekov effect). Its frame x is at \f$p(x) = l(x, C) \ne 0\f$, so
  /// \f$M(x)\f$ couples the linear and angular parts and \f$b(x)\f$ has its centripetal part;
  /// the centre of mass drifts at a constant velocity.
  ///
  /// We simulate the same body with its frame at x, and again with its frame at C, with the
  /// step \f$h = 0.005\f$ s, and check:
  /// - the kinetic energy \f$\tfrac12 V^*(x) M(x) V(x)\f$ (the same at every point, slide 72)
  ///   and the spatial momentum about the inertial origin O,
  ///   \f$h(O) = \phi(O,x)\,M(x)\,V(x)\f$ (slides 76-77; soa::inertial_momentum), are
  ///   conserved, since no force acts;
  /// - \f$|\mathfrak q| = 1\f$ all along;
  /// - the two runs describe one motion: the centre of mass
  ///   \f$l(I,C) = l(I,x) + R\,p(x)\f$ of the x run follows that of the C run.
  ///
  /// These hold to the truncation error of the integrator, not to rounding. Its a-priori scale
  /// after a time T is \f$T\,\Omega\,(\Omega h)^4\f$, the tolerance here; section 8 checks that
  /// each error falls like \f$h^4\f$. The attitudes of the two runs agree much more closely:
  /// \f$\dot\omega\f$ from the 6x6 solve at x is, in exact arithmetic, the same function of
  /// \f$\omega\f$ as Euler's equation at C, so the two runs make the same rotational
  /// computation and differ by rounding only (amplified by the unstable spin). We check that
  /// their difference is far below the attitude's truncation error, measured against a run
  /// with \f$h/8\f$.
  ///
  /// *Now do exercise 2.6* (`soa::ex02::spin_stability`): predict, for any body and each of
  /// its principal axes, whether the spin is stable, and the growth rate or the wobble
  /// frequency, by linearizing Euler's equation yourself.
  checks.section("7. The Dzhanibekov flip, simulated about a point away from C");
  const double mass = 1.0, Omega = 2 * std::acos(-1.0), T = 20.0, h_ref = 0.005;
  const double t1 = 3.0;  // after the first flip, back to a steady spin
  const Mat3 J_body = 0.02 * Vec3(1, 2, 3).asDiagonal().toDenseMatrix();
  const Vec3 p_body(0.2, -0.1, 0.15);  // p(x) = l(x, C) in body coordinates
  const SpatialInertia body_C = SpatialInertia::from_cm(mass, Vec3::Zero(), J_body);
  const SpatialInertia body_x = SpatialInertia::from_cm(mass, p_body, J_body);
  FreeBodyState start_C;
  start_C.q = UnitQuaternion::exp(Vec3(0.3, -0.2, 0.1));
  start_C.r = Vec3(1.0, 0.0, 0.5);
  start_C.V = Velocity(Vec3(0.02, Omega, 0.02), Vec3(0.05, -0.02, 0.03));
  FreeBodyState start_x = start_C;                   // the same body, its frame moved from C to x
  start_x.r = start_C.r - start_C.q.rotate(p_body);  // l(I,x) = l(I,C) - R p
  start_x.V = Phi::translation(-p_body).transpose_apply(start_C.V);  // V(x) = phi*(C,x) V(C)
  const double lambda = Omega * std::sqrt((2.0 - 1.0) * (3.0 - 2.0) / (1.0 * 3.0));
  std::printf("  growth rate of the perturbation: lambda = %.3f 1/s\n", lambda);

  const double E0 = soa::kinetic_energy(body_x, start_x);
  const soa::Vec6<double> h0 = soa::inertial_momentum(body_x, start_x).vector();
  checks.check("E at x = E at C (initial state)",
               std::abs(E0 - soa::kinetic_energy(body_C, start_C)), 16 * eps * E0);
  checks.check("h(O) from x = h(O) from C (initial state)",
               (h0 - soa::inertial_momentum(body_C, start_C).vector()).norm(),
               32 * eps * h0.norm());

  const auto steps_for = [&](double h) { return int(std::lround(T / h)); };
  const Run run_x = simulate(body_x, start_x, h_ref, steps_for(h_ref));
  const Run run_C = simulate(body_C, start_C, h_ref, steps_for(h_ref));
  const Run fine = simulate(body_x, start_x, h_ref / 8, steps_for(h_ref / 8));
  const Errors e_ref = errors(body_x, p_body, run_x, run_C, fine, t1);
  int flips = 0;
  for (std::size_t k = 1; k < run_x.x.size(); ++k)
    if ((run_x.x[k - 1].V.angular()[1] > 0) != (run_x.x[k].V.angular()[1] > 0)) ++flips;
  double dq = 0, dR = 0, att_err = 0;
  for (std::size_t k = 0; k < run_x.x.size(); ++k) {
    const UnitQuaternion& q = run_x.x[k].q;
    dq = std::max(dq, std::abs(q.coeffs().norm() - 1));
    dR = std::max(dR, (run_C.x[k].q.conjugate() * q).log().norm());
    att_err = std::max(att_err, (fine.x[8 * k].q.conjugate() * q).log().norm());
  }
  const double tol_rk4 = T * Omega * std::pow(Omega * h_ref, 4);
  std::printf("  h = %.3f s, %d steps; a-priori RK4 error scale T W (W h)^4 = %.2e\n", h_ref,
              steps_for(h_ref), tol_rk4);
  std::printf("  w_2 changed sign %d times in %.0f s\n", flips, T);
  checks.check("the intermediate-axis spin flips (w_2 changes sign >= 2 times)", flips >= 2);
  checks.check("kinetic energy conserved (max relative change)", e_ref.energy, tol_rk4);
  checks.check("h(O) conserved (max relative change)", e_ref.momentum, tol_rk4);
  checks.check("|q| = 1 along the run", dq, 4 * eps);
  checks.check("CM of the x run = CM of the C run (max, relative)", e_ref.cm, tol_rk4);
  std::printf("  attitude error of the x run against h/8: %.2e rad\n", att_err);
  checks.check("attitude of the x run = attitude of the C run (rad), << its error", dR,
               att_err / 10);

  const double drift_naive = naive_quaternion_drift(body_C, start_C, 0.04, steps_for(0.04));
  std::printf("  classical RK4 on q in R^4, h = 0.04 s: max ||q| - 1| = %.2e\n", drift_naive);
  checks.check("classical RK4 on q in R^4 leaves the unit sphere (> 1e6 eps)",
               drift_naive > 1e6 * eps);

  /// ### The flip in 3D
  ///
  /// The viewer `l2_flip_view` (a folder of the output: open its `index.html` in a browser;
  /// \ref viewer) replays the x run, a frame every 25 ms: the body with its inertia ellipsoid
  /// (\f$J_3 = J_1 + J_2\f$: a flat plate, its ellipsoid a disc), its frame x and \f$V(x)\f$, and
  /// the angular momentum about C, \f$h(C) = R\,J(C)\,\omega\f$ in world axes (slides 76-77), an
  /// arrow fixed in space: no torque acts, so it is conserved (checked on every frame, to the
  /// tolerance above) while \f$\omega\f$ wanders in the body. The motion is seen from the frame
  /// that moves with C, where C stands still. The tip path follows the point \f$p(x) + 0.4\,e_2\f$
  /// m on the intermediate axis. Since \f$h(C)^* R\,e_2 = (J(C)\omega)^* e_2 = J_2\,\omega_2\f$,
  /// that point crosses the plane through C normal to \f$h(C)\f$ exactly when \f$\omega_2\f$
  /// changes sign: each flip is the path jumping from one side of the plane to the other, as often
  /// in the viewer's frames as \f$\omega_2\f$ changes sign in the run (checked).
  {
    const std::size_t every = 5;
    const Vec3 tip = p_body + 0.4 * Vec3::UnitY();
    const soa::view::View view = flip_view(body_x, J_body, run_x, every, tip);
    const soa::view::FixedVector& h_C = view.fixed.front();
    double h_C_change = 0;
    for (std::size_t k = 0; k < run_x.x.size(); k += every) {
      const FreeBodyState& x = run_x.x[k];
      h_C_change = std::max(h_C_change, (x.q.rotate(J_body * x.V.angular()) - h_C.vector).norm());
    }
    checks.check("viewer: h(C) = R J(C) w of every frame = the fixed arrow (relative)",
                 h_C_change / h_C.vector.norm(), tol_rk4);
    int crossings = 0;
    const auto side = [&](const soa::view::Frame& f) {
      return (f.tip - h_C.origin).dot(h_C.vector) > 0;
    };
    const std::vector<soa::view::Frame>& frames = view.runs.front().frames;
    for (std::size_t k = 1; k < frames.size(); ++k)
      if (side(frames[k - 1]) != side(frames[k])) ++crossings;
    std::printf("  viewer: %zu frames; the tip crosses the plane normal to h(C) %d times\n",
                frames.size(), crossings);
    checks.check("viewer: the tip crosses the plane normal to h(C) as often as w_2 changes sign",
                 crossings == flips);
    // The still image (and its caption in the notes) is taken during the third flip: the
    // third sign change of w_2 is within half a second of it.
    const double t_still = 9.5;
    std::vector<double> t_flips;
    for (std::size_t k = 1; k < run_x.x.size(); ++k)
      if ((run_x.x[k - 1].V.angular()[1] > 0) != (run_x.x[k].V.angular()[1] > 0))
        t_flips.push_back(run_x.t(k));
    checks.check("viewer: its still image (t = 9.5 s) is during the third flip",
                 t_flips.size() >= 3 && std::abs(t_flips[2] - t_still) < 0.5);
    soa::lesson::check_viewer(
        checks, out, "l2_flip_view", view,
        "paused=1&t=" + soa::lesson::num(t_still, "%g") + "&show=ellipsoids,fixed,frames,tip,V");
  }

  /// ## 8. The order of the method
  ///
  /// RK4 is fourth order: halving h divides the global error by \f$2^4 = 16\f$. We repeat the
  /// runs with \f$h = 0.04, 0.02, 0.01, 0.005\f$ s and fit, by least squares, the slope of
  /// \f$\log(\text{error})\f$ against \f$\log h\f$ for: the state \f$V(x)\f$ at T against the
  /// h/8 run of section 7, the change of \f$h(O)\f$, and the gap between the CM of the x and C
  /// runs. Each slope must lie in [3.5, 4.5]: the Lie-group update keeps the order of the
  /// classical method (a first-order attitude update would have spoiled it).
  ///
  /// The energy error is a finer story: of order \f$h^4\f$ at most, it falls faster here. Its
  /// \f$h^4\f$ part does not accumulate: it shows during each flip, as the spikes of the first
  /// figure of section 9, and is gone when the body spins steadily again. We measure it as the
  /// excursion of the energy error during the first flip,
  /// \f$\max_{t \le t_1} |E(t) - E(t_1)|/E(0)\f$ with \f$t_1 = 3\f$ s, after that flip; its
  /// slope must lie in [3.5, 4.5]. What is left between flips, and builds up flip after flip,
  /// falls like \f$h^5\f$ (the error at the end of the run: slope in [4.5, 5.5]). At these
  /// steps the accumulated part dominates the largest error over the run: it falls between
  /// \f$2^4 = 16\f$ and \f$2^5 = 32\f$ times per halving (slope in [3.5, 5.5]; the ratios are
  /// printed below and checked), the ratio shrinking with h as the \f$h^4\f$ part of the flips
  /// takes over.
  checks.section("8. The order of the method");
  const std::vector<double> hs = {0.04, 0.02, 0.01, 0.005};
  std::vector<Run> runs;
  std::vector<double> e_state, e_momentum, e_cm, e_energy, e_flip, e_end;
  std::printf("  %-7s %-11s %-11s %-11s %-11s %-11s %-11s\n", "h [s]", "V(T) err", "max dh/|h|",
              "max CM gap", "max dE/E", "flip dE/E", "dE/E at T");
  for (const double h : hs) {
    runs.push_back(h == h_ref ? run_x : simulate(body_x, start_x, h, steps_for(h)));
    const Run run_c = h == h_ref ? run_C : simulate(body_C, start_C, h, steps_for(h));
    const Errors e = errors(body_x, p_body, runs.back(), run_c, fine, t1);
    e_state.push_back(e.state);
    e_momentum.push_back(e.momentum);
    e_cm.push_back(e.cm);
    e_energy.push_back(e.energy);
    e_flip.push_back(e.energy_flip);
    e_end.push_back(e.energy_end);
    std::printf("  %-7.3f %-11.3e %-11.3e %-11.3e %-11.3e %-11.3e %-11.3e\n", h, e.state,
                e.momentum, e.cm, e.energy, e.energy_flip, e.energy_end);
  }
  std::printf("  the ratio e(2h) / e(h):\n");
  for (std::size_t i = 1; i < hs.size(); ++i)
    std::printf("  %-7.3f %-11.1f %-11.1f %-11.1f %-11.1f %-11.1f %-11.1f\n", hs[i],
                e_state[i - 1] / e_state[i], e_momentum[i - 1] / e_momentum[i],
                e_cm[i - 1] / e_cm[i], e_energy[i - 1] / e_energy[i], e_flip[i - 1] / e_flip[i],
                e_end[i - 1] / e_end[i]);
  const auto order_check = [&](const std::string& what, const std::vector<double>& e, double lo,
                               double hi) {
    const double order = fitted_order(hs, e);
    char label[128];
    std::snprintf(label, sizeof label, "order of %s: %.2f, in [%.1f, %.1f]", what.c_str(), order,
                  lo, hi);
    checks.check(label, order >= lo && order <= hi);
  };
  order_check("the state error", e_state, 3.5, 4.5);
  order_check("the h(O) error", e_momentum, 3.5, 4.5);
  order_check("the CM gap", e_cm, 3.5, 4.5);
  order_check("the energy excursion in the flip", e_flip, 3.5, 4.5);
  order_check("the energy error at T", e_end, 4.5, 5.5);
  order_check("the largest energy error", e_energy, 3.5, 5.5);
  bool ratios_in = true, ratios_shrink = true;
  for (std::size_t i = 1; i < hs.size(); ++i) {
    const double r = e_energy[i - 1] / e_energy[i];
    ratios_in = ratios_in && r >= 16 && r <= 32;
    if (i > 1) ratios_shrink = ratios_shrink && r < e_energy[i - 2] / e_energy[i - 1];
  }
  checks.check("largest energy error: each e(2h)/e(h) in [16, 32]", ratios_in);
  checks.check("largest energy error: e(2h)/e(h) shrinks with h", ratios_shrink);

  /// ## 9. Figures
  ///
  /// `l2_energy_error.csv`: the relative energy error \f$(E(t) - E(0))/E(0)\f$ of the x run for
  /// each step size, sampled every 0.04 s; `l2_energy_error.png` plots its magnitude on a log
  /// scale: a staircase that steps up at each flip, with a spike during the flip, the curves
  /// of successive step sizes between 16 and 32 times apart. The program checks these three
  /// statements on the data it writes: with the flips at the sign changes of \f$\omega_2\f$
  /// (section 7), the error at the midpoints between flips grows from one to the next for every
  /// h; the largest error within 0.5 s of each flip exceeds the error at the next midpoint; and
  /// the ratio of the curves of h and h/2, at every sample after t = 1 s, lies between
  /// \f$2^4\f$ and \f$2^5\f$ (checked in [16, 32.5]: the accumulated \f$h^5\f$ part brings it
  /// close to 32; the range met is printed).
  ///
  /// \image html l2_energy_error.png "Energy error of the Lie-group RK4, body about x" width=600px
  ///
  /// `l2_flip.csv` and `l2_flip.png`: the body-frame components of \f$\omega\f$ for h = 0.005 s;
  /// \f$\omega_2\f$ switches between \f$+\Omega\f$ and \f$-\Omega\f$ while \f$\omega_1\f$ and
  /// \f$\omega_3\f$ peak during each flip.
  ///
  /// \image html l2_flip.png "The Dzhanibekov flip: body-frame angular velocity" width=600px
  checks.section("9. Figures");
  {
    std::ofstream csv(out / "l2_energy_error.csv");
    csv << "t";
    for (const double h : hs) csv << ",h = " << h << " s";
    csv << "\n";
    const double dt = hs.front();
    for (int k = 0; k <= steps_for(dt); ++k) {
      char cell[64];
      std::snprintf(cell, sizeof cell, "%.2f", k * dt);
      csv << cell;
      for (std::size_t i = 0; i < hs.size(); ++i) {
        const auto stride = std::size_t(std::lround(dt / hs[i]));
        const FreeBodyState& xs = runs[i].x[std::size_t(k) * stride];
        std::snprintf(cell, sizeof cell, ",%.6e", (soa::kinetic_energy(body_x, xs) - E0) / E0);
        csv << cell;
      }
      csv << "\n";
    }
    checks.check("l2_energy_error.csv written", bool(csv));
  }
  {
    std::ofstream csv(out / "l2_flip.csv");
    csv << "t,w1,w2,w3\n";
    for (std::size_t k = 0; k < run_x.x.size(); k += 2) {
      const Vec3 wk = run_x.x[k].V.angular();
      char line[96];
      std::snprintf(line, sizeof line, "%.3f,%.6f,%.6f,%.6f\n", run_x.t(k), wk[0], wk[1], wk[2]);
      csv << line;
    }
    checks.check("l2_flip.csv written", bool(csv));
  }
  {
    // The flip times (sign changes of w_2 on the h_ref run) and the midpoints between them.
    std::vector<double> t_flip;
    for (std::size_t k = 1; k < run_x.x.size(); ++k)
      if ((run_x.x[k - 1].V.angular()[1] > 0) != (run_x.x[k].V.angular()[1] > 0))
        t_flip.push_back(run_x.t(k));
    std::vector<double> t_mid;
    for (std::size_t i = 0; i < t_flip.size(); ++i)
      t_mid.push_back(i + 1 < t_flip.size() ? (t_flip[i] + t_flip[i + 1]) / 2 : T);
    const auto dE = [&](std::size_t i, double t) {
      const auto k = std::min(std::size_t(std::lround(t / hs[i])), runs[i].x.size() - 1);
      return std::abs(soa::kinetic_energy(body_x, runs[i].x[k]) - E0) / E0;
    };
    bool staircase = true, spikes = true;
    for (std::size_t i = 0; i < hs.size(); ++i) {
      for (std::size_t j = 1; j < t_mid.size(); ++j)
        staircase = staircase && dE(i, t_mid[j]) > dE(i, t_mid[j - 1]);
      for (std::size_t j = 0; j < t_flip.size(); ++j) {
        double peak = 0;
        for (double t = std::max(0.0, t_flip[j] - 0.5); t <= t_flip[j] + 0.5; t += hs[i])
          peak = std::max(peak, dE(i, t));
        spikes = spikes && peak > dE(i, t_mid[j]);
      }
    }
    double gap_lo = 1e300, gap_hi = 0;
    for (std::size_t i = 1; i < hs.size(); ++i)
      for (double t = 1.0; t <= T + hs[0] / 2; t += hs[0]) {
        const double r = dE(i - 1, t) / dE(i, t);
        gap_lo = std::min(gap_lo, r), gap_hi = std::max(gap_hi, r);
      }
    std::printf("  %zu flips; energy-error curves of h and h/2 are %.2f to %.2f times apart\n",
                t_flip.size(), gap_lo, gap_hi);
    checks.check("energy error steps up from one flip to the next, every h", staircase);
    checks.check("energy error spikes during each flip, every h", spikes);
    checks.check("curves of h and h/2 between 16 and 32.5 times apart (t >= 1 s)",
                 gap_lo >= 16 && gap_hi <= 32.5);
  }
  checks.check("figure written: l2_energy_error.png",
               soa::lesson::plot("energy_error.gp", out, "l2_energy_error.png"));
  checks.check("figure written: l2_flip.png", soa::lesson::plot("flip.gp", out, "l2_flip.png"));

  return checks.finish();
}
