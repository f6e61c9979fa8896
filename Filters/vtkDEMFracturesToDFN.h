/**
 * @class   vtkDEMFracturesToDFN
 * @brief   Exports the broken bonds of a RockDEM model as a discrete fracture network:
 *          one polygon (disc) per planar cluster of cracks.
 *
 * The reference guide's "Exporting fractures to a DFN". The broken bonds of each set
 * (tensile, shear, inherited) are grouped into spatially connected clusters, a plane is
 * fitted through each (principal axes of the crack positions, weighted by bond area) and
 * a planar cluster becomes a disc; see dem/Fractures.h and Documentation/Fractures.md.
 *
 * Input: a RockDEM model (vtkDEMModelConversion.h). The export follows time: with a
 * stepped upstream model (DEM Load Test) it is computed from the model at the time asked
 * for, so the discs shown match the model shown as the animation plays (the upstream
 * time steps pass through). Output port 0: vtkPolyData, one polygon per disc,
 * with cell arrays Dip, Azimuth (degrees), Set (0 tensile, 1 shear, 2 inherited), SetName,
 * Radius (m), Area (m^2), Normal (3), Center (m, 3), CrackCount, Planarity, Fill. Output
 * port 1: vtkTable, one row per disc: CenterX/Y/Z (m), NormalX/Y/Z, Dip, Azimuth
 * (degrees), Radius (m), Area (m^2), Set, SetName, CrackCount, Planarity, Fill (CSV
 * through Save Data).
 *
 * What happened (broken bonds, clusters, discs per set, clusters rejected as too small
 * and as non-planar, and why nothing was emitted) goes to the Output Messages and to the
 * read-only values. Invalid parameters are reported with vtkErrorMacro naming the
 * parameter, its value and the valid range; the outputs are then empty.
 */
#ifndef vtkDEMFracturesToDFN_h
#define vtkDEMFracturesToDFN_h

#include "RockDEMFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // for the read-only message

class ROCKDEMFILTERS_EXPORT vtkDEMFracturesToDFN : public vtkPolyDataAlgorithm
{
public:
  static vtkDEMFracturesToDFN* New();
  vtkTypeMacro(vtkDEMFracturesToDFN, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// A cluster with fewer cracks (broken bonds) is rejected as too small (>= 3).
  vtkSetMacro(MinimumCracks, int);
  vtkGetMacro(MinimumCracks, int);
  ///@}

  ///@{
  /// A cluster whose Planarity (1 - l1/l2, dimensionless) is below this is not a
  /// fracture, [0, 1].
  vtkSetMacro(MinimumPlanarity, double);
  vtkGetMacro(MinimumPlanarity, double);
  ///@}

  ///@{
  /// Cracks closer than this (m) belong to the same cluster (>= 0; 0 = two mean
  /// particle diameters).
  vtkSetMacro(ClusterDistance, double);
  vtkGetMacro(ClusterDistance, double);
  ///@}

  ///@{
  /// A disc whose Fill (the fraction of the bonds crossing it that are broken,
  /// dimensionless) is below this is rejected as sparse, [0, 1]; 0 = no such test.
  vtkSetMacro(MinimumFill, double);
  vtkGetMacro(MinimumFill, double);
  ///@}

  ///@{
  /// Planes grown through a non-planar cluster take cracks whose local plane is within
  /// this angle of the plane's running normal, degrees, [0, 90); 0 = off (dem::FractureParameters).
  vtkSetMacro(OrientationTolerance, double);
  vtkGetMacro(OrientationTolerance, double);

  /// Band Significance, standard deviations, >= 0 (0 = off): the leftover damage of a
  /// non-planar cluster is scanned for flat bands one Cluster Distance thick; the band
  /// whose cracks most exceed the cluster's damage fraction becomes a candidate disc when
  /// the excess reaches this many standard deviations (dem::FractureParameters).
  vtkSetMacro(BandSignificance, double);
  vtkGetMacro(BandSignificance, double);
  ///@}

  ///@{
  /// Vertices of each disc polygon (>= 3).
  vtkSetMacro(DiscSides, int);
  vtkGetMacro(DiscSides, int);
  ///@}

  ///@{
  /// Read-only values of the last execution (0 after an error).
  vtkGetMacro(NumberOfBrokenBonds, vtkIdType);  ///< Broken Bonds
  vtkGetMacro(NumberOfClusters, vtkIdType);     ///< Clusters
  vtkGetMacro(NumberOfDiscs, vtkIdType);        ///< Discs Emitted
  vtkGetMacro(NumberOfTensileDiscs, vtkIdType); ///< Tensile Discs
  vtkGetMacro(NumberOfShearDiscs, vtkIdType);   ///< Shear Discs
  vtkGetMacro(NumberOfInheritedDiscs, vtkIdType); ///< Inherited Discs
  vtkGetMacro(RejectedTooSmall, vtkIdType);     ///< clusters with fewer than Minimum Cracks
  vtkGetMacro(RejectedNonPlanar, vtkIdType);    ///< clusters below Minimum Planarity
  vtkGetMacro(RejectedSparse, vtkIdType);       ///< planar clusters below Minimum Fill
  vtkGetMacro(UsedClusterDistance, double);     ///< m, the Cluster Distance used
  const char* GetLastMessage() const { return this->LastMessageText.c_str(); }
  ///@}

protected:
  vtkDEMFracturesToDFN();
  ~vtkDEMFracturesToDFN() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int MinimumCracks;
  double MinimumPlanarity;
  double ClusterDistance;
  double MinimumFill;
  double OrientationTolerance;
  double BandSignificance;
  int DiscSides;

  // Read-only values are results, not parameters: setting them must not call Modified().
  vtkIdType NumberOfBrokenBonds;
  vtkIdType NumberOfClusters;
  vtkIdType NumberOfDiscs;
  vtkIdType NumberOfTensileDiscs;
  vtkIdType NumberOfShearDiscs;
  vtkIdType NumberOfInheritedDiscs;
  vtkIdType RejectedTooSmall;
  vtkIdType RejectedNonPlanar;
  vtkIdType RejectedSparse;
  double UsedClusterDistance;
  std::string LastMessageText;

private:
  vtkDEMFracturesToDFN(const vtkDEMFracturesToDFN&) = delete;
  void operator=(const vtkDEMFracturesToDFN&) = delete;
  void ResetCounts();
};

#endif
