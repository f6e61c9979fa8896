// RockDEM engine: the memory a model will take, known before it is built.
//
// DEM Pack Source publishes it (Estimated Memory) from the particle count it will make, so
// that a user sees before Apply whether a model fits the machine. The bytes per particle
// are measured (Documentation/Benchmarks-Solver.md: growth of the resident memory per
// particle; Documentation/SpeedAccuracy.md "Memory"), not computed from the structures.
// SI-style units: bytes.
#pragma once

#include <cstdint>

namespace dem {

struct Domain;
struct PackParameters;

/// Measured bytes per particle of a dem::Model without bonds (Benchmarks-Solver.md: 180 B
/// in every pack).
constexpr double ModelBytesPerParticle = 180.0;
/// Measured bytes per particle the solver adds while it steps a contact-rich (dense) pack
/// (Benchmarks-Solver.md: 545-549 B on the lattice; 140-180 B on a loose pack).
constexpr double SolverBytesPerParticle = 550.0;
/// Bytes per bond of a cemented model (the Bonds arrays: ids, radius, stiffnesses,
/// strengths, forces, moments and the failure record), counted from the element sizes.
constexpr double BytesPerBond = 8.0 * 2 + 8.0 * 7 + 8.0 + 24.0 + 8.0 + 24.0 + 1.0 + 8.0 + 24.0 + 24.0;

/// Bytes a model of `particles` grains takes while a stage steps it: particles x
/// (ModelBytesPerParticle + SolverBytesPerParticle), plus `bonds` x BytesPerBond.
double estimateMemory(double particles, double bonds = 0.0);

/// The particles a pack will hold: Initial Elements, or, when it also adds elements until
/// the Target Porosity (`addsToPorosity`, the Add Elements command), the larger of that and
/// the count that fills the box (and the fine zone, with its own sizes) to Target Porosity:
/// volume x (1 - porosity) / mean sphere volume, the radii uniform in [min, max]
/// (mean r^3 = (a + b)(a^2 + b^2) / 4). A 2D section counts discs in its slab.
double expectedParticleCount(const PackParameters& params, const Domain& domain, bool addsToPorosity);

} // namespace dem
