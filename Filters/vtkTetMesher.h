/**
 * @class   vtkTetMesher
 * @brief   Boundary-conforming tetrahedral mesh of a closed triangulated surface.
 *
 * The method of George, Hecht and Saltel (1990): Delaunay insertion of the surface points in
 * a 5-tet box, recovery of the missing surface edges and triangles by flips and Steiner
 * points strictly inside the volume, removal of the exterior by a flood fill.
 *
 * Input: a vtkPolyData of triangles (polygons are triangulated), closed, possibly several shells;
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
 * the quality summary and `SteinerPointCount`, `RegionCount`.
 * Output 1: the histogram of Q as a vtkTable (as vtkTetQuality).
 * Output 2: the input defects found by the check, to look at (see GetDefectsOutput).
 *
 * Today the output is the boundary mesh (the paper's figure 2): interior point creation
 * (size field) and quality optimisation are not implemented yet.
 */
#ifndef vtkTetMesher_h
#define vtkTetMesher_h

#include "vtkFiltersTetMesherModule.h" // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

#include <string> // for LastError

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
   * an error naming the cell (off).
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

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool EnclosedShellsAreHoles = false;
  int MaximumSteinerPoints = -1;
  bool RemoveSteinerPoints = true;
  bool CheckInput = true;
  bool TriangulatePolygons = true;
  int NumberOfBins = 20;
  std::string LastError;

private:
  vtkTetMesher(const vtkTetMesher&) = delete;
  void operator=(const vtkTetMesher&) = delete;
};

#endif
