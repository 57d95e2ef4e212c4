// Lesson 3 exercises: replace each body with your code (statements in exercises.hpp).
#include "exercises.hpp"

#include "not_done.hpp"

namespace soa::ex03 {

Matrix6X joint_map(const Hinge& hinge, const VecX<double>& theta) {
  (void)hinge, (void)theta;
  throw exercise::NotDone("3.1 joint_map");
}

std::vector<Velocity> scatter_velocities(const std::vector<Phi>& phi,
                                         const std::vector<Velocity>& dV) {
  (void)phi, (void)dV;
  throw exercise::NotDone("3.2 scatter_velocities");
}

MatX<double> shift_operator(const std::vector<Phi>& phi) {
  (void)phi;
  throw exercise::NotDone("3.3 shift_operator");
}

MatX<double> phi_operator(const std::vector<Phi>& phi) {
  (void)phi;
  throw exercise::NotDone("3.4 phi_operator");
}

Matrix6X frame_jacobian(const Model& m, const VecX<double>& theta, int k, const Pose& frame) {
  (void)m, (void)theta, (void)k, (void)frame;
  throw exercise::NotDone("3.5 frame_jacobian");
}

Acceleration coriolis_acceleration(const Phi& phi, const Velocity& V_parent, const Velocity& dV,
                                   const Acceleration& Hdot_beta) {
  (void)phi, (void)V_parent, (void)dV, (void)Hdot_beta;
  throw exercise::NotDone("3.6 coriolis_acceleration");
}

PlanarJointMap planar_joint_map(const Vec3<double>& a, const Vec3<double>& b,
                                const Vec3<double>& theta, const Vec3<double>& beta) {
  (void)a, (void)b, (void)theta, (void)beta;
  throw exercise::NotDone("3.7 planar_joint_map");
}

Vec3<double> point_velocity(const Model& m, const State& x, int k, const Vec3<double>& p) {
  throw exercise::NotDone("3.8 point_velocity");
  // The code below has one bug. Delete the throw line above, run the test, find the bug.
  Workspace ws(m);
  update_phi(m, x.theta, ws);
  update_poses(m, ws);
  // V(k) by the scatter recursion, from the base to body k.
  Velocity V;  // V(n+1) = 0
  for (int i = m.n(); i >= k; --i) {
    const Body& B = m.body(i);
    V = ws.phi[i - 1].transpose_apply(V) +
        B.hinge.H_star_times(x.theta.data() + B.q_offset, x.beta.data() + B.v_offset);
  }
  // The angular velocity and the velocity of O_k in inertial coordinates, then the point's:
  // v(P) = v(O_k) + omega x l(O_k, P).
  const Mat3<double> R = ws.pose[k - 1].R();
  const Vec3<double> w = R * V.angular(), v = R * V.linear();
  return v + w.cross(p);
}

}  // namespace soa::ex03
