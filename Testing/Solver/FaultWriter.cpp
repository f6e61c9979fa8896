// A process that keeps saving a model with its history (dem::writeStateAndHistory), one
// more history row per save, until it is killed: Faults.KillDuringSavesLeavesAConsistentPair
// kills it with SIGKILL at an arbitrary moment, as a crash or a power cut would.
//
//   rockdem_fault_writer <state file> <particles>
//
// Prints "saved <k>" after each completed save (stdout, flushed).
#include "Specimens.h"

#include "dem/StateFile.h"

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv)
{
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s <state file> <particles>\n", argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  const int particles = std::atoi(argv[2]);
  dem::Model m = dem::testing::specimen(particles, 0.03, 0.0004, 0.0008, 2);
  for (long k = 0;; ++k) {
    std::array<double, dem::HistoryColumnCount> row{};
    row[0] = static_cast<double>(k); // Time (s): the save's number
    row[1] = static_cast<double>(k); // Step
    m.test.history.push_back(row);
    m.clock.step = k;
    dem::writeStateAndHistory(m, path);
    std::printf("saved %ld\n", k);
    std::fflush(stdout);
  }
}
