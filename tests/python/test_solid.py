"""The 3-D body through the Python package: the CLI's JSON, `(n1, n2, n3, k)` fields, and the
hexahedral `body.vtu` read back by meshio."""

import numpy as np

import capstan
from conftest import without_timings

SOLID = {
    "body.dimension": 3,
    "discretisation.method": "fem-q1",
    "obstacle.shape": "ellipse",
    "obstacle.b": 1.5,
    "grid.n1": 3,
    "grid.n2": 17,
    "grid.n3": 5,
    "loads.tau_max": 1.5,
}


def _sets():
    return [a for k, v in SOLID.items() for a in ("--set", f"{k}={v}")]


def test_solid_contact_matches_cli_and_has_3d_fields(cli):
    r = capstan.contact(capstan.Scene(SOLID))
    assert without_timings(r.to_dict()) == without_timings(cli("contact", *_sets()))
    d = r.to_dict()
    assert d["solid"]["grid"] == [3, 17, 5]
    u = r.fields["displacement_contravariant"]
    assert u.shape == (3, 17, 5, 3)
    # the contact profile is the bottom layer x3 = 0 of the whole-body field, x2 fastest
    v1 = np.array(d["solid"]["contact"]["v1"]).reshape(3, 17)
    assert np.array_equal(u[:, :, 0, 0], v1)
    assert r.fields["stress"].shape == (3, 17, 5, 9)
    assert r.fields["points"].shape == (3, 17, 5, 3)


def test_solid_body_vtu_is_hexahedra_meshio_reads(tmp_path):
    import meshio

    r = capstan.contact(capstan.Scene(SOLID), out=tmp_path)
    mesh = meshio.read(tmp_path / "body.vtu")
    assert [c.type for c in mesh.cells] == ["hexahedron"]
    assert mesh.cells[0].data.shape == (2 * 16 * 4, 8)
    assert mesh.points.shape == (3 * 17 * 5, 3)
    u = mesh.point_data["displacement_contravariant"]
    assert np.array_equal(u, r.fields["displacement_contravariant"].reshape(-1, 3))
    # every hexahedron has a positive volume (VTK's node order): the signed volume of the
    # corner tetrahedron at node 0
    p = mesh.points[mesh.cells[0].data]
    e = p[:, [1, 3, 4]] - p[:, [0]]
    assert (np.einsum("ij,ij->i", e[:, 0], np.cross(e[:, 1], e[:, 2])) > 0).all()
    assert set(mesh.point_data) >= {"contact_slip_1", "x1", "stress_physical"}
