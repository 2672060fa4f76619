#include "interrupt.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace heavytop::python {

namespace py = pybind11;

bool signalled() {
  const py::gil_scoped_acquire gil;
  return PyErr_CheckSignals() != 0;
}

std::function<void(double)> poll_signals() {
  auto next = std::make_shared<std::chrono::steady_clock::time_point>(std::chrono::steady_clock::now());
  return [next](double) {
    const auto now = std::chrono::steady_clock::now();
    if (now < *next) return;
    *next = now + std::chrono::milliseconds(100);
    if (signalled()) throw Interrupted{};
  };
}

void parallel_blocks(std::size_t count, std::size_t block, const std::function<void(std::size_t, std::size_t)>& f) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::exception_ptr failure;
  std::once_flag failed;
  std::mutex mutex;
  std::condition_variable finished;
  const std::size_t threads =
      std::min<std::size_t>(std::max(1u, std::thread::hardware_concurrency()), (count + block - 1) / block);
  std::size_t running = threads;
  auto work = [&] {
    for (std::size_t first; !stop && (first = next.fetch_add(block)) < count;) {
      try {
        f(first, std::min(count, first + block));
      } catch (...) {
        std::call_once(failed, [&] { failure = std::current_exception(); });
        stop = true;
      }
    }
    const std::lock_guard lock(mutex);
    if (--running == 0) finished.notify_one();
  };
  bool interrupted = false;
  {
    std::vector<std::jthread> pool;
    for (std::size_t t = 0; t < threads; ++t) pool.emplace_back(work);
    std::unique_lock lock(mutex);
    while (!finished.wait_for(lock, std::chrono::milliseconds(100), [&] { return running == 0; })) {
      lock.unlock();
      if (!interrupted && signalled()) {
        interrupted = true;
        stop = true;
      }
      lock.lock();
    }
  }
  if (interrupted) throw Interrupted{};
  if (failure) std::rethrow_exception(failure);
}

}  // namespace heavytop::python
