/**
 * @file vtkDEMModelConversion.h
 * @brief The one place where a dem::Model becomes VTK data and back (not wrapped).
 *
 * A model travels between RockDEM filters as a vtkMultiBlockDataSet:
 * - block "Particles": vtkPolyData, one vertex per particle, double-precision points
 *   (m) and point arrays Id, Radius (m), Velocity (m/s), AngularVelocity (rad/s),
 *   Displacement (m), Force (N), Mass (kg), Inertia (kg m^2), Flags, Fixed, SizeClass, and
 *   the derived stress the particle carries (dem/ParticleStress.h; not read back): Stress
 *   (Pa, 6 components xx yy zz xy yz xz, compression positive), MeanStress, VonMisesStress.
 * - block "Walls": vtkPolyData, the active walls as quads with cell arrays Axis, Side,
 *   Position (m), Velocity (m/s), Force (N) and Stress (Pa, normal force over face area).
 * - block "Contacts": vtkPolyData without points whose field data holds the contact
 *   history needed to resume exactly (IdA, IdB, ShearSpring (m), RollingSpring (N m)).
 * - block "Bonds": vtkPolyData, one line per bond from the centre of particle A to the
 *   centre of B (across a periodic seam: to A + the minimum-image branch, so the line
 *   never spans the box), with cell arrays for the whole bond state: IdA, IdB,
 *   BondRadius (m), NormalStiffness, ShearStiffness (N/m^3), TensileStrength, Cohesion
 *   (Pa), FrictionAngle (rad), NormalForce (N), ShearForce (N, 3), TwistingMoment (N m),
 *   BendingMoment (N m, 3), FailureMode (0 intact, 1 tension, 2 shear, 3 inherited),
 *   FailureTime (s), FailurePosition (m, 3), FailureNormal (3) and the derived Broken
 *   (0/1, for Threshold). Absent in models from before bonds: read as no bonds.
 * - field data of the multiblock: the model-level state (domain, material, gravity,
 *   clock, random state, next id), see Documentation/DataModel.md.
 * The round trip Model -> VTK -> Model is lossless: every stored quantity is written in
 * double or exact integer form and read back unchanged.
 */
#ifndef vtkDEMModelConversion_h
#define vtkDEMModelConversion_h

#include "dem/Model.h"
#include "dem/ParticleStress.h"

#include <string>
#include <vector>

class vtkMultiBlockDataSet;
class vtkPolyData;

namespace rockdem
{
/// Names of the blocks.
constexpr const char* ParticlesBlockName = "Particles";
constexpr const char* WallsBlockName = "Walls";
constexpr const char* ContactsBlockName = "Contacts";
constexpr const char* BondsBlockName = "Bonds";
/// Values per wall in the field-data array WallState: axis, side, position (m),
/// velocity (m/s), active, reaction force x, y, z (N), contact stiffness (N/m), elastic
/// push (N), contacts.
constexpr int WallStateComponents = 11;
/// Version of the in-memory VTK layout (field data "RockDEMModelVersion").
constexpr int ModelLayoutVersion = 1;

/// Writes the model into `output` (which is cleared first). The particles' Stress,
/// MeanStress and VonMisesStress are `stresses` (slot order) when given: those of
/// dem::particleStresses for the model, which a running stage has at hand
/// (dem::Simulation::freshInteractionForces); otherwise they are evaluated here.
void ModelToMultiBlock(const dem::Model& model, vtkMultiBlockDataSet* output,
  const std::vector<dem::StressTensor>* stresses = nullptr);

/// Reads a model written by ModelToMultiBlock. Throws dem::InputError when `input` is
/// not a RockDEM model (missing block or array, inconsistent sizes).
dem::Model MultiBlockToModel(vtkMultiBlockDataSet* input);

/// The particles as polydata (points, vertices, point arrays), as in the Particles block
/// (`stresses` as in ModelToMultiBlock).
void ParticlesToPolyData(const dem::Model& model, vtkPolyData* output,
  const std::vector<dem::StressTensor>* stresses = nullptr);

/// The active walls as quads (for display), as in the Walls block.
void WallsToPolyData(const dem::Model& model, vtkPolyData* output);

/// The contact history as field data of an empty polydata, as in the Contacts block.
void ContactsToPolyData(const dem::Model& model, vtkPolyData* output);

/// The bonds as lines with their state as cell arrays, as in the Bonds block.
void BondsToPolyData(const dem::Model& model, vtkPolyData* output);

/// The twelve edges of the model box as line cells (the domain outline).
void DomainBoxToPolyData(const dem::Domain& domain, vtkPolyData* output);
}

#endif
