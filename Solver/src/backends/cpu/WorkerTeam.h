// RockDEM engine: the CPU backend's team of threads for the loops of a step.
//
// OpenMP starts and joins a team for every parallel loop. With passive waiting
// (OMP_WAIT_POLICY=passive, which a shared machine needs) each start and join sleeps and
// wakes a thread through the kernel, 20-80 us on the development VM, three times per step;
// with libgomp's default the waiting threads spin for up to about a millisecond, which
// costs several times the work when another process holds a core (Benchmarks-Solver.md).
// The team here keeps its threads between loops: a waiting thread spins for a short,
// bounded time (kSpinMicroseconds) and then sleeps, so that the loops of a step start and
// join in about a microsecond on an idle machine and a busy one loses at most that spin.
//
// Which thread computes what never changes a result: each loop gives each rank a fixed
// range and writes each result once.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace dem {

class WorkerTeam {
public:
  /// How long a waiting thread spins before it sleeps (us).
  static constexpr int kSpinMicroseconds = 50;

  WorkerTeam() = default;
  ~WorkerTeam();
  WorkerTeam(const WorkerTeam&) = delete;
  WorkerTeam& operator=(const WorkerTeam&) = delete;

  /// Calls job(rank) once for each rank in [0, ranks), rank 0 on the calling thread and the
  /// others on the team's threads (started at the first call, or again when `ranks`
  /// changes), and returns when all have returned. The first exception a job throws is
  /// rethrown here, after all ranks have finished. ranks <= 1 calls job(0) alone.
  ///
  /// Each rank calls its own copy of `job`: a local object whose address does not escape,
  /// so the compiler may keep what the job captured by value in registers across the
  /// stores of its loops (through the shared closure it reloaded them after every byte
  /// stored, and a loop such as the gather ran about 10 % slower).
  template <class Job> void run(int ranks, const Job& job)
  {
    if (ranks <= 1) {
      Job local(job);
      local(0);
      return;
    }
    runErased(ranks, [](const void* shared, int rank) {
      Job local(*static_cast<const Job*>(shared));
      local(rank);
    }, &job);
  }

  /// Threads the team holds besides the caller's.
  std::size_t workers() const { return workers_.size(); }

private:
  using Entry = void (*)(const void*, int);
  void runErased(int ranks, Entry entry, const void* job);
  void startWorkers(int count);
  void stopWorkers();
  void workerLoop(int rank, std::uint64_t seen);
  void record(std::exception_ptr error);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_; // a new job (or stop) for the workers
  std::condition_variable done_; // the last worker finished
  std::atomic<std::uint64_t> generation_{ 0 }; // counts the jobs; a worker waits for a change
  std::atomic<int> pending_{ 0 };              // workers still on the current job
  std::atomic<int> sleepingWorkers_{ 0 };
  std::atomic<bool> callerSleeping_{ false };
  std::atomic<bool> stopping_{ false };
  Entry entry_ = nullptr;
  const void* job_ = nullptr;
  std::mutex errorMutex_;
  std::exception_ptr error_;
};

} // namespace dem
