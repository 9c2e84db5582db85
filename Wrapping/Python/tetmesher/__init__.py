"""TetMesher: boundary-conforming tetrahedral meshing for VTK.

    from tetmesher import vtkTetMesher, vtkTetQuality
"""
from .vtkFiltersTetMesher import *  # noqa: F401,F403  (the wrapped VTK classes)
