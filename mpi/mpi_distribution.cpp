#include "mpi_distribution.hpp"

#include <mpi.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "heavytop/io/map_file.hpp"

namespace heavytop::mpi {
namespace {

// Every rank but 0 first sends one word, kRequest (ready for work) or kFailure (it stopped
// before computing: bad input, --help; or while computing); it then gets one kAssign for each
// kRequest or kResult it sends, an empty range meaning "stop".
enum Tag : int { kRequest = 1, kAssign = 2, kResult = 3, kFailure = 4 };

std::string receive(const MPI_Status& probed) {
  int count = 0;
  MPI_Get_count(&probed, MPI_BYTE, &count);
  std::string bytes(static_cast<std::size_t>(count), '\0');
  MPI_Recv(bytes.data(), count, MPI_BYTE, probed.MPI_SOURCE, probed.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return bytes;
}

void assign(int rank, std::uint64_t begin, std::uint64_t end) {
  const std::uint64_t range[2] = {begin, end};
  MPI_Send(range, 2, MPI_UINT64_T, rank, kAssign, MPI_COMM_WORLD);
}

/// A rank's failure ([its exit status][what it printed]): shown once, then the whole job ends
/// with that status. Rank 0 has flushed whole blocks only, so FILE.partial stays resumable.
[[noreturn]] void abort_job(int rank, const std::string& failure) {
  const int status = failure.empty() || failure[0] == 0 ? 1 : static_cast<unsigned char>(failure[0]);
  const std::string text =
      failure.size() > 1 ? failure.substr(1) : fmt::format("heavytop: error: sweep: rank {} stopped computing\n", rank);
  std::fputs(text.c_str(), stderr);
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, status);
  std::abort();
}

/// Cores for this rank's threads: those it is bound to (mpirun --bind-to, Slurm's
/// --cpus-per-task), else the node's shared by the ranks on the node.
unsigned threads_per_rank() {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0 && static_cast<unsigned>(CPU_COUNT(&set)) < cores)
    return static_cast<unsigned>(CPU_COUNT(&set));
  unsigned local = 1;
  for (const char* name : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS", "SLURM_NTASKS_PER_NODE"})
    if (const char* value = std::getenv(name)) {
      local = std::max(1u, static_cast<unsigned>(std::strtoul(value, nullptr, 10)));
      break;
    }
  return std::max(1u, cores / local);
}

}  // namespace

MpiDistribution::MpiDistribution() : threads_(threads_per_rank()) {
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  heard_.assign(static_cast<std::size_t>(size_), 0);
  stopped_.assign(static_cast<std::size_t>(size_), 0);
}

void MpiDistribution::capture_stderr() {
  if (rank_ == 0) return;
  std::fflush(stdout);
  std::fflush(stderr);
  if (std::FILE* null = std::fopen("/dev/null", "w")) dup2(fileno(null), STDOUT_FILENO);  // rank 0 prints
  captured_ = std::tmpfile();
  if (captured_) dup2(fileno(captured_), STDERR_FILENO);
}

void MpiDistribution::run(std::size_t begin, std::size_t total, std::size_t block, const cli::ComputeBlock& compute,
                          const cli::WriteBlock& write) const {
  if (rank_ != 0) {  // compute what rank 0 hands out
    served_ = true;
    MPI_Send(nullptr, 0, MPI_BYTE, 0, kRequest, MPI_COMM_WORLD);
    for (;;) {
      std::uint64_t range[2] = {0, 0};
      MPI_Recv(range, 2, MPI_UINT64_T, 0, kAssign, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (range[0] == range[1]) return;
      std::string result(sizeof range[0], '\0');
      std::memcpy(result.data(), &range[0], sizeof range[0]);
      io::pack_verdicts(compute(range[0], range[1]), result);
      MPI_Send(result.data(), static_cast<int>(result.size()), MPI_BYTE, 0, kResult, MPI_COMM_WORLD);
    }
  }

  if (size_ == 1) {  // a job of one rank: the serial sweep, without polling for messages
    served_ = true;
    SweepDistribution::run(begin, total, block, compute, write);
    return;
  }
  // Rank 0: the blocks are handed out in grid order from `next`, to the other ranks on
  // request and to this rank's own computing thread; `ready` holds finished blocks until the
  // ones before them are written.
  std::mutex mutex;
  std::size_t next = begin;
  std::map<std::size_t, std::vector<SweepVerdict>> ready;
  auto take = [&]() -> std::optional<std::pair<std::size_t, std::size_t>> {
    const std::lock_guard guard(mutex);
    if (next >= total) return std::nullopt;
    const std::size_t first = next;
    next = std::min(total, next + block);
    return std::pair{first, next};
  };
  auto hand_out = [&](int rank) {
    if (const auto range = take()) {
      assign(rank, range->first, range->second);
    } else {
      assign(rank, 0, 0);
      stopped_[static_cast<std::size_t>(rank)] = 1;
    }
  };
  std::atomic<bool> stop{false};
  std::exception_ptr local_failure;
  std::atomic<bool> local_failed{false};
  failed_ = true;  // until the loop below completes
  {
    std::jthread local([&] {
      try {
        while (!stop)
          if (const auto range = take()) {
            std::vector<SweepVerdict> verdicts = compute(range->first, range->second);
            const std::lock_guard guard(mutex);
            ready.emplace(range->first, std::move(verdicts));
          } else {
            break;
          }
      } catch (...) {
        local_failure = std::current_exception();
        local_failed = true;
      }
    });
    struct StopLocal {
      std::atomic<bool>& stop;
      ~StopLocal() { stop = true; }  // before `local` joins, also when writing throws
    } stop_local{stop};
    // Idle, the loop sleeps 50 us, doubling up to 2 ms while nothing arrives: each probe runs
    // MPI's progress engine, and probing every 200 us cost a bound core 15% of its time.
    std::chrono::microseconds idle{50};
    for (std::size_t written = begin; written < total;) {
      bool busy = false;
      int arrived = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status);
      if (arrived) {
        busy = true;
        const std::string message = receive(status);
        heard_[static_cast<std::size_t>(status.MPI_SOURCE)] = 1;
        if (status.MPI_TAG == kFailure) abort_job(status.MPI_SOURCE, message);
        if (status.MPI_TAG == kResult) {
          std::uint64_t first = 0;
          std::memcpy(&first, message.data(), sizeof first);
          std::vector<SweepVerdict> verdicts = io::unpack_verdicts(std::string_view(message).substr(sizeof first));
          const std::lock_guard guard(mutex);
          ready.emplace(first, std::move(verdicts));
        }
        hand_out(status.MPI_SOURCE);
      }
      for (;;) {  // write every block that is now contiguous with what is written
        std::vector<SweepVerdict> verdicts;
        {
          const std::lock_guard guard(mutex);
          const auto it = ready.find(written);
          if (it == ready.end()) break;
          verdicts = std::move(it->second);
          ready.erase(it);
        }
        const std::size_t first = written;
        written += verdicts.size();
        write(first, std::move(verdicts));
        busy = true;
      }
      if (local_failed) std::rethrow_exception(local_failure);
      if (busy) {
        idle = std::chrono::microseconds{50};
      } else {
        std::this_thread::sleep_for(idle);
        idle = std::min(2 * idle, std::chrono::microseconds{2000});
      }
    }
  }
  failed_ = false;
  served_ = true;
}

int MpiDistribution::finish(int status) {
  if (rank_ != 0) {
    if (status != 0 || !served_) {  // tell rank 0 why this rank stopped
      std::string failure(1, static_cast<char>(status));
      if (captured_) {
        std::fflush(stderr);
        std::rewind(captured_);
        for (int c; (c = std::fgetc(captured_)) != EOF;) failure.push_back(static_cast<char>(c));
      }
      MPI_Send(failure.data(), static_cast<int>(failure.size()), MPI_BYTE, 0, kFailure, MPI_COMM_WORLD);
    }
    return status;
  }
  if (failed_) {  // the work began and failed here: end every rank (rank 0 has said why)
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, status == 0 ? 1 : status);
  }
  // Release every rank not yet told to stop; each sends its first word if it has not yet.
  for (int rank = 1; rank < size_; ++rank) {
    if (stopped_[static_cast<std::size_t>(rank)]) continue;
    if (!heard_[static_cast<std::size_t>(rank)]) {
      MPI_Status probed;
      MPI_Probe(rank, MPI_ANY_TAG, MPI_COMM_WORLD, &probed);
      const std::string message = receive(probed);
      // A rank that failed alone while this one succeeded fails the job; if this one failed
      // too, its own message (already shown) is the one that counts.
      if (probed.MPI_TAG == kFailure) {
        if (status == 0 && served_ && !message.empty() && message[0] != 0) abort_job(rank, message);
        continue;
      }
    }
    assign(rank, 0, 0);
  }
  return status;
}

}  // namespace heavytop::mpi
