"""Hostile-but-fair use of outputs and processes: output folders, sweep workers, cache
records, size guards and the command line's one-line errors.

Every test is small (a coarse P1 shoe, sleeping stand-in run functions); the expected numbers are
closed forms of the cosine film (h_min = 1 - gamma at phi = phi0 + pi = 0 inside the arc).
"""

import fcntl
import hashlib
import json
import math
import os
import signal
import stat
import subprocess
import sys
import textwrap
import time
import types
import warnings
from pathlib import Path

import pytest

from bearingfe.cli import main
from bearingfe.io.writers import atomic_path, write_pvd
from bearingfe.core.limits import DEFAULT_LIMITS, LimitError, check_limit, limit
from bearingfe.io.outfolder import MANIFEST, OutputFolderError, output_folder, read_manifest
from bearingfe.sweep import CacheWarning, ShoeCase, expand_cases, read_study, sweep
from tests.helpers import ROOT

PY = sys.executable

#: The tiny scene of these tests (overrides of the shipped scenes/default.toml): a plain shoe, a 0.25 P1 mesh,
#: the thinnest film h_min = 1 - gamma at phi = phi0 + pi = 0, no pictures.
TINY = dict(title="tiny", surface={"inlets": None}, film={"phi0": math.pi}, operating={"inlet_pressure": None},
            solver={"size": 0.25, "inlet_size": None, "element": "P1"}, output={"pictures": []})

BASE = ShoeCase(gamma=0.5, mesh_size=0.2)


def _run(scene, out, *extra) -> int:
    return main(["run", str(scene), "--out", str(out), "--no-progress", *extra])


def _one_line_error(capsys, *words) -> str:
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    for word in words:
        assert word in err, err
    return err


def _visible(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if not p.name.startswith("."))


# -- run --out: replace only what bearingfe wrote ------------------------------------------------------

def test_user_files_survive_reruns_and_old_outputs_are_removed(tmp_path, capsys, scene_file):
    out = tmp_path / "out"
    scene = scene_file("reynolds", TINY, output={"pictures": ["pressure"]})
    assert _run(scene, out) == 0
    assert set(read_manifest(out)) == {"field.vtu", "pressure.png", "summary.json"}
    (out / "notes.txt").write_text("mine")
    (out / "sub").mkdir()
    (out / "sub" / "data.csv").write_text("1,2\n")
    for extra in ((), ("--force",)):
        assert _run(scene_file("reynolds", TINY), out, *extra) == 0  # no pictures this time
        # pressure.png was the package's and is not written any more: removed; the user's files stay
        assert _visible(out) == ["field.vtu", "notes.txt", "sub", "summary.json"]
        assert (out / "notes.txt").read_text() == "mine" and (out / "sub" / "data.csv").read_text() == "1,2\n"
    assert sorted(p.name for p in out.iterdir() if p.name.startswith(".")) == [MANIFEST]  # no work folder left


def test_an_edited_output_is_the_users_and_never_overwritten(tmp_path, capsys, scene_file):
    out = tmp_path / "out"
    scene = scene_file("reynolds", TINY)
    assert _run(scene, out) == 0
    capsys.readouterr()
    (out / "summary.json").write_text("my edits")
    for extra in ((), ("--force",)):
        assert _run(scene, out, *extra) == 2
        _one_line_error(capsys, "summary.json", "not written by bearingfe")
        assert (out / "summary.json").read_text() == "my edits"


def test_foreign_folder_needs_force_and_keeps_its_files(tmp_path, capsys, scene_file):
    scene = scene_file("reynolds", TINY)
    out = tmp_path / "mine"
    out.mkdir()
    (out / "thesis.tex").write_text("precious")
    (out / "summary.json").write_text("{}")  # a summary.json alone does not make a folder a bearingfe output
    assert _run(scene, out) == 2
    _one_line_error(capsys, "--force")
    assert _visible(out) == ["summary.json", "thesis.tex"]
    (out / "summary.json").unlink()
    assert _run(scene, out, "--force") == 0
    assert (out / "thesis.tex").read_text() == "precious"
    assert _visible(out) == ["field.vtu", "summary.json", "thesis.tex"]


def test_scene_file_inside_the_output_folder_is_never_touched(tmp_path, capsys, scene_file):
    out = tmp_path / "out"
    out.mkdir()
    scene = scene_file("reynolds", TINY, name="out/s.toml")
    text = scene.read_bytes()
    assert _run(scene, out, "--force") == 0
    # a manifest that claims the scene file (right hash): it is still not removed
    data = json.loads((out / MANIFEST).read_text())
    data["files"]["s.toml"] = hashlib.sha256(text).hexdigest()
    (out / MANIFEST).write_text(json.dumps(data))
    assert _run(scene, out) == 0
    assert scene.read_bytes() == text
    # a scene file named like an output is an error, never an overwrite
    named = scene_file("reynolds", TINY, name="out/summary.json")
    named_text = named.read_bytes()
    assert _run(named, out) == 2
    _one_line_error(capsys, "scene file")
    assert named.read_bytes() == named_text


