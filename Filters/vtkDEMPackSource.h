/**
 * @class   vtkDEMPackSource
 * @brief   Builds a random, non-overlapping particle pack in the model box.
 *
 * The reference guide's "Creating a DE volume", "Putting the model where the rock is"
 * and "Building the particle pack". Places Initial Elements particles with radii drawn
 * uniformly between Minimum Size and Maximum Size (m), rejecting overlaps; an optional
 * fine zone (a box inside the model) draws radii from a finer range. The commands
 * AddElements (insert until Target Porosity or saturation), GrowElements (expand
 * each particle into the gap to its nearest neighbour or wall) and CompactElements
 * (radius expansion with relaxation to Target Porosity, dem::compactElements) densify
 * the pack; ResetPack discards the commands and rebuilds from scratch.
 *
 * The output is a pure function of the parameters and of the sequence of commands
 * pressed since the last reset (Commands, e.g. "AGC"): a parameter change rebuilds the
 * pack from its seed and replays the commands, so the same inputs always give the same
 * pack. The sequence is recorded in the proxy (vtkSMDEMPackSourceProxy) so that a saved
 * state rebuilds the same pack.
 */
#ifndef vtkDEMPackSource_h
#define vtkDEMPackSource_h

#include "RockDEMFiltersModule.h" // for export macro
#include "vtkDEMModelSourceBase.h"

namespace dem
{
struct PackParameters;
}

class ROCKDEMFILTERS_EXPORT vtkDEMPackSource : public vtkDEMModelSourceBase
{
public:
  static vtkDEMPackSource* New();
  vtkTypeMacro(vtkDEMPackSource, vtkDEMModelSourceBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Number of particles placed when the pack is built or reset.
  vtkSetMacro(InitialElements, vtkIdType);
  vtkGetMacro(InitialElements, vtkIdType);
  ///@}

  ///@{
  /// Particle radius range, m. Radii are uniform between the two.
  vtkSetMacro(MinimumSize, double);
  vtkGetMacro(MinimumSize, double);
  vtkSetMacro(MaximumSize, double);
  vtkGetMacro(MaximumSize, double);
  ///@}

  ///@{
  /// Void fraction Add Elements aims for, in (0, 1).
  vtkSetMacro(TargetPorosity, double);
  vtkGetMacro(TargetPorosity, double);
  ///@}

  ///@{
  /// Seed of the placement random stream.
  vtkSetMacro(RandomSeed, int);
  vtkGetMacro(RandomSeed, int);
  ///@}

  ///@{
  /// Optional fine zone: a box (origin and dimensions in m) inside the model where
  /// radii are drawn between Fine Zone Minimum Size and Fine Zone Maximum Size (m).
  vtkSetMacro(FineZone, vtkTypeBool);
  vtkGetMacro(FineZone, vtkTypeBool);
  vtkBooleanMacro(FineZone, vtkTypeBool);
  vtkSetVector3Macro(FineZoneOrigin, double);
  vtkGetVector3Macro(FineZoneOrigin, double);
  vtkSetVector3Macro(FineZoneDimensions, double);
  vtkGetVector3Macro(FineZoneDimensions, double);
  vtkSetMacro(FineZoneMinimumSize, double);
  vtkGetMacro(FineZoneMinimumSize, double);
  vtkSetMacro(FineZoneMaximumSize, double);
  vtkGetMacro(FineZoneMaximumSize, double);
  ///@}

  /// Command: insert particles until Target Porosity is reached or placement saturates.
  void AddElements();
  /// Command: expand each particle into the gap to its nearest neighbour or wall.
  void GrowElements();
  /// Command: radius expansion with relaxation to Target Porosity (or, when the pack jams
  /// first, to the largest density whose locked-in stress stays within
  /// MaximumLockedInStress).
  void CompactElements();
  /// Command: forget Add/Grow/Compact commands and rebuild the pack from Initial Elements.
  void ResetPack();

  ///@{
  /// Ceiling on the isotropic stress Compact Elements may lock into the pack, Pa (>= 0);
  /// 0 = 2e-6 x Young's Modulus.
  vtkSetMacro(MaximumLockedInStress, double);
  vtkGetMacro(MaximumLockedInStress, double);
  ///@}

  ///@{
  /// Unbalanced force ratio at which Compact Elements counts the pack relaxed, - (dimensionless),
  /// [1e-6, 0.5], default 0.01; each growth stage relaxes to 5 x this. Lower packs denser
  /// and takes more steps.
  vtkSetMacro(EquilibriumRatio, double);
  vtkGetMacro(EquilibriumRatio, double);
  ///@}

  /// Read-only, from the last Compact Elements: the locked-in isotropic stress (Pa) and
  /// the largest overlap (over the smaller radius); 0 before any compaction.
  vtkGetMacro(LockedInStress, double);
  vtkGetMacro(LargestOverlap, double);

  /// Read-only: bytes the model will take while a stage steps it (dem::estimateMemory):
  /// before the pack is built from the particles it will make (Initial Elements, or the
  /// count at Target Porosity when the commands add elements), once built from its count.
  vtkGetMacro(EstimatedMemory, double);

  /// Number of Add/Grow commands applied since the last reset.
  int GetNumberOfCommands() const { return static_cast<int>(this->Commands.size()); }

  ///@{
  /// The commands pressed since the last reset, in order: 'A' Add Elements, 'G' Grow
  /// Elements, 'C' Compact Elements (e.g. "AGC"). Setting it replays exactly those
  /// presses on a fresh pack, which is how a saved state (.pvsm) rebuilds the same pack; any other character is
  /// an error (reported when the pack is built).
  void SetCommands(const char* commands);
  const char* GetCommands() const { return this->Commands.c_str(); }
  ///@}

protected:
  vtkDEMPackSource();
  ~vtkDEMPackSource() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// The pack parameters from the properties.
  dem::PackParameters PackSettings() const;
  /// An empty model with the box (resolved against the input with Fit To Input) and the
  /// material of the properties.
  dem::Model ConfiguredModel(vtkInformationVector** inputVector);

  vtkIdType InitialElements; ///< 64-bit: a count beyond 2^31 reaches the engine's memory check
  double MinimumSize;
  double MaximumSize;
  double TargetPorosity;
  int RandomSeed;
  vtkTypeBool FineZone;
  double FineZoneOrigin[3];
  double FineZoneDimensions[3];
  double FineZoneMinimumSize;
  double FineZoneMaximumSize;
  double MaximumLockedInStress;
  double EquilibriumRatio;
  // Results, not parameters: setting them must not call Modified().
  double LockedInStress;
  double LargestOverlap;
  double EstimatedMemory; ///< bytes

  /// Commands pressed since the last reset: 'A' (add), 'G' (grow) or 'C' (compact).
  std::string Commands;

private:
  vtkDEMPackSource(const vtkDEMPackSource&) = delete;
  void operator=(const vtkDEMPackSource&) = delete;

  struct vtkInternals;
  vtkInternals* Internals;
};

#endif
