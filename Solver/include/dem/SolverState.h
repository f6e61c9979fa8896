// RockDEM engine: the parts of a Model that the time-stepping solver owns: its
// settings, the walls and the contact history. SI units.
#pragma once

#include "dem/ContactLawKind.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dem {

using Vec3 = Eigen::Vector3d;

/// Solver parameters (DESIGN.md "Solver step", PHYSICS.md sections 1-2).
struct SolverSettings {
  ContactLaw contactLaw = ContactLaw::HertzMindlin;
  double timestepSafety = 0.1;    ///< fraction of the critical timestep used, (0, 1]
  double requestedTimestep = 0.0; ///< s; 0 = automatic; a larger-than-safe request is overridden
  double settlingDamping = 0.7;   ///< Cundall local damping alpha, [0, 1); 0 for real dynamics
  double skin = 0.2;              ///< Verlet skin as a fraction of the smallest radius, > 0
  int threads = 0;                ///< 0 = all cores; results never depend on it
  /// Work per step below which the step runs serially, in particle-equivalents: particles
  /// + 5 x neighbour pairs + 6 x bonds, counted at every neighbour-list build (a loose
  /// pack of N particles is about 3 N, a dense one about 15 N, a cemented one about 32 N).
  /// 0: always on threads. Set from the measured crossover of one and two threads on a
  /// 2-core machine (Documentation/Benchmarks-Solver.md section 1, "Serial or parallel").
  std::int64_t parallelThreshold = 8000;
  /// Test-only: use requestedTimestep even above the critical timestep (to show that an
  /// unstable run is detected). Never exposed in the GUI.
  bool allowUnsafeTimestep = false;
};

/// A planar wall of the model box. Walls sit on the faces of the box: the low and high
/// face of each non-periodic axis (no Z walls in a 2D section).
struct Wall {
  int axis = 0;            ///< 0, 1, 2 = X, Y, Z
  int side = 0;            ///< 0: low face (normal +axis), 1: high face (normal -axis)
  double position = 0.0;   ///< m, coordinate of the face along its axis
  double velocity = 0.0;   ///< m/s, along the axis
  bool active = true;      ///< enforced
  Vec3 force{ 0.0, 0.0, 0.0 }; ///< N, reaction: total force the particles exert on the wall
  double contactStiffness = 0.0; ///< N/m, sum of the normal stiffness of its contacts (servo gain)
  double elasticForce = 0.0;     ///< N, elastic part of the particles' normal push (what the servo controls)
  std::int64_t contacts = 0;     ///< number of particles touching it

  /// Unit normal pointing into the box.
  Vec3 normal() const
  {
    Vec3 n = Vec3::Zero();
    n[axis] = side == 0 ? 1.0 : -1.0;
    return n;
  }
};

/// Whether a centre lies beyond an active wall: outside the walls on an axis that has them
/// (walls stored as X-, X+, Y-, Y+, Z-, Z+; none yet: false). Such a particle has escaped.
inline bool beyondActiveWalls(const std::vector<Wall>& walls, const Vec3& x)
{
  for (std::size_t k = 0; k < 3 && walls.size() == 6; ++k) {
    const Wall& low = walls[2 * k];
    if (low.active && (x[static_cast<int>(k)] < low.position || x[static_cast<int>(k)] > walls[2 * k + 1].position)) {
      return true;
    }
  }
  return false;
}

/// Identifier of wall w as a contact partner: -(w + 1).
inline std::int64_t wallPartnerId(int wallIndex) { return -static_cast<std::int64_t>(wallIndex) - 1; }

/// History of the contacts that carry it (tangential and rolling springs), keyed by the
/// global ids of the two partners (idB < 0: a wall, see wallPartnerId). Sorted by
/// (idA, idB) with idA < idB for particle pairs. Structure of arrays.
struct ContactHistory {
  std::vector<std::int64_t> idA;
  std::vector<std::int64_t> idB;
  std::vector<Vec3> shearSpring;   ///< m, tangential spring displacement
  std::vector<Vec3> rollingSpring; ///< N m, rolling spring torque; empty unless rolling friction is on

  std::size_t size() const { return idA.size(); }
  void clear()
  {
    idA.clear();
    idB.clear();
    shearSpring.clear();
    rollingSpring.clear();
  }
};

} // namespace dem
