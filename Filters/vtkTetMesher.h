/**
 * @class   vtkTetMesher
 * @brief   Boundary-conforming tetrahedral mesh of a closed triangulated surface.
 *
 * The method of George, Hecht and Saltel (1990): Delaunay insertion of the surface points in
 * a 5-tet box, recovery of the missing surface edges and triangles by flips and Steiner
 * points strictly inside the volume, removal of the exterior by a flood fill.
 *
 * Input: a vtkPolyData of triangles (polygons are triangulated, triangle strips decomposed),
 * closed, possibly several shells;
 * triangles shared by two regions (multi-material interfaces, edges with 3+ triangles) are allowed.
 * The surface is checked first (exactly): open or non-manifold edges, self-intersections,
 * degenerate or duplicate triangles, coincident points, non-finite coordinates are refused with an
 * error naming the defect and the ids involved.
 *
 * Output 0: a vtkUnstructuredGrid of VTK_TETRA whose boundary faces are exactly the input
 * triangles. Output points 0..n-1 are the input points with the same coordinates (stored as
 * doubles); Steiner points follow. Cell data: `Quality` (vtkTetQuality's Q), the dihedral
 * angles, `RegionId`, and `InputFaceIds` (4 components: for face i of the tet, the face
 * opposite its point i, the input cell id of the triangle it lies on, or -1). Field data:
 * the quality summary and `SteinerPointCount`, `RegionCount`; `SurfaceQualityBound`, the
 * highest Q min any mesh keeping the surface can have (a tet on input triangle F has
 * Q <= 2 sqrt(6) area(F) / (longest edge of F)^2; capped at 1), and
 * `SurfaceQualityBoundCellId`, the input cell giving it (-1 when it is 1).
 * Output 1: the histogram of Q as a vtkTable (as vtkTetQuality), with a column
 * `CountBeforeOptimization`.
 * Output 2: the input defects found by the check, to look at (see GetDefectsOutput).
 *
 * Then, unless turned off: interior points where edges are too long for the size field h
 * (the paper's section 4.4), and quality optimisation by flips, edge removal and smoothing
 * (sections 4.3, 4.5). h comes from, first that applies: the point array SizeArrayName of
 * the input; the controlling space on input port 1 (any vtkDataSet with a point array named
 * ControllingSpaceArrayName, interpolated in its cells); the mean length of the boundary
 * edges at each input point. SizeScale multiplies h, MinSize/MaxSize clamp it, Gradation
 * bounds its growth, and inside a tet h = (sum b_i h_i^p)^(1/p) with p = InterpolationPower.
 * The point array `h` of the output is the size used.
 */
#ifndef vtkTetMesher_h
#define vtkTetMesher_h

#include "vtkFiltersTetMesherModule.h" // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

#include <string> // for LastError
#include <vector> // for RegionPoints

class vtkAlgorithmOutput;
class vtkPoints;
class vtkPolyData;
class vtkTable;

