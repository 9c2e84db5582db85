"""The picture a ParaView user gets: a surface meshed by the TetMesher plugin, cut in half to
show the tetrahedra inside (crinkle clip, the paper's figure 5), coloured by Quality.

Runs in the ParaView GUI's Python (paraview --script=GuiCutMesh.py) or in pvpython. Reads
TETMESHER_PLUGIN, TETMESHER_SURFACE and TETMESHER_SCREENSHOT from the environment.
"""
import os

from paraview.simple import (Clip, ColorBy, GetActiveViewOrCreate, GetColorTransferFunction,
                             Hide, LoadPlugin, Render, SaveScreenshot, Show, XMLPolyDataReader)

LoadPlugin(os.environ["TETMESHER_PLUGIN"], remote=False, ns=globals())
surface = XMLPolyDataReader(FileName=[os.environ["TETMESHER_SURFACE"]])
mesh = TetMesher(Input=surface)  # noqa: F821 (defined by LoadPlugin)
cut = Clip(Input=mesh)
cut.ClipType = "Plane"
cut.ClipType.Origin = [0.0, 0.0, 0.0]
cut.ClipType.Normal = [0.0, 1.0, 0.0]
cut.Crinkleclip = 1
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [600, 450]
view.OrientationAxesVisibility = 0
view.Background = [1.0, 1.0, 1.0]
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
Hide(surface, view)
display = Show(cut, view)
display.SetRepresentationType("Surface With Edges")
ColorBy(display, ("CELLS", "Quality"))
lut = GetColorTransferFunction("Quality")
lut.RescaleTransferFunction(0.0, 1.0)
try:
    from paraview.simple import Hide3DWidgets
    Hide3DWidgets(proxy=cut.ClipType)  # the GUI shows the plane widget; keep the picture clean
except ImportError:
    pass
# The clip keeps y < 0: look at the cut face from +y.
view.CameraPosition = [1.2, 4.5, 2.6]
view.CameraFocalPoint = [0.0, 0.0, 0.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.CameraParallelProjection = 0
Render(view)
SaveScreenshot(os.environ["TETMESHER_SCREENSHOT"], view, ImageResolution=[600, 450])
print("screenshot written:", os.environ["TETMESHER_SCREENSHOT"])
