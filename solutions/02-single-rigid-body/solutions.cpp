// Lesson 2 exercises, solved from the formulas of the statements (exercises.hpp).
#include <Eigen/Cholesky>
#include <cmath>

#include "exercises.hpp"

namespace soa::ex02 {

// 2.1: b(x) = [w~ J(x) w; m w~ w~ p(x)].
Force gyroscopic_term(const SpatialInertia& M, const Velocity& V) {
  const Vec3<double> w = V.angular();
  const Vec3<double> N = w.cross(M.J() * w);
  const Vec3<double> F = M.mass() * w.cross(w.cross(M.p()));
  return Force(N, F);
}

// 2.2: through the centre of mass, f(x) = phi(x,C) (M(C) alpha(C) + b(C)).
Force spatial_force(double m, const Mat3<double>& J_C, const Vec3<double>& p, const Velocity& V,
                    const Acceleration& alpha) {
  const Vec3<double> w = V.angular(), w_dot = alpha.angular(), v_dot_x = alpha.linear();
  // alpha(C) = phi*(x,C) alpha(x) + [0; w~w~p]: the angular part is unchanged.
  const Vec3<double> v_dot_C = v_dot_x + w_dot.cross(p) + w.cross(w.cross(p));
  // Newton and Euler at C.
  const Vec3<double> N_C = J_C * w_dot + w.cross(J_C * w);
  const Vec3<double> F_C = m * v_dot_C;
  // f(x) = phi(x,C) f(C).
  return Force(N_C + p.cross(F_C), F_C);
}

// 2.3: alpha = M^-1 (f - b), w_dot = alpha_w, v_dot = alpha_v - w x v, r_dot = R v.
FreeBodyRateT<double> body_rates(const SpatialInertia& M, const FreeBodyState& x, const Force& f) {
  const Vec3<double> w = x.V.angular(), v = x.V.linear();
  const Vec3<double> p = M.p();
  Vec6<double> b;
  b << w.cross(M.J() * w), M.mass() * w.cross(w.cross(p));
  const Vec6<double> alpha = M.matrix().llt().solve(f.vector() - b);
  FreeBodyRateT<double> d;
  d.omega = w;
  d.r_dot = x.q.matrix() * v;
  d.V_dot << alpha.head<3>(), alpha.tail<3>() - w.cross(v);
  return d;
}

// 2.4: Runge-Kutta-Munthe-Kaas, RK4 on (delta, r, V) with q = q0 (x) exp(delta).
FreeBodyState rk4_torque_free(const SpatialInertia& M, const FreeBodyState& x0, double h) {
  struct Stage {
    Vec3<double> e;           // delta rate, dexp^-1_{-delta} omega
    FreeBodyRateT<double> d;  // r_dot, V_dot
  };
  const auto stage = [&](const Vec3<double>& delta, const Vec3<double>& r, const Vec6<double>& V) {
    FreeBodyState x;
    x.q = x0.q * UnitQuaternion::exp(delta);
    x.r = r;
    x.V = Velocity(V);
    Stage s;
    s.d = free_body_rate(M, x, Force::Zero());
    s.e = dexp_inv_right(delta, s.d.omega);
    return s;
  };
  const Vec6<double> V0 = x0.V.vector();
  const Stage k1 = stage(Vec3<double>::Zero(), x0.r, V0);
  const Stage k2 = stage(h / 2 * k1.e, x0.r + h / 2 * k1.d.r_dot, V0 + h / 2 * k1.d.V_dot);
  const Stage k3 = stage(h / 2 * k2.e, x0.r + h / 2 * k2.d.r_dot, V0 + h / 2 * k2.d.V_dot);
  const Stage k4 = stage(h * k3.e, x0.r + h * k3.d.r_dot, V0 + h * k3.d.V_dot);
  FreeBodyState x1;
  x1.q = x0.q * UnitQuaternion::exp(h / 6 * (k1.e + 2 * k2.e + 2 * k3.e + k4.e));
  x1.r = x0.r + h / 6 * (k1.d.r_dot + 2 * k2.d.r_dot + 2 * k3.d.r_dot + k4.d.r_dot);
  x1.V = Velocity(
      Vec6<double>(V0 + h / 6 * (k1.d.V_dot + 2 * k2.d.V_dot + 2 * k3.d.V_dot + k4.d.V_dot)));
  return x1;
}

// 2.5: f(x) = M V_dot + V-bar M V, V-bar = [[w~, v~], [0, w~]] on h = M V = [h_w; h_v].
Force body_frame_force(const SpatialInertia& M, const Velocity& V, const Acceleration& V_dot) {
  const Vec3<double> w = V.angular(), v = V.linear();
  const Vec6<double> h = M.matrix() * V.vector();
  const Vec3<double> h_w = h.head<3>(), h_v = h.tail<3>();
  const Vec6<double> f = M.matrix() * V_dot.vector();
  const Vec6<double> V_bar_h =
      (Vec6<double>() << w.cross(h_w) + v.cross(h_v), w.cross(h_v)).finished();
  return Force(Vec6<double>(f + V_bar_h));
}

// 2.6: linearize J w_dot + w x J w = 0 about w = W e_i (i = axis, j, k the next two,
// cyclically). With w = W e_i + d and the principal axes as body axes, to first order
//   J_j d_j' = (J_k - J_i) W d_k,   J_k d_k' = (J_i - J_j) W d_j   (d_i' = 0),
// so d_j'' = s d_j with s = W^2 (J_k - J_i)(J_i - J_j) / (J_j J_k): e^{+-sqrt(s) t} when
// s > 0 (i the intermediate axis), cos(sqrt(-s) t) when s < 0 (the largest or the smallest).
SpinStability spin_stability(const Vec3<double>& J, int axis, double spin) {
  const int i = axis, j = (axis + 1) % 3, k = (axis + 2) % 3;
  const double s = spin * spin * (J[k] - J[i]) * (J[i] - J[j]) / (J[j] * J[k]);
  return SpinStability{s < 0.0, std::sqrt(std::abs(s))};
}

// 2.7: the given step turned the attitude by exp(h w) on the left, as if w were in inertial
// coordinates. w is the body-frame angular velocity: R_dot = R w~ (q_dot = q (x) [w; 0] / 2),
// whose solution for constant w is R(t) = R0 exp(t w~), so the update multiplies on the right.
FreeBodyState lie_euler_step(const SpatialInertia& M, const FreeBodyState& x0, const Force& f,
                             double h) {
  const Vec3<double> w = x0.V.angular(), v = x0.V.linear();
  const Force b(Vec3<double>(w.cross(M.J() * w)), Vec3<double>(w.cross(w.cross(M.h()))));
  const Vec6<double> alpha = M.matrix().llt().solve((f - b).vector());
  Vec6<double> V_dot;
  V_dot << alpha.head<3>(), alpha.tail<3>() - w.cross(v);
  const Vec3<double> r_dot = x0.q.rotate(v);
  FreeBodyState x1;
  x1.q = x0.q * UnitQuaternion::exp(h * w);
  x1.r = x0.r + h * r_dot;
  x1.V = Velocity(Vec6<double>(x0.V.vector() + h * V_dot));
  return x1;
}

}  // namespace soa::ex02
