// RockDEM engine: the model, as plain data.
//
// A dem::Model holds everything needed to continue a run bit for bit. Algorithms are
// free functions over a Model; there is no hidden global state. SI units throughout:
// metres, kilograms, seconds, newtons, pascals, radians.
//
// Particles are stored as a structure of arrays: one std::vector per quantity, indexed
// by particle slot. A particle's slot may change (e.g. after removal); its `id` is the
// stable global identity.
#pragma once

#include "dem/Bonds.h"
#include "dem/LoadTest.h"
#include "dem/Random.h"
#include "dem/RemovedParticles.h"
#include "dem/SolverState.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dem {

using Vec3 = Eigen::Vector3d;

/// The model box.
struct Domain {
  Vec3 origin{ 0.0, 0.0, 0.0 };        ///< m, minimum corner
  Vec3 size{ 0.1, 0.1, 0.1 };          ///< m, edge lengths; in 2D, size.z() is the slab thickness
  std::array<bool, 3> periodic{ { false, false, false } }; ///< join the two faces of an axis
  bool section2D = false;              ///< discs in the XY plane at mid-slab (z = origin.z + size.z/2)
  /// The specimen's outline in the box: -1, the box itself; 0, 1, 2 (X, Y, Z): a cylinder
  /// along that axis inscribed in the box, its cross-section the ellipse whose diameters
  /// are the box's two other edges (DEM Specimen's Cylinder and Disc set it; a 2D disc is
  /// a cylinder along Z). The press measures areas and volumes with it (crossSectionArea).
  int cylinderAxis = -1;

  Vec3 upper() const { return origin + size; }
  double slabThickness() const { return size.z(); }
  double midPlaneZ() const { return origin.z() + 0.5 * size.z(); }
  /// Number of spatial dimensions in which particles live and move (2 or 3).
  int dimension() const { return section2D ? 2 : 3; }
};

/// Material of the particles (applies whether or not the model is cemented).
struct Material {
  double density = 2650.0;        ///< kg/m^3
  double youngsModulus = 1.0e9;   ///< Pa
  double poissonsRatio = 0.25;    ///< dimensionless, [0, 0.5)
  double restitution = 0.5;       ///< dimensionless, [0, 1]
  double friction = 0.5;          ///< Coulomb coefficient, dimensionless, >= 0
  double rollingFriction = 0.0;   ///< rolling resistance coefficient, dimensionless, >= 0 (0 = free rolling)
};

/// Per-particle flag bits (Particles::flags).
enum ParticleFlag : std::uint32_t {
  FlagFixed = 1u << 0,    ///< kinematic: forces do not move it; it keeps its given velocity (at rest by default)
  FlagFineZone = 1u << 1, ///< radius was drawn from the fine-zone range
  FlagAttachedLow = 1u << 2,  ///< tension test: attached to the low platen (kinematic)
  FlagAttachedHigh = 1u << 3, ///< tension test: attached to the high platen (kinematic)
};

/// Particle state, structure of arrays. All vectors have the same length.
struct Particles {
  std::vector<Vec3> position;         ///< m
  std::vector<Vec3> velocity;         ///< m/s
  std::vector<Vec3> angularVelocity;  ///< rad/s
  std::vector<Vec3> displacement;     ///< m, accumulated since the pack was built
  std::vector<Vec3> force;            ///< N, resultant of the last step, after damping (zero before stepping)
  std::vector<Vec3> torque;           ///< N m, resultant torque of the last step, after damping
  std::vector<double> radius;         ///< m
  std::vector<double> mass;           ///< kg (sphere: rho 4/3 pi r^3; 2D disc: rho pi r^2 t)
  std::vector<double> inertia;        ///< kg m^2 (sphere: 2/5 m r^2; disc about z: 1/2 m r^2)
  std::vector<std::int64_t> id;       ///< stable global id
  std::vector<std::uint32_t> flags;   ///< ParticleFlag bits

  std::size_t size() const { return radius.size(); }
  bool empty() const { return radius.empty(); }
  void clear();
  void reserve(std::size_t n);
  /// Appends a particle at rest; mass and inertia are set by updateMassProperties().
  void append(const Vec3& x, double r, std::int64_t globalId, std::uint32_t flagBits = 0);
  /// Bytes of storage per particle in this structure.
  static constexpr std::size_t bytesPerParticle()
  {
    return 6 * sizeof(Vec3) + 3 * sizeof(double) + sizeof(std::int64_t) + sizeof(std::uint32_t);
  }
};

