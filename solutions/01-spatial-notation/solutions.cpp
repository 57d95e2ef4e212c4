// Lesson 1 exercises, solved (the statements are in exercises/01-spatial-notation/exercises.hpp).
// Each is written from its slide's formula, as a student would, not by calling the library
// function the exercise reproduces.
#include <cmath>
#include <string>

#include "exercises.hpp"

namespace soa::ex01 {

// 1.1, slides 43 and 48-49: rotate both parts into x-coordinates, then
// N(x) = N(y) + l(x,y) x F(y) and F(x) = F(y).
Force apply_phi(const Phi& phi_xy, const Force& f_y) {
  const Mat3<double>& R = phi_xy.R();
  const Vec3<double> N_y = R * f_y.angular();              // N(y), x-coordinates
  const Vec3<double> F = R * f_y.linear();                 // F(y) = F(x), x-coordinates
  const Vec3<double> offset_moment = phi_xy.l().cross(F);  // l(x,y) x F, x-coordinates
  return Force(Vec3<double>(N_y + offset_moment), F);
}

// 1.2, slide 53: [x~ 0; y~ x~] [w; v] = [x~ w; y~ w + x~ v].
Acceleration spatial_cross(const Velocity& X, const Velocity& Y) {
  const Mat3<double> x = tilde<double>(X.angular()), y = tilde<double>(X.linear());
  const Vec3<double> w = Y.angular(), v = Y.linear();
  return Acceleration(x * w, y * w + x * v);
}

// 1.3, slides 66 and 70, through the centre of mass C:
//   J(C) = J(y) + m p~(y) p~(y)           (slide 66 read backwards, y-coordinates)
//   p(x) = l(x,y) + R p(y)                 (C is the same point; x-coordinates)
//   J(x) = R J(C) R* - m p~(x) p~(x)      (rotate, then slide 66 at x)
SpatialInertia parallel_axis(const Phi& phi_xy, const SpatialInertia& M_y) {
  const double m = M_y.mass();
  const Mat3<double>& R = phi_xy.R();
  const Vec3<double> p_y = M_y.h() / m;
  const Mat3<double> P_y = tilde(p_y);
  const Mat3<double> J_C = M_y.J() + m * P_y * P_y;
  const Vec3<double> p_x = phi_xy.l() + R * p_y;
  const Mat3<double> P_x = tilde(p_x);
  const Mat3<double> J_x = R * J_C * R.transpose() - m * P_x * P_x;
  return SpatialInertia(m, m * p_x, J_x);
}

// 1.4, slide 19: [sin(theta/2) n; cos(theta/2)], n normalized; bad input refused.
UnitQuaternion quaternion_from_axis_angle(const Vec3<double>& n, double theta) {
  if (!n.allFinite() || !std::isfinite(theta))
    throw Error("quaternion_from_axis_angle: axis or angle not finite");
  const double length = n.norm();
  if (!(length > 0.0)) throw Error("quaternion_from_axis_angle: zero axis names no rotation");
  const Vec3<double> unit = n / length;
  const double half = theta / 2;
  return UnitQuaternion(std::sin(half) * unit, std::cos(half));
}

// 1.5, slide 68: V* M V = w* J w + w* h~ v - v* h~ w + m v* v = w* J w + 2 w.(h x v) + m v.v,
// since -v.(h x w) = w.(h x v).
double kinetic_energy(const SpatialInertia& M_x, const Velocity& V_x) {
  const Vec3<double> w = V_x.angular(), v = V_x.linear();
  const Vec3<double>& h = M_x.h();
  return 0.5 * w.dot(M_x.J() * w) + w.dot(h.cross(v)) + 0.5 * M_x.mass() * v.squaredNorm();
}

// 1.6, slides 36 and 46: in x-coordinates, w(y,x) = -w(x,y) and
// v(y,x) = -v(x,y) + w(x,y) x l(x,y).
Velocity reverse_velocity(const Phi& phi_xy, const Velocity& V_xy) {
  const Mat3<double>& R = phi_xy.R();
  const Vec3<double> w_xy = R * V_xy.angular();  // x-coordinates
  const Vec3<double> v_xy = R * V_xy.linear();
  return Velocity(-w_xy, -v_xy + w_xy.cross(phi_xy.l()));
}

// 1.7, slide 63: exp(xi^) = (I + g1 W + g2 W^2, (I + g2 W + g3 W^2) v), W = w~, since
// W^3 = -theta^2 W folds the series. Below theta = 1e-2 the quotients cancel (g3 loses
// about 2 log10(1/theta) digits): four terms of their series are exact to rounding there
// (the next term is theta^8 / 10! < 1e-22).
Pose exp_twist(const Velocity& xi) {
  const Vec3<double> w = xi.angular();
  const double t = w.norm(), t2 = t * t;
  double g1, g2, g3;
  if (t < 1e-2) {
    g1 = 1 - t2 / 6 * (1 - t2 / 20 * (1 - t2 / 42));
    g2 = 0.5 * (1 - t2 / 12 * (1 - t2 / 30 * (1 - t2 / 56)));
    g3 = (1 - t2 / 20 * (1 - t2 / 42 * (1 - t2 / 72))) / 6;
  } else {
    g1 = std::sin(t) / t;
    g2 = (1 - std::cos(t)) / t2;
    g3 = (t - std::sin(t)) / (t2 * t);
  }
  const Mat3<double> W = tilde(w), W2 = W * W, I = Mat3<double>::Identity();
  return Pose(I + g1 * W + g2 * W2, (I + g2 * W + g3 * W2) * Vec3<double>(xi.linear()));
}

// 1.8, slides 53-55: (X_bar f)* Y = -f* (X~ Y) for all f, Y says X_bar = -X~*. With
// X~ = [x~ 0; y~ x~] and x~* = -x~: X~* = -[x~ y~; 0 x~], so X_bar = [x~ y~; 0 x~] and
// X_bar f = [x x N + y x F; x x F].
Force force_cross(const Velocity& X, const Force& f) {
  const Vec3<double> x = X.angular(), y = X.linear();
  const Vec3<double> N = f.angular(), F = f.linear();
  return Force(Vec3<double>(x.cross(N) + y.cross(F)), Vec3<double>(x.cross(F)));
}

// 1.9, slides 53-54: X~ [w; v] = [x x w; y x w + x x v] = 0.
// - x != 0: the first row gives w = a x; the second, x x (v - a y) = 0, so v = a y + b x:
//   two free parameters (a, b), the kernel is spanned by X = [x; y] and [0; x]: rank 4.
// - x = 0, y != 0: y x w = 0 gives w = a y, v is free: four parameters, rank 2.
// - X = 0: X~ = 0, rank 0.
int spatial_cross_rank(const Velocity& X) {
  const bool x_zero = X.angular().isZero(0.0), y_zero = X.linear().isZero(0.0);
  if (!x_zero) return 4;
  return y_zero ? 0 : 2;
}

}  // namespace soa::ex01
