"""The command line through main([...]): run, mesh, validate, --version and scene-file errors."""

import json

import numpy as np
import pytest

import bearingfe
from bearingfe.cli import main
from bearingfe.geometry.meshing import load_mesh
from bearingfe.scenes import SceneError, load_scene
from bearingfe.scenes.reynolds import settings as reynolds_settings
from tests.helpers import ROOT

#: The small scene of these tests (overrides of the shipped scenes/default.toml): a 0.1 P2 mesh, one picture.
SMALL = dict(title="small", surface={"inlets": {0: {"radius": 0.16}}},
             solver={"size": 0.1, "inlet_size": None, "linear_solver": None}, output={"pictures": ["pressure"]})


def test_version(capsys):
    assert main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"bearingfe {bearingfe.__version__}"


def test_run_writes_outputs_and_prints_table(tmp_path, capsys, scene_file):
    out = tmp_path / "out"
    scene = scene_file("reynolds", SMALL)
    assert main(["run", str(scene), "--out", str(out), "--no-progress"]) == 0
    text = capsys.readouterr().out
    assert "smallest film" in text and "flow inlet" in text and "l/min" in text
    assert sorted(p.name for p in out.iterdir()) == [".bearingfe-manifest.json", "field.vtu", "pressure.png",
                                                     "summary.json"]  # the manifest lists the three files
    summary = json.loads((out / "summary.json").read_text())
    # film is thinnest at the arc end phi = -0.5: 1 + 0.6 cos(0.8)
    assert summary["results"]["h_min"] == pytest.approx(1 + 0.6 * np.cos(0.8), rel=1e-12)
    # pocket flow: converged reference 3.71433 (same problem, P2 on a size-0.01 curved mesh);
    # the size-0.1 scene mesh gives 3.71514, within 0.05 %
    assert summary["results"]["flows"]["inlet"] == pytest.approx(3.71433, rel=5e-4)
    # the shipped [scale] (R0 = 50 mm, c = 20 um, mu = 0.03 Pa s, 1500 rpm = 50 pi rad/s) gives SI: film in c,
    # flow in omega R0^2 c, pressure in mu omega R0^2 / c^2
    si, res = summary["results_si"], summary["results"]
    omega = 50 * np.pi
    assert summary["scale"]["omega_rad_s"] == pytest.approx(omega, rel=1e-15)
    assert si["min_film_m"] == pytest.approx(res["h_min"] * 20e-6, rel=1e-14)
    assert si["flows_m3s"]["inlet"] == pytest.approx(res["flows"]["inlet"] * omega * 0.05**2 * 20e-6, rel=1e-14)
    assert si["peak_pressure_Pa"] == pytest.approx(res["max_pressure"] * 0.03 * omega * 0.05**2 / 20e-6**2,
                                                   rel=1e-14)
    rows = {q: (v, u) for q, v, u in summary["table"]}
    assert rows["flow inlet"] == (pytest.approx(si["flows_m3s"]["inlet"] * 6e4), "l/min")
    assert rows["peak pressure"] == (pytest.approx(si["peak_pressure_Pa"]), "Pa")
    import meshio

    vtu = meshio.read(out / "field.vtu")
    assert {"pressure_Pa", "film_thickness_m", "pressure_nondimensional"} <= set(vtu.point_data)
    assert np.abs(vtu.points[:, 1]).max() == pytest.approx(0.4 * 0.05)  # z in m: the half width 0.4 R0
    import matplotlib.image as mpimg

    img = mpimg.imread(out / "pressure.png")
    assert np.ptp(img[..., :3]) > 0.5
    # leftovers of the temporary directory: none
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out", "reynolds.toml"]
    # running again replaces a previous output
    assert main(["run", str(scene), "--out", str(out), "--no-progress"]) == 0


