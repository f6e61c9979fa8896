// RockDEM engine: parallel bonds (Potyondy & Cundall 2004; PHYSICS.md section 3).
//
// A bond joins two particles with a cement of circular section (3D: radius
// Rb = multiplier x min(rA, rB); 2D: a rectangle 2 Rb x slab thickness) that acts in
// parallel with their contact. It carries a normal force, a shear force, a twisting
// moment (3D only) and a bending moment, updated incrementally from the relative motion
// and rotated with the contact plane. It breaks for good when its peripheral stress
// reaches its strength. SI units: m, N, N m, Pa.
//
// Rule for a bonded pair: the total interaction is the contact force (Hertz or linear,
// compression only, while the particles overlap) PLUS the bond force (tension and
// compression, while the bond is intact). In compression the two springs act in
// parallel and their stiffnesses add; in tension only the bond acts.
#pragma once

#include "dem/BondLawLanes.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace dem {

using Vec3 = Eigen::Vector3d;

/// How a bond failed.
enum class BondFailure : std::uint8_t {
  Intact = 0,
  Tension = 1,   ///< peripheral tensile stress reached the tensile strength
  Shear = 2,     ///< peripheral shear stress reached the Mohr-Coulomb strength
  Inherited = 3, ///< broken before the run (seeded from a fracture network)
};

/// All bonds of a model, structure of arrays, sorted by (idA, idB) with idA < idB.
struct Bonds {
  // Identity and geometry.
  std::vector<std::int64_t> idA;      ///< global id of particle A
  std::vector<std::int64_t> idB;      ///< global id of particle B (idA < idB)
  std::vector<double> radius;         ///< m, bond radius Rb
  // Stiffness per unit area (Pa/m = N/m^3).
  std::vector<double> normalStiffness; ///< kn_bar
  std::vector<double> shearStiffness;  ///< ks_bar
  // Strengths drawn at cementing.
  std::vector<double> tensileStrength; ///< Pa, sigma_c
  std::vector<double> cohesion;        ///< Pa, c
  std::vector<double> frictionAngle;   ///< rad, phi
  /// Moment contribution factor beta in [0, 1]: the share of the bond's moments in its
  /// peripheral stresses (PFC's moment-contribution factor; 1 = Potyondy & Cundall 2004).
  std::vector<double> momentContribution;
  /// Softening Ratio r >= 0 (tension softening, dem::softenedBondFailure): after its
  /// tensile strength the bond's stress falls linearly to zero over r times the stretch
  /// that reached the strength; 0 = brittle (Potyondy & Cundall 2004).
  std::vector<double> softening;
  // State (forces and moments on particle A; B gets the opposite).
  std::vector<double> normalForce;     ///< N, positive in tension
  std::vector<Vec3> shearForce;        ///< N, in the bond plane
  std::vector<double> twistingMoment;  ///< N m, about the bond axis (0 in 2D)
  std::vector<Vec3> bendingMoment;     ///< N m, in the bond plane
  /// Tension-softening damage D in [0, 1) of an intact bond (0 unless softening > 0): the
  /// forces and moments above are the undamaged (elastic) ones, the bond applies (1 - D)
  /// times them. D only grows; a broken bond keeps its last value.
  std::vector<double> damage;
  // Failure record.
  std::vector<std::uint8_t> failure;   ///< BondFailure
  std::vector<double> failureTime;     ///< s (model time), when broken
  std::vector<Vec3> failurePosition;   ///< m, contact point when broken
  std::vector<Vec3> failureNormal;     ///< unit bond axis (A to B) when broken

  std::size_t size() const { return idA.size(); }
  bool broken(std::size_t b) const { return failure[b] != static_cast<std::uint8_t>(BondFailure::Intact); }
  void clear();
  /// Appends an intact, undamaged bond with zero force; strengths, stiffness, moment
  /// contribution and softening ratio as given.
  void append(std::int64_t a, std::int64_t b, double bondRadius, double kn, double ks,
              double sigmaC, double c, double phi, double beta = 1.0, double softeningRatio = 0.0);
  /// The share of its elastic forces and moments that bond k applies: 1 - damage.
  double intactShare(std::size_t k) const { return 1.0 - damage[k]; }
  /// Breaks bond k for good: records how, when (s), where (m, the contact point on the
  /// line of centres) and its orientation (unit normal from A to B), and zeroes its force
  /// and moments.
  void markBroken(std::size_t k, BondFailure how, double time, const Vec3& position, const Vec3& normal);
};