def test_manifest_cannot_reach_outside_the_folder(tmp_path):
    out = tmp_path / "out"
    with output_folder(out) as work:
        (work / "a.txt").write_text("a")
    outside = tmp_path / "victim.txt"
    outside.write_text("v")
    sha = hashlib.sha256(b"v").hexdigest()
    (out / MANIFEST).write_text(json.dumps({"files": {"../victim.txt": sha, str(outside): sha, "a.txt": "0"}}))
    assert read_manifest(out) == {}  # escaping and absolute paths dropped; a.txt changed hash -> not ours
    with pytest.raises(OutputFolderError, match="a.txt is there and was not written by bearingfe"):
        with output_folder(out) as work:
            (work / "a.txt").write_text("b")
    assert outside.read_text() == "v" and (out / "a.txt").read_text() == "a"


def test_second_run_into_a_locked_folder_fails_clearly(tmp_path, capsys, scene_file):
    out = tmp_path / "out"
    scene = scene_file("reynolds", TINY)
    assert _run(scene, out) == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    capsys.readouterr()
    fd = os.open(out, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)  # another run holding the folder
        assert _run(scene, out) == 2
        _one_line_error(capsys, "another bearingfe run")
        (tmp_path / "study.toml").write_text(STUDY)
        assert main(["sweep", str(tmp_path / "study.toml"), "--out", str(out), "--no-progress"]) == 2
        _one_line_error(capsys, "another bearingfe run")
    finally:
        os.close(fd)
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before


def test_interrupted_run_keeps_previous_outputs_and_leaves_no_work_folder(tmp_path, capsys, monkeypatch, scene_file):
    import bearingfe.scenes

    out = tmp_path / "out"
    scene = scene_file("reynolds", TINY)
    assert _run(scene, out) == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}

    def interrupted(path, work, tick=None):
        (work / "summary.json").write_text("half")
        raise KeyboardInterrupt

    monkeypatch.setattr(bearingfe.scenes, "run_scene", interrupted)
    assert _run(scene, out) == 130
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    # a work folder left by a killed run (its mark names its own inode) is removed by the next run;
    # a hidden folder of the user's with a similar name is not, nor one copied from elsewhere (mark of
    # another inode) or one whose mark is not the package's
    stale = out / ".bearingfe-work-killed"
    stale.mkdir()
    (stale / ".bearingfe-work").write_text(json.dumps({"inode": stale.stat().st_ino}))
    (stale / "summary.json").write_text("half")
    users = out / ".bearingfe-work-mine"
    users.mkdir()
    copied = out / ".bearingfe-work-copied"
    copied.mkdir()
    (copied / ".bearingfe-work").write_text(json.dumps({"inode": stale.stat().st_ino}))
    (copied / "data.csv").write_text("someone's")
    plain = out / ".bearingfe-work-plain"
    plain.mkdir()
    (plain / ".bearingfe-work").write_text("")
    monkeypatch.undo()
    assert _run(scene, out) == 0
    assert not stale.exists() and users.is_dir()
    assert (copied / "data.csv").read_text() == "someone's" and (plain / ".bearingfe-work").is_file()


def test_sigkill_during_the_move_into_place_is_finished_by_the_next_run(tmp_path):
    out = tmp_path / "out"
    with output_folder(out) as work:
        for name in "abc":
            (work / f"{name}.txt").write_text(f"old {name}")
    (out / "notes.txt").write_text("mine")
    script = textwrap.dedent(f"""
        import os, signal
        from pathlib import Path
        import bearingfe.io.outfolder as of
        out, real = Path({str(out)!r}), os.replace
        def replace(src, dst):
            real(src, dst)
            if Path(dst).name == "a.txt":  # killed after the first of the renames
                os.kill(os.getpid(), signal.SIGKILL)
        os.replace = replace
        with of.output_folder(out) as work:
            (work / "a.txt").write_text("new a")
            (work / "b.txt").write_text("new b")
    """)
    proc = subprocess.run([PY, "-c", script], cwd=ROOT, timeout=120)
    assert proc.returncode == -signal.SIGKILL
    assert (out / "a.txt").read_text() == "new a" and (out / "b.txt").read_text() == "old b"  # half moved
    with pytest.raises(RuntimeError, match="the next run fails"):
        with output_folder(out):
            raise RuntimeError("the next run fails")
    # the journal was finished first: the killed run's results whole, its dropped output removed
    assert (out / "b.txt").read_text() == "new b" and not (out / "c.txt").exists()
    assert (out / "notes.txt").read_text() == "mine"
    assert set(read_manifest(out)) == {"a.txt", "b.txt"}
    assert sorted(p.name for p in out.iterdir()) == [MANIFEST, "a.txt", "b.txt", "notes.txt"]


