#pragma once
// Private to the library: the integrators of the nonlinear model with their samples streamed
// (SampleStream), behind simulate_nonlinear/simulate_splitting and simulate_streaming().

#include "integrators/integration.hpp"
#include "heavytop/nonlinear.hpp"
#include "heavytop/splitting.hpp"
#include "heavytop/taylor.hpp"

namespace heavytop::detail {

void stream_nonlinear(const Body& body, const InitialState& initial, const SampleStream& samples,
                      const Tolerances& options, NonlinearSummary* summary);

void stream_splitting(const Body& body, const InitialState& initial, const SampleStream& samples,
                      const SplittingOptions& options, SplittingSummary* summary);

void stream_taylor(const Body& body, const InitialState& initial, const SampleStream& samples,
                   const Tolerances& options, TaylorSummary* summary);

// The general body (SPEC section 11), general_body.cpp: the conservative body only.
void stream_general(const Body& body, const InitialState& initial, const SampleStream& samples,
                    const Tolerances& options, NonlinearSummary* summary);

void stream_dop853(const Body& body, const InitialState& initial, const SampleStream& samples,
                   const Tolerances& options, NonlinearSummary* summary);

}  // namespace heavytop::detail
