// State file figures (Documentation/StateFile.md, "Size and speed"): file size per
// particle and write / read times for a cemented specimen in the middle of a triaxial test.
//   rockdem_bench_state_file [--particles N] [--dir DIR]
#include "dem/Bonds.h"
#include "dem/Cement.h"
#include "dem/LoadTest.h"
#include "dem/Model.h"
#include "dem/Pack.h"
#include "dem/Simulation.h"
#include "dem/StateFile.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {
double seconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}
}

int main(int argc, char** argv)
{
  long particles = 100000;
  std::string dir = "/tmp";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--particles")) {
      particles = std::atol(argv[i + 1]);
    } else if (!std::strcmp(argv[i], "--dir")) {
      dir = argv[i + 1];
    }
  }
  dem::Model m;
  const double r = 0.001;
  const double side = std::cbrt(particles * 4.0 / 3.0 * M_PI * std::pow(1.25 * r, 3) / 0.3); // random placement saturates near porosity 0.7
  m.domain.size = dem::Vec3(side, side, side);
  m.material.youngsModulus = 1e8;
  m.material.rollingFriction = 0.1;
  m.gravity.setZero();
  dem::PackParameters p;
  p.initialElements = particles;
  p.minimumSize = r;
  p.maximumSize = 1.5 * r;
  auto t0 = std::chrono::steady_clock::now();
  dem::buildPack(m, p);
  dem::growElements(m);
  dem::CementParameters c;
  c.gapTolerance = 0.5; // a loose pack: bond near neighbours too, as a dense specimen has
  dem::cement(m, c);
  dem::LoadTestSettings s;
  s.mode = dem::TestMode::Triaxial;
  s.confiningStress = 1e5;
  s.sampleInterval = 10;
  dem::startLoadTest(m, s);
  {
    dem::Simulation sim(m);
    sim.advance(100);
  }
  std::printf("model: %zu particles, %zu contacts, %zu bonds, %zu history rows (built in %.1f s)\n",
              m.particles.size(), m.contacts.size(), m.bonds.size(), m.test.history.size(), seconds(t0));
  const std::string path = dir + "/rockdem_bench_state.rdem";
  t0 = std::chrono::steady_clock::now();
  const std::vector<unsigned char> image = dem::writeStateToMemory(m);
  const double encode = seconds(t0);
  t0 = std::chrono::steady_clock::now();
  dem::writeState(m, path);
  const double write = seconds(t0);
  t0 = std::chrono::steady_clock::now();
  const dem::Model back = dem::readState(path);
  const double read = seconds(t0);
  t0 = std::chrono::steady_clock::now();
  const std::uint64_t h = dem::fnv1a64(image.data(), image.size());
  const double hash = seconds(t0);
  const double n = static_cast<double>(m.particles.size());
  std::printf("file: %zu bytes = %.1f bytes per particle (%.2f contacts, %.2f bonds per particle)\n",
              image.size(), image.size() / n, m.contacts.size() / n, m.bonds.size() / n);
  std::printf("write (encode in memory): %.3f s; writeState (encode + write + fsync + rename): %.3f s; "
              "readState (read + check + decode + validate): %.3f s; checksum alone: %.3f s (%.0f MB/s)%s\n",
              encode, write, read, hash, image.size() / hash / 1e6, h ? "" : " ");
  std::printf("read back: %zu particles, %zu contacts, %zu bonds\n", back.particles.size(), back.contacts.size(),
              back.bonds.size());
  std::remove(path.c_str());
  return 0;
}
