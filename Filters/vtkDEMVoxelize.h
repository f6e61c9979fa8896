/**
 * @class   vtkDEMVoxelize
 * @brief   The voxel model of a RockDEM model: a vtkImageData of solid fraction, bond
 *          damage, stress and displacement, and fracture intensity when a DFN is given.
 *
 * The reference guide's "Convert to Voxel Model", filled: see dem/Voxelize.h and
 * Documentation/Sections.md. Voxels are cubes of Voxel Size (m), or of the longest extent
 * of the particles divided by Number Of Voxels (Size By); on a periodic axis they divide
 * the model box; a 2D section model gives one layer through its slab.
 *
 * Input 0: a RockDEM model (vtkDEMModelConversion.h). Input 1 (optional, "Fractures"):
 * a DFN as polygonal data (DEM Fractures To DFN's Discs, or any polygons); its Set cell
 * array, when present, gives FractureSet. The voxel model follows time (with a stepped
 * upstream model it is built from the model at the time asked for).
 *
 * The grid is fitted (RequestInformation) to the model at the upstream's first time step
 * (the model as it is when it is not stepped) and stays fixed while time changes, so the
 * voxels of all frames coincide and ParaView knows the image's extent before it asks for
 * a time; the parts of particles that leave it later (fragments flying off) are not
 * counted and the message says how much (Margin leaves room for the specimen to spread).
 *
 * Output: vtkImageData with one point per voxel, at the voxel's centre (so that volume
 * rendering, Contour and Slice work on it directly), spacing = the voxel edges, point
 * arrays SolidFraction, Bonds, BrokenBonds, Damage, BrokenBondDensity (1/m^3), Stress (Pa,
 * 6 components xx yy zz xy yz xz, compression positive), MeanStress, DeviatoricStress (Pa,
 * von Mises), Displacement (m, 3), and with a DFN FractureIntensity (P32, 1/m) and
 * FractureSet. A grid needing more than Memory Limit (MiB) is refused with an error that
 * names the voxel size, the grid, the memory it needs and the limit; invalid parameters
 * are named with their value and valid range; the output is then empty.
 */
#ifndef vtkDEMVoxelize_h
#define vtkDEMVoxelize_h

#include "RockDEMFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <string> // for the read-only message

class ROCKDEMFILTERS_EXPORT vtkDEMVoxelize : public vtkImageAlgorithm
{
public:
  static vtkDEMVoxelize* New();
  vtkTypeMacro(vtkDEMVoxelize, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Size By: 0 Voxel Size, 1 Number Of Voxels (along the longest axis).
  vtkSetMacro(SizeBy, int);
  vtkGetMacro(SizeBy, int);
  ///@}

  ///@{
  /// Edge of a voxel, m (> 0; Size By Voxel Size).
  vtkSetMacro(VoxelSize, double);
  vtkGetMacro(VoxelSize, double);
  ///@}

  ///@{
  /// Voxels along the longest axis of the particles' extent (>= 1; Size By Number Of Voxels).
  vtkSetMacro(NumberOfVoxels, int);
  vtkGetMacro(NumberOfVoxels, int);
  ///@}

  ///@{
  /// Room around the particles' extent on each side, as a fraction of its longest axis
  /// (>= 0): a grid fitted to the start of a run keeps the particles as they spread.
  vtkSetMacro(Margin, double);
  vtkGetMacro(Margin, double);
  ///@}

  ///@{
  /// The largest grid to build, MiB (> 0).
  vtkSetMacro(MemoryLimit, double);
  vtkGetMacro(MemoryLimit, double);
  ///@}

  ///@{
  /// Read-only values of the last execution (0 after an error).
  vtkGetVector3Macro(GridDimensions, int);   ///< voxels per axis
  vtkGetVector3Macro(VoxelSpacing, double);  ///< m
  vtkGetMacro(SolidVolume, double);          ///< m^3
  vtkGetMacro(FractureArea, double);         ///< m^2 inside the grid
  const char* GetLastMessage() const { return this->LastMessageText.c_str(); }
  ///@}

protected:
  vtkDEMVoxelize();
  ~vtkDEMVoxelize() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int SizeBy;
  double VoxelSize;
  int NumberOfVoxels;
  double Margin;
  double MemoryLimit;

  int GridDimensions[3];
  double VoxelSpacing[3];
  double GridOrigin[3]; // m, the lowest corner of the grid fitted in RequestInformation
  int GridWraps[3];     // periodic axes
  bool GridValid;
  double SolidVolume;
  double FractureArea;
  std::string LastMessageText;

private:
  vtkDEMVoxelize(const vtkDEMVoxelize&) = delete;
  void operator=(const vtkDEMVoxelize&) = delete;
  void ResetResults();
};

#endif
