// RockDEM engine: the elastic stress field of a disc squeezed along a diameter, the
// reference of the Brazilian test (Documentation/Press.md, "Check against the elastic
// solution").
//
// A disc of diameter D = 2R and thickness t carries two equal and opposite point loads P
// at the ends of a diameter (Hertz 1883; Frocht, Photoelasticity vol. 2, 1948; Timoshenko
// and Goodier, Theory of Elasticity, s. 41): two Flamant radial fields (one per load)
// plus a uniform biaxial tension that frees the rim. Plane stress, thickness-averaged. In
// the disc's frame (origin at the centre, y along the loaded diameter, x across it), with
// sigma0 = 2P/(pi D t) (dem::brazilianStress), r1^2 = x^2 + (R - y)^2,
// r2^2 = x^2 + (R + y)^2 and TENSION positive:
//
//   sigma_xx = sigma0 [1 - D (x^2 (R - y) / r1^4 + x^2 (R + y) / r2^4)]
//   sigma_yy = sigma0 [1 - D ((R - y)^3 / r1^4 + (R + y)^3 / r2^4)]
//   tau_xy   = sigma0 D [x (R - y)^2 / r1^4 - x (R + y)^2 / r2^4]
//
// At the centre: sigma_xx = sigma0 (tension across the loaded diameter), sigma_yy =
// -3 sigma0; along the loaded diameter (x = 0) sigma_xx = sigma0 everywhere.
//
// The mean over the concentric disc of radius a <= R, in closed form:
//
//   mean sigma_xx = sigma0 (1 - a^2 / R^2),  mean sigma_yy = -sigma0 (3 - a^2 / R^2),  mean tau_xy = 0.
//
// Why: each stress component of a plane elastic field without body force is biharmonic,
// and the mean of a biharmonic f over a disc of radius a is f(0) + a^2 Laplacian f(0) / 8,
// so each mean is its centre value plus a multiple of a^2; at a = R the mean stress of
// the whole disc is fixed by its loads alone, (1 / (pi R^2 t)) sum x (x) F: sigma_xx = 0,
// sigma_yy = -2 sigma0, tau_xy = 0 (the sum of the two, harmonic, keeps its centre value
// -2 sigma0 for every a). Testing/Solver/TestLabTests.cpp integrates the point field
// numerically against it.
//
// The functions below return the engine's convention (dem/ParticleStress.h): COMPRESSION
// positive, components {xx, yy, zz, xy, yz, xz} in the disc's frame (zz, yz, xz = 0), so
// that they compare directly with dem::particleStresses. SI units: m, N, Pa.
#pragma once

#include "dem/ParticleStress.h"

namespace dem {

/// The elastic stress at (x, y) (m, from the disc's centre; y along the loaded diameter,
/// x across it) of a disc of the given diameter and thickness (m) under the diametral load
/// (N), compression positive. Throws InputError for a diameter or thickness that is not
/// positive, a negative load, or a point outside the disc or on a load point (the
/// field is singular there).
StressTensor brazilianElasticStress(double x, double y, double load, double diameter, double thickness);

/// The mean elastic stress over the concentric disc of the given radius (m, in [0, D/2])
/// through the whole thickness, compression positive (closed form, see above). Throws
/// InputError naming the parameter for a radius outside [0, D/2], a diameter or thickness
/// that is not positive, or a negative load.
StressTensor brazilianElasticMean(double radius, double load, double diameter, double thickness);

} // namespace dem
