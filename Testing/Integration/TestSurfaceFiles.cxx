// The lean .vtp reader (Apps/SurfaceFiles.h) against vtkXMLPolyDataReader: for each .vtp
// given, as it is and rewritten by vtkXMLPolyDataWriter in every encoding VTK writes (ascii,
// base64 binary, appended raw and base64; no compression and zlib; 32- and 64-bit headers;
// float points; point arrays of several types; vertices and lines before the polygons),
// ReadVtp must give the same points bit for bit, the same polygons, cell counts and point
// arrays. Encodings it does not handle (lz4, lzma, big-endian) must be declined, not misread.
//   TestSurfaceFiles WORK_DIR FILE.vtp...
#include "IntegrationCheck.h"
#include "SurfaceFiles.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <cstring>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using tetmesher::testing::Check;
using tetmesher::testing::failures;

bool SameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof a) == 0;
}

vtkPolyData* ReadWithVtk(const std::string& path, vtkXMLPolyDataReader* reader)
{
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}

// Compares the lean reader's result with VTK's for one file.
void Compare(const std::string& path)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  vtkPolyData* expected = ReadWithVtk(path, reader);
  tetmesher::cli::SurfaceData got;
  if (!tetmesher::cli::ReadVtp(path, got))
  {
    Check(false, path + ": declined");
    return;
  }
  const vtkIdType n = expected->GetNumberOfPoints();
  Check(got.PointCount() == n, path + ": point count");
  bool pointsSame = got.PointCount() == n;
  for (vtkIdType p = 0; pointsSame && p < n; ++p)
  {
    double x[3];
    expected->GetPoint(p, x);
    for (int k = 0; k < 3; ++k)
      pointsSame = pointsSame && SameBits(x[k], got.points[static_cast<std::size_t>(3 * p + k)]);
  }
  Check(pointsSame, path + ": points differ");
  Check(got.vertexCells == expected->GetNumberOfVerts() &&
      got.lineCells == expected->GetNumberOfLines() &&
      got.stripCells == expected->GetNumberOfStrips(),
    path + ": vertex, line or strip counts");
  Check(got.PolygonCount() == expected->GetNumberOfPolys(), path + ": polygon count");
  bool polysSame = got.PolygonCount() == expected->GetNumberOfPolys();
  vtkNew<vtkIdList> ids;
  vtkCellArray* polys = expected->GetPolys();
  for (vtkIdType c = 0; polysSame && c < polys->GetNumberOfCells(); ++c)
  {
    polys->GetCellAtId(c, ids);
    const auto begin = static_cast<std::size_t>(got.polygonOffsets[static_cast<std::size_t>(c)]);
    const auto end = static_cast<std::size_t>(got.polygonOffsets[static_cast<std::size_t>(c + 1)]);
    polysSame = static_cast<vtkIdType>(end - begin) == ids->GetNumberOfIds();
    for (vtkIdType k = 0; polysSame && k < ids->GetNumberOfIds(); ++k)
      polysSame = got.polygonPoints[begin + static_cast<std::size_t>(k)] == ids->GetId(k);
  }
  Check(polysSame, path + ": polygons differ");
  vtkPointData* data = expected->GetPointData();
  Check(static_cast<int>(got.pointArrays.size()) == data->GetNumberOfArrays(),
    path + ": point array count");
  for (const tetmesher::cli::PointArray& array : got.pointArrays)
  {
    vtkDataArray* other = data->GetArray(array.name.c_str());
    if (!other)
    {
      Check(false, path + ": point array " + array.name + " not in VTK's");
      continue;
    }
    bool same = other->GetNumberOfComponents() == array.components &&
      other->GetNumberOfTuples() == n &&
      array.values.size() == static_cast<std::size_t>(n * array.components);
    for (vtkIdType p = 0; same && p < n; ++p)
      for (int k = 0; same && k < array.components; ++k)
        same = SameBits(other->GetComponent(p, k),
          array.values[static_cast<std::size_t>(p * array.components + k)]);
    Check(same, path + ": point array " + array.name + " differs");
  }
}

