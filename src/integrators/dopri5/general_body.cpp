#include "heavytop/general_body.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <fmt/format.h>

#include "integrators/dopri5/driver.hpp"
#include "integrators/integration.hpp"
#include "integrators/monitor.hpp"
#include "integrators/sampling.hpp"
#include "integrators/streams.hpp"

namespace heavytop {

using namespace detail;

Eigen::Matrix3d inertia_tensor(const Body& body) {
  const GeneralInertia& g = body.general;
  Eigen::Matrix3d I;
  I << body.A, -g.Ixy, -g.Ixz, -g.Ixy, body.B, -g.Iyz, -g.Ixz, -g.Iyz, body.C;
  return I;
}

Eigen::Vector3d centre_of_mass(const Body& body) {
  return {body.general.offset_x, body.general.offset_y, body.length};
}

GeneralRigidBodySystem::GeneralRigidBodySystem(const Body& body)
    : inertia(inertia_tensor(body)),
      inverse(inertia.inverse()),
      weight(body.mass * body.gravity * centre_of_mass(body)) {}

void GeneralRigidBodySystem::operator()(const RigidBodyVector& x, RigidBodyVector& dxdt, double) const {
  const double qw = x[0], qx = x[1], qy = x[2], qz = x[3];
  const Eigen::Vector3d w(x[4], x[5], x[6]);
  // q' = q (x) (0, w) / 2, as RigidBodySystem.
  dxdt[0] = 0.5 * (-qx * w[0] - qy * w[1] - qz * w[2]);
  dxdt[1] = 0.5 * (qw * w[0] + qy * w[2] - qz * w[1]);
  dxdt[2] = 0.5 * (qw * w[1] + qz * w[0] - qx * w[2]);
  dxdt[3] = 0.5 * (qw * w[2] + qx * w[1] - qy * w[0]);
  // gamma = R^T e_zeta: the third row of R(q), divided by |q|^2.
  const double n2 = qw * qw + qx * qx + qy * qy + qz * qz;
  const Eigen::Vector3d gamma(2.0 * (qx * qz - qw * qy) / n2, 2.0 * (qy * qz + qw * qx) / n2,
                              (qw * qw - qx * qx - qy * qy + qz * qz) / n2);
  // I w' = (I w) x w + m g gamma x c.
  const Eigen::Vector3d rate = inverse * ((inertia * w).cross(w) + gamma.cross(weight));
  dxdt[4] = rate[0];
  dxdt[5] = rate[1];
  dxdt[6] = rate[2];
}

void detail::refuse_damped_general(const Body& body) {
  if (!body.damping.conservative())
    throw InvalidInput(body.damping.transverse != 0.0 ? "damping.transverse"
                       : body.damping.axial != 0.0    ? "damping.axial"
                       : body.damping.friction != 0.0 ? "damping.friction"
                                                      : "motion.driven",
                       "the general body (SPEC section 11) is integrated without damping, friction or motor only");
}

Scales detail::general_scales(const Body& body, const RigidBodyState& x0) {
  const Eigen::Matrix3d I = inertia_tensor(body);
  Scales s;
  s.energy = 0.5 * x0.omega.dot(I * x0.omega) + body.mass * body.gravity * centre_of_mass(body).norm();
  const double largest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I, Eigen::EigenvaluesOnly).eigenvalues()[2];
  s.momentum = std::sqrt(2.0 * largest * s.energy);
  if (!(s.energy > 0.0)) s.energy = 1.0;
  if (!(s.momentum > 0.0)) s.momentum = 1.0;
  return s;
}

ConservedQuantities general_conserved_quantities(const Body& body, const RigidBodyState& x) {
  const Eigen::Vector3d L = inertia_tensor(body) * x.omega;
  const Eigen::Vector3d gamma = x.attitude.row(2).transpose();  // R^T e_zeta
  ConservedQuantities q;
  q.energy = 0.5 * x.omega.dot(L) + body.mass * body.gravity * centre_of_mass(body).dot(gamma);
  q.vertical_momentum = L.dot(gamma);
  q.axial_momentum = L.z();
  return q;
}

namespace {

using State = RigidBodyVector;

void check_general(const Body& body, const Tolerances& options) {
  validate(body);
  validate(options);
  refuse_damped_general(body);
}

// The general body's plain state (q, body-axes w: rigid_body.hpp's vector) for the dopri5
// driver (driver.hpp), conservative only (SPEC section 11).
struct GeneralVariables {
  using State = heavytop::State;
  using Equations = GeneralRigidBodySystem;
  static constexpr bool kSymmetric = false, kDamped = false;

  static Equations equations(const Body& body) { return Equations(body); }
  // Back onto |q| = 1 before each step (the quaternion's rate scales with it).
  static double project(State& x, State& dxdt) { return renormalise_quaternion(x, dxdt); }
  static State state_of(const RigidBodyState& rb0) { return to_vector(rb0); }
  static Scales scales(const Body& body, const RigidBodyState& rb0, const State&) { return general_scales(body, rb0); }
  static ConservedQuantities initial(const Body& body, const RigidBodyState& rb0, const State&) {
    return general_conserved_quantities(body, rb0);
  }
  static ConservedQuantities conserved(const Body& body, const State& x) {
    return general_conserved_quantities(body, from_vector(x));
  }
};

using GeneralIntegrator = Dopri5Driver<GeneralVariables>;

}  // namespace

std::vector<RigidBodyState> integrate_general_body(const Body& body, const RigidBodyState& x0,
                                                   const std::vector<double>& times, const Tolerances& options,
                                                   NonlinearSummary* summary, const Progress& progress) {
  check_general(body, options);
  validate_times(times);
  std::vector<RigidBodyState> out(times.size());
  GeneralIntegrator integrator(body, x0, times.empty() ? 0.0 : times.back(), options, summary);
  for_each_sample(integrator, times.size(), [&times](std::size_t i) { return times[i]; }, progress,
                  [&](std::size_t i, double, const State* x) { out[i] = x ? from_vector(*x) : x0; });
  return out;
}

void detail::stream_general(const Body& body, const InitialState& initial, const SampleStream& samples,
                            const Tolerances& options, NonlinearSummary* summary) {
  check_general(body, options);
  validate(initial);
  const RigidBodyState x0 = initial_rigid_body_state(initial);
  GeneralIntegrator integrator(body, x0, samples.horizon(), options, summary);
  write_samples(integrator, body, x0, general_conserved_quantities(body, x0), false, samples,
                [&body](const State& x) {
                  const RigidBodyState rb = from_vector(x);
                  return sample_of(rb, general_conserved_quantities(body, rb));
                });
}

Trajectory simulate_general_body(const Body& body, const InitialState& initial, const std::vector<double>& times,
                                 const Tolerances& options, NonlinearSummary* summary, const Progress& progress) {
  return gathered(times, progress, [&](const SampleStream& samples) {
    detail::stream_general(body, initial, samples, options, summary);
  });
}

}  // namespace heavytop
