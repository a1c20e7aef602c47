"""The ``bearingfe`` command line.

::

    bearingfe run SCENE.toml --out DIR       run a scene file, write pictures and data into DIR
    bearingfe mesh FILE.geo --size S --out FILE.msh
    bearingfe validate [--quick]             closed-form and published comparisons
    bearingfe --version

:func:`main` takes ``argv`` (default ``sys.argv[1:]``) and returns the exit
code: 0 success, 1 a failed validation or a numerical failure, 2 bad input
(scene-file errors, bad arguments, file-system errors, a missing optional
package), 130 interrupted (Ctrl-C, SIGTERM), with a one-line message and no
traceback; warnings print as one-line notes. Text from input files (titles)
is printed with control characters escaped. ``run`` writes into a hidden
work folder inside ``DIR`` and moves the files into place only when
everything is written; it replaces only the files of a previous run and
locks ``DIR`` against a second run (:mod:`bearingfe.io.outfolder`); ``sweep``
follows the same rules.
"""

from __future__ import annotations

import argparse
import contextlib
import gc
import os
import re
import shutil
import signal
import sys
import threading
import warnings
from pathlib import Path
from typing import NoReturn, Sequence

from .version import __version__

# the package's modules (numpy, scipy, scikit-fem) load with the collector off: their objects live as long as
# the process, and its passes over them while they load are wasted (bearingfe.core.lazy.without_collections,
# not importable before them)
_collecting = gc.isenabled()
gc.disable()
try:
    from .core.tempdirs import private_tempdir
finally:
    if _collecting:
        gc.enable()

