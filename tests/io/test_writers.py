"""VTU/PVD round trip through meshio, CSV and JSON contents, atomic writes."""

import csv
import json
import math

import meshio
import numpy as np
import pytest

import bearingfe as bf
from bearingfe import io


@pytest.fixture(scope="module")
def results():
    shoe = bf.Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=[bf.Circle((0.0, 0.0), 0.16)])
    mesh = bf.mesh_surface(shoe, 0.1, order=2)
    sup = bf.superpose(mesh, bf.CosineFilm(0.6, 0.3), element="P2")
    return [sup.combine(1.0, (0.0, 0.0), ps) for ps in (0.5, 1.0, 2.0)]


def test_vtu_round_trip(tmp_path, results):
    res = results[-1]
    io.write_vtu(res, tmp_path / "f.vtu")
    back = meshio.read(tmp_path / "f.vtu")
    m = res.basis.mesh
    np.testing.assert_allclose(back.points[:, :2], m.p[:, : m.nvertices].T)
    np.testing.assert_array_equal(back.cells_dict["triangle"], m.t[:3].T)
    # without scales only the solver's values, named as such
    assert set(back.point_data) == {"pressure_nondimensional", "film_thickness_nondimensional"}
    np.testing.assert_allclose(back.point_data["pressure_nondimensional"], res.pressure[: m.nvertices])
    x = m.p[:, : m.nvertices]
    np.testing.assert_allclose(back.point_data["film_thickness_nondimensional"], 1 + 0.6 * np.cos(x[0] - 0.3))


#: The shipped pump's scales (mechanisms/eccentric_pump.toml): R0 = 50 mm, c = 20 um, mu = 0.03 Pa s,
#: 1500 rpm; pressure scale mu omega R0^2/c^2 = 0.03 * 50 pi * 0.05^2 / (20e-6)^2 = 29.45 MPa.
SCALE = bf.Scale(radius=0.05, clearance=20e-6, viscosity=0.03, speed=50 * math.pi)


def test_vtu_with_scales_holds_si_fields_on_a_mesh_in_metres(tmp_path, results):
    res = results[-1]
    io.write_vtu(res, tmp_path / "f.vtu", SCALE, field_data={"shaft_angle_deg": 212.0})
    back = meshio.read(tmp_path / "f.vtu")
    m = res.basis.mesh
    x = m.p[:, : m.nvertices]
    assert SCALE.pressure == pytest.approx(0.03 * 50 * math.pi * 0.05**2 / 20e-6**2, rel=1e-15)
    np.testing.assert_allclose(back.points[:, :2], 0.05 * x.T)  # (R0 phi, R0 z) [m]
    np.testing.assert_allclose(back.point_data["pressure_Pa"], SCALE.pressure * res.pressure[: m.nvertices])
    np.testing.assert_allclose(back.point_data["film_thickness_m"], 20e-6 * (1 + 0.6 * np.cos(x[0] - 0.3)))
    np.testing.assert_allclose(back.point_data["pressure_nondimensional"], res.pressure[: m.nvertices])
    np.testing.assert_allclose(back.point_data["film_thickness_nondimensional"], 1 + 0.6 * np.cos(x[0] - 0.3))
    assert float(np.ravel(back.field_data["shaft_angle_deg"])[0]) == 212.0


def test_pvd_series_round_trip(tmp_path, results):
    times = [0.0, 0.5, 1.0]
    io.write_pvd(results, times, tmp_path / "series.pvd")
    entries = io.read_pvd(tmp_path / "series.pvd")
    assert [t for t, _ in entries] == times
    for (t, f), res in zip(entries, results):
        back = meshio.read(f)
        np.testing.assert_allclose(back.point_data["pressure_nondimensional"],
                                   res.pressure[: res.basis.mesh.nvertices])
    # with scales: SI fields, the time [s] and the shaft angle [deg] of every frame
    io.write_pvd(results, times, tmp_path / "si.pvd", scale=SCALE, angles=[0.0, 90.0, 180.0])
    for (t, f), res, angle in zip(io.read_pvd(tmp_path / "si.pvd"), results, (0.0, 90.0, 180.0)):
        back = meshio.read(f)
        np.testing.assert_allclose(back.point_data["pressure_Pa"],
                                   SCALE.pressure * res.pressure[: res.basis.mesh.nvertices])
        assert float(np.ravel(back.field_data["shaft_angle_deg"])[0]) == angle
        assert float(np.ravel(back.field_data["time_s"])[0]) == t
    # existing VTU files referenced by path, relative to the pvd
    sub = tmp_path / "sub"
    sub.mkdir()
    files = [io.write_vtu(r, sub / f"s{k}.vtu") for k, r in enumerate(results)]
    io.write_pvd(files, times, tmp_path / "paths.pvd")
    assert "sub/s1.vtu" in (tmp_path / "paths.pvd").read_text()
    assert [f.resolve() for _, f in io.read_pvd(tmp_path / "paths.pvd")] == [f.resolve() for f in files]


