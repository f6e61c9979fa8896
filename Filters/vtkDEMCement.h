/**
 * @class   vtkDEMCement
 * @brief   Cements a RockDEM model into rock: installs a parallel bond between every
 *          pair of particles that touch or nearly so.
 *
 * The reference guide's "Cementing the model". Input: a RockDEM model (see
 * vtkDEMModelConversion.h); a stepped upstream model (DEM Load Test) is read at its last
 * time step, so changing the animation time never re-runs the stage before this one.
 * Output: the same model with the bond set replaced (block "Bonds"). Re-cementing, or
 * cementing an already cemented model, heals it: the bond set is replaced, never added to.
 *
 * The stage is instantaneous: its output publishes no time steps.
 *
 * Units are SI (Pa, N/m^3) except Friction Angle, which is in degrees. Invalid
 * parameters are reported with vtkErrorMacro naming the parameter, its value and the
 * valid range; the output is then empty.
 */
#ifndef vtkDEMCement_h
#define vtkDEMCement_h

#include "RockDEMFiltersModule.h" // for export macro
#include "vtkDEMInstantStage.h"

#include <string> // for the read-only message

class ROCKDEMFILTERS_EXPORT vtkDEMCement : public vtkDEMInstantStage
{
public:
  static vtkDEMCement* New();
  vtkTypeMacro(vtkDEMCement, vtkDEMInstantStage);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Pairs whose surface gap is at most this fraction of the smaller radius are bonded
  /// (dimensionless, [0, 1]; 0 = touching or overlapping pairs only).
  vtkSetMacro(GapTolerance, double);
  vtkGetMacro(GapTolerance, double);
  ///@}

  ///@{
  /// Interaction range: pairs whose centre distance is at most this x (rA + rB) are
  /// bonded too (dimensionless, [1, 2]; 1 = Gap Tolerance alone).
  vtkSetMacro(BondRange, double);
  vtkGetMacro(BondRange, double);
  ///@}

  ///@{
  /// Bond radius as a fraction of the smaller particle radius, (0, 1].
  vtkSetMacro(BondRadiusMultiplier, double);
  vtkGetMacro(BondRadiusMultiplier, double);
  ///@}

  ///@{
  /// Elastic modulus of the cement, Pa (> 0): kn = Bond Modulus / (rA + rB).
  vtkSetMacro(BondModulus, double);
  vtkGetMacro(BondModulus, double);
  ///@}

  ///@{
  /// Bond shear stiffness over bond normal stiffness (dimensionless, > 0).
  vtkSetMacro(BondStiffnessRatio, double);
  vtkGetMacro(BondStiffnessRatio, double);
  ///@}

  ///@{
  /// Explicit bond normal stiffness per unit area, N/m^3 (>= 0); 0 = from Bond Modulus.
  vtkSetMacro(BondNormalStiffness, double);
  vtkGetMacro(BondNormalStiffness, double);
  ///@}

  ///@{
  /// Mean tensile strength, Pa (> 0).
  vtkSetMacro(TensileStrength, double);
  vtkGetMacro(TensileStrength, double);
  ///@}

  ///@{
  /// Mean cohesion (shear strength at zero normal stress), Pa (> 0).
  vtkSetMacro(Cohesion, double);
  vtkGetMacro(Cohesion, double);
  ///@}

  ///@{
  /// Friction angle of the Mohr-Coulomb envelope, degrees, [0, 90).
  vtkSetMacro(FrictionAngle, double);
  vtkGetMacro(FrictionAngle, double);
  ///@}

  ///@{
  /// Moment contribution factor beta, [0, 1]: the share of the bond's bending and twisting
  /// moments in its peripheral stresses (1 = Potyondy & Cundall 2004; 0 = moments are
  /// carried but never break a bond).
  vtkSetMacro(MomentContribution, double);
  vtkGetMacro(MomentContribution, double);
  ///@}

  ///@{
  /// Tension softening, dimensionless, [0, 100]: after reaching its tensile strength a bond's
  /// peripheral stress falls linearly to zero over this many times the stretch that reached
  /// the strength (0 = brittle, Potyondy & Cundall 2004).
  vtkSetMacro(SofteningRatio, double);
  vtkGetMacro(SofteningRatio, double);
  ///@}

  ///@{
  /// Coefficient of variation of the bond strengths, [0, 1]; 0 = every bond identical.
  vtkSetMacro(StrengthScatter, double);
  vtkGetMacro(StrengthScatter, double);
  ///@}

  ///@{
  /// Seed of the strength draw: the same model and settings draw the same strengths.
  vtkSetMacro(RandomSeed, int);
  vtkGetMacro(RandomSeed, int);
  ///@}

  ///@{
  /// Read-only values of the last execution (0 after an error).
  vtkGetMacro(NumberOfBonds, vtkIdType);       ///< Bonds: installed
  vtkGetMacro(BondedCoordination, double);     ///< 2 x Bonds / particles
  vtkGetMacro(NumberOfBrokenBonds, vtkIdType); ///< Broken Bonds
  vtkGetMacro(Damage, double);                 ///< broken / installed, 0-1
  vtkGetMacro(BrokenInTension, vtkIdType);
  vtkGetMacro(BrokenInShear, vtkIdType);
  vtkGetMacro(BondStiffness, double); ///< N/m^3, kn for two particles of the largest radius
  ///@}

protected:
  vtkDEMCement();
  ~vtkDEMCement() override;

  const char* StageName() const override;
  std::string Execute(vtkInformationVector** inputVector, vtkMultiBlockDataSet* output) override;
  void ClearResults() override;

  double GapTolerance;
  double BondRange;
  double BondRadiusMultiplier;
  double BondModulus;
  double BondStiffnessRatio;
  double BondNormalStiffness;
  double TensileStrength;
  double Cohesion;
  double FrictionAngle;
  double MomentContribution;
  double SofteningRatio;
  double StrengthScatter;
  int RandomSeed;

  // Read-only values are results, not parameters: setting them must not call Modified().
  vtkIdType NumberOfBonds;
  double BondedCoordination;
  vtkIdType NumberOfBrokenBonds;
  double Damage;
  vtkIdType BrokenInTension;
  vtkIdType BrokenInShear;
  double BondStiffness;

private:
  vtkDEMCement(const vtkDEMCement&) = delete;
  void operator=(const vtkDEMCement&) = delete;

  struct vtkInternals;
  vtkInternals* Internals;
};

#endif