__all__ = ["main", "command"]


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="bearingfe", description=__doc__.split("\n")[0])
    parser.add_argument("--version", action="version", version=f"bearingfe {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="{run,mesh,validate,sweep}")

    run = sub.add_parser("run", help="run a scene file (TOML)")
    run.add_argument("scene", type=Path, help="scene file, e.g. scenes/default.toml")
    run.add_argument("--out", type=Path, required=True, help="output directory (the files of a previous "
                     "bearingfe run there are replaced; other files are kept)")
    run.add_argument("--force", action="store_true", help="write into DIR even if it holds files and no "
                     "previous bearingfe output (those files are kept)")
    run.add_argument("--no-progress", action="store_true", help="no progress bar")

    mesh = sub.add_parser("mesh", help="mesh a gmsh .geo file into a .msh 4.1 file")
    mesh.add_argument("geo", type=Path)
    mesh.add_argument("--size", type=float, required=True,
                      help="largest element size, in the length unit of the .geo file (R0 for the shipped ones)")
    mesh.add_argument("--out", type=Path, required=True, help="target .msh file")
    mesh.add_argument("--order", type=int, choices=(1, 2), default=1, help="geometry order")
    mesh.add_argument("--trust-geo", action="store_true", help="hand the script to gmsh's own interpreter, "
                      "commands outside the geometry subset included (shell, files, Include, Exit...); only for "
                      "files you trust")
    mesh.add_argument("--geo-timeout", type=float, default=None, metavar="SECONDS",
                      help="time limit for reading and meshing (default 120 s or $BEARINGFE_GEO_TIMEOUT)")
    mesh.add_argument("--max-elements", type=int, default=None, metavar="N",
                      help="largest number of triangles (default 1000000 or $BEARINGFE_MAX_ELEMENTS)")

    val = sub.add_parser("validate", help="compare with closed forms and published data")
    val.add_argument("--quick", action="store_true", help="coarser meshes")
    val.add_argument("--only", action="append", metavar="CHECK", help="run only this check (repeatable)")
    sweep = sub.add_parser("sweep", help="run a design study (docs/sweeps.md)")
    sweep.add_argument("study", type=Path, help="study file, e.g. studies/pocket_study.toml")
    sweep.add_argument("--out", type=Path, required=True, help="output directory (results, cache)")
    sweep.add_argument("--scheduler", default=None, help="Dask scheduler tcp://HOST:8786 or local[:N]")
    sweep.add_argument("--force", action="store_true", help="write into DIR even if it holds files and no "
                       "previous bearingfe output (those files are kept)")
    sweep.add_argument("--no-progress", action="store_true", help="no progress bar")
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line ``argv`` (default ``sys.argv[1:]``); returns the exit code."""
    return _main(argv)[0]


def command(argv: Sequence[str] | None = None) -> NoReturn:
    """The ``bearingfe`` command: :func:`main`, then this process ends with its exit code.

    After ``run`` it ends at once, without Python's teardown of its modules (numpy, scipy, matplotlib,
    scikit-fem: about a tenth of a second of the main scene, spent on nothing a user sees): by then the
    command has closed its files, moved them into place, removed its work folder and ended its
    processes; the output streams are flushed first. Other commands (a sweep's Dask workers) end the
    usual way."""
    code, name = _main(argv)
    if name in _NO_TEARDOWN:
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(OSError, ValueError):
                stream.flush()
        os._exit(code)
    sys.exit(code)


#: Commands after which :func:`command` ends the process without the interpreter's teardown.
_NO_TEARDOWN = frozenset({"run"})


def _main(argv: Sequence[str] | None) -> tuple[int, str | None]:
    """The exit code and the command's name (None before a command was read)."""
    parser = _parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # --help, --version, usage errors
        return int(exc.code or 0), None
    commands = {"run": _run, "mesh": _mesh, "validate": _validate, "sweep": _sweep}
    name = args.command
    try:
        with _one_line_warnings(name), _sigterm_exits():
            return commands[name](args), name
    except (ValueError, OSError, ImportError) as exc:  # bad input, file system, missing optional package
        print(f"bearingfe {name}: error: {_one_line(exc)}", file=sys.stderr)
        return 2, name
    except (RuntimeError, ArithmeticError) as exc:
        print(f"bearingfe {name}: failed: {_one_line(exc)}", file=sys.stderr)
        return 1, name
    except KeyboardInterrupt:
        print(f"bearingfe {name}: interrupted", file=sys.stderr)
        return 130, name


@contextlib.contextmanager
def _one_line_warnings(command: str):
    """Show warnings (e.g. a cache record recomputed) as one line each: ``bearingfe CMD: note: ...``."""
    def show(message, category, filename, lineno, file=None, line=None):
        print(f"bearingfe {command}: note: {_one_line(message)}", file=sys.stderr)

    with warnings.catch_warnings():
        warnings.showwarning = show
        yield


@contextlib.contextmanager
def _sigterm_exits():
    """SIGTERM ends the command like Ctrl-C (so work folders and sweep workers are cleaned up)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def stop(signum, frame):
        raise KeyboardInterrupt

    before = signal.signal(signal.SIGTERM, stop)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, before)


def _sweep(args) -> int:
    """``bearingfe sweep STUDY.toml --out DIR [--scheduler ADDRESS] [--force]``.

    Writes ``DIR/results.csv`` (the table, headers with units), ``DIR/best.json``
    (the best design) and ``DIR/cache/`` (per-case records: rerunning resumes).
    ``DIR`` follows the rules of ``run --out`` (:mod:`bearingfe.io.outfolder`):
    the table and the best design replace only a previous sweep's, a folder
    with other files needs ``--force``; the cache folder is written as cases
    finish (a killed sweep resumes). A case whose film closes is a result of
    the study: ``status`` "ruptured" in the table, counted on the summary line.
    Exit code 0 if no case failed for another reason, 1 if some did (they are
    in the table, ``status`` "failed"), 2 if the study file is invalid or no
    case completed.
    """
    from .io.outfolder import output_folder
    from .io.writers import write_json
    from .sweep import CACHE_FILES, best_design, csv_headers, read_study, si_columns, sweep

    study = read_study(args.study)  # ValueError -> exit code 2 in main()
    out = Path(args.out)
    no_best = None
    with output_folder(out, force=args.force, keep=[args.study], own={"cache": CACHE_FILES}) as work:
        _remove_temporaries(out / "cache")
        client = _client_for(args.scheduler) if args.scheduler else None
        try:
            table = sweep(study.base, study.changes, study.outputs, run=study.run, client=client,
                          cache=out / "cache", progress=not args.no_progress, time_limit=study.time_limit)
        finally:
            if client is not None:
                cluster = client.cluster if args.scheduler.startswith("local") else None
                client.close()
                if cluster is not None:
                    cluster.close()
        table = si_columns(table, study.scale)  # a shoe study with [scale]: SI beside the non-dimensional
        table.rename(columns=csv_headers(table.columns, study.run)).to_csv(work / "results.csv", index=False)
        try:
            best = best_design(table, study.objective, study.sense)
        except ValueError as exc:  # no case succeeded: the table is still written
            no_best = exc
        else:
            write_json({k: (v.item() if hasattr(v, "item") else v) for k, v in best.items()}, work / "best.json")
    counts = table["status"].value_counts()
    failed, ruptured = int(counts.get("failed", 0)), int(counts.get("ruptured", 0))
    print(f"{_printable(study.name)}: {len(table)} cases: {int(counts.get('completed', 0))} completed, "
          f"{ruptured} ruptured (the film closed: a result, status 'ruptured' in the table), {failed} failed; "
          f"{int(table['cached'].sum())} from cache; table in {_printable(out / 'results.csv')}")
    if no_best is not None:
        raise no_best
    changed = table.columns[:table.columns.get_loc("seconds")]
    headers = csv_headers(list(changed), study.run)  # "name [unit]" where the unit is known
    print(f"best ({study.sense} {study.objective}): "
          + ", ".join(_printable(f"{headers.get(k, k)}={best[k]:.6g}" if isinstance(best[k], float)
                                 else f"{headers.get(k, k)}={best[k]}") for k in changed))
    return 1 if failed else 0


def _remove_temporaries(cache: Path) -> None:
    """Remove record temporaries a killed sweep left in its cache folder (names only the package makes)."""
    if cache.is_dir() and not cache.is_symlink():
        for path in cache.iterdir():
            if _CACHE_TEMPORARY.fullmatch(path.name) and path.is_file() and not path.is_symlink():
                path.unlink()


_CACHE_TEMPORARY = re.compile(r"\.[0-9a-f]{24}\.json\.tmp")


def _client_for(scheduler: str):
    """A Dask client: ``"local"`` / ``"local:N"`` starts a LocalCluster of N workers,
    anything else is a scheduler address (``tcp://host:8786``). The local workers end with this process
    (even on SIGKILL): the preload :func:`bearingfe.sweep.workers.dask_setup` ties them to it."""
    from distributed import Client, LocalCluster

    if scheduler == "local" or scheduler.startswith("local:"):
        n = int(scheduler.partition(":")[2] or (os.cpu_count() or 1))
        return Client(LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                   preload=["bearingfe.sweep.workers"]))
    return Client(scheduler)


def _one_line(exc: BaseException | str) -> str:
    return _printable(" ".join(str(exc).split()) or type(exc).__name__)


def _printable(text: str) -> str:
    """``text`` with terminal escapes and other control characters shown as ``\\x1b``-style escapes."""
    return "".join(ch if ch.isprintable() else repr(ch)[1:-1] for ch in str(text))


# -- run --------------------------------------------------------------------------

def _run(args) -> int:
    from .core.lazy import without_collections

    with without_collections():  # the scene kind's modules load with the collector off
        from .io.outfolder import output_folder
        from .scenes import SCENES, load_scene, run_scene

        data, _ = load_scene(args.scene)  # fail on the scene file before touching the output directory
        SCENES[data["kind"]]
    with output_folder(args.out, force=args.force, keep=[args.scene]) as work:
        with _progress(not args.no_progress) as tick:
            summary = run_scene(args.scene, work, tick)
    print(f"{_printable(summary.get('title', args.scene.name))}: results in {_printable(args.out)}")
    print(_table(summary.get("table", [])))
    return 0


class _progress:
    """A tqdm bar driven by ``tick(done, total, what)`` (a no-op when disabled)."""

    def __init__(self, enabled: bool):
        self.enabled, self.bar = enabled, None

    def __enter__(self):
        return self.tick

    def tick(self, done: int, total: int, what: str) -> None:
        if not self.enabled:
            return
        if self.bar is None:
            from tqdm import tqdm

            self.bar = tqdm(total=total, file=sys.stderr, leave=False, dynamic_ncols=True)
        if self.bar.total != total:
            self.bar.total = total
        self.bar.set_description(what)
        self.bar.update(done - self.bar.n)

    def __exit__(self, *exc):
        if self.bar is not None:
            self.bar.close()
        return False


def _table(rows) -> str:
    if not rows:
        return ""
    cells = [(_printable(q), _printable(_fmt(v)), _printable(u)) for q, v, u in rows]
    w = [max(len(c[i]) for c in cells) for i in range(3)]
    lines = [f"{'quantity':<{w[0]}}  {'value':>{w[1]}}  unit", "-" * (w[0] + w[1] + w[2] + 4)]
    lines += [f"{q:<{w[0]}}  {v:>{w[1]}}  {u}" for q, v, u in cells]
    return "\n".join(lines)


def _fmt(value) -> str:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return str(value)
    return str(value) if isinstance(value, int) else f"{value:.6g}"


# -- mesh -------------------------------------------------------------------------

def _mesh(args) -> int:
    """``bearingfe mesh FILE.geo --size S --out FILE.msh``: the file is read by bearingfe's parser of
    the geometry subset (gmsh's interpreter only with ``--trust-geo``) and meshed by gmsh in a separate
    process with a time limit; the element count is estimated first (bearingfe.geometry.geofiles)."""
    from .geometry.geofiles import run_geo
    from .io.writers import atomic_path
    from .geometry.meshing import load_mesh

    geo, out = args.geo, args.out
    if not geo.is_file():
        raise FileNotFoundError(f"geometry file not found: {geo}")
    if geo.suffix != ".geo":
        raise ValueError(f"FILE must be a gmsh .geo file, got {geo.name}")
    if out.suffix != ".msh":
        raise ValueError(f"--out must end in .msh, got {out.name}")
    if not (args.size > 0 and args.size < float("inf")):
        raise ValueError(f"--size must be a finite element size > 0, got {args.size}")
    out.parent.mkdir(parents=True, exist_ok=True)
    # gmsh writes into a private temporary folder (the system's: a kill during meshing leaves nothing next to
    # --out); only the checked result is copied to a temporary name beside --out and renamed onto it
    with private_tempdir("mesh") as work:
        made = Path(work) / out.name
        run_geo(geo, made, size=args.size, order=args.order, trusted=args.trust_geo, timeout=args.geo_timeout,
                max_elements=args.max_elements)
        mesh = load_mesh(made, max_elements=args.max_elements)  # the file must load with its named boundaries
        with atomic_path(out) as tmp:
            shutil.copyfile(made, tmp)
    names = ", ".join(sorted(mesh.boundaries))
    print(f"{out}: {mesh.n_nodes} nodes, {mesh.n_elements} triangles, boundaries: {names}")
    return 0


# -- validate ---------------------------------------------------------------------

def _validate(args) -> int:
    from .validation import run_checks

    rows = run_checks(quick=args.quick, names=args.only)
    w = max(len(r.name) for r in rows)
    print(f"{'check':<{w}}  {'computed':>12}  {'expected':>12}  {'rel. error':>10}  {'tol':>7}  ok    reference")
    for r in rows:
        print(f"{r.name:<{w}}  {r.computed:>12.6g}  {r.expected:>12.6g}  {r.error:>10.2e}  {r.tolerance:>7.0e}  "
              f"{'yes' if r.passed else 'NO ':<4}  {r.reference}")
    failed = [r.name for r in rows if not r.passed]
    print(f"{len(rows) - len(failed)} of {len(rows)} passed" + (f"; failed: {', '.join(failed)}" if failed else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    command()