/// Model clock.
struct Clock {
  double time = 0.0;       ///< s, model time
  std::int64_t step = 0;   ///< physics steps taken
  double timestep = 0.0;   ///< s, the step the solver uses (0 until it is chosen)
};

/// Everything needed to continue a run bit for bit (a later issue adds the load-test
/// state machine).
struct Model {
  Domain domain;
  Material material;
  Vec3 gravity{ 0.0, 0.0, -9.81 };  ///< m/s^2 (2D sections point it along -Y)
  Particles particles;
  SolverSettings solver;            ///< time-stepping parameters
  std::vector<Wall> walls;          ///< the box walls (empty until the solver first runs)
  ContactHistory contacts;          ///< tangential and rolling history of live contacts
  Bonds bonds;                      ///< cement bonds, intact and broken
  LoadTestState test;               ///< the virtual press: mode, stage, history
  Clock clock;
  Random random{ 1 };               ///< the model's random stream (pack placement, strength draws)
  std::int64_t nextId = 0;          ///< next global id to hand out
};

/// Volume (m^3) of one particle of radius r (m): a sphere, 4/3 pi r^3, or in a 2D
/// section a disc through the slab, pi r^2 t (t = domain.slabThickness()).
double particleVolume(const Domain& domain, double radius);

/// Separation b - a (m) by the minimum image: across a periodic axis the nearest copy of
/// b; in a 2D section z is 0. Valid while the separation is below half the box on every
/// periodic axis.
inline Vec3 minimumImage(const Domain& domain, const Vec3& a, const Vec3& b)
{
  Vec3 s = b - a;
  for (int k = 0; k < 3; ++k) {
    if (domain.periodic[k]) {
      s[k] -= domain.size[k] * std::nearbyint(s[k] / domain.size[k]);
    }
  }
  if (domain.section2D) {
    s.z() = 0.0;
  }
  return s;
}

/// Removes the particles with remove[slot] != 0 (remove has one entry per particle), with
/// their contact history and every bond that joins them; the others keep their order.
RemovedParticles removeParticles(Model& model, const std::vector<std::uint8_t>& remove);

/// The particle slots in a space-filling order: the cells of a grid whose edge is the
/// largest diameter, visited along a Morton (Z-order) curve, slots within a cell in their
/// present order. Neighbours in space then sit near each other in memory. Deterministic.
std::vector<std::size_t> spatialOrder(const Model& model);

/// Reorders every per-particle array: slot s receives the particle of slot order[s]
/// (order is a permutation of the slots). Ids move with their particles; contact history
/// and bonds are keyed by id and stay valid.
void permuteParticles(Particles& particles, const std::vector<std::size_t>& order);

/// Sets mass and inertia of every particle from its radius, the density and 2D/3D.
void updateMassProperties(Model& model);

/// The grains' extent along `axis` (0 X, 1 Y, 2 Z): {lowest centre - radius, highest centre +
/// radius} (m). {+inf, -inf} without grains.
std::array<double, 2> grainExtent(const Particles& particles, int axis);

/// Throws InputError for an invalid domain (non-positive dimensions, non-finite origin,
/// Periodic Z with 2D Section).
void validate(const Domain& domain);
/// Throws InputError for invalid material properties.
void validate(const Material& material);
/// Throws InputError for a particle whose position is not finite or whose radius is not
/// positive and finite (the message names the particle by its id).
void validate(const Particles& particles);

/// The read-only Contact Stiffness (N/m): the normal stiffness of a linear contact
/// between two particles of radius r, kn = A E / L with A = pi r^2 (3D) or 2 r t (2D)
/// and L = 2 r (PHYSICS.md section 3). Reported for the largest particle size.
double derivedContactStiffness(const Material& material, const Domain& domain, double radius);

/// Available physical memory in bytes (MemAvailable on Linux; total physical memory
/// otherwise), used to refuse particle counts that cannot fit.
std::size_t availableMemoryBytes();

} // namespace dem
