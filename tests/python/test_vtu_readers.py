"""meshio and VTK read capstan's VTU files, uncompressed and zlib-compressed, with the same
values (and the same values as the Python result's fields); the active Scalars/Vectors and the
obstacle piece are what ParaView sees."""

import numpy as np
import pytest

import capstan

meshio = pytest.importorskip("meshio")

SMALL = {"grid.n2": 31, "grid.n3": 7, "loads.tau_max": 1.5}


def solve(tmp_path, name, **output):
    scene = capstan.Scene({**SMALL, **{f"output.{k}": v for k, v in output.items()}})
    out = tmp_path / name
    r = capstan.contact(scene, out=out)
    return r, out / "body.vtu"


def test_meshio_reads_compressed_and_uncompressed_alike(tmp_path):
    r, plain = solve(tmp_path, "plain")
    _, packed = solve(tmp_path, "zlib", vtu_compression="zlib")
    assert b'compressor="vtkZLibDataCompressor"' in packed.read_bytes()
    assert b"compressor" not in plain.read_bytes()
    a, b = meshio.read(plain), meshio.read(packed)
    np.testing.assert_array_equal(a.points, b.points)
    assert set(a.point_data) == set(b.point_data)
    for name in a.point_data:
        np.testing.assert_array_equal(a.point_data[name], b.point_data[name])
    # the file holds the result's fields, node k = i2 n3 + i3
    n2, n3 = SMALL["grid.n2"], SMALL["grid.n3"]
    np.testing.assert_array_equal(a.points, r.fields["points"].reshape(n2 * n3, 3))
    np.testing.assert_array_equal(
        a.point_data["displacement"], r.fields["displacement"].reshape(n2 * n3, 3)
    )
    np.testing.assert_array_equal(
        a.point_data["stress"], r.fields["stress"].reshape(n2 * n3, 9)
    )


def test_vtk_reads_compressed_and_uncompressed_alike(tmp_path):
    vtk = pytest.importorskip("vtk", reason="the vtk wheel is not installed")
    from vtk.util.numpy_support import vtk_to_numpy

    def read(path):
        reader = vtk.vtkXMLUnstructuredGridReader()
        reader.SetFileName(str(path))
        reader.Update()
        grid = reader.GetOutput()
        pd = grid.GetPointData()
        arrays = {pd.GetArrayName(i): vtk_to_numpy(pd.GetArray(i)) for i in range(pd.GetNumberOfArrays())}
        scalars = pd.GetScalars().GetName() if pd.GetScalars() else None
        vectors = pd.GetVectors().GetName() if pd.GetVectors() else None
        return vtk_to_numpy(grid.GetPoints().GetData()), arrays, (scalars, vectors), grid

    r, plain = solve(tmp_path, "plain")
    _, packed = solve(tmp_path, "zlib", vtu_compression="zlib")
    pa, aa, active, grid = read(plain)
    pb, ab, _, _ = read(packed)
    np.testing.assert_array_equal(pa, pb)
    assert set(aa) == set(ab) and "displacement" in aa
    for name in aa:
        np.testing.assert_array_equal(aa[name], ab[name])
    assert active == ("contact_state", "displacement")
    n2, n3 = SMALL["grid.n2"], SMALL["grid.n3"]
    assert grid.GetNumberOfCells() == (n2 - 1) * (n3 - 1)
    np.testing.assert_array_equal(aa["x2"], r.fields["x2"].reshape(-1))


def test_obstacle_piece_is_read_beside_the_body(tmp_path):
    n2, n3 = SMALL["grid.n2"], SMALL["grid.n3"]
    _, path = solve(tmp_path, "both", vtu_obstacle=True, vtu_compression="zlib")
    mesh = meshio.read(path)
    body = n2 * n3
    ribbon = mesh.points[body:]
    assert len(ribbon) == 4 * n2 * 3
    # the ribbon lies on the ellipse (y/a)^2 + (z/b)^2 = 1, a = b = 2
    np.testing.assert_allclose((ribbon[:, 1] / 2) ** 2 + (ribbon[:, 2] / 2) ** 2, 1.0, rtol=1e-12)
    assert np.all(mesh.point_data["displacement"][body:] == 0.0)
    vtk = pytest.importorskip("vtk")
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(path))
    reader.Update()
    assert reader.GetNumberOfPieces() == 2
    assert reader.GetOutput().GetNumberOfPoints() == body + len(ribbon)
