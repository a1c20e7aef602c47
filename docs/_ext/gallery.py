"""Sphinx extension: the example gallery, executed at build time.

Before Sphinx reads the sources, every numbered example ``examples/[0-9]*.py`` runs in its own process
with ``BEARINGFE_OUT`` set to a folder of the build (``_generated/gallery/<example>``); its printed
output and the pictures it writes go into the generated page ``_generated/gallery.md`` beside the
example's docstring and source. An example that fails (its own checks against its stated reference
are assertions) fails the build. ``BEARINGFE_GALLERY_QUICK=1`` (the default) runs the examples on their
coarse meshes (``BEARINGFE_QUICK=1``), ``0`` on their full ones.
"""

from __future__ import annotations

import ast
import os
import shutil
import subprocess
import sys
from pathlib import Path

from sphinx.errors import ExtensionError

#: Seconds one example may take before the build fails.
EXAMPLE_TIMEOUT = 900


def _examples(root: Path) -> list[Path]:
    return sorted((root / "examples").glob("[0-9]*.py"))


def _run(script: Path, out: Path, root: Path, quick: bool) -> str:
    """Run one example into ``out``; its standard output (the build fails if the example does)."""
    env = dict(os.environ, BEARINGFE_OUT=str(out), BEARINGFE_QUICK="1" if quick else "0", MPLBACKEND="Agg")
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(root), env.get("PYTHONPATH", "")]))
    done = subprocess.run([sys.executable, str(script)], cwd=out, env=env, capture_output=True, text=True,
                          timeout=EXAMPLE_TIMEOUT)
    if done.returncode != 0:
        raise ExtensionError(f"example {script.name} failed (exit {done.returncode}):\n{done.stderr[-3000:]}")
    return done.stdout


def _section(script: Path, out: Path, printed: str, docs: Path) -> list[str]:
    doc = ast.get_docstring(ast.parse(script.read_text(encoding="utf-8"))) or script.stem
    title, _, body = doc.partition("\n")
    lines = [f"## {script.stem}: {title.strip()}", "", "```text", body.strip(), "```", ""]
    for png in sorted(out.rglob("*.png")):
        rel = png.relative_to(docs / "_generated").as_posix()
        lines += [f"![{png.stem}]({rel})", ""]
    if printed.strip():
        lines += ["What it prints:", "", "```text", printed.strip(), "```", ""]
    source = os.path.relpath(script, docs / "_generated")
    lines += [f"```{{literalinclude}} {Path(source).as_posix()}", ":language: python", "```", ""]
    return lines


def build_gallery(app) -> None:
    """Run the examples and write ``_generated/gallery.md`` (Sphinx ``builder-inited``)."""
    docs = Path(app.srcdir)
    root = docs.parent
    quick = os.environ.get("BEARINGFE_GALLERY_QUICK", "1") != "0"
    generated = docs / "_generated"
    gallery = generated / "gallery"
    if gallery.exists():
        shutil.rmtree(gallery)  # only what this extension wrote at the previous build
    lines = ["# Example gallery", "",
             "*Generated at build time: each example below ran while these pages were built"
             + (" (on its coarse meshes, `BEARINGFE_QUICK=1`)" if quick else "")
             + "; its checks against its stated reference passed, and the pictures are the ones it wrote.*",
             ""]
    for script in _examples(root):
        out = gallery / script.stem
        out.mkdir(parents=True)
        lines += _section(script, out, _run(script, out, root, quick), docs)
    (generated / "gallery.md").write_text("\n".join(lines), encoding="utf-8")


def setup(app):
    app.connect("builder-inited", build_gallery)
    return {"version": "1", "parallel_read_safe": True}