@pytest.mark.parametrize("mask", [0o022, 0o027])
def test_output_files_follow_the_umask(tmp_path, mask, scene_file):
    old = os.umask(mask)
    try:
        out = tmp_path / "out"
        assert _run(scene_file("reynolds", TINY), out) == 0
        with atomic_path(tmp_path / "x.txt") as tmp:
            tmp.write_text("x")
    finally:
        os.umask(old)
    for path in [out / "summary.json", out / "field.vtu", out / MANIFEST, tmp_path / "x.txt"]:
        assert stat.S_IMODE(path.stat().st_mode) == 0o666 & ~mask, path


# -- sweep workers ----------------------------------------------------------------------------------

def _children(pid: int) -> dict[int, str]:
    """Processes whose parent is ``pid``: ``{pid: command line}`` (from /proc)."""
    found = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            if int(fields[1]) == pid:
                found[int(entry.name)] = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode()
        except (OSError, IndexError, ValueError):
            pass
    return found


def _alive(pid: int) -> bool:
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except (OSError, IndexError):
        return False


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM])
def test_workers_end_with_their_parent(sig):
    script = ("import time\nfrom bearingfe.sweep.workers import run_pool\n"
              "print('started', flush=True)\n"
              "for _ in run_pool({'a': 600, 'b': 600}, time.sleep, lambda t: (t,), max_workers=2, time_limit=900):\n"
              "    pass\n")
    parent = subprocess.Popen([PY, "-c", script], cwd=ROOT, stdout=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 90
        children = {}
        while time.monotonic() < deadline:
            children = _children(parent.pid)
            if sum("spawn_main" in c for c in children.values()) == 2:
                break
            time.sleep(0.2)
        assert sum("spawn_main" in c for c in children.values()) == 2, children
        time.sleep(1.0)  # let the workers start their cases
        parent.send_signal(sig)
        parent.wait(30)
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline and any(_alive(p) for p in children):
            time.sleep(0.2)
        assert not [p for p in children if _alive(p)]  # workers (and the resource tracker) are gone
    finally:
        if parent.poll() is None:
            parent.kill()
        parent.stdout.close()


# A Dask case that holds the GIL in compiled code for minutes (as a long factorization or meshing call can):
# ``sum(range(10**12))`` loops in C without releasing it. It marks its start with a file named by its pid.
GIL_HOLDING_SWEEP = """\
import os, sys
import bearingfe.sweep.execute as execute
from bearingfe.cli import main
flags = sys.argv[2]
def hold_gil(*args):
    open(os.path.join(flags, str(os.getpid())), "w").close()
    return sum(range(10**12))
execute.run_case_timed = hold_gil  # pickled by value: the Dask workers run this stand-in
main(["sweep", sys.argv[1], "--out", sys.argv[3], "--scheduler", "local:2", "--no-progress"])
"""


def _descendants(pid: int) -> dict[int, str]:
    """Children, grandchildren, ... of ``pid``: ``{pid: command line}``."""
    found, todo = {}, [pid]
    while todo:
        children = _children(todo.pop())
        found.update(children)
        todo.extend(children)
    return found


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM])
def test_dask_local_workers_end_with_their_parent(sig, tmp_path):
    # Dask's own tie (a thread that waits on a pipe) needs the GIL, which these cases never give back:
    # without the worker preload of `--scheduler local` the workers ran on (checked: still alive after 30 s)
    (tmp_path / "study.toml").write_text(STUDY)
    flags = tmp_path / "flags"
    flags.mkdir()
    parent = subprocess.Popen([PY, "-c", GIL_HOLDING_SWEEP, str(tmp_path / "study.toml"), str(flags),
                               str(tmp_path / "out")], cwd=ROOT, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
    family: dict[int, str] = {}
    try:
        deadline = time.monotonic() + 90
        while time.monotonic() < deadline and len(list(flags.iterdir())) < 2 and parent.poll() is None:
            time.sleep(0.2)
        busy = {int(f.name) for f in flags.iterdir()}
        assert len(busy) == 2, parent.poll()  # both cases run (in two Dask worker processes)
        family = _descendants(parent.pid)
        assert busy <= set(family)
        parent.send_signal(sig)
        parent.wait(30)
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline and any(_alive(p) for p in family):
            time.sleep(0.2)
        assert not [p for p in family if _alive(p)]  # workers (and the resource tracker) are gone
    finally:
        if parent.poll() is None:
            parent.kill()
        for pid in family:  # survivors of a failed check: do not leave them busy
            if _alive(pid):
                os.kill(pid, signal.SIGKILL)


def napping_run(case):
    """Stand-in run: h_min = 1 - gamma at once, or sleep for 10 minutes when gamma > 0.8."""
    if case.gamma > 0.8:
        time.sleep(600)
    return types.SimpleNamespace(h_min=1.0 - case.gamma)


def test_every_case_has_a_time_limit():
    start = time.monotonic()
    table = sweep(BASE, {"gamma": [0.3, 0.9]}, ["h_min"], run=napping_run, time_limit=2.0, max_workers=2)
    assert time.monotonic() - start < 120  # not the 600 s nap
    assert table.loc[0, "error"] is None and table.loc[0, "h_min"] == pytest.approx(0.7, abs=1e-15)
    assert table.loc[1, "error"].startswith("CaseTimeout") and "time limit of 2 s" in table.loc[1, "error"]
    with pytest.raises(ValueError, match="time_limit"):
        sweep(BASE, {"gamma": [0.3]}, ["h_min"], run=napping_run, time_limit=0)


def test_study_time_limit_reaches_the_cases(tmp_path, capsys, monkeypatch):
    # 80 000 triangles (2.31 x 0.96 / 0.0055^2 estimated) take well over 0.2 s to mesh and solve
    (tmp_path / "study.toml").write_text(STUDY.replace("mesh_size = 0.2", "mesh_size = 0.0055")
                                         .replace("[study]", "[study]\ntime_limit = 0.2"))
    assert read_study(tmp_path / "study.toml").time_limit == 0.2
    assert main(["sweep", str(tmp_path / "study.toml"), "--out", str(tmp_path / "out"), "--no-progress"]) == 2
    _one_line_error(capsys, "no case of the sweep succeeded")
    text = (tmp_path / "out" / "results.csv").read_text()
    assert text.count("CaseTimeout") == 2
    (tmp_path / "bad.toml").write_text(STUDY.replace("[study]", "[study]\ntime_limit = -1"))
    with pytest.raises(ValueError, match=r"\[study\] time_limit: must be > 0"):
        read_study(tmp_path / "bad.toml")


# -- cache records ------------------------------------------------------------------------------------

GAMMAS = [0.3, 0.4, 0.5, 0.6, 0.7, 0.75, 0.8]


def _cached_sweep(cache, expect_notes=0):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        table = sweep(BASE, {"gamma": GAMMAS}, ["h_min"], run=napping_run, cache=cache, max_workers=1)
    notes = [str(w.message) for w in caught if issubclass(w.category, CacheWarning)]
    assert len(notes) == expect_notes, notes
    assert table["h_min"].tolist() == pytest.approx([1 - g for g in GAMMAS], abs=1e-15)  # 1 - gamma
    assert table["error"].isna().all()
    return table, notes


def _checksum(record):
    body = {k: v for k, v in record.items() if k != "checksum"}
    return hashlib.sha256(json.dumps(body, sort_keys=True).encode()).hexdigest()


def test_forged_cache_records_are_recomputed(tmp_path):
    cache = tmp_path / "cache"
    first, _ = _cached_sweep(cache)
    paths = [cache / f"{key}.json" for key in first["key"]]
    records = [json.loads(p.read_text()) for p in paths]
    assert all(r["checksum"] == _checksum(r) and r["version"] for r in records)
    forgeries = [
        dict(records[1], outputs={"h_min": 5.0}),                      # edited, checksum stale
        dict(records[2], outputs={"h_min": 5.0}, checksum=None),       # checksum removed
        dict(records[3], outputs={"h_min": 5.0}, version="0.0.1"),     # another version (checksum made to fit)
        dict(records[0], outputs={"h_min": 5.0}),                      # another case's record ...
    ]
    forgeries[2]["checksum"] = _checksum(forgeries[2])
    forgeries[3]["checksum"] = _checksum(forgeries[3])  # ... with a fitting checksum
    for path, forged in zip(paths[1:], forgeries):
        path.write_text(json.dumps(forged))
    table, notes = _cached_sweep(cache, expect_notes=4)
    assert all("computed again" in n for n in notes)
    assert {n.split()[2] for n in notes} == {p.name for p in paths[1:5]}
    assert table["cached"].tolist() == [True, False, False, False, False, True, True]
    assert table.loc[table["h_min"].idxmax(), "gamma"] == 0.3  # a forged 5.0 is never the best design


MALFORMED = ["not json", "[]", '{"outputs": 3}', "[" * 100000 + "]" * 100000,
             '{"outputs": {"h_min": "x"}, "seconds": 1, "error": null}', "\xff\xfe", ""]


def test_malformed_cache_records_are_recomputed_with_a_note(tmp_path):
    cache = tmp_path / "cache"
    first, _ = _cached_sweep(cache)
    paths = [cache / f"{key}.json" for key in first["key"]]
    for path, content in zip(paths, MALFORMED):
        path.write_bytes(content.encode("latin-1"))
    table, notes = _cached_sweep(cache, expect_notes=len(MALFORMED))
    assert all("not used" in n for n in notes) and not table["cached"].any()
    assert json.loads(paths[0].read_text())["outputs"] == {"h_min": pytest.approx(0.7, abs=1e-15)}  # rewritten


STUDY = """
[study]
name = "tiny"
run = "shoe"
outputs = ["h_min"]
[base]
kind = "shoe"
[base.set]
mesh_size = 0.2
[grid]
gamma = [0.3, 0.5]
"""


def test_cli_sweep_notes_a_malformed_record_and_writes_results_atomically(tmp_path, capsys):
    (tmp_path / "study.toml").write_text(STUDY)
    out = tmp_path / "out"
    argv = ["sweep", str(tmp_path / "study.toml"), "--out", str(out), "--no-progress"]
    assert main(argv) == 0
    record = next((out / "cache").glob("*.json"))
    record.write_text('{"outputs": ')
    # a record temporary of a killed sweep (a name the package's cache writer makes) and a user's file
    (out / "cache" / ".0123456789abcdef01234567.json.tmp").write_text("torn")
    (out / ".results.mine.csv").write_text("mine")
    capsys.readouterr()
    assert main(argv) == 0
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "note: cache record" in err and "Traceback" not in err
    assert sorted(p.name for p in out.iterdir()) == [MANIFEST, ".results.mine.csv", "best.json", "cache",
                                                     "results.csv"]
    assert not [p for p in (out / "cache").iterdir() if p.name.startswith(".")]
    assert stat.S_IMODE((out / "results.csv").stat().st_mode) == 0o666 & ~_umask()


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


# -- size guards --------------------------------------------------------------------------------------

def test_limits_have_documented_defaults_and_an_environment_override(monkeypatch):
    assert dict(DEFAULT_LIMITS) == {"revolutions": 100, "frames": 1000, "cases": 10_000, "elements": 1_000_000,
                                    "case_seconds": 3600, "compliance": 4000, "samples": 100_000}
    with pytest.raises(LimitError, match=r"revolutions = 1e\+06 is above the limit of 100.*max_revolutions=.*"
                                         r"BEARINGFE_MAX_REVOLUTIONS"):
        check_limit("revolutions", 1e6, keyword="max_revolutions")
    monkeypatch.setenv("BEARINGFE_MAX_REVOLUTIONS", "2e6")
    assert limit("revolutions") == 2e6
    check_limit("revolutions", 1e6)  # raised: passes
    monkeypatch.setenv("BEARINGFE_MAX_REVOLUTIONS", "lots")
    with pytest.raises(ValueError, match="BEARINGFE_MAX_REVOLUTIONS must be a number > 0"):
        limit("revolutions")


def test_simulate_and_frame_writer_refuse_runaway_sizes(tmp_path):
    import bearingfe as bf

    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    start = time.monotonic()
    with pytest.raises(LimitError, match="revolutions = 1e\\+06 .* max_revolutions="):
        bf.simulate(pump, revolutions=1e6)
    with pytest.raises(LimitError, match="frames = 1001 .* max_frames="):
        write_pvd([str(tmp_path / "x.vtu")] * 1001, range(1001), tmp_path / "x.pvd")
    assert time.monotonic() - start < 5  # refused before any work


def test_grid_and_mesh_size_guards_act_before_work():
    start = time.monotonic()
    with pytest.raises(LimitError, match="cases = 1e\\+06 .* max_cases="):
        expand_cases({"a": range(1000), "b": range(1000)})
    with pytest.raises(LimitError, match="cases = 1e\\+06"):
        sweep(BASE, {"gamma": [0.5] * 1000, "phi0": [0.0] * 1000}, ["h_min"])
    # 2.31 x 0.96 / 1e-4^2 = 2.2e8 triangles
    with pytest.raises(LimitError, match="elements = 2.2.*e\\+08 .* max_elements="):
        sweep(ShoeCase(mesh_size=1e-4), [{"gamma": 0.5}], ["h_min"])
    assert time.monotonic() - start < 10
    assert len(expand_cases({"a": range(100), "b": range(100)}, max_cases=10_000)) == 10_000


def _axis(name, n=100):
    return f"{name} = [{', '.join(str(0.3 + k * 1e-3) for k in range(n))}]"


@pytest.mark.parametrize("change, words", [
    (("mesh_size = 0.2", "mesh_size = 1e-4"), ["elements = 2.2", "max_elements", "BEARINGFE_MAX_ELEMENTS"]),
    (("gamma = [0.3, 0.5]", "\n".join(_axis(n) for n in ("gamma", "phi0", "inlet_pressure"))),  # 100^3 cases
     ["cases = 1e+06", "max_cases", "BEARINGFE_MAX_CASES"]),
])
def test_study_guards_through_the_cli(tmp_path, capsys, change, words):
    (tmp_path / "study.toml").write_text(STUDY.replace(*change))
    start = time.monotonic()
    assert main(["sweep", str(tmp_path / "study.toml"), "--out", str(tmp_path / "out"), "--no-progress"]) == 2
    _one_line_error(capsys, *words)
    assert time.monotonic() - start < 20


#: The shipped pump scene on a 100x thinner oil (weak.toml beside the scene file, written by _weak_mechanism):
#: a quarter turn from a steady start on a 0.2 P1 mesh, two frames, no pictures.
WEAK_PUMP = dict(title="weak pump", pump={"mechanism": "weak.toml"}, elastic=None, output={"pictures": []},
                 run={"revolutions": 0.25, "start": "steady", "mesh_size": 0.2, "element": "P1", "rtol": None,
                      "frames": 2})


def _weak_mechanism(folder: Path) -> None:
    # the shipped pump with a 100x thinner oil: the film closes below 2 % of the clearance (rupture)
    text = (ROOT / "mechanisms" / "eccentric_pump.toml").read_text()
    (folder / "weak.toml").write_text(text.replace("viscosity = 0.03 ", "viscosity = 0.0003 "))


@pytest.mark.parametrize("field, value", [("revolutions", 1e6), ("frames", 10**9)])
def test_pump_scene_size_guards(tmp_path, capsys, scene_file, field, value):
    _weak_mechanism(tmp_path)
    scene = scene_file("pump", WEAK_PUMP, run={field: value})
    start = time.monotonic()
    assert _run(scene, tmp_path / "out") == 2
    _one_line_error(capsys, f"{field} = {value:.6g}", f"BEARINGFE_MAX_{field.upper()}")
    assert time.monotonic() - start < 10 and not (tmp_path / "out").exists()


def test_ruptured_pump_runs_report_status_not_a_ratio(tmp_path, capsys, scene_file):
    out = tmp_path / "out"
    _weak_mechanism(tmp_path)
    assert _run(scene_file("pump", WEAK_PUMP), out) == 0
    text = capsys.readouterr().out
    summary = json.loads((out / "summary.json").read_text())
    assert summary["results"]["pocket"]["status"] == "ruptured" == summary["results"]["plain"]["status"]
    assert summary["results"]["film_ratio"] is None
    ratio_line = next(line for line in text.splitlines() if line.startswith("smallest film ratio"))
    assert "not computed: pocket ruptured, plain ruptured" in ratio_line


# -- the command line: one-line errors, neutral titles ------------------------------------------------

def test_file_system_errors_are_one_line(tmp_path, capsys, scene_file):
    scene = scene_file("reynolds", TINY)
    (tmp_path / "file.txt").write_text("x")
    cases = [(tmp_path / "file.txt", "not a folder"),
             (tmp_path / "file.txt" / "sub", "Not a directory"),
             (tmp_path / ("n" * 300), "File name too long"),
             (Path("/proc/bearingfe-out"), "/proc/bearingfe-out")]  # refused even to root
    for out, words in cases:
        assert _run(scene, out) == 2
        _one_line_error(capsys, words)
    (tmp_path / "g.geo").write_text("")
    assert main(["mesh", str(tmp_path / "g.geo"), "--size", "0.1", "--out", str(tmp_path / "file.txt" / "m.msh")]) == 2
    _one_line_error(capsys, "file.txt")


def test_missing_linear_solver_is_one_line(tmp_path, capsys, monkeypatch, scene_file):
    from bearingfe import available_solvers

    monkeypatch.setitem(sys.modules, "sksparse", None)  # scikit-sparse not installed, wherever this runs
    monkeypatch.setitem(sys.modules, "sksparse.cholmod", None)
    assert "cholmod" not in available_solvers()
    scene = scene_file("reynolds", TINY, solver={"linear_solver": "cholmod"})
    assert _run(scene, tmp_path / "out") == 2
    _one_line_error(capsys, "scikit-sparse")
    assert not (tmp_path / "out").exists()


def test_titles_print_with_escapes_neutralised(tmp_path, capsys, scene_file):
    scene = scene_file("reynolds", TINY, title="red\x1b[31m\x07 title")
    assert _run(scene, tmp_path / "out") == 0
    out = capsys.readouterr().out
    assert "\x1b" not in out and "\x07" not in out
    assert out.startswith("red\\x1b[31m\\x07 title: results in")


def test_dask_path_reports_a_case_past_its_time_limit():
    from bearingfe.sweep.execute import run_case_timed

    start = time.monotonic()
    late = run_case_timed(ShoeCase(gamma=0.9), napping_run, ["h_min"], 0.5)  # the 600 s nap
    assert time.monotonic() - start < 30
    assert late["error"].startswith("CaseTimeout") and "0.5 s" in late["error"] and late["seconds"] == 0.5
    ok = run_case_timed(ShoeCase(gamma=0.3), napping_run, ["h_min"], 30.0)
    assert ok["error"] is None and ok["outputs"]["h_min"] == pytest.approx(0.7, abs=1e-15)


def test_sigterm_ends_a_cli_sweep_and_its_workers(tmp_path):
    # 2.31 x 0.96 / 0.004^2 = 1.4e5 triangles per case: seconds of meshing, stopped long before the end
    (tmp_path / "study.toml").write_text(STUDY.replace("mesh_size = 0.2", "mesh_size = 0.004"))
    parent = subprocess.Popen([PY, "-m", "bearingfe", "sweep", str(tmp_path / "study.toml"), "--out",
                               str(tmp_path / "out"), "--no-progress"], cwd=ROOT, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 90
        children = {}
        while time.monotonic() < deadline:
            children = _children(parent.pid)
            if sum("spawn_main" in c for c in children.values()) == 2:
                break
            time.sleep(0.2)
        assert sum("spawn_main" in c for c in children.values()) == 2, children
        parent.send_signal(signal.SIGTERM)
        _, err = parent.communicate(timeout=30)
        assert parent.returncode == 130 and err == "bearingfe sweep: interrupted\n"
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline and any(_alive(p) for p in children):
            time.sleep(0.2)
        assert not [p for p in children if _alive(p)]
        assert not (tmp_path / "out" / "results.csv").exists()
    finally:
        if parent.poll() is None:
            parent.kill()
            parent.communicate()


def test_sigint_during_the_move_into_place_waits_for_its_end(tmp_path):
    out = tmp_path / "out"
    with output_folder(out) as work:
        for name in "ab":
            (work / f"{name}.txt").write_text(f"old {name}")
    script = textwrap.dedent(f"""
        import os, signal
        from pathlib import Path
        import bearingfe.io.outfolder as of
        # a normal Ctrl-C whatever the test runner's process left to its children (mask, disposition)
        signal.pthread_sigmask(signal.SIG_UNBLOCK, [signal.SIGINT])
        signal.signal(signal.SIGINT, signal.default_int_handler)
        out, real = Path({str(out)!r}), os.replace
        def replace(src, dst):
            real(src, dst)
            if Path(dst).name == "a.txt":  # Ctrl-C after the first of the renames
                os.kill(os.getpid(), signal.SIGINT)
        os.replace = replace
        try:
            with of.output_folder(out) as work:
                (work / "a.txt").write_text("new a")
                (work / "b.txt").write_text("new b")
        except KeyboardInterrupt:
            raise SystemExit(42)  # delivered, but only once the move was complete
    """)
    run = subprocess.run([PY, "-c", script], cwd=ROOT, timeout=120, capture_output=True, text=True)
    assert run.returncode == 42, (run.returncode, run.stderr[-2000:])
    assert (out / "a.txt").read_text() == "new a" and (out / "b.txt").read_text() == "new b"
    assert sorted(p.name for p in out.iterdir()) == [MANIFEST, "a.txt", "b.txt"]  # no journal, no work folder


# -- sweep --out follows the rules of run --out; forged manifests and journals are not acted on --------

@pytest.fixture(scope="module")
def sweep_cache(tmp_path_factory) -> Path:
    """The cache folder of one real CLI sweep of STUDY: later sweeps given a copy of it run no case."""
    folder = tmp_path_factory.mktemp("sweep")
    (folder / "study.toml").write_text(STUDY)
    assert main(["sweep", str(folder / "study.toml"), "--out", str(folder / "out"), "--no-progress"]) == 0
    return folder / "out" / "cache"


def _cached_cli_sweep(tmp_path, sweep_cache, out, *extra) -> int:
    """A CLI sweep of STUDY into ``out`` whose cases all come from a copy of ``sweep_cache`` (beside out)."""
    import shutil

    (tmp_path / "study.toml").write_text(STUDY)
    cache = tmp_path / "cases"
    if not cache.exists():
        shutil.copytree(sweep_cache, cache)
    out.mkdir(exist_ok=True)
    if not (out / "cache").exists():
        shutil.copytree(cache, out / "cache")
    return main(["sweep", str(tmp_path / "study.toml"), "--out", str(out), "--no-progress", *extra])


def test_sweep_out_never_overwrites_the_users_results(tmp_path, capsys, sweep_cache):
    out = tmp_path / "out"
    out.mkdir()
    for name in ("results.csv", "best.json", "notes.txt"):
        (out / name).write_text(f"my {name}")
    # no manifest: a folder of someone's files needs --force
    assert _cached_cli_sweep(tmp_path, sweep_cache, out) == 2
    _one_line_error(capsys, "not a bearingfe output", "--force")
    # with --force the user's results.csv is still never overwritten
    assert _cached_cli_sweep(tmp_path, sweep_cache, out, "--force") == 2
    capsys.readouterr()
    assert {n: (out / n).read_text() for n in ("results.csv", "best.json", "notes.txt")} == \
        {n: f"my {n}" for n in ("results.csv", "best.json", "notes.txt")}
    (out / "results.csv").unlink()
    (out / "best.json").unlink()
    assert _cached_cli_sweep(tmp_path, sweep_cache, out, "--force") == 0
    assert set(read_manifest(out)) == {"results.csv", "best.json"}
    assert (out / "notes.txt").read_text() == "my notes.txt"
    assert _cached_cli_sweep(tmp_path, sweep_cache, out) == 0  # its own previous output: no --force needed
    assert json.loads((out / "best.json").read_text())["gamma"] == 0.3  # h_min = 1 - gamma is largest at 0.3


def test_killed_first_sweep_resumes_without_force(tmp_path, capsys, sweep_cache):
    # a sweep killed before its table leaves only cache records (names the package makes): not foreign
    out = tmp_path / "out"
    assert _cached_cli_sweep(tmp_path, sweep_cache, out) == 0
    assert "2 cases: 2 completed, 0 ruptured" in (text := capsys.readouterr().out) and "0 failed; 2 from cache" in text
    # a cache folder holding a user's file is foreign; a link in its place is refused even with --force
    other = tmp_path / "other"
    other.mkdir()
    import shutil
    shutil.copytree(sweep_cache, other / "cache")
    (other / "cache" / "notes.txt").write_text("mine")
    assert _cached_cli_sweep(tmp_path, sweep_cache, other) == 2
    _one_line_error(capsys, "cache", "--force")
    linked = tmp_path / "linked"
    linked.mkdir()
    (linked / "cache").symlink_to(sweep_cache)
    assert _cached_cli_sweep(tmp_path, sweep_cache, linked, "--force") == 2
    _one_line_error(capsys, "cache is there and is not a folder bearingfe made")


def test_study_file_inside_the_sweep_folder_is_kept(tmp_path, capsys, sweep_cache):
    out = tmp_path / "out"
    assert _cached_cli_sweep(tmp_path, sweep_cache, out) == 0
    (out / "study.toml").write_text(STUDY)
    assert main(["sweep", str(out / "study.toml"), "--out", str(out), "--no-progress"]) == 0
    assert (out / "study.toml").read_text() == STUDY


def test_copied_output_folder_is_not_the_packages(tmp_path, capsys, scene_file):
    # a folder copied from someone else: same names, same hashes, other files (inodes): nothing of it is
    # replaced or removed, and outputs named like its files are an error, never an overwrite
    import shutil

    scene = scene_file("reynolds", TINY, output={"pictures": ["pressure"]})
    assert _run(scene, tmp_path / "theirs") == 0
    shutil.copytree(tmp_path / "theirs", tmp_path / "mine")
    mine = tmp_path / "mine"
    assert read_manifest(mine) == {}
    before = {p.name: p.read_bytes() for p in mine.iterdir()}
    capsys.readouterr()
    assert _run(scene_file("reynolds", TINY), mine) == 2  # would replace summary.json, remove pressure.png
    _one_line_error(capsys, "not written by bearingfe")
    assert {p.name: p.read_bytes() for p in mine.iterdir()} == before


def test_forged_manifest_cannot_delete_a_users_file(tmp_path):
    out = tmp_path / "out"
    with output_folder(out) as work:
        (work / "a.txt").write_text("a")
    (out / "thesis.tex").write_text("precious")
    data = json.loads((out / MANIFEST).read_text())
    thesis = (out / "thesis.tex")
    right_hash = {"sha256": hashlib.sha256(b"precious").hexdigest(), "size": 8}
    data["files"]["thesis.tex"] = dict(right_hash, inode=thesis.stat().st_ino + 1)  # another file's inode
    data["files"]["old.tex"] = hashlib.sha256(b"precious").hexdigest()  # the format of older manifests
    (out / MANIFEST).write_text(json.dumps(data))
    assert set(read_manifest(out)) == {"a.txt"}
    with output_folder(out) as work:
        (work / "a.txt").write_text("a2")  # thesis.tex is not rewritten: a manifest entry would remove it
    assert thesis.read_text() == "precious" and (out / "a.txt").read_text() == "a2"


def test_forged_journal_is_refused_not_acted_on(tmp_path):
    # a journal and a marked work folder copied into the folder (unpacked from an archive) would move
    # their files over the user's and remove the listed ones: refused, nothing changes
    out = tmp_path / "out"
    out.mkdir()
    (out / "thesis.tex").write_text("precious")
    work = out / ".bearingfe-work-forged"
    work.mkdir()
    (work / ".bearingfe-work").write_text(json.dumps({"inode": 1}))
    (work / "thesis.tex").write_text("overwritten")
    sha = hashlib.sha256(b"precious").hexdigest()
    journal = {"work": work.name, "work_inode": 1, "replace": ["thesis.tex"], "old": {},
               "remove": {"thesis.tex": {"sha256": sha, "size": 8, "inode": (out / "thesis.tex").stat().st_ino}},
               "manifest": {}}
    (out / ".bearingfe-commit.json").write_text(json.dumps(journal))
    before = sorted(str(p.relative_to(out)) for p in out.rglob("*"))
    for bad in (journal, "not json", {"work": "../x"}):
        (out / ".bearingfe-commit.json").write_text(bad if isinstance(bad, str) else json.dumps(bad))
        with pytest.raises(OutputFolderError, match="does not match an unfinished run of bearingfe"):
            with output_folder(out, force=True):
                pass
        assert (out / "thesis.tex").read_text() == "precious"
        assert sorted(str(p.relative_to(out)) for p in out.rglob("*")) == before
