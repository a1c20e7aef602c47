"""The test suite's own helpers (tests/helpers.py, the ``scene_file`` fixture): the TOML writer reads back
with ``tomllib`` as written, and a scene file is its shipped scene with exactly the overrides applied."""

import math
import tomllib

import pytest

from bearingfe.scenes import load_scene
from bearingfe.scenes.reynolds import settings as reynolds_settings
from tests.helpers import SHIPPED_SCENES, scene_data, toml_text


@pytest.mark.parametrize("kind", sorted(SHIPPED_SCENES))
def test_shipped_scenes_round_trip_through_tomllib(kind):
    shipped = tomllib.loads(SHIPPED_SCENES[kind].read_text(encoding="utf-8"))
    assert tomllib.loads(toml_text(shipped)) == shipped


def test_toml_text_writes_every_value_type_the_files_use():
    data = {"kind": "x", "title": 'a "quoted" \\ path\twith\x1b[31m escapes\x07', "n": -3, "x": 1e-300, "big": 1e16,
            "flag": False, "pairs": [[0.0, 180.0], [190.0, 360.0]], "empty": [], "words": ["a", "b"],
            "odd key": 1, "inf": -math.inf,
            "table": {"inner": {"deep": 1}, "items": [{"a": 1, "sub": {"b": 2}}, {"a": 2}]}}
    back = tomllib.loads(toml_text(data))
    assert back == data
    assert math.isnan(tomllib.loads(toml_text({"v": math.nan}))["v"])
    with pytest.raises(TypeError, match="no TOML form"):
        toml_text({"v": None})


def test_scene_file_applies_overrides_to_the_shipped_scene(scene_file, root, tmp_path):
    shipped = tomllib.loads((root / "scenes" / "default.toml").read_text(encoding="utf-8"))
    layer = {"title": "small", "surface": {"inlets": {0: {"radius": 0.16}}}, "solver": {"inlet_size": None}}
    path = scene_file("reynolds", layer, name="sub/s.toml", solver={"size": 0.1}, output={"pictures": ["pressure"]})
    assert path == tmp_path / "sub" / "s.toml"
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    expected = dict(shipped, title="small")
    expected["surface"] = dict(shipped["surface"], inlets=[dict(shipped["surface"]["inlets"][0], radius=0.16)])
    expected["solver"] = {k: v for k, v in shipped["solver"].items() if k != "inlet_size"} | {"size": 0.1}
    expected["output"] = dict(shipped["output"], pictures=["pressure"])
    assert data == expected
    data, label = load_scene(path)
    assert reynolds_settings(data, label)["solver"]["inlet_size"] is None  # removed: the schema's default
    # the pump's mechanism path is made absolute (the shipped file names it relative to scenes/)
    pump = tomllib.loads(scene_file("pump").read_text(encoding="utf-8"))
    assert pump["pump"]["mechanism"] == (root / "mechanisms" / "eccentric_pump.toml").as_posix()
    assert scene_data("pump", pump={"mechanism": "weak.toml"})["pump"]["mechanism"] == "weak.toml"
    # an item of an array of tables removed; a removal of what is not there is an error
    assert "inlets" not in scene_data("reynolds", surface={"inlets": None})["surface"]
    assert scene_data("reynolds", surface={"inlets": {0: None}})["surface"]["inlets"] == []
    with pytest.raises(KeyError, match="film.gama"):
        scene_data("reynolds", film={"gama": None})
    # text is written as it is
    raw = scene_file(text="kind = [", name="bad.toml")
    assert raw.read_text(encoding="utf-8") == "kind = ["
    with pytest.raises(TypeError, match="text="):
        scene_file("reynolds", text="kind = [")