def test_scene_without_scale_reports_non_dimensional_values_named_as_such(tmp_path, capsys, scene_file):
    out = tmp_path / "out"
    assert main(["run", str(scene_file("reynolds", SMALL, scale=None, output={"pictures": []})), "--out", str(out),
                 "--no-progress"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert "results_si" not in summary and summary["results"]["h_min"] == pytest.approx(1 + 0.6 * np.cos(0.8))
    rows = {q: u for q, _, u in summary["table"]}
    assert rows["h_min"] == "c" and rows["max p"] == "mu w R0^2/c^2"  # the scales as units
    import meshio

    assert set(meshio.read(out / "field.vtu").point_data) == {"pressure_nondimensional",
                                                              "film_thickness_nondimensional"}


@pytest.mark.parametrize("scale, message", [
    ({"omega": 100.0}, r"\[scale\] speed_rpm/omega: give exactly one"),
    ({"speed_rpm": None}, r"\[scale\] speed_rpm/omega: give exactly one"),
    ({"clearance": None}, r"\[scale\] clearance: missing \(required with \[scale\]\)"),
    ({"clearance": 0.1}, r"\[scale\] Scale.clearance must be smaller than radius"),
    ({"speed_rpm": -1.0}, r"\[scale\] speed_rpm: must be > 0"),
])
def test_scale_errors_name_the_field(scene_file, scale, message):
    data, label = load_scene(scene_file("reynolds", SMALL, name="bad.toml", scale=scale))
    with pytest.raises(SceneError, match=r"^bad\.toml: " + message):
        reynolds_settings(data, label)


def test_run_refuses_foreign_directory(tmp_path, capsys, scene_file):
    out = tmp_path / "mine"
    out.mkdir()
    (out / "thesis.tex").write_text("precious")
    assert main(["run", str(scene_file("reynolds", SMALL)), "--out", str(out), "--no-progress"]) == 2
    assert "--force" in capsys.readouterr().err
    assert (out / "thesis.tex").read_text() == "precious"


@pytest.mark.parametrize("change, message", [
    (dict(solver={"element": "P3"}), "[solver] element: must be one of 'P1', 'P2'; got 'P3'"),
    (dict(film={"gamma": None, "gama": 0.6}), "[film] gama: unknown field; allowed: gamma, phi0"),
    (dict(surface={"inlets": {0: {"shape": "star"}}}), "[surface.inlets.0] shape: must be one of 'circle', 'ellipse'"),
    (dict(surface={"inlets": {0: {"radius": 0.6}}}), "[surface] Surface.inlets[0] (Circle) is not inside"),
    (dict(kind="turbine"), "kind: must be one of 'reynolds'"),
    (dict(solver={"size": -1}), "[solver] size: must be > 0"),
    (dict(output={"pictures": ["movie"]}), "[output] pictures: must be one of"),
    (dict(film=None), "[film]: missing table"),
])
def test_scene_errors_name_field_and_allowed_values(tmp_path, capsys, scene_file, change, message):
    scene = scene_file("reynolds", SMALL, change)
    out = tmp_path / "out"
    assert main(["run", str(scene), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1 and "Traceback" not in err
    assert not out.exists() and sorted(p.name for p in tmp_path.iterdir()) == ["reynolds.toml"]
    with pytest.raises(SceneError):
        data, label = load_scene(scene)
        reynolds_settings(data, label)


def test_failure_during_run_leaves_nothing(tmp_path, capsys, scene_file):
    # gamma = 2.5 makes h = 1 + 2.5 cos(phi - 3.14) negative on the arc: the solver refuses
    scene = scene_file("reynolds", SMALL, film={"gamma": 2.5, "phi0": 3.14})
    assert main(["run", str(scene), "--out", str(tmp_path / "out"), "--no-progress"]) == 2
    assert "h_min" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["reynolds.toml"]


def test_default_scene_is_valid():
    data, label = load_scene(ROOT / "scenes" / "default.toml")
    s = reynolds_settings(data, label)
    assert s["surface"].inlet_fraction == pytest.approx(0.10, rel=1e-3)  # radius chosen for 10 %
    assert s["film"]["gamma"] == 0.6


def test_mesh_writes_msh_with_named_boundaries(tmp_path, capsys):
    out = tmp_path / "m.msh"
    assert main(["mesh", str(ROOT / "meshes" / "central_pocket_10pct.geo"), "--size", "0.1", "--out", str(out)]) == 0
    mesh = load_mesh(out)
    assert {"outer", "inlet", "side", "arc_start", "arc_end"} <= set(mesh.boundaries)
    assert out.read_text().startswith("$MeshFormat\n4.1")
    assert f"{mesh.n_nodes} nodes" in capsys.readouterr().out
    assert main(["mesh", str(tmp_path / "none.geo"), "--size", "0.1", "--out", str(out)]) == 2
    assert main(["mesh", str(ROOT / "meshes" / "plain_shoe.geo"), "--size", "0", "--out", str(out)]) == 2


def test_validate_prints_table(capsys):
    assert main(["validate", "--quick"]) == 0
    out = capsys.readouterr().out
    assert "annular pad load W" in out and "short bearing" in out and "Raimondi & Boyd" in out
    assert "JFO pocket slider" in out and "Rayleigh step load W" in out and "orifice-fed pad stiffness" in out
    # 2 annular pad + 1 Ocvirk + 3 journal rows x (S, attitude) + 4 JFO pocket slider (load, flow, x_r, peak)
    # + 1 finite-width Rayleigh step + 2 fed recess pads x (ratio, flow, stiffness)
    assert "20 of 20 passed" in out
    assert main(["validate", "--only", "nonsense"]) == 2


def test_usage_error_returns_2(capsys):
    assert main(["run"]) == 2
    assert main([]) == 2


def test_the_command_ends_with_the_exit_code_and_all_its_output(tmp_path, scene_file):
    # `python -m bearingfe.cli` is `command()`: after `run` the process ends without the interpreter's
    # teardown, so the printed table must be complete (flushed) into a pipe, the files in place, and the
    # exit code the command's; a failing run, and a command other than run, end with theirs
    import subprocess
    import sys

    scene = scene_file("reynolds", SMALL)
    out = tmp_path / "out"
    env_cmd = [sys.executable, "-m", "bearingfe.cli"]
    done = subprocess.run([*env_cmd, "run", str(scene), "--out", str(out), "--no-progress"], cwd=ROOT,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.rstrip().splitlines()[-1].startswith("seconds")  # the table's last row
    assert {"pressure.png", "summary.json"} <= {p.name for p in out.iterdir()}
    bad = subprocess.run([*env_cmd, "run", str(tmp_path / "missing.toml"), "--out", str(out)], cwd=ROOT,
                         capture_output=True, text=True)
    assert bad.returncode == 2 and "scene file not found" in bad.stderr
    version = subprocess.run([*env_cmd, "--version"], cwd=ROOT, capture_output=True, text=True)
    assert version.returncode == 0 and version.stdout.strip() == f"bearingfe {bearingfe.__version__}"