class VTKFILTERSTETMESHER_EXPORT vtkTetMesher : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkTetMesher* New();
  vtkTypeMacro(vtkTetMesher, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * A closed shell enclosed by another one bounds a region of its own (RegionId), the
   * default, what multi-material users expect; or, when on, a hole (its inside is removed).
   */
  vtkSetMacro(EnclosedShellsAreHoles, bool);
  vtkGetMacro(EnclosedShellsAreHoles, bool);
  vtkBooleanMacro(EnclosedShellsAreHoles, bool);
  ///@}

  ///@{
  /**
   * Inner facets, as in TetGen's piecewise linear complexes (off by default): input triangles
   * with the volume on both sides (a free-standing sheet, a fin on a wall, a crack) are kept as
   * faces inside their region, with open edges allowed. Off, such triangles and open edges
   * are defects of the input. On, a triangle outside the volume is still an error naming it.
   */
  vtkSetMacro(InnerFacets, bool);
  vtkGetMacro(InnerFacets, bool);
  vtkBooleanMacro(InnerFacets, bool);
  ///@}

  ///@{
  /**
   * Points inside regions to remove, as TetGen's hole list: the region containing each point
   * (a shell's inside, a cavity) is dropped like the exterior. A point outside the surface or
   * on it (decided exactly) fails the run naming the point, and so does a removed region
   * between an input triangle and the exterior (the triangle would bound nothing). nullptr,
   * the default: none. The filter's modification time includes the points'.
   */
  virtual void SetHolePoints(vtkPoints* points);
  vtkGetObjectMacro(HolePoints, vtkPoints);
  ///@}

  ///@{
  /**
   * The hole list one point at a time (the ParaView plugin's HolePoints property).
   * AddHolePoint appends to a copy in doubles, so a vtkPoints given to SetHolePoints is never
   * modified; RemoveAllHolePoints empties the list.
   */
  void AddHolePoint(double x, double y, double z);
  void RemoveAllHolePoints();
  ///@}

  ///@{
  /**
   * TetGen's region list (its `-A`): a point inside a region and an attribute. The output then
   * has a cell array `RegionAttribute` (doubles): each region's tets take the attribute of the
   * first region point in it, regions without one the largest given attribute + 1, + 2, ...
   * in RegionId order. A point outside the surface, on it or in a removed region fails the run
   * naming the point. RegionId (tetmesher's own numbering) stays as it is. `maxSize` > 0 also
   * bounds h in that region (TetGen's volume bound per region; when refining), as MaxSize
   * bounds it everywhere.
   */
  void AddRegionPoint(double x, double y, double z, double attribute);
  void AddRegionPoint(double x, double y, double z, double attribute, double maxSize);
  void RemoveAllRegionPoints();
  int GetNumberOfRegionPoints();
  ///@}

  ///@{
  /**
   * Points that must be vertices of the mesh, strictly inside it (TetGen's `-i` list, Gmsh's
   * points embedded in a volume: a load, a sensor, a source). In the output they are points
   * N .. N + k - 1 in the order added, N the number of input points (the Steiner points of
   * boundary recovery come after them); refinement grades its points around them and the
   * optimiser never moves them. Inserted also with Refine and Optimize off. A point outside
   * the surface or in a hole, on an input triangle or edge, or equal to an input point or to
   * another of these (decided exactly) fails the run naming the point.
   */
  void AddInteriorPoint(double x, double y, double z);
  void RemoveAllInteriorPoints();
  int GetNumberOfInteriorPoints();
  ///@}

  vtkMTimeType GetMTime() override;

  ///@{
  /**
   * Create interior points for the size field (default on). Off gives the boundary mesh
   * alone (the paper's figure 2).
   */
  vtkSetMacro(Refine, bool);
  vtkGetMacro(Refine, bool);
  vtkBooleanMacro(Refine, bool);
  ///@}

  ///@{
  /**
   * Name of a point array of the input surface with the wanted edge length h at each point.
   * Empty (default): the controlling space if connected, else the boundary edge lengths.
   */
  vtkSetStringMacro(SizeArrayName);
  vtkGetStringMacro(SizeArrayName);
  ///@}

  ///@{
  /**
   * Name of the size array of the controlling space (input port 1). Default "h".
   */
  vtkSetStringMacro(ControllingSpaceArrayName);
  vtkGetStringMacro(ControllingSpaceArrayName);
  ///@}

  /**
   * Connect a controlling space: any vtkDataSet carrying a point array of sizes (a
   * background mesh, an image, ...), interpolated in its cells. Optional.
   */
  void SetControllingSpaceConnection(vtkAlgorithmOutput* output)
  {
    this->SetInputConnection(1, output);
  }

  ///@{
  /**
   * Multiplies every size (default 1). MinSize / MaxSize clamp h (0: no bound).
   */
  vtkSetClampMacro(SizeScale, double, 1e-6, 1e6);
  vtkGetMacro(SizeScale, double);
  vtkSetClampMacro(MinSize, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MinSize, double);
  vtkSetClampMacro(MaxSize, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaxSize, double);
  ///@}

  ///@{
  /**
   * Largest ratio of the sizes of neighbours one h apart (like Gmsh's and MMG's hgrad);
   * default 1.5; 1 or less: no limit. Next to input triangles larger than h, the sizes also
   * fall from the triangles' own to h, at 0.8 of this rate, and next to triangles smaller than
   * h they grow from 1.2 times the triangles' own at this rate, so that the tets on them are
   * neither flat nor needles (the output point array `h` is the size used); 1 or less turns
   * that off too.
   */
  vtkSetClampMacro(Gradation, double, 0.0, 100.0);
  vtkGetMacro(Gradation, double);
  ///@}

  ///@{
  /**
   * The exponent p of the paper's interpolation h = (sum b_i h_i^p)^(1/p). Default 1.
   */
  vtkSetClampMacro(InterpolationPower, double, -10.0, 10.0);
  vtkGetMacro(InterpolationPower, double);
  ///@}

  ///@{
  /**
   * Improve the worst elements by flips, edge removal and vertex smoothing (default on).
   * Boundary faces never change.
   */
  vtkSetMacro(Optimize, bool);
  vtkGetMacro(Optimize, bool);
  vtkBooleanMacro(Optimize, bool);
  ///@}

  ///@{
  /**
   * Rounds of optimisation (default 3), and the quality below which tets are worked on
   * (default 0.35: a margin above the usual 0.3 for the dihedral stage to move in).
   */
  vtkSetClampMacro(OptimizationPasses, int, 0, 100);
  vtkGetMacro(OptimizationPasses, int);
  vtkSetClampMacro(QualityTarget, double, 0.0, 1.0);
  vtkGetMacro(QualityTarget, double);
  ///@}

  ///@{
  /**
   * When > 0 (degrees): after the Q stage, a second optimisation stage raises the smallest
   * dihedral angles towards this target, keeping the minimum Q. Default 25; 0 turns the
   * stage off.
   */
  vtkSetClampMacro(DihedralTarget, double, 0.0, 70.0);
  vtkGetMacro(DihedralTarget, double);
  ///@}

  enum QualityMeasures
  {
    PAPER_Q = 0,     // 2 sqrt(6) r_in / l_max
    MIN_DIHEDRAL = 1 // the smallest dihedral angle
  };
  ///@{
  /**
   * What the optimisation maximises: the paper's Q (default) or the smallest dihedral angle.
   */
  vtkSetClampMacro(QualityMeasure, int, PAPER_Q, MIN_DIHEDRAL);
  vtkGetMacro(QualityMeasure, int);
  ///@}

  ///@{
  /**
   * Budget of Steiner points for the boundary recovery; -1 (default): 100 + 4 per triangle.
   * Exceeding it is an error naming the face being recovered.
   */
  vtkSetClampMacro(MaximumSteinerPoints, int, -1, VTK_INT_MAX);
  vtkGetMacro(MaximumSteinerPoints, int);
  ///@}

  ///@{
  /**
   * After recovery, remove the Steiner points that flips can take out again. Default on.
   */
  vtkSetMacro(RemoveSteinerPoints, bool);
  vtkGetMacro(RemoveSteinerPoints, bool);
  vtkBooleanMacro(RemoveSteinerPoints, bool);
  ///@}

  ///@{
  /**
   * Time limit in seconds for the whole run (0, the default: none). Past it the filter
   * stops with an error saying which stage ran out of time (and, in boundary recovery, which
   * input edge or triangle it was recovering); no partial mesh is returned.
   */
  vtkSetClampMacro(TimeLimit, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(TimeLimit, double);
  ///@}

  ///@{
  /**
   * Memory limit in MB (10^6 bytes). Before the boundary mesh (about 2.5 kB per surface
   * point) and before inserting interior points (about 2 kB per point the size field asks for)
   * the filter estimates the memory needed and stops with an error naming the estimate when it
   * exceeds the limit. 0, the default: the memory
   * available on the machine when the filter runs; negative: no check.
   */
  vtkSetMacro(MemoryLimit, double);
  vtkGetMacro(MemoryLimit, double);
  ///@}

  ///@{
  /**
   * Check the input surface (exactly) before meshing. Default on. Off saves the time of
   * the self-intersection test on surfaces known to be good; a defect then surfaces as a
   * recovery failure, with a less precise message.
   */
  vtkSetMacro(CheckInput, bool);
  vtkGetMacro(CheckInput, bool);
  vtkBooleanMacro(CheckInput, bool);
  ///@}

  ///@{
  /**
   * Polygons with more than 3 points are split into triangles of their own points (on, the
   * default; their count is in the field data `TriangulatedPolygonCount`), or refused with
   * an error naming the cell (off). The split is the core's triangulatePolygon (ear
   * clipping in the polygon's plane, the best-shaped ear first), as on the command line.
   */
  vtkSetMacro(TriangulatePolygons, bool);
  vtkGetMacro(TriangulatePolygons, bool);
  vtkBooleanMacro(TriangulatePolygons, bool);
  ///@}

  ///@{
  /**
   * Number of bins of the Q histogram (output 1). Default 20.
   */
  vtkSetClampMacro(NumberOfBins, int, 1, 10000);
  vtkGetMacro(NumberOfBins, int);
  ///@}

  /**
   * The message of the last failure (empty after a success), for scripts.
   */
  const char* GetLastError() { return this->LastError.c_str(); }

  /**
   * The input check's warnings of the last run (inconsistently oriented triangles, unused
   * points: the mesh is made all the same), one line per kind; empty when there are none.
   */
  const char* GetLastWarnings() { return this->LastWarnings.c_str(); }

  /**
   * Wall time per stage of the last run, one line per stage "seconds<TAB>stage", in order
   * (input conversion and check, the core stages, output conversion, quality arrays).
   */
  const char* GetStageTimings() { return this->StageTimings.c_str(); }

  vtkTable* GetHistogramOutput();

  /**
   * Output 2: what the input check found, to look at: the defective input triangles
   * (polygons) and points (vertices), cell data `DefectKind`, `DefectRecord`, `InputCellId`,
   * field data `DefectSummary`. Empty when the surface is good or CheckInput is off.
   */
  vtkPolyData* GetDefectsOutput();

protected:
  vtkTetMesher();
  ~vtkTetMesher() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  // The properties the core's job takes: their defaults are those of
  // tetmesher::SurfaceMeshSettings, set by the constructor (the command line shares them).
  bool EnclosedShellsAreHoles{};
  bool InnerFacets{};
  bool Refine{};
  char* SizeArrayName = nullptr;
  char* ControllingSpaceArrayName = nullptr;
  double SizeScale{};
  double MinSize{};
  double MaxSize{};
  double Gradation{};
  double InterpolationPower{};
  bool Optimize{};
  int OptimizationPasses{};
  double QualityTarget{};
  double DihedralTarget{};
  double TimeLimit{};
  double MemoryLimit{};
  int QualityMeasure = PAPER_Q;
  int MaximumSteinerPoints{};
  bool RemoveSteinerPoints{};
  bool CheckInput{};
  bool TriangulatePolygons = true;
  int NumberOfBins{};
  std::string LastError;
  std::string LastWarnings;
  std::string StageTimings;

  vtkPoints* HolePoints = nullptr;
  std::vector<double> RegionPoints;   // 4 per point: x, y, z, attribute
  std::vector<double> RegionMaxSizes; // 1 per point (0: none)
  std::vector<double> InteriorPoints; // 3 per point

private:
  vtkTetMesher(const vtkTetMesher&) = delete;
  void operator=(const vtkTetMesher&) = delete;
};

#endif
