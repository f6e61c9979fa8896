#include "backends/cpu/WorkerTeam.h"

#include <chrono>

namespace dem {
namespace {

inline void cpuRelax()
{
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

/// Spins until ready() or until kSpinMicroseconds have passed; true when ready.
template <class Ready> bool spinUntil(Ready ready)
{
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  const auto budget = std::chrono::microseconds(WorkerTeam::kSpinMicroseconds);
  for (unsigned n = 1;; ++n) {
    if (ready()) {
      return true;
    }
    cpuRelax();
    if ((n & 63u) == 0 && Clock::now() - start > budget) {
      return ready();
    }
  }
}

} // namespace

WorkerTeam::~WorkerTeam() { stopWorkers(); }

void WorkerTeam::record(std::exception_ptr error)
{
  std::lock_guard<std::mutex> lock(errorMutex_);
  if (!error_) {
    error_ = error;
  }
}

void WorkerTeam::startWorkers(int count)
{
  stopWorkers();
  const std::uint64_t seen = generation_.load();
  workers_.reserve(static_cast<std::size_t>(count));
  for (int w = 0; w < count; ++w) {
    workers_.emplace_back([this, w, seen] { workerLoop(w + 1, seen); });
  }
}

void WorkerTeam::stopWorkers()
{
  if (workers_.empty()) {
    return;
  }
  stopping_.store(true);
  generation_.fetch_add(1);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    wake_.notify_all();
  }
  for (std::thread& t : workers_) {
    t.join();
  }
  workers_.clear();
  stopping_.store(false);
}

void WorkerTeam::workerLoop(int rank, std::uint64_t seen)
{
  for (;;) {
    // A new job: spin a little, then sleep. (The counter and the sleeper count are
    // sequentially consistent: either the caller sees this thread asleep and wakes it,
    // or this thread sees the new job before it sleeps.)
    auto changed = [&] { return generation_.load() != seen; };
    if (!spinUntil(changed)) {
      std::unique_lock<std::mutex> lock(mutex_);
      sleepingWorkers_.fetch_add(1);
      wake_.wait(lock, changed);
      sleepingWorkers_.fetch_sub(1);
    }
    seen = generation_.load();
    if (stopping_.load()) {
      return;
    }
    try {
      entry_(job_, rank);
    } catch (...) {
      record(std::current_exception());
    }
    if (pending_.fetch_sub(1) == 1 && callerSleeping_.load()) {
      std::lock_guard<std::mutex> lock(mutex_);
      done_.notify_one();
    }
  }
}

void WorkerTeam::runErased(int ranks, Entry entry, const void* job)
{
  if (workers_.size() != static_cast<std::size_t>(ranks - 1)) {
    startWorkers(ranks - 1);
  }
  entry_ = entry;
  job_ = job;
  error_ = nullptr;
  pending_.store(ranks - 1);
  generation_.fetch_add(1); // publishes the job (sequentially consistent)
  if (sleepingWorkers_.load() > 0) {
    std::lock_guard<std::mutex> lock(mutex_);
    wake_.notify_all();
  }
  try {
    entry(job, 0);
  } catch (...) {
    record(std::current_exception());
  }
  auto finished = [&] { return pending_.load() == 0; };
  if (!spinUntil(finished)) {
    std::unique_lock<std::mutex> lock(mutex_);
    callerSleeping_.store(true);
    done_.wait(lock, finished);
    callerSleeping_.store(false);
  }
  if (error_) {
    std::exception_ptr error = error_;
    error_ = nullptr;
    std::rethrow_exception(error);
  }
}

} // namespace dem
