// Boost.Odeint's Rosenbrock 4 behind rosenbrock4.hpp (built as C++17: see there).
#include "integrators/rosenbrock/rosenbrock4.hpp"

#include <vector>

#include <boost/numeric/odeint/stepper/rosenbrock4.hpp>
#include <boost/numeric/odeint/stepper/rosenbrock4_controller.hpp>
#include <boost/numeric/odeint/stepper/rosenbrock4_dense_output.hpp>

namespace heavytop::detail {

namespace odeint = boost::numeric::odeint;
using Vector = boost::numeric::ublas::vector<double>;
using Matrix = boost::numeric::ublas::matrix<double>;
using Controller = odeint::rosenbrock4_controller<odeint::rosenbrock4<double>>;

struct Rosenbrock4Dense::Impl {
  std::size_t n;
  Rates rates;
  Jacobian jacobian;
  odeint::rosenbrock4_dense_output<Controller> dense;
  std::vector<double> y, f, J;  // scratch: one state, one rate, one Jacobian

  void derivative(const Vector& x, Vector& dxdt) {
    for (std::size_t i = 0; i < n; ++i) y[i] = x[i];
    rates(y.data(), f.data());
    for (std::size_t i = 0; i < n; ++i) dxdt[i] = f[i];
  }
  void jacobi(const Vector& x, Matrix& M, Vector& dfdt) {
    for (std::size_t i = 0; i < n; ++i) y[i] = x[i];
    jacobian(y.data(), J.data());
    for (std::size_t i = 0; i < n; ++i) {
      dfdt[i] = 0.0;  // autonomous
      for (std::size_t j = 0; j < n; ++j) M(i, j) = J[i * n + j];
    }
  }
};

Rosenbrock4Dense::Rosenbrock4Dense(std::size_t n, Rates rates, Jacobian jacobian, const double* y0, double dt0,
                                   double atol, double rtol)
    : impl_(new Impl{n, std::move(rates), std::move(jacobian), odeint::rosenbrock4_dense_output<Controller>(
                                                                       Controller(atol, rtol)),
                     std::vector<double>(n), std::vector<double>(n), std::vector<double>(n * n)}) {
  Vector x(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = y0[i];
  impl_->dense.initialize(x, 0.0, dt0);
}

Rosenbrock4Dense::~Rosenbrock4Dense() = default;

std::pair<double, double> Rosenbrock4Dense::step() {
  Impl& m = *impl_;
  auto derivative = [&m](const Vector& x, Vector& dxdt, double) { m.derivative(x, dxdt); };
  auto jacobi = [&m](const Vector& x, Matrix& M, double, Vector& dfdt) { m.jacobi(x, M, dfdt); };
  return m.dense.do_step(std::make_pair(derivative, jacobi));
}

double Rosenbrock4Dense::next_step() const { return impl_->dense.current_time_step(); }

void Rosenbrock4Dense::set_next_step(double dt) {
  const Vector x = impl_->dense.current_state();
  impl_->dense.initialize(x, impl_->dense.current_time(), dt);
}

double Rosenbrock4Dense::time() const { return impl_->dense.current_time(); }

const double* Rosenbrock4Dense::state() const { return &impl_->dense.current_state()[0]; }

void Rosenbrock4Dense::state_at(double t, double* out) {
  Vector x(impl_->n);
  impl_->dense.calc_state(t, x);
  for (std::size_t i = 0; i < impl_->n; ++i) out[i] = x[i];
}

}  // namespace heavytop::detail