// The surface with point arrays of several types, and a vertex and a line cell when asked.
vtkSmartPointer<vtkPolyData> Decorated(vtkPolyData* surface, bool floatPoints, bool extraCells)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(surface);
  const vtkIdType n = copy->GetNumberOfPoints();
  if (floatPoints)
  {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToFloat();
    points->SetNumberOfPoints(n);
    for (vtkIdType p = 0; p < n; ++p)
      points->SetPoint(p, copy->GetPoint(p));
    copy->SetPoints(points);
  }
  vtkNew<vtkFloatArray> h;
  h->SetName("h");
  vtkNew<vtkIntArray> ids;
  ids->SetName("point ids");
  vtkNew<vtkUnsignedCharArray> flags;
  flags->SetName("flags");
  vtkNew<vtkDoubleArray> vectors;
  vectors->SetName("vectors");
  vectors->SetNumberOfComponents(3);
  for (vtkIdType p = 0; p < n; ++p)
  {
    const double* x = copy->GetPoint(p);
    h->InsertNextValue(static_cast<float>(0.1 + 0.01 * x[0]));
    ids->InsertNextValue(static_cast<int>(p) - 7);
    flags->InsertNextValue(static_cast<unsigned char>(p % 251));
    vectors->InsertNextTuple3(x[2] / 3.0, -x[1], 1e-300 * x[0]);
  }
  copy->GetPointData()->AddArray(h);
  copy->GetPointData()->AddArray(ids);
  copy->GetPointData()->AddArray(flags);
  copy->GetPointData()->AddArray(vectors);
  if (extraCells)
  {
    vtkNew<vtkCellArray> verts, lines;
    const vtkIdType vertex[1] = { 0 }, line[2] = { 0, 1 };
    verts->InsertNextCell(1, vertex);
    lines->InsertNextCell(2, line);
    copy->SetVerts(verts);
    copy->SetLines(lines);
  }
  return copy;
}
// Writes `surface` with vtkXMLPolyDataWriter (appended raw, no compression, unless
// `configure` says otherwise).
void Write(vtkPolyData* surface,
  const std::string& path,
  const std::function<void(vtkXMLPolyDataWriter*)>& configure)
{
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(surface);
  writer->SetDataModeToAppended();
  writer->SetEncodeAppendedData(false);
  writer->SetCompressorTypeToNone();
  configure(writer);
  writer->SetFileName(path.c_str());
  Check(writer->Write() == 1, path + ": VTK could not write it");
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: TestSurfaceFiles WORK_DIR FILE.vtp...\n";
    return 2;
  }
  const std::string work = argv[1];
  int variants = 0, declined = 0;
  for (int f = 2; f < argc; ++f)
  {
    const std::string path = argv[f];
    Compare(path);
    vtkNew<vtkXMLPolyDataReader> reader;
    vtkPolyData* surface = ReadWithVtk(path, reader);
    // Every encoding VTK writes, as 16 variants (mode, compressor, header size).
    for (int variant = 0; variant < 16; ++variant)
    {
      const int mode = variant / 4, compressor = variant / 2 % 2, header = variant % 2;
      const std::string out =
        work + "/variant-" + std::to_string(f) + "-" + std::to_string(variant) + ".vtp";
      Write(Decorated(surface, (mode + header) % 2 == 1, (mode + compressor) % 2 == 1),
        out,
        [=](vtkXMLPolyDataWriter* writer)
        {
          if (mode == 0)
            writer->SetDataModeToAscii();
          else if (mode == 1)
            writer->SetDataModeToBinary();
          writer->SetEncodeAppendedData(mode == 3);
          if (compressor == 1)
            writer->SetCompressorTypeToZLib();
          writer->SetHeaderType(header == 0 ? vtkXMLWriter::UInt32 : vtkXMLWriter::UInt64);
          // Small blocks: several zlib blocks per array, and a short last one.
          writer->SetBlockSize(header == 0 ? 1000 : 32768);
        });
      Compare(out);
      ++variants;
    }
    // What the lean reader leaves to VTK: lz4, lzma, big-endian.
    const std::function<void(vtkXMLPolyDataWriter*)> others[] = { [](vtkXMLPolyDataWriter* writer)
      { writer->SetCompressorTypeToLZ4(); },
      [](vtkXMLPolyDataWriter* writer) { writer->SetCompressorTypeToLZMA(); },
      [](vtkXMLPolyDataWriter* writer) { writer->SetByteOrderToBigEndian(); } };
    for (const auto& configure : others)
    {
      const std::string out =
        work + "/declined-" + std::to_string(f) + "-" + std::to_string(declined) + ".vtp";
      Write(surface, out, configure);
      tetmesher::cli::SurfaceData got;
      Check(!tetmesher::cli::ReadVtp(out, got), out + ": read, not declined");
      ++declined;
    }
  }
  std::cout << "TestSurfaceFiles: " << argc - 2 << " files, " << variants << " variants, "
            << declined << " declined, " << failures() << " failure(s)\n";
  return failures() == 0 ? 0 : 1;
}
