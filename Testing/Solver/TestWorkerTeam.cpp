// The CPU backend's WorkerTeam (Solver/src/backends/cpu/WorkerTeam.h): every rank runs
// each job exactly once, the caller returns only when all have finished, jobs follow
// each other without a lost or doubled rank whether the threads are spinning or asleep
// between them, a different number of ranks restarts the team, and an exception from any
// rank reaches the caller after all ranks have finished.
#include "backends/cpu/WorkerTeam.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using dem::WorkerTeam;

TEST(WorkerTeam, EveryRankRunsEveryJobOnce)
{
  WorkerTeam team;
  for (int ranks : { 1, 2, 3, 4, 2, 1 }) {
    std::vector<int> runs(static_cast<std::size_t>(ranks), 0);
    const int jobs = 2000;
    for (int job = 0; job < jobs; ++job) {
      // Each rank writes its own slot: counts that come out right mean each rank ran
      // once per job, and that the caller saw the job's writes when run() returned.
      team.run(ranks, [&](int rank) { runs[static_cast<std::size_t>(rank)] += 1; });
      if (job % 500 == 0) {
        for (int r = 0; r < ranks; ++r) {
          ASSERT_EQ(runs[static_cast<std::size_t>(r)], job + 1) << ranks << " ranks, rank " << r;
        }
      }
    }
    for (int r = 0; r < ranks; ++r) {
      EXPECT_EQ(runs[static_cast<std::size_t>(r)], jobs);
    }
    if (ranks > 1) {
      EXPECT_EQ(team.workers(), static_cast<std::size_t>(ranks - 1));
    }
  }
}

TEST(WorkerTeam, JobsAfterTheThreadsFellAsleep)
{
  // Pauses longer than the spin make the waiting threads sleep: the next job must wake
  // them (and the caller, waiting for a slow rank, must be woken by it).
  WorkerTeam team;
  std::atomic<int> total{ 0 };
  for (int job = 0; job < 20; ++job) {
    team.run(3, [&](int rank) {
      if (rank == 2 && job % 2 == 0) {
        std::this_thread::sleep_for(std::chrono::microseconds(5 * WorkerTeam::kSpinMicroseconds));
      }
      total.fetch_add(rank + 1);
    });
    EXPECT_EQ(total.load(), (job + 1) * 6);
    std::this_thread::sleep_for(std::chrono::microseconds(4 * WorkerTeam::kSpinMicroseconds));
  }
}

TEST(WorkerTeam, AnExceptionReachesTheCallerAfterAllRanks)
{
  WorkerTeam team;
  for (int thrower : { 0, 1 }) {
    std::atomic<int> finished{ 0 };
    try {
      team.run(2, [&](int rank) {
        if (rank == thrower) {
          throw std::runtime_error("rank " + std::to_string(rank));
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        finished.fetch_add(1);
      });
      ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "rank " + std::to_string(thrower));
    }
    EXPECT_EQ(finished.load(), 1); // the other rank had finished when run() threw
    // The team still works.
    std::atomic<int> after{ 0 };
    team.run(2, [&](int) { after.fetch_add(1); });
    EXPECT_EQ(after.load(), 2);
  }
}
