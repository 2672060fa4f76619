#include "heavytop/rigid_body.hpp"

#include <Eigen/Geometry>

#include "integrators/integration.hpp"

namespace heavytop {

void RigidBodySystem::operator()(const RigidBodyVector& x, RigidBodyVector& dxdt, double) const {
  const double qw = x[0], qx = x[1], qy = x[2], qz = x[3], w1 = x[4], w2 = x[5], w3 = x[6];
  // q' = q (x) (0, w) / 2.
  dxdt[0] = 0.5 * (-qx * w1 - qy * w2 - qz * w3);
  dxdt[1] = 0.5 * (qw * w1 + qy * w3 - qz * w2);
  dxdt[2] = 0.5 * (qw * w2 + qz * w1 - qx * w3);
  dxdt[3] = 0.5 * (qw * w3 + qx * w2 - qy * w1);
  // gamma = R^T e_zeta: the third row of R(q), divided by |q|^2 (R of a non-unit q scales by it).
  const double n2 = qw * qw + qx * qx + qy * qy + qz * qz;
  const double g1 = 2.0 * (qx * qz - qw * qy) / n2, g2 = 2.0 * (qy * qz + qw * qx) / n2;
  const double mgR = body.mgR();
  // I w' = (I w) x w + m g R (gamma x e3), gamma x e3 = (g2, -g1, 0).
  dxdt[4] = ((body.B - body.C) * w2 * w3 + mgR * g2) / body.A;
  dxdt[5] = ((body.C - body.A) * w3 * w1 - mgR * g1) / body.B;
  dxdt[6] = (body.A - body.B) * w1 * w2 / body.C;
}

RigidBodyVector to_vector(const RigidBodyState& state) {
  const Eigen::Quaterniond q = detail::unit_quaternion(state.attitude);
  return {q.w(), q.x(), q.y(), q.z(), state.omega.x(), state.omega.y(), state.omega.z()};
}

RigidBodyState from_vector(const RigidBodyVector& x) {
  // R(q / |q|) from q itself: Eigen's toRotationMatrix() with 2 / |q|^2 for its 2, one
  // division where normalizing first took a square root and four (a sample's cost, every
  // integrator's). q = 0 gives the identity, as normalized() then did.
  const double qw = x[0], qx = x[1], qy = x[2], qz = x[3];
  const double n2 = qw * qw + qx * qx + qy * qy + qz * qz;
  const double s = n2 > 0.0 ? 2.0 / n2 : 0.0;
  const double tx = s * qx, ty = s * qy, tz = s * qz;
  const double twx = tx * qw, twy = ty * qw, twz = tz * qw;
  const double txx = tx * qx, txy = ty * qx, txz = tz * qx, tyy = ty * qy, tyz = tz * qy, tzz = tz * qz;
  RigidBodyState state;
  state.attitude << 1.0 - (tyy + tzz), txy - twz, txz + twy,  //
      txy + twz, 1.0 - (txx + tzz), tyz - twx,                //
      txz - twy, tyz + twx, 1.0 - (txx + tyy);
  state.omega = Eigen::Vector3d(x[4], x[5], x[6]);
  return state;
}

}  // namespace heavytop
