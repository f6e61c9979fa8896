// RockDEM engine: building the particle pack.
//
// Random sequential placement of non-overlapping spheres (or discs in a 2D section)
// in the model box, with rejection; Add Elements (insert until a target porosity or
// saturation) and Grow Elements (expand each particle into the gap to its nearest
// neighbour or wall, never creating overlap). Overlap search uses one grid per size
// class (SizeClassGrids.h). SI units: metres.
//
// Placement, in detail. A particle to place first gets a zone: with a fine zone enabled,
// the fine zone with probability proportional to the number of particles it would hold at
// equal porosity (zone volume / mean particle volume of its radius range), else the rest
// of the box; then a radius, uniform in that zone's range. A try draws a centre uniformly
// where a particle of that radius fits: [origin + r, upper - r] on a walled axis (clipped
// to the fine zone for fine particles), [origin, upper) on a periodic one; a main-zone
// centre that falls inside the fine zone is rejected, so every particle centred in the
// fine zone has a fine radius. In a 2D section z = domain.midPlaneZ(). The try fails if
// the particle would overlap any other (touching is allowed).
//
// Build Pack draws all Initial Elements radii first and places them largest first, each
// keeping its radius through failed tries (only the centre is redrawn): the pack's radii
// are exactly the uniform draws asked for, and slot order runs from large to small.
// (Redrawing the radius after every failure would favour small particles, which fit more
// easily: at porosity 0.7 their mean volume would come out about 25% low.)
// Add Elements draws a fresh zone, radius and centre for every try, so that it fills
// whatever holes are left; as the pack fills, the particles it manages to add are
// therefore mostly the smaller ones of the range.
//
// Saturation: placement stops, with saturated = true, after kSaturationFailureRun
// consecutive failed tries (the chance that a try succeeds is then below about
// 1/kSaturationFailureRun), or when a command has used its attempt budget,
// kAttemptsPerParticle times the number of particles it expects to end with (at least
// kMinimumAttemptBudget). Build Pack also reports saturation when more particles are
// asked for than could fit in the box even without voids.
//
// Grow Elements, in detail. Slot by slot, each particle that is not fixed (FlagFixed)
// grows by the smallest of: the gap to the nearest particle surface (others' radii as
// already grown in this call), the gap to each wall on a walled moving axis (x, y in 2D;
// x, y, z in 3D), its own radius (so a radius at most doubles per call, which bounds the
// search reach), and on a periodic axis the room left below a quarter of the period
// (radii stay <= L/4, so the minimum image is exact). A gap is reduced by a relative
// 1e-12 of the coordinates' magnitude so that rounding can never turn "touching" into
// overlap. Repeated calls keep growing particles that still have room.
#pragma once

#include "dem/Model.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace dem {

/// An optional box inside the model where radii come from a finer range (graded pack).
struct FineZone {
  bool enabled = false;
  Vec3 origin{ 0.0, 0.0, 0.0 };  ///< m, minimum corner
  Vec3 size{ 0.0, 0.0, 0.0 };    ///< m
  double minimumSize = 0.0;      ///< m, radius
  double maximumSize = 0.0;      ///< m, radius
};

/// Pack-shaping parameters.
struct PackParameters {
  std::int64_t initialElements = 2000;  ///< particles placed when the pack is built
  double minimumSize = 0.002;           ///< m, minimum radius
  double maximumSize = 0.004;           ///< m, maximum radius (radii uniform in [min, max])
  double targetPorosity = 0.4;          ///< void fraction Add Elements aims for, (0, 1)
  std::uint64_t randomSeed = 1;         ///< seed of the model's random stream
  FineZone fineZone;
};

/// Saturation limits of random sequential placement (see the comment at the top).
constexpr std::size_t kSaturationFailureRun = 2000;
constexpr double kAttemptsPerParticle = 40.0;
constexpr std::size_t kMinimumAttemptBudget = 200000;

/// What a placement command did.
struct PackReport {
  std::string command = "Build Pack"; ///< "Build Pack" or "Add Elements", for summary()
  std::size_t requested = 0;       ///< Build Pack: Initial Elements asked for
  double targetPorosity = 0.0;     ///< Add Elements: the Target Porosity aimed for
  std::size_t placed = 0;          ///< particles inserted by this command
  std::size_t attempts = 0;        ///< candidate positions tried
  bool targetReached = false;      ///< porosity <= target after the command
  bool saturated = false;          ///< stopped because placement no longer succeeds
  double porosity = 1.0;           ///< Current Porosity after the command
  std::string summary() const;     ///< one line for the user
};

/// What Grow Elements did.
struct GrowReport {
  std::size_t particles = 0;       ///< particles in the model
  std::size_t grown = 0;           ///< particles whose radius increased
  double meanRadiusGain = 0.0;     ///< m, mean radius increase over all particles
  double porosityBefore = 1.0;
  double porosityAfter = 1.0;
  std::string summary() const;
};

