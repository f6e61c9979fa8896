// Writes the seed corpus of the state file fuzzer: small valid state files (an empty
// model; a few particles with contacts, a bond, walls and a test history).
#include "dem/Bonds.h"
#include "dem/LoadTest.h"
#include "dem/Model.h"
#include "dem/Simulation.h"
#include "dem/StateFile.h"

#include <iostream>
#include <string>

int main(int argc, char** argv)
{
  if (argc != 2) {
    std::cerr << "usage: rockdem_make_fuzz_seeds <directory>\n";
    return 2;
  }
  const std::string dir = argv[1];
  dem::writeState(dem::Model(), dir + "/empty.rdem");
  dem::Model m;
  m.domain.size = dem::Vec3(0.01, 0.01, 0.01);
  m.gravity.setZero();
  m.material.youngsModulus = 1e8;
  m.material.rollingFriction = 0.1;
  m.particles.append(dem::Vec3(0.004, 0.005, 0.005), 0.0011, m.nextId++);
  m.particles.append(dem::Vec3(0.006, 0.005, 0.005), 0.0011, m.nextId++);
  m.particles.append(dem::Vec3(0.005, 0.005, 0.007), 0.0011, m.nextId++);
  dem::updateMassProperties(m);
  m.particles.velocity[1] = dem::Vec3(0.0, 0.01, 0.0); // sliding: the contacts carry slip history
  m.particles.angularVelocity[2] = dem::Vec3(1.0, 0.0, 0.0);
  m.bonds.append(0, 1, 0.001, 1e12, 4e11, 1e6, 2e6, 0.5);
  dem::LoadTestSettings s;
  s.mode = dem::TestMode::Triaxial;
  s.confiningStress = 1e4;
  s.sampleInterval = 1;
  dem::startLoadTest(m, s);
  {
    dem::Simulation sim(m);
    sim.advance(3); // the overlapping pairs still touch: the seed has contact history
  }
  dem::writeState(m, dir + "/tiny.rdem");
  std::cout << "seeds: empty.rdem, tiny.rdem (" << m.contacts.size() << " contacts, " << m.test.history.size()
            << " history rows)\n";
  return 0;
}
