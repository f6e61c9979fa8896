// Compaction benchmark: Compact Elements (radius expansion with relaxation) on a random
// pack of N particles with a 2:1 radius range (1-2 mm) in a cubic box (3D) or a square
// section (2D discs, slab 2 mm), starting from the placed pack (porosity about 0.70 in 3D,
// 0.45 in 2D). Prints the porosity reached, the locked-in stress, the largest overlap and
// the wall-clock time of each command. Material: E 1e8 Pa, nu 0.25, 2650 kg/m^3.
//
//   rockdem_bench_compact [--sizes 10000,100000] [--2d] [--target 0.36] [--threads 2]
//                         [--ceiling Pa] [--equilibrium-ratio r] [--periodic] [--quick]
#include "CommaList.h"
#include "dem/Pack.h"
#include "dem/SphereBoxVolume.h"

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
  std::vector<long> sizes{ 10000, 100000 };
  bool planar = false;
  double target = -1.0; // default: 0.36 in 3D, 0.16 in 2D
  double ceiling = 0.0;
  double equilibriumRatio = 0.01;
  int threads = 0;
  bool quick = false;
  bool periodic = false;
};

Options parse(int argc, char** argv)
{
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--sizes" && i + 1 < argc) {
      o.sizes = rockdem_bench::parseList<long>(argv[++i]);
    } else if (a == "--2d") {
      o.planar = true;
    } else if (a == "--target" && i + 1 < argc) {
      o.target = std::atof(argv[++i]);
    } else if (a == "--ceiling" && i + 1 < argc) {
      o.ceiling = std::atof(argv[++i]);
    } else if (a == "--equilibrium-ratio" && i + 1 < argc) {
      o.equilibriumRatio = std::atof(argv[++i]);
    } else if (a == "--threads" && i + 1 < argc) {
      o.threads = std::atoi(argv[++i]);
    } else if (a == "--periodic") {
      o.periodic = true;
    } else if (a == "--quick") {
      o.quick = true;
    } else {
      std::fprintf(stderr, "usage: %s [--sizes N1,N2] [--2d] [--target n] [--ceiling Pa] [--equilibrium-ratio r] [--periodic] [--threads T] [--quick]\n", argv[0]);
      std::exit(2);
    }
  }
  if (o.target < 0.0) {
    o.target = o.planar ? 0.16 : 0.36;
  }
  return o;
}

double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

int main(int argc, char** argv)
{
  const Options options = parse(argc, argv);
  dem::PackParameters params;
  params.minimumSize = 0.001; // m
  params.maximumSize = 0.002; // m
  params.randomSeed = 12345;
  const double a = params.minimumSize;
  const double b = params.maximumSize;
  const double slab = 0.002; // m, 2D slab thickness
  // Mean particle volume (3D: 4/3 pi E[r^3]; 2D: pi t E[r^2]) for r uniform in [a, b].
  const double meanVolume = options.planar ? kPi * slab * (a * a + a * b + b * b) / 3.0
                                           : 4.0 / 3.0 * kPi * (a + b) * (a * a + b * b) / 4.0;
  const double placement = options.planar ? 0.45 : 0.70;

  std::printf("RockDEM compaction benchmark: %s, radii %g-%g m (2:1), Target Porosity %.3f, threads %s\n",
              options.planar ? "2D discs" : "3D spheres", a, b, options.target,
              options.threads > 0 ? std::to_string(options.threads).c_str() : "all");
  std::printf("%9s %9s %9s %9s %12s %10s %8s %8s %9s  %s\n", "N", "placed", "porosity0", "porosity",
              "stress(Pa)", "overlap(%)", "stages", "steps", "time(s)", "result");
  for (long n : options.sizes) {
    dem::Model model;
    model.material.youngsModulus = 1e8;
    model.material.poissonsRatio = 0.25;
    model.material.density = 2650.0;
    model.domain.section2D = options.planar;
    model.solver.threads = options.threads;
    model.solver.parallelThreshold = 0; // compaction: results do not depend on threads
    if (options.planar) {
      const double edge = std::sqrt(static_cast<double>(n) * meanVolume / ((1.0 - placement) * slab));
      model.domain.size = dem::Vec3(edge, edge, slab);
      model.gravity = dem::Vec3(0.0, -9.81, 0.0);
    } else {
      const double edge = std::cbrt(static_cast<double>(n) * meanVolume / (1.0 - placement));
      model.domain.size = dem::Vec3(edge, edge, edge);
    }
    if (options.periodic) {
      model.domain.periodic = { { true, true, !options.planar } };
      model.gravity.setZero();
    }
    params.initialElements = n;
    params.targetPorosity = options.target;
    auto start = std::chrono::steady_clock::now();
    const dem::PackReport built = dem::buildPack(model, params);
    const double placeSeconds = secondsSince(start);
    if (options.quick) {
      std::printf("%9ld %9zu %9.4f  (placed in %.2f s; --quick: no compaction)\n", n,
                  model.particles.size(), built.porosity, placeSeconds);
      continue;
    }
    dem::CompactParameters c;
    c.targetPorosity = options.target;
    c.stressCeiling = options.ceiling;
    c.equilibriumRatio = options.equilibriumRatio;
    start = std::chrono::steady_clock::now();
    const dem::CompactReport r = dem::compactElements(model, c);
    const double seconds = secondsSince(start);
    std::printf("%9ld %9zu %9.4f %9.4f %12.4g %10.3f %8zu %8lld %9.2f  %s\n", n, r.particles,
                r.porosityBefore, r.porosity, r.lockedInStress, 100.0 * r.largestOverlap, r.stages,
                static_cast<long long>(r.steps), seconds,
                r.targetReached ? "target reached" : (r.jammed ? "jammed at the ceiling" : "not reached"));
    {
      const auto& P = model.particles;
      const auto& D = model.domain;
      for (double k : {1.0, 2.0, 4.0}) {
        const double m = k * 2.0 * params.maximumSize;
        dem::Vec3 lo = D.origin, hi = D.upper();
        for (int a = 0; a < (options.planar ? 2 : 3); ++a) { lo[a] += m; hi[a] -= m; }
        double solid = 0.0;
        for (std::size_t i = 0; i < P.size(); ++i) {
          solid += options.planar ? dem::discRectangleArea(P.position[i].x(), P.position[i].y(), P.radius[i], lo.x(), lo.y(), hi.x(), hi.y())
                                  : dem::sphereBoxVolume(P.position[i], P.radius[i], lo, hi);
        }
        const double vol = options.planar ? (hi.x() - lo.x()) * (hi.y() - lo.y()) : (hi - lo).prod();
        std::printf("   interior (walls minus %.0f largest diameters): porosity %.4f\n", k, 1.0 - solid / vol);
      }
    }
    std::fflush(stdout);
  }
  return 0;
}
