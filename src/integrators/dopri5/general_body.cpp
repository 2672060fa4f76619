#include "heavytop/general_body.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <boost/numeric/odeint/stepper/controlled_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <fmt/format.h>

#include "integrators/integration.hpp"
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

namespace odeint = boost::numeric::odeint;
using State = RigidBodyVector;

void check_general(const Body& body, const Tolerances& options) {
  validate(body);
  validate(options);
  refuse_damped_general(body);
}

// Dormand-Prince 5(4) with its continuous extension, one accepted step at a time (the pattern
// of nonlinear.cpp's Integrator, without its spin-factored variables and damping).
class GeneralIntegrator {
 public:
  using State = heavytop::State;
  using Stepper = odeint::runge_kutta_dopri5<State>;
  using Controlled = odeint::controlled_runge_kutta<Stepper>;

  GeneralIntegrator(const Body& body, const RigidBodyState& x0, double horizon, const Tolerances& options,
                    NonlinearSummary* summary)
      : body_(body), system_(body), controlled_(Controlled::error_checker_type(options.atol, options.rtol)),
        max_steps_(options.max_steps), summary_(summary), x_(to_vector(x0)) {
    system_(x_, dxdt_, 0.0);
    dt_ = initial_step(options, horizon);
    if (summary_) {
      *summary_ = NonlinearSummary{};
      summary_->symmetric = false;
      summary_->rhs_evaluations = 1;
      scales_ = general_scales(body, x0);
      initial_ = general_conserved_quantities(body, x0);
    }
  }

  double time() const { return t_; }

  void step() {
    commit();
    x_old_ = x_;
    dxdt_old_ = dxdt_;
    t_old_ = t_;
    controlled_step(controlled_, system_, x_old_, dxdt_old_, t_, x_, dxdt_, dt_, attempts_, max_steps_, summary_);
    if (summary_) {
      ++summary_->steps;
      summary_->final_time = t_;
      note_drift(*summary_, general_conserved_quantities(body_, from_vector(x_)), initial_, scales_);
    }
  }

  // The state at t in [previous step's start, time()] from the continuous extension.
  void interpolate(double t, State& out) const {
    if (t == t_) {
      out = x_;
      return;
    }
    controlled_.stepper().calc_state(t, out, x_old_, dxdt_old_, t_old_, x_, dxdt_, t_);
  }

 private:
  double initial_step(const Tolerances& o, double horizon) const {
    return first_step_guess(x_, dxdt_, o, horizon);
  }

  // Back onto |q| = 1 before each step (the quaternion's rate scales with it).
  void commit() {
    const double norm = std::sqrt(x_[0] * x_[0] + x_[1] * x_[1] + x_[2] * x_[2] + x_[3] * x_[3]);
    if (summary_)
      summary_->max_quaternion_norm_error = std::max(summary_->max_quaternion_norm_error, std::abs(norm - 1.0));
    for (int i = 0; i < 4; ++i) {
      x_[i] /= norm;
      dxdt_[i] /= norm;
    }
  }

  const Body& body_;
  GeneralRigidBodySystem system_;
  Controlled controlled_;
  std::size_t max_steps_;
  NonlinearSummary* summary_;
  std::size_t attempts_ = 0;
  Scales scales_;
  ConservedQuantities initial_;
  State x_, dxdt_{}, x_old_{}, dxdt_old_{};
  double t_ = 0.0, t_old_ = 0.0, dt_ = 0.0;
};


}  // namespace

std::vector<RigidBodyState> integrate_general_body(const Body& body, const RigidBodyState& x0,
                                                   const std::vector<double>& times, const Tolerances& options,
                                                   NonlinearSummary* summary) {
  check_general(body, options);
  validate_times(times);
  std::vector<RigidBodyState> out(times.size());
  GeneralIntegrator integrator(body, x0, times.empty() ? 0.0 : times.back(), options, summary);
  for_each_sample(integrator, times.size(), [&times](std::size_t i) { return times[i]; }, options.progress,
                  [&](std::size_t i, double, const State* x) { out[i] = x ? from_vector(*x) : x0; });
  return out;
}

void detail::stream_general(const Body& body, const InitialState& initial, const SampleStream& samples,
                            const Tolerances& options, NonlinearSummary* summary) {
  check_general(body, options);
  validate(initial);
  const RigidBodyState x0 = initial_rigid_body_state(initial);
  GeneralIntegrator integrator(body, x0, samples.horizon(), options, summary);
  write_samples(integrator, body, x0, general_conserved_quantities(body, x0), false, samples, options.progress,
                [&body](const State& x) {
                  const RigidBodyState rb = from_vector(x);
                  return sample_of(rb, general_conserved_quantities(body, rb));
                });
}

Trajectory simulate_general_body(const Body& body, const InitialState& initial, const std::vector<double>& times,
                                 const Tolerances& options, NonlinearSummary* summary) {
  return gathered(times, [&](const SampleStream& samples) {
    detail::stream_general(body, initial, samples, options, summary);
  });
}

}  // namespace heavytop
