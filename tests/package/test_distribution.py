"""The package as it would be published: ``python -m build`` makes an sdist and, from the sdist, a wheel;
the wheel installed on its own (outside the checkout) runs the main scene.

``python -m build`` builds the wheel from the unpacked sdist, so a file missing from the sdist fails
here too. The wheel is installed with ``--no-deps`` into a folder put first on ``PYTHONPATH`` (its
dependencies are the test environment's); the scene runs in a folder outside the checkout, so
``import bearingfe`` can only find the installed copy (checked).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from tests.helpers import ROOT


@pytest.mark.slow
def test_the_wheel_built_from_the_sdist_installs_and_runs_the_main_scene(tmp_path):
    dist = tmp_path / "dist"
    subprocess.run([sys.executable, "-m", "build", "--outdir", str(dist), str(ROOT)], check=True,
                   capture_output=True, timeout=600)
    wheels, sdists = sorted(dist.glob("bearingfe-*.whl")), sorted(dist.glob("bearingfe-*.tar.gz"))
    assert len(wheels) == 1 and len(sdists) == 1
    target = tmp_path / "site"
    subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "--no-index", "--target", str(target),
                    str(wheels[0])], check=True, capture_output=True, timeout=300)
    run = tmp_path / "run"
    run.mkdir()
    env = dict(os.environ, PYTHONPATH=str(target))
    where = subprocess.run([sys.executable, "-c", "import bearingfe; print(bearingfe.__file__)"], cwd=run, env=env,
                           check=True, capture_output=True, text=True).stdout.strip()
    assert where.startswith(str(target))
    done = subprocess.run([sys.executable, "-c", "import sys, bearingfe_cli; sys.exit(bearingfe_cli.main(sys.argv[1:]))",
                           "run", str(ROOT / "scenes" / "pump.toml"), "--out", str(run / "out")],
                          cwd=run, env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    summary = json.loads((run / "out" / "summary.json").read_text(encoding="utf-8"))
    assert summary  # the scene wrote its summary, and its pictures:
    assert {p.name for p in (run / "out").glob("*.png")} >= {"trajectory.png", "summary.png"}
