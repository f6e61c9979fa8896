// RockDEM engine: the stress carried by each particle (Love-Weber average over its
// volume; PHYSICS.md section 4; Documentation/Sections.md).
//
// A particle p with volume V_p carries the stress
//
//   sigma_p = -(1 / V_p) sum over its interactions c of sym(a_c (x) f_c),
//
// a_c the arm from its centre to the contact point, f_c the force on it (contacts with
// other particles and walls, and intact bonds). The sign makes compression positive, the
// engine's convention (the press's Love-Weber tensor, dem/LoadTest.h). Because the two
// arms of a pair differ by exactly the branch vector, the volume-weighted sum of the
// particle stresses is the specimen's Love-Weber tensor:
//
//   sum_p V_p sigma_p = V sigma_specimen   (Simulation::measurements, V the specimen volume).
//
// Stress of a model (no live Simulation): the forces are evaluated from the model state
// alone (positions, velocities, contact history, bond state), the way a Simulation
// built on the model evaluates them. A model and its saved-and-reloaded copy are equal
// bit for bit, so their particle stresses are too. SI units: Pa, m, N.
#pragma once

#include "dem/Model.h"

#include <array>
#include <cstdint>
#include <vector>

namespace dem {

/// Symmetric stress tensor, Pa, compression positive: xx, yy, zz, xy, yz, xz (the
/// component order ParaView reads for a 6-component tensor array).
using StressTensor = std::array<double, 6>;

/// Partner of a wall contact in InteractionForces::slotB.
constexpr std::uint32_t WallPartner = 0xffffffffu;

/// Every force between particles (and between a particle and a wall) in a state of the
/// model: touching contacts, intact bonds, touching wall contacts. Structure of arrays.
struct InteractionForces {
  std::vector<std::uint32_t> slotA;  ///< particle slot
  std::vector<std::uint32_t> slotB;  ///< particle slot, or WallPartner
  std::vector<Vec3> force;           ///< N, on A (B gets the opposite)
  std::vector<Vec3> armA;            ///< m, from the centre of A to the contact point
  std::vector<Vec3> armB;            ///< m, from the centre of B to the contact point (unused for a wall)

  std::size_t size() const { return slotA.size(); }
  void clear();
  void append(std::uint32_t a, std::uint32_t b, const Vec3& f, const Vec3& arm_a, const Vec3& arm_b);
};

/// The stress of each particle (slot order) from the given interaction forces.
std::vector<StressTensor> particleStresses(const Model& model, const InteractionForces& forces);

/// The stress of each particle of a model state: the interaction forces are evaluated by a
/// Simulation built on a copy of the model (the model itself is not changed). Throws
/// InputError when the model cannot be simulated (invalid material, a bond to a missing
/// particle, ...).
std::vector<StressTensor> particleStresses(const Model& model);

/// Mean stress (Pa): trace / 3; in a 2D section the in-plane mean (xx + yy) / 2, as the
/// press reports it.
double meanStress(const StressTensor& s, bool section2D);

/// Von Mises equivalent stress (Pa), sqrt(3 J2): for a triaxial state (s2 = s3) it is
/// the deviator stress s1 - s3. In a 2D section the in-plane deviator s1 - s2 =
/// 2 sqrt(((xx - yy) / 2)^2 + xy^2).
double vonMisesStress(const StressTensor& s, bool section2D);

} // namespace dem