def test_pvd_rejects_bad_times(tmp_path, results):
    with pytest.raises(ValueError, match="strictly increasing"):
        io.write_pvd(results, [0.0, 0.0, 1.0], tmp_path / "s.pvd")
    with pytest.raises(ValueError, match="one value per entry"):
        io.write_pvd(results, [0.0, 1.0], tmp_path / "s.pvd")
    assert not list(tmp_path.iterdir())


def test_csv_columns(tmp_path):
    traj = {"beta": np.linspace(0, 1, 4), "gamma": np.array([0.1, 0.2, 0.3, math.pi]),
            "h_min": np.ones(4), "not_a_column": np.zeros(4)}
    io.write_csv(traj, tmp_path / "t.csv")
    rows = list(csv.reader(open(tmp_path / "t.csv")))
    assert rows[0] == ["beta", "gamma", "h_min"]
    assert float(rows[4][1]) == math.pi  # repr keeps full precision
    with pytest.raises(ValueError, match="differ in length"):
        io.write_csv({"beta": np.zeros(3), "gamma": np.zeros(2)}, tmp_path / "bad.csv")
    assert not (tmp_path / "bad.csv").exists()


def test_json_converts_numpy_and_nan(tmp_path):
    io.write_json({"force": np.array([1.5, -2.0]), "n": np.int64(3), "bad": float("nan"), "ok": True},
                  tmp_path / "s.json")
    assert json.loads((tmp_path / "s.json").read_text()) == {"force": [1.5, -2.0], "n": 3, "bad": None, "ok": True}


def test_failed_write_leaves_nothing_and_keeps_old_file(tmp_path):
    target = tmp_path / "s.json"
    target.write_text("old")
    with pytest.raises(ValueError, match="cannot write"):
        io.write_json({"x": object()}, target)
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["s.json"]


def test_vtu_is_read_by_vtk_itself(tmp_path, results):
    """The document read by VTK's own XML reader (through pyvista): the points, the triangles (VTK type 5), the
    point arrays to the last bit (binary, little-endian) and the field data, a quoted name included."""
    import pyvista as pv

    res = results[0]
    io.write_vtu(res, tmp_path / "v.vtu", SCALE, field_data={'angle "beta"': 33.5})
    grid = pv.read(tmp_path / "v.vtu")
    m = res.basis.mesh
    assert (grid.n_points, grid.n_cells) == (m.nvertices, m.t.shape[1])
    assert set(grid.celltypes) == {5}
    np.testing.assert_array_equal(grid.cell_connectivity.reshape(-1, 3), m.t[:3].T)
    np.testing.assert_array_equal(grid.points[:, :2], 0.05 * m.p[:, : m.nvertices].T)
    np.testing.assert_array_equal(grid["pressure_Pa"], SCALE.pressure * res.pressure[: m.nvertices])
    assert float(grid.field_data['angle "beta"'][0]) == 33.5


def test_vtu_document_refuses_arrays_of_the_wrong_shape():
    pts, tri = np.zeros((4, 3)), np.array([[0, 1, 2], [1, 2, 3]])
    with pytest.raises(ValueError, match="points must be"):
        io.writers.vtu_document(np.zeros((4, 2)), tri, {})
    with pytest.raises(ValueError, match="'p' must hold 4 values"):
        io.writers.vtu_document(pts, tri, {"p": np.zeros(3)})
