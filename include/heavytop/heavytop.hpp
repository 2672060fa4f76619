#pragma once
/// \file
/// The umbrella header: every public header of heavytop's numeric core (heavytop::core), so
/// that `#include <heavytop/heavytop.hpp>` gives the whole API. The symbolic derivations
/// (heavytop::symbolic, GiNaC) are not included; include <heavytop/symbolic/derive.hpp> and
/// friends for those. A new public header of the core belongs here too (the package test
/// checks that every installed heavytop/*.hpp is listed).

#include "heavytop/version.hpp"

#include "heavytop/body.hpp"            // Body, validate(), example_toy_top()
#include "heavytop/damping.hpp"         // Damping (SPEC section 6) and the spin-decay law
#include "heavytop/fit_decay.hpp"       // d_a and tau0 fitted to a measured spin decay
#include "heavytop/state.hpp"           // InitialState, Trajectory
#include "heavytop/frames.hpp"          // the frames and angles (SPEC section 2)
#include "heavytop/linear_models.hpp"   // the three linear models as data
#include "heavytop/stability.hpp"       // linear stability and the stable spins
#include "heavytop/answer.hpp"          // the answer first: does it stay up, for how long (SPEC 14)
#include "heavytop/lyapunov.hpp"        // the real body's Lyapunov verdict and the wander
#include "heavytop/normal_form.hpp"     // the order-4 Birkhoff normal form (Arnold, Markeev)
#include "heavytop/linear_motion.hpp"   // motion of the linear models
#include "heavytop/progress.hpp"        // the progress callback, an argument of a run
#include "heavytop/nonlinear.hpp"       // the full rigid body, integrated adaptively
#include "heavytop/splitting.hpp"       // the structure-preserving splitting integrator
#include "heavytop/taylor.hpp"          // the Taylor-series integrator of the full body
#include "heavytop/batch.hpp"           // the Taylor integrator on many bodies at once (sweeps)
#include "heavytop/verdicts.hpp"        // a sweep's verdicts, each at the tolerance that decides it
#include "heavytop/general_body.hpp"    // the general body (SPEC section 11) in nonlinear
#include "heavytop/dop853.hpp"          // the 8th-order Runge-Kutta of the full body
#include "heavytop/lagrange_exact.hpp"  // the symmetric top's motion in closed form
#include "heavytop/compare.hpp"         // the models against each other
#include "heavytop/lifetime.hpp"        // how long a damped top stays up (SPEC section 8)
#include "heavytop/chaos.hpp"           // Lyapunov exponents, MEGNO, the Poincare section (SPEC section 17)
#include "heavytop/sweep.hpp"           // sweeps across machines
#include "heavytop/simulate.hpp"        // simulate(Model, ...): one entry point for every model
#include "heavytop/rigid_body.hpp"      // RigidBodySystem for odeint-style steppers
#include "heavytop/mass_properties.hpp" // a body from its parts or a mesh (SPEC section 10)
#include "heavytop/precession.hpp"      // steady precessions and permanent rotations at a tilt
#include "heavytop/units.hpp"           // rpm (SPEC section 9)
#include "heavytop/table.hpp"           // the body on a table (SPEC section 16)
#include "heavytop/contact_losses.hpp"  // Hertz's patch, drilling friction and the air on a real top
#include "heavytop/uncertainty.hpp"     // how sure the answer is under uncertain inputs (SPEC 17)
