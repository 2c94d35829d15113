# Reads a breakwater run with ParaView (pvpython) and prints what ParaView sees, one
# fact a line, for paraview_test to compare with the frames read through libcore:
#
#   pvpython read_run.py OUTDIR/run.xdmf2 FRAME.h5 ...
#
#   reader INDEX READER_NAME          the reader ParaView picks for the file by itself
#   times T0 T1 ...                   the index's time steps
#   block TIME NAME POINTS CELLS      one grid of the spatial collection at TIME
#   points TIME NAME SX SY SZ         sums of its point coordinates
#   array TIME NAME ARRAY CENTER TUPLES COMPONENTS S0 [S1 ...]   sums of one field's components
#   first TIME NAME ARRAY V0 [V1 ...] the field's first tuple
#   frame FILE TIME POINTS ARRAY,ARRAY,...   a frame file opened alone (H5Part reader; - for none)
#
# Times and sums are printed with 17 digits. Every data set is read on its own
# (`Fetch`), as a user stepping through times in the GUI would.
import sys

from paraview import simple, servermanager
from vtkmodules.util import numpy_support
import numpy


def number(x):
    return "%.17g" % x


def sums(array):
    values = numpy_support.vtk_to_numpy(array).astype(numpy.float64)
    values = values.reshape(array.GetNumberOfTuples(), array.GetNumberOfComponents())
    return values.sum(axis=0), (values[0] if len(values) else [])


def leaves(data, name, out):
    """(name, dataset) of every leaf of a multiblock, named after its block."""
    if data is None:
        return
    if data.IsA("vtkMultiBlockDataSet"):
        if data.GetNumberOfBlocks() == 0:  # a part without points at this time
            out.append((name, None))
        for i in range(data.GetNumberOfBlocks()):
            child_name = name
            if data.HasMetaData(i) and data.GetMetaData(i).Has(data.NAME()):
                child_name = data.GetMetaData(i).Get(data.NAME())
            leaves(data.GetBlock(i), child_name, out)
    else:
        out.append((name, data))


def describe(time, name, data):
    t = number(time)
    if data is None:
        print("block", t, name, 0, 0)
        return
    print("block", t, name, data.GetNumberOfPoints(), data.GetNumberOfCells())
    if data.GetNumberOfPoints() > 0:
        s, _ = sums(data.GetPoints().GetData())
        print("points", t, name, *[number(v) for v in s])
    for center, arrays in (("Node", data.GetPointData()), ("Cell", data.GetCellData())):
        for i in range(arrays.GetNumberOfArrays()):
            a = arrays.GetArray(i)
            if a is None or a.GetName().startswith("vtk"):
                continue
            s, first = sums(a)
            print("array", t, name, a.GetName(), center, a.GetNumberOfTuples(), a.GetNumberOfComponents(),
                  *[number(v) for v in s])
            if len(first):
                print("first", t, name, a.GetName(), *[number(v) for v in first])


def time_steps(reader):
    # A proxy property of one value reads as a number, of several as a list.
    values = reader.TimestepValues
    return list(values) if hasattr(values, "__len__") else [values]


def main(index_path, frames):
    index = simple.OpenDataFile(index_path)
    print("reader index", index.GetXMLName())
    times = time_steps(index)
    print("times", *[number(t) for t in times])
    for t in times:
        index.UpdatePipeline(t)
        out = []
        leaves(servermanager.Fetch(index), "run", out)
        for name, data in out:
            describe(t, name, data)
    for path in frames:
        reader = simple.H5PartReader(FileName=path)
        reader.UpdatePipeline()
        data = servermanager.Fetch(reader)
        names = [data.GetPointData().GetArrayName(i) for i in range(data.GetPointData().GetNumberOfArrays())]
        steps = time_steps(reader)
        time = steps[0] if steps else float("nan")
        print("frame", path, number(time), data.GetNumberOfPoints(), ",".join(sorted(names)) or "-")
        simple.Delete(reader)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