/// What stepping changes in a Bonds: the forces, moments and damage and the failure record
/// (the arrays the Vulkan backend moves each way as its dynamic state). Identities,
/// geometry, stiffnesses and strengths do not change while a model steps, so a rollback
/// (Simulation::advance's last good state) keeps and restores this part only.
struct BondStepState {
  std::vector<double> normalForce;
  std::vector<Vec3> shearForce;
  std::vector<double> twistingMoment;
  std::vector<Vec3> bendingMoment;
  std::vector<double> damage;
  std::vector<std::uint8_t> failure;
  std::vector<double> failureTime;
  std::vector<Vec3> failurePosition;
  std::vector<Vec3> failureNormal;
  /// Copies bonds' step state here (into the buffers already held: no allocation when the
  /// count is unchanged).
  void save(const Bonds& bonds);
  /// Puts the saved state back into bonds, which must hold as many bonds as were saved.
  void restore(Bonds& bonds) const;
};

/// Bond counts for the read-only values.
struct BondCounts {
  std::size_t installed = 0;
  std::size_t broken = 0;
  std::size_t tension = 0;
  std::size_t shear = 0;
  std::size_t inherited = 0;
  double damage() const { return installed ? static_cast<double>(broken) / installed : 0.0; }
};
BondCounts countBonds(const Bonds& bonds);

/// Section properties of a bond (PHYSICS.md s.3): 3D A = pi Rb^2, I = pi Rb^4 / 4,
/// J = pi Rb^4 / 2; 2D (slab t) A = 2 Rb t, I = 2/3 t Rb^3, J = 0 (no twisting). Fields
/// area (m^2), inertia (m^4, bending), polar (m^4, twisting); dem/BondLawLanes.h.
using BondSection = BondSectionLanes<double>;
BondSection bondSection(double bondRadius, bool section2D, double slab);

/// Peripheral stresses of a bond state (PHYSICS.md s.3), Pa:
/// sigma_max = Fn/A + beta |Mb| Rb / I (tension positive), tau_max = |Fs|/A + beta |Mt| Rb / J
/// (3D), with beta the moment contribution factor (1: the full moments, Potyondy & Cundall
/// 2004; 0: the moments are carried but never break the bond).
using BondStresses = BondStressesLanes<double>; // sigmaMax, tauMax, compressive (Pa)
BondStresses bondStresses(const BondSection& s, double bondRadius, double normalForce,
                          const Vec3& shearForce, double twistingMoment, const Vec3& bendingMoment,
                          double momentContribution = 1.0);

/// The failure a stress state causes (Intact if none): tension if sigma_max >= sigma_c,
/// else shear if tau_max >= c + sigma tan(phi).
BondFailure bondFailure(const BondStresses& stresses, double tensileStrength, double cohesion,
                        double frictionAngle);

/// Largest Softening Ratio (the softening stretch is at most this many times the elastic
/// stretch at the strength).
constexpr double kMaxSofteningRatio = 100.0;

/// Tension-softening damage after an elastic peripheral stress of `stressRatio` times the
/// tensile strength, for Softening Ratio r > 0: 0 up to 1, then the damage D with
/// (1 - D) x = 1 - (x - 1) / r, so that the applied peripheral stress falls linearly from
/// the strength at x = 1 to zero at x = 1 + r (where D reaches 1).
double softeningDamage(double stressRatio, double softeningRatio);

/// The bond law's failure rule with tension softening. `elastic`: the peripheral stresses
/// of the undamaged forces and moments. Softening Ratio 0: exactly dem::bondFailure
/// (`damage` untouched). r > 0: tension failure when sigma_max >= (1 + r) sigma_c;
/// below it `damage` becomes max(damage, softeningDamage(sigma_max / sigma_c, r)); shear
/// failure as in dem::bondFailure on the undamaged stresses (the damaged bond's shear
/// stress and its shear strength both scale with 1 - D).
BondFailure softenedBondFailure(const BondStresses& elastic, double tensileStrength, double cohesion,
                                double frictionAngle, double softeningRatio, double& damage);

/// dem::softenedBondFailure with tan(phi) given (`tanFriction` = std::tan(frictionAngle)):
/// the same result, for a caller that computes the tangent once for many bonds (the CPU
/// backend: the tangent was about 6 % of a cemented specimen's step).
BondFailure softenedBondFailureWithTan(const BondStresses& elastic, double tensileStrength, double cohesion,
                                       double tanFriction, double softeningRatio, double& damage);

} // namespace dem
