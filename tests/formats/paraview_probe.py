"""Run by pvpython (ParaView's Python) from test_paraview_sidecars.py: opens each XDMF sidecar
given with ParaView's XDMF 3 readers (S, and T for the grids' names), writes what ParaView sees (per leaf dataset: cell types,
point bounds, every array with its components and per-component range; the time steps) to a JSON
file, and renders one field to a PNG.

  pvpython paraview_probe.py OUT.json PICTURE.png FIELD_FILE FIELD_NAME SIDECAR...
"""
import json
import os
import sys

from paraview import servermanager
from paraview.simple import ColorBy, GetActiveViewOrCreate, ResetCamera, SaveScreenshot, Show
from paraview.simple import Xdmf3ReaderS, Xdmf3ReaderT
from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet


def block_name(data, i):
    """The name ParaView gives block or piece i (the XDMF grid's Name), or None."""
    if not data.HasMetaData(i):
        return None
    return data.GetMetaData(i).Get(vtkCompositeDataSet.NAME())


def leaves(data, name=None):
    """The leaf datasets of what the reader returns (a grid, a multiblock of multipieces), each
    with the name of the innermost named block holding it."""
    if data is None:
        return
    if data.IsA("vtkMultiPieceDataSet"):
        for i in range(data.GetNumberOfPieces()):
            yield from leaves(data.GetPiece(i), block_name(data, i) or name)
    elif data.IsA("vtkMultiBlockDataSet"):
        for i in range(data.GetNumberOfBlocks()):
            yield from leaves(data.GetBlock(i), block_name(data, i) or name)
    else:
        yield name, data


def describe(name, leaf):
    arrays = {}
    for association, field_data in (("point", leaf.GetPointData()), ("cell", leaf.GetCellData())):
        for i in range(field_data.GetNumberOfArrays()):
            array = field_data.GetArray(i)
            components = array.GetNumberOfComponents()
            arrays[array.GetName()] = {
                "association": association,
                "components": components,
                "tuples": array.GetNumberOfTuples(),
                "ranges": [list(array.GetRange(c)) for c in range(components)],
            }
    cell_types = sorted({leaf.GetCellType(c) for c in range(leaf.GetNumberOfCells())})
    return {"name": name, "points": leaf.GetNumberOfPoints(), "cells": leaf.GetNumberOfCells(),
            "cell_types": cell_types, "bounds": list(leaf.GetBounds()), "arrays": arrays}


def main():
    out_json, picture, field_file, field_name = sys.argv[1:5]
    report = {}
    for sidecar in sys.argv[5:]:
        # An absolute name: ParaView 5.11's XDMF reader joins a bare file name to the data file's
        # name without a separator ("flow.xdmfflow.h5").
        reader = Xdmf3ReaderS(FileName=os.path.abspath(sidecar))
        reader.UpdatePipeline()
        times = list(reader.TimestepValues) if reader.TimestepValues else []
        report[sidecar] = {"times": times,
                           "leaves": [describe(n, l) for n, l in leaves(servermanager.Fetch(reader))]}
        # Xdmf3ReaderS merges the grids of a spatial collection into unnamed pieces; Xdmf3ReaderT
        # (and the XDMF Reader) keep each grid a block under its Name, as ParaView lists them.
        named = Xdmf3ReaderT(FileName=os.path.abspath(sidecar))
        named.UpdatePipeline()
        report[sidecar]["named_leaves"] = [describe(n, l)
                                           for n, l in leaves(servermanager.Fetch(named))]
    reader = Xdmf3ReaderS(FileName=os.path.abspath(field_file))
    view = GetActiveViewOrCreate("RenderView")
    view.ViewSize = [800, 500]
    view.OrientationAxesVisibility = 0
    view.Background = [1.0, 1.0, 1.0]
    try:  # ParaView 5.11 uses the palette's background unless told otherwise
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    display = Show(reader, view)
    ColorBy(display, ("POINTS", field_name))
    display.RescaleTransferFunctionToDataRange(True, False)
    view.InteractionMode = "2D"
    ResetCamera(view)
    SaveScreenshot(picture, view, ImageResolution=[800, 500])
    with open(out_json, "w") as f:
        json.dump(report, f, indent=1)


main()
