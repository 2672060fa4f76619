#pragma once
// Private to the library: Boost.Odeint's Rosenbrock 4 with its dense output (Shampine's L-stable
// method of order 4, its embedded order-3 error estimate and order-3 continuous extension; Hairer
// and Wanner, Solving ODEs II, section IV.7) over plain arrays. Its own translation unit is built
// as C++17 (rosenbrock4.cpp): Boost 1.74's uBLAS, odeint's state type there, calls
// std::allocator members that C++20 removed. Nothing of Boost crosses this header.

#include <cstddef>
#include <functional>
#include <memory>
#include <utility>

namespace heavytop::detail {

class Rosenbrock4Dense {
 public:
  /// dydt = f(y), n values each.
  using Rates = std::function<void(const double* y, double* dydt)>;
  /// J = df/dy at y, n x n, row-major.
  using Jacobian = std::function<void(const double* y, double* J)>;

  /// From y0 (n values) at t = 0 with a first trial step dt0 (s), error-controlled at atol, rtol.
  Rosenbrock4Dense(std::size_t n, Rates rates, Jacobian jacobian, const double* y0, double dt0, double atol,
                   double rtol);
  ~Rosenbrock4Dense();
  Rosenbrock4Dense(const Rosenbrock4Dense&) = delete;
  Rosenbrock4Dense& operator=(const Rosenbrock4Dense&) = delete;

  /// One accepted step (odeint retries rejected ones; std::runtime_error after 500 in a row):
  /// its start and end times.
  std::pair<double, double> step();
  /// The next trial step (s), and a new one (the step that ends at a horizon).
  double next_step() const;
  void set_next_step(double dt);
  double time() const;
  /// The state at the last step's end, n values.
  const double* state() const;
  /// The state at t in the last step's interval, from the continuous extension, into y (n values).
  void state_at(double t, double* y);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace heavytop::detail
