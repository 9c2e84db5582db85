"""Compares a screenshot with its baseline (vtkImageDifference, tolerant to a few pixels of
rendering noise). Usage: CompareImages.py IMAGE BASELINE [THRESHOLD]. On failure, writes
IMAGE.diff.png beside IMAGE."""
import sys

from vtkmodules.vtkImagingCore import vtkImageDifference
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter

image, baseline = sys.argv[1], sys.argv[2]
threshold = float(sys.argv[3]) if len(sys.argv) > 3 else 10.0
readers = []
for path in (image, baseline):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    readers.append(reader)
dims = [r.GetOutput().GetDimensions() for r in readers]
if dims[0] != dims[1]:
    sys.exit(f"size {dims[0]} differs from the baseline's {dims[1]}")
diff = vtkImageDifference()
diff.SetInputConnection(readers[0].GetOutputPort())
diff.SetImageConnection(readers[1].GetOutputPort())
diff.Update()
error = diff.GetThresholdedError()
print(f"image difference {error:.3f} (threshold {threshold})")
if error > threshold:
    writer = vtkPNGWriter()
    writer.SetInputConnection(diff.GetOutputPort())
    writer.SetFileName(image + ".diff.png")
    writer.Write()
    sys.exit(f"{image} differs from {baseline}: {error:.3f} > {threshold}")
