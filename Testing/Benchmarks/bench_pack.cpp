// Pack benchmark: random sequential placement of N particles (radius 1 to 2 mm, a 2:1
// range) in a cubic box sized so that N particles give porosity ~0.70, then (unless
// --quick) alternating Add Elements (Target Porosity 0.35) and Grow Elements, printing the
// porosity after each command and its wall-clock time.
//
//   rockdem_bench_pack [--sizes 10000,100000,1000000] [--quick] [--rounds 4]
#include "CommaList.h"
#include "dem/Pack.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Options {
  std::vector<long> sizes{ 10000, 100000, 1000000 };
  bool quick = false;
  int rounds = 4;
};

Options parse(int argc, char** argv)
{
  Options o;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--sizes") == 0 && i + 1 < argc) {
      o.sizes = rockdem_bench::parseList<long>(argv[++i]);
    } else if (std::strcmp(argv[i], "--quick") == 0) {
      o.quick = true;
    } else if (std::strcmp(argv[i], "--rounds") == 0 && i + 1 < argc) {
      o.rounds = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: %s [--sizes N1,N2,...] [--quick] [--rounds R]\n", argv[0]);
      std::exit(2);
    }
  }
  return o;
}

double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void printRow(long n, const char* command, std::size_t particles, double porosity,
              double seconds, const std::string& note)
{
  std::printf("%10ld  %-14s %10zu  %8.4f  %8.2f  %s\n", n, command, particles, porosity, seconds,
              note.c_str());
  std::fflush(stdout);
}

} // namespace

int main(int argc, char** argv)
{
  const Options options = parse(argc, argv);

  dem::PackParameters params;
  params.minimumSize = 0.001;   // m
  params.maximumSize = 0.002;   // m
  params.targetPorosity = 0.35;
  params.randomSeed = 12345;
  // Mean sphere volume for r uniform in [a, b]: 4/3 pi (a + b)(a^2 + b^2) / 4.
  const double a = params.minimumSize;
  const double b = params.maximumSize;
  const double meanVolume = 4.0 / 3.0 * kPi * (a + b) * (a * a + b * b) / 4.0; // m^3
  const double placementPorosity = 0.70;

  std::printf("RockDEM pack benchmark: radii %g-%g m (2:1), box for porosity %.2f at placement\n",
              a, b, placementPorosity);
  std::printf("%10s  %-14s %10s  %8s  %8s  %s\n", "N", "command", "particles", "porosity",
              "time(s)", "note");

  for (long n : options.sizes) {
    dem::Model model;
    const double edge = std::cbrt(static_cast<double>(n) * meanVolume / (1.0 - placementPorosity));
    model.domain.size = dem::Vec3(edge, edge, edge);
    params.initialElements = n;

    auto start = std::chrono::steady_clock::now();
    const dem::PackReport build = dem::buildPack(model, params);
    printRow(n, "place", model.particles.size(), build.porosity, secondsSince(start),
             std::to_string(build.attempts) + " attempts" +
               (build.saturated ? ", saturated" : ""));
    if (options.quick) {
      continue;
    }
    const auto densifyStart = std::chrono::steady_clock::now();
    for (int round = 0; round < options.rounds; ++round) {
      start = std::chrono::steady_clock::now();
      const dem::PackReport add = dem::addElements(model, params);
      printRow(n, "Add Elements", model.particles.size(), add.porosity, secondsSince(start),
               "+" + std::to_string(add.placed) + " in " + std::to_string(add.attempts) +
                 " attempts" + (add.targetReached ? ", target reached" : ", saturated"));
      if (add.targetReached) {
        break;
      }
      start = std::chrono::steady_clock::now();
      const dem::GrowReport grow = dem::growElements(model);
      char note[96];
      std::snprintf(note, sizeof(note), "grew %zu, mean gain %.3g mm", grow.grown,
                    grow.meanRadiusGain * 1e3);
      printRow(n, "Grow Elements", model.particles.size(), grow.porosityAfter,
               secondsSince(start), note);
    }
    const double porosity = dem::currentPorosity(model);
    printRow(n, "Add+Grow total", model.particles.size(), porosity, secondsSince(densifyStart),
             porosity <= 0.45 ? "porosity <= 0.45 reached" : "porosity 0.45 NOT reached");
  }
  return 0;
}