/// Compact Elements: radius expansion with relaxation (Potyondy & Cundall 2004), the way
/// bonded-particle codes build dense material. Stage by stage, every particle that is not
/// fixed grows by the same factor (at most kMaxStageGrowth per stage, adaptively less as
/// the pack jams), and the solver cycles the pack frictionless, without gravity, in the
/// closed box, with local damping kCompactDamping, until it is in equilibrium: the
/// unbalanced force ratio below Equilibrium Ratio, or every overlap below a fifth of
/// kOverlapBar (a pack looser than jamming relaxes to no contact at all). Growth stops at
/// the Target Porosity (solid volume over the box volume) or when the relaxed mean
/// (Love-Weber) stress passes the ceiling; then the radius factor is bisected back to the
/// largest one whose relaxed stress stays within it. The pack that comes out is at rest,
/// never stepped, with the user's material, gravity and settings.
struct CompactParameters {
  double targetPorosity = 0.37;   ///< void fraction to reach, (0, 1)
  double stressCeiling = 0.0;     ///< Pa, Maximum Locked-In Stress, >= 0; 0 = kDefaultCeilingOverModulus x Young's Modulus
  double equilibriumRatio = 0.01; ///< unbalanced force ratio that counts as equilibrium, [1e-6, 0.5]
};
/// The default Maximum Locked-In Stress over Young's Modulus: a Hertz pack at this mean
/// stress keeps its largest overlaps near 0.3 % of the radius.
constexpr double kDefaultCeilingOverModulus = 2.0e-6;
/// Cundall local damping while compacting.
constexpr double kCompactDamping = 0.0;
/// The bar on overlaps left after compaction: 0.5 % of the smaller radius.
constexpr double kOverlapBar = 0.005;

/// What Compact Elements did.
struct CompactReport {
  std::size_t particles = 0;
  double targetPorosity = 0.0;
  double porosityBefore = 1.0;
  double porosity = 1.0;            ///< Current Porosity after compaction
  double lockedInStress = 0.0;      ///< Pa, relaxed mean stress (compression positive)
  double stressCeiling = 0.0;       ///< Pa, the ceiling used
  double largestOverlap = 0.0;      ///< largest overlap over the smaller radius (walls: over the radius)
  double unbalancedForceRatio = 0.0; ///< at the end of the last relaxation
  std::size_t stages = 0;           ///< growth (and bisection) stages
  std::int64_t steps = 0;           ///< solver steps in all
  bool targetReached = false;
  bool jammed = false;              ///< stopped by the stress ceiling before the target
  std::string summary() const;
};

/// Throws InputError naming the parameter for any invalid pack parameter, domain, or
/// combination (Minimum Size > Maximum Size, box that cannot hold one particle, a
/// particle count whose memory exceeds the machine's, a fine zone outside the box, ...).
void validate(const PackParameters& params, const Domain& domain);

/// Volume of the model's box (m^3; a 2D section: its area x the slab thickness).
double boxVolume(const Domain& domain);

/// Mean volume (m^3) of a placed particle, the radii uniform in [Minimum Size, Maximum
/// Size] (4/3 pi (a + b)(a^2 + b^2) / 4; a 2D section: pi t (a^2 + a b + b^2) / 3), over the
/// box and the fine zone with its own sizes, weighted as Add Elements draws candidates.
double meanPlacedVolume(const Domain& domain, const PackParameters& params);

/// Throws InputError ("<what> needs about X GiB of memory but the machine has Y GiB
/// available.") when this many particles would not fit in availableMemoryBytes() while a
/// stage steps them (dem::estimateMemory, the figure DEM Pack Source shows as Estimated
/// Memory; it is larger than what placement alone takes).
void requireMemoryForParticles(const std::string& what, double particles);

/// Clears the particles, reseeds the model's random stream from params.randomSeed and
/// places params.initialElements particles (stopping early, with saturated = true, if
/// placement saturates). Sets mass properties. Validates first.
PackReport buildPack(Model& model, const PackParameters& params);

/// Inserts particles until Current Porosity <= params.targetPorosity or placement
/// saturates. Continues the model's random stream.
PackReport addElements(Model& model, const PackParameters& params);

/// Expands each particle, in slot order, into the gap to its nearest neighbour surface
/// (or wall on a non-periodic axis). Never creates overlap.
GrowReport growElements(Model& model);

/// Throws InputError naming the parameter for an invalid compaction parameter.
void validate(const CompactParameters& params);
/// The Maximum Locked-In Stress used when the parameter is 0 (Pa).
double defaultStressCeiling(const Material& material);
/// Brings the pack to params.targetPorosity by radius expansion with relaxation (see
/// CompactParameters). Throws InputError for a cemented model.
CompactReport compactElements(Model& model, const CompactParameters& params);
/// The largest overlap in the model: over particle pairs, overlap / min(rA, rB); against
/// the box walls (non-periodic moving axes), overlap / r. 0 when nothing overlaps.
double largestOverlap(const Model& model);

/// Current Porosity: 1 - (solid volume) / (occupied volume), never below 0. The solid
/// volume counts the volume two overlapping particles share once (dem/Overlaps.h). The occupied volume is the
/// box, except along the "up" axis (opposite to gravity) when that axis has walls: there
/// it extends only up to the top of the highest particle (a settled pack is measured to
/// its top, not to the box ceiling). 2D: areas of discs over the section area.
double currentPorosity(const Model& model);
/// The same, with the volume the overlapping pairs share given (m^3, measureOverlaps's
/// volume: a running solver measures it on its neighbour list, Simulation::overlaps).
double currentPorosity(const Model& model, double sharedVolume);

} // namespace dem
