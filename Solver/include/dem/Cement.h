// RockDEM engine: cementing a pack into rock (reference guide "Cementing the model").
#pragma once

#include "dem/Model.h"

#include <cstdint>
#include <string>

namespace dem {

/// Cement parameters (PHYSICS.md section 3). SI units.
struct CementParameters {
  double gapTolerance = 0.05;        ///< bond pairs whose surface gap <= this x the smaller radius, [0, kMaxGapTolerance]
  double bondRange = 1.0;            ///< also bond pairs whose centre distance <= this x (rA + rB), [1, kMaxBondRange]
  double bondRadiusMultiplier = 1.0; ///< Rb = multiplier x min(rA, rB), (0, 1]
  double bondModulus = 1.0e9;        ///< Pa, E_bar: kn_bar = E_bar / (rA + rB)
  double bondStiffnessRatio = 0.4;   ///< ks_bar / kn_bar, > 0
  double bondNormalStiffness = 0.0;  ///< N/m^3, explicit kn_bar overriding the modulus; 0 = from modulus
  double tensileStrength = 10.0e6;   ///< Pa, mean sigma_c, > 0
  double cohesion = 20.0e6;          ///< Pa, mean c, > 0
  double frictionAngle = 30.0;       ///< degrees, phi in [0, 90)
  double momentContribution = 1.0;   ///< beta in [0, 1]: share of the moments in the peripheral stresses
  double softeningRatio = 0.0;       ///< tension softening, [0, kMaxSofteningRatio]: softening stretch / stretch at the strength; 0 = brittle
  double strengthScatter = 0.0;      ///< coefficient of variation of the strengths, [0, 1]
  std::uint64_t randomSeed = 1;      ///< seed of the strength draw
};

/// Upper bounds of the bond selection. Gap Tolerance 1 bonds across a gap of one smaller
/// radius; Bond Range 2 reaches centre distances of twice the touching distance, past the
/// first shell of neighbours (interaction ranges in use are 1.2-1.5, Scholtes & Donze
/// 2013). Larger values would bond a grain to most of the grains around it.
constexpr double kMaxGapTolerance = 1.0;
constexpr double kMaxBondRange = 2.0;

/// Throws InputError naming the parameter for an invalid value.
void validate(const CementParameters& params);

/// What Cement did.
struct CementReport {
  std::size_t bonds = 0;           ///< bonds installed
  std::size_t replaced = 0;        ///< bonds of the previous set discarded (re-cementing heals)
  std::size_t particles = 0;       ///< particles in the model
  std::size_t longBonds = 0;       ///< bonds between particles that did not touch (gap > 0)
  double bondedCoordination = 0.0; ///< 2 x bonds / particles
  double bondStiffness = 0.0;      ///< N/m^3, kn_bar for two particles of the largest radius
  std::string summary() const;
};

/// Installs a bond between every pair touching or nearly so (gap <= gapTolerance x the
/// smaller radius) or within the interaction range (centre distance <= bondRange x (rA +
/// rB), applied when bondRange > 1; Scholtes & Donze 2013), periodic seams included,
/// replacing any existing bond set. A bond is installed unstressed: its forces and moments
/// start at zero and grow with the relative motion from here (its rest length is the
/// centre distance at cementing). Every bond, long or touching, gets the section radius
/// Rb = bondRadiusMultiplier x min(rA, rB) and the stiffness per unit area
/// kn = bondModulus / (rA + rB) of a touching pair of the same radii (not of its length). Each bond
/// draws its tensile strength and cohesion from a lognormal distribution with the
/// requested mean and coefficient of variation (identical when the scatter is 0) from a
/// random stream keyed by (randomSeed, idA, idB): the draw is reproducible and does not
/// depend on bond order or thread count.
CementReport cement(Model& model, const CementParameters& params);

/// Bonded Coordination: 2 x installed bonds / particles (0 without particles).
double bondedCoordination(std::size_t bonds, std::size_t particles);

/// The random strength factor (mean 1, coefficient of variation `cov`) of the bond
/// between ids a < b for a seed; `which` selects independent draws (0 tension, 1 cohesion).
double strengthFactor(std::uint64_t seed, std::int64_t a, std::int64_t b, int which, double cov);

} // namespace dem
