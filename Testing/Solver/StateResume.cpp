// rockdem_state_resume: exact resume across processes (Documentation/StateFile.md).
//
//   rockdem_state_resume start <settling|cemented|triaxial|membrane> <steps> <out.rdem>
//       builds the specimen (StateFixtures.h), runs <steps> steps with one simulation and
//       writes the state file;
//   rockdem_state_resume continue <in.rdem> <steps> <out.rdem>
//       reads a state file in this fresh process, runs <steps> more, writes the result;
//   rockdem_state_resume compare <a.rdem> <b.rdem>
//       exit status 0 when particles, contacts, bonds, walls, test and clock are bitwise
//       identical, 1 otherwise (naming the first difference).
// state_resume.cmake runs A = start 2N, B = start N then continue N, and compares.
#include "StateFixtures.h"

#include "dem/StateFile.h"

#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>

int main(int argc, char** argv)
{
  try {
    const std::string command = argc > 1 ? argv[1] : "";
    if ((command == "start" || command == "continue") && argc == 5) {
      dem::Model m = command == "start" ? dem::statetest::byName(argv[2]) : dem::readState(argv[2]);
      const long long steps = std::atoll(argv[3]);
      {
        dem::Simulation sim(m);
        sim.advance(steps);
      }
      dem::writeState(m, argv[4]);
      std::cout << command << ": " << m.particles.size() << " particles, " << m.contacts.size() << " contacts, "
                << m.bonds.size() << " bonds (" << dem::countBonds(m.bonds).broken << " broken), stage "
                << dem::stageName(m.test.stage) << ", step " << m.clock.step << " -> " << argv[4] << "\n";
      return 0;
    }
    if (command == "compare" && argc == 4) {
      const dem::Model a = dem::readState(argv[2]);
      const dem::Model b = dem::readState(argv[3]);
      const std::string diff = dem::statetest::firstDifference(a, b);
      if (diff.empty()) {
        std::cout << "bitwise identical: step " << a.clock.step << ", " << a.particles.size() << " particles, "
                  << a.contacts.size() << " contacts, " << a.bonds.size() << " bonds\n";
        return 0;
      }
      std::cout << "DIFFERENT: first difference in " << diff << "\n";
      return 1;
    }
    std::cerr << "usage: rockdem_state_resume start <settling|cemented|triaxial|membrane> <steps> <out.rdem>\n"
                 "       rockdem_state_resume continue <in.rdem> <steps> <out.rdem>\n"
                 "       rockdem_state_resume compare <a.rdem> <b.rdem>\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "rockdem_state_resume: " << e.what() << "\n";
    return 2;
  }
}
