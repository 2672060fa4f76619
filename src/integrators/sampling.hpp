#pragma once
// Private to the library: the one sample loop of every integrator of the nonlinear model
// (dopri5, DOP853, Taylor, the general body's dopri5, the splitting) and the one writer of its
// columns. An integrator is a DenseStepper and says only how to read its own state
// (SampleValues); the loop, the columns, the damping slots, the chunked flushing and the
// progress calls are here (the pattern of Boost.Odeint's integrate_times: one dense-output
// loop for every stepper, its output through an observer).
//
// A new output column of the nonlinear model is one change in this file: its name in
// SampleWriter's constructor and its value in SampleWriter::write (from the sample's body
// state, the body and t).

#include <array>
#include <concepts>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "heavytop/body.hpp"
#include "heavytop/frames.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/state.hpp"
#include "integrators/integration.hpp"

namespace heavytop::detail {

// An integrator with dense output: its state type, the time it has reached (s), one step
// on, and its state at a time t (s) inside the last step. The loop steps it until time() >= t
// and then interpolates, unless it has a member advance_to(t, progress) of its own (the
// splitting, whose grid point before t is where its interpolation starts).
template <class S>
concept DenseStepper = requires(S& stepper, const S& const_stepper, double t, typename S::State& x) {
  { const_stepper.time() } -> std::convertible_to<double>;
  stepper.step();
  stepper.interpolate(t, x);
};

// Brings `stepper` to where interpolate(t, .) is valid: its own advance_to if it has one, else
// steps until it has passed t, calling `progress` every kStepsPerProgress steps.
template <DenseStepper S>
void advance_stepper(S& stepper, double t, const Progress& progress) {
  if constexpr (requires { stepper.advance_to(t, progress); }) stepper.advance_to(t, progress);
  else advance_to(stepper, t, progress);
}

// Calls observer(i, t, x) for every sample i of `samples` at its time t, x the stepper's state
// at t, or nullptr at t = 0 (the input state itself, which SPEC section 2 defines, rather than
// its round trip through the stepper's variables); then progress(t) if set. Times are
// non-decreasing, so the stepper only ever moves forward.
template <DenseStepper S, class Observer>
void for_each_sample(S& stepper, std::size_t count, const std::function<double(std::size_t)>& time,
                     const Progress& progress, Observer&& observer) {
  typename S::State x{};
  for (std::size_t i = 0; i < count; ++i) {
    const double t = time(i);
    if (t > 0.0) {
      advance_stepper(stepper, t, progress);
      stepper.interpolate(t, x);
      observer(i, t, &x);
    } else {
      observer(i, t, static_cast<const typename S::State*>(nullptr));
    }
    if (progress) progress(t);
  }
}

// What an integrator reads off its state at one sample.
struct SampleValues {
  AxisAngles angles;                ///< SPEC section 2's theta, phi and their rates
  RigidBodyState body;              ///< the attitude (body to fixed) and w (body axes, rad/s)
  ConservedQuantities conserved;    ///< E, L_zeta, C w3 (J, kg m^2/s, kg m^2/s)
  /// A damped body's integrals of what its torques took away (J, kg m^2/s, kg m^2/s: the
  /// dissipated work, the vertical and the axial momentum loss); zero otherwise.
  std::array<double, 3> taken{};
};

// A sample read off a body state rb with E, L_zeta, C w3 `conserved`, its angles from rb.
inline SampleValues sample_of(const RigidBodyState& rb, const ConservedQuantities& conserved) {
  return {axis_angles_of(rb), rb, conserved, {}};
}

// The sample at t = 0 from the input state rb0 itself, with E, L_zeta, C w3 `initial` (as the
// integrator computes them for its body).
inline SampleValues initial_sample(const RigidBodyState& rb0, const ConservedQuantities& initial) {
  return sample_of(rb0, initial);
}

// The nonlinear model's columns: t and SPEC's angles, E, L_zeta, C w3 and their drifts, and
// for a damped body what its torques took away and a driven body's motor torque. Samples go
// to `samples.flush` a chunk at a time.
class SampleWriter {
 public:
  SampleWriter(const Body& body, const SampleStream& samples, const ConservedQuantities& initial, bool damped)
      : body_(body), samples_(samples), initial_(initial), damped_(damped) {
    const std::size_t room = std::min(samples.count, samples.chunk);
    out_.reserve(room);
    std::vector<const char*> names;
    if (samples.axis_direction) names = {kAxisDirectionColumns[0].data(), kAxisDirectionColumns[1].data()};
    for (const char* name : {"energy", "vertical_momentum", "axial_momentum", "energy_drift",
                             "vertical_momentum_drift", "axial_momentum_drift"})
      names.push_back(name);
    if (damped_) {
      for (const char* name : {"dissipated_work", "vertical_momentum_loss", "axial_momentum_loss"})
        names.push_back(name);
      if (body.damping.driven) names.push_back("motor_torque");
    }
    for (const char* name : names) {
      out_.extra.emplace_back(name, std::vector<double>{});
      out_.extra.back().second.reserve(room);
    }
  }

  // Sample i at t; the last sample (and every full chunk) is flushed.
  void write(std::size_t i, double t, const SampleValues& v) {
    push_angles(out_, t, v.angles);
    std::size_t c = 0;
    if (samples_.axis_direction) {
      // From k itself: frames.cpp's tilt() and azimuth() of theta and phi are the same angles
      // through a round trip (two sines and cosines more a sample, the last digit apart).
      const auto k = v.body.attitude.col(2);
      out_.extra[c++].second.push_back(tilt_of_axis(k.x(), k.y(), k.z()));
      out_.extra[c++].second.push_back(azimuth_.of_axis(k.x(), k.y()));
    }
    const ConservedQuantities& q = v.conserved;
    for (const double value : {q.energy, q.vertical_momentum, q.axial_momentum, q.energy - initial_.energy,
                               q.vertical_momentum - initial_.vertical_momentum,
                               q.axial_momentum - initial_.axial_momentum})
      out_.extra[c++].second.push_back(value);
    if (damped_) {
      for (const double value : v.taken) out_.extra[c++].second.push_back(value);
      if (body_.damping.driven) {
        const Eigen::Vector3d& w = v.body.omega;
        out_.extra[c++].second.push_back(motor_torque(body_.damping, w.z(), (body_.A - body_.B) * w.x() * w.y()));
      }
    }
    maybe_flush(samples_, out_, i + 1 == samples_.count);
  }

 private:
  const Body& body_;
  const SampleStream& samples_;
  ConservedQuantities initial_;
  bool damped_;
  ContinuousAzimuth azimuth_;
  Trajectory out_;
};

// The one sample loop: every sample of `samples` from `stepper` into the nonlinear model's
// columns, read(x) saying what the stepper's state x is (SampleValues); t = 0 from rb0 itself.
template <DenseStepper S, class Read>
void write_samples(S& stepper, const Body& body, const RigidBodyState& rb0, const ConservedQuantities& initial,
                   bool damped, const SampleStream& samples, const Read& read) {
  SampleWriter writer(body, samples, initial, damped);
  const SampleValues start = initial_sample(rb0, initial);
  for_each_sample(stepper, samples.count, samples.time, samples.progress,
                  [&](std::size_t i, double t, const typename S::State* x) {
                    writer.write(i, t, x ? read(*x) : start);
                  });
}

}  // namespace heavytop::detail
