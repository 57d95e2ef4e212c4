// Lesson 3 exercises, solved from the formulas of the statements (exercises.hpp).
#include "exercises.hpp"

namespace soa::ex03 {

// 3.1: the joint map H*(k), column by column.
Matrix6X joint_map(const Hinge& hinge, const VecX<double>& theta) {
  const Vec3<double>& a = hinge.axis;
  Matrix6X Hs;
  switch (hinge.type) {
    case HingeType::Revolute:
      Hs.setZero(6, 1);
      Hs.col(0).head<3>() = a;
      break;
    case HingeType::Prismatic:
      Hs.setZero(6, 1);
      Hs.col(0).tail<3>() = a;
      break;
    case HingeType::Helical:
      Hs.setZero(6, 1);
      Hs.col(0).head<3>() = a;
      Hs.col(0).tail<3>() = hinge.pitch * a;
      break;
    case HingeType::Universal:
      // The first axis seen from O_k: exp(-theta_2 a_2~) a.
      Hs.setZero(6, 2);
      Hs.col(0).head<3>() = exp_so3<double>(-theta[1] * hinge.axis2) * a;
      Hs.col(1).head<3>() = hinge.axis2;
      break;
    case HingeType::Spherical:
      Hs.setZero(6, 3);
      Hs.topRows<3>().setIdentity();
      break;
    case HingeType::Free:
      Hs.setIdentity(6, 6);
      break;
    case HingeType::Locked:
      Hs.setZero(6, 0);
      break;
  }
  return Hs;
}

// 3.2: V(k) = phi*(k+1,k) V(k+1) + H*(k) beta(k), from k = n (V(n+1) = 0) to the tip.
std::vector<Velocity> scatter_velocities(const std::vector<Phi>& phi,
                                         const std::vector<Velocity>& dV) {
  const int n = int(phi.size());
  std::vector<Velocity> V(phi.size());
  Velocity V_parent;  // V(n+1) = 0
  for (int k = n; k >= 1; --k) {
    V[k - 1] = phi[k - 1].transpose_apply(V_parent) + dV[k - 1];
    V_parent = V[k - 1];
  }
  return V;
}

// 3.3: phi(k+1,k) at block (k+1, k).
MatX<double> shift_operator(const std::vector<Phi>& phi) {
  const int n = int(phi.size());
  MatX<double> E = MatX<double>::Zero(6 * n, 6 * n);
  for (int k = 1; k < n; ++k) E.block<6, 6>(6 * k, 6 * (k - 1)) = phi[k - 1].matrix();
  return E;
}

// 3.4: phi(j,j) = I, phi(i+1,j) = phi(i+1,i) phi(i,j), zero above the diagonal.
MatX<double> phi_operator(const std::vector<Phi>& phi) {
  const int n = int(phi.size());
  MatX<double> P = MatX<double>::Zero(6 * n, 6 * n);
  for (int j = 1; j <= n; ++j) {
    Mat6<double> block = Mat6<double>::Identity();
    P.block<6, 6>(6 * (j - 1), 6 * (j - 1)) = block;
    for (int i = j; i < n; ++i) {
      block = phi[i - 1].matrix() * block;  // phi(i+1,i) phi(i,j)
      P.block<6, 6>(6 * i, 6 * (j - 1)) = block;
    }
  }
  return P;
}

// 3.5: column block i of J = phi*(O_i, F) H*(i) for i >= k.
Matrix6X frame_jacobian(const Model& m, const VecX<double>& theta, int k, const Pose& frame) {
  Workspace ws(m);
  update_phi(m, theta, ws);
  update_poses(m, ws);
  Matrix6X J = Matrix6X::Zero(6, m.nv());
  const Pose T_F = ws.pose[k - 1] * frame;  // ^I T_F
  for (int i = k; i <= m.n(); ++i) {
    const Body& B = m.body(i);
    const Mat6<double> phi_iF = Phi(ws.pose[i - 1].inverse() * T_F).matrix();
    J.middleCols(B.v_offset, B.hinge.nv()) =
        phi_iF.transpose() * B.hinge.H_star(theta.data() + B.q_offset);
  }
  return J;
}

// 3.6: a(k) = [w(k+1) x dw; w(k) x dv + w(k+1) x (v(k) - v(k+1))] + Hdot beta, in O_k.
Acceleration coriolis_acceleration(const Phi& phi, const Velocity& V_parent, const Velocity& dV,
                                   const Acceleration& Hdot_beta) {
  const Velocity V = phi.transpose_apply(V_parent) + dV;
  const Mat3<double> Rt = phi.R().transpose();
  const Vec3<double> w_p = Rt * V_parent.angular(), v_p = Rt * V_parent.linear();
  const Vec3<double> w = V.angular(), v = V.linear();
  const Vec3<double> dw = dV.angular(), dv = dV.linear();
  return Acceleration(w_p.cross(dw), w.cross(dv) + w_p.cross(v - v_p)) + Hdot_beta;
}

// 3.7: R = exp(theta_1 a~), l = theta_2 b + theta_3 c. From lesson 1, w~ = R* R_dot and
// v = R* l_dot: R_dot = R a~ beta_1 gives w = beta_1 a (a is its own axis, R* a = a), and
// l_dot = beta_2 b + beta_3 c gives v = R*(beta_2 b + beta_3 c). So
//   H* = [a 0 0; 0 R*b R*c],
// and the columns R*b, R*c turn: d/dt R* = (R a~ beta_1)* = -beta_1 a~ R*, so
//   Hdot beta = [0; -beta_1 a x R*(beta_2 b + beta_3 c)] = [0; beta_1 v x a].
PlanarJointMap planar_joint_map(const Vec3<double>& a, const Vec3<double>& b,
                                const Vec3<double>& theta, const Vec3<double>& beta) {
  const Mat3<double> Rt = exp_so3<double>(theta[0] * a).transpose();
  const Vec3<double> c = a.cross(b);
  PlanarJointMap out;
  out.H_star = Matrix6X::Zero(6, 3);
  out.H_star.col(0).head<3>() = a;
  out.H_star.col(1).tail<3>() = Rt * b;
  out.H_star.col(2).tail<3>() = Rt * c;
  const Vec3<double> v = Rt * (beta[1] * b + beta[2] * c);
  out.Hdot_beta = Acceleration(Vec3<double>::Zero(), beta[0] * v.cross(a));
  return out;
}

// 3.8: the given code mixed coordinates: omega and v(O_k) were turned to inertial
// coordinates, p was not. v(P) = R (v + omega x p), every vector in O_k coordinates first.
Vec3<double> point_velocity(const Model& m, const State& x, int k, const Vec3<double>& p) {
  Workspace ws(m);
  update_phi(m, x.theta, ws);
  update_poses(m, ws);
  Velocity V;  // V(n+1) = 0
  for (int i = m.n(); i >= k; --i) {
    const Body& B = m.body(i);
    V = ws.phi[i - 1].transpose_apply(V) +
        B.hinge.H_star_times(x.theta.data() + B.q_offset, x.beta.data() + B.v_offset);
  }
  const Mat3<double> R = ws.pose[k - 1].R();
  const Vec3<double> w = R * V.angular(), v = R * V.linear();
  return v + w.cross(R * p);
}

}  // namespace soa::ex03
