"""Output folders: replace only what this package wrote there, all at once, one run at a time.

:func:`output_folder` is how ``bearingfe run --out DIR`` writes:

- a run writes into a hidden work folder ``DIR/.bearingfe-work-XXXXXXXX``
  (marked as the package's by a file ``.bearingfe-work`` inside it); the
  files are moved into ``DIR`` only when all of them are written, so ``DIR``
  holds either the previous results or the new ones;
- ``DIR/.bearingfe-manifest.json`` lists the files a run wrote with their
  SHA-256; the next run replaces or removes those files only, and only
  while their content is still what the package wrote. Every other file in
  ``DIR`` is left alone, ``--force`` or not; a new output whose name is
  taken by such a file is an error, never an overwrite. Files given as
  ``keep`` (the scene file) are never replaced or removed;
- a folder that holds files but no manifest is not a previous output: it is
  written into only when the caller says so (``force=True``, ``--force``);
- the folder is locked (``flock`` on the folder itself) for the whole run:
  a second run into the same folder fails at once with
  :class:`OutputFolderError` instead of mixing or losing results;
- the move into place is journalled in ``DIR/.bearingfe-commit.json`` and
  done with SIGINT/SIGTERM/SIGHUP held back; a process killed in those few
  renames (SIGKILL) leaves the journal, and the next run into ``DIR``
  finishes the move first. Work folders left by a killed run are removed by
  the next run (only folders carrying the mark).
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import shutil
import signal
import tempfile
import threading
from pathlib import Path, PurePosixPath
from typing import Iterable, Iterator

from .writers import atomic_path
from ..version import __version__

__all__ = ["MANIFEST", "OutputFolderError", "lock_folder", "output_folder", "read_manifest"]

MANIFEST = ".bearingfe-manifest.json"
JOURNAL = ".bearingfe-commit.json"
WORK_PREFIX = ".bearingfe-work-"
WORK_MARK = ".bearingfe-work"
_OURS = (MANIFEST, JOURNAL)


class OutputFolderError(ValueError):
    """The output folder cannot be written as asked (foreign files, a taken name, another run)."""


# -- lock -------------------------------------------------------------------------

@contextlib.contextmanager
def lock_folder(folder: Path) -> Iterator[None]:
    """Hold an exclusive ``flock`` on ``folder`` (a directory); fail at once if another process holds it."""
    import fcntl

    fd = os.open(folder, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise OutputFolderError(f"{folder}: another bearingfe run is writing into this folder "
                                    f"(it holds the folder's lock); wait for it or choose another folder") from None
        yield
    finally:
        os.close(fd)


# -- manifest ----------------------------------------------------------------------

def _sha256(path: Path) -> str:
    digest = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def _safe(folder: Path, rel) -> Path | None:
    """``folder / rel`` if ``rel`` is a plain relative path that stays inside ``folder``, else None."""
    if not isinstance(rel, str) or not rel or "\\" in rel or "\0" in rel:
        return None
    parts = PurePosixPath(rel).parts
    if PurePosixPath(rel).is_absolute() or any(p in ("", ".", "..") for p in parts) or parts[0] in _OURS:
        return None
    path = folder.joinpath(*parts)
    try:
        if not path.parent.resolve().is_relative_to(folder.resolve()):
            return None
    except OSError:
        return None
    return path


def _is_ours(path: Path, sha: str) -> bool:
    """True if ``path`` is a regular file (not a link) whose content has hash ``sha``."""
    try:
        return path.is_file() and not path.is_symlink() and _sha256(path) == sha
    except OSError:
        return False


def read_manifest(folder: str | Path) -> dict[str, str] | None:
    """Files of the previous run still as it wrote them: ``{relative path: sha256}``.

    None if ``folder`` has no readable manifest. Entries that leave the
    folder, are not files or were changed since are dropped (they are no
    longer the package's to replace).
    """
    folder = Path(folder)
    try:
        data = json.loads((folder / MANIFEST).read_text())
        files = data["files"]
        if not isinstance(files, dict):
            return None
    except (OSError, ValueError, KeyError, TypeError):
        return None
    return {rel: sha for rel, sha in files.items()
            if isinstance(sha, str) and (p := _safe(folder, rel)) is not None and _is_ours(p, sha)}


# -- the folder ----------------------------------------------------------------------

def _work_folders(folder: Path) -> list[Path]:
    return [p for p in folder.iterdir() if p.name.startswith(WORK_PREFIX) and p.is_dir()
            and not p.is_symlink() and (p / WORK_MARK).is_file()]


def _foreign(folder: Path) -> list[str]:
    work = set(_work_folders(folder))
    return sorted(p.name for p in folder.iterdir() if p.name not in _OURS and p not in work)


@contextlib.contextmanager
def output_folder(out: str | Path, *, force: bool = False, keep: Iterable[str | Path] = ()) -> Iterator[Path]:
    """Yield an empty work folder inside ``out``; move its files into ``out`` when the block succeeds.

    Parameters
    ----------
    out : str or Path
        The output folder (created if missing; removed again if the run fails
        and it is still empty).
    force : bool
        Write into a folder that holds files but no manifest of a previous
        run. Files not written by the package survive either way.
    keep : iterable of path
        Files never replaced or removed (e.g. the scene file, which may live
        in ``out``).

    Raises
    ------
    OutputFolderError
        ``out`` holds foreign files (without ``force``), a new output's name
        is taken by a file the package did not write or by a ``keep`` file,
        or another run holds the folder's lock.
    NotADirectoryError
        ``out`` exists and is not a folder.
    """
    out = Path(out).absolute()
    if out.exists() and not out.is_dir():
        raise NotADirectoryError(f"--out {out}: exists and is not a folder")
    created = not out.exists()
    out.mkdir(parents=True, exist_ok=True)
    keep = {Path(k).resolve() for k in keep}
    try:
        with lock_folder(out):
            _finish_journal(out)
            for stale in _work_folders(out):  # left by a killed run (we hold the lock: no run is using it)
                shutil.rmtree(stale, ignore_errors=True)
            old = read_manifest(out)
            foreign = _foreign(out)
            if old is None and foreign and not force:
                raise OutputFolderError(f"--out {out} holds files that are not a bearingfe output "
                                        f"({', '.join(foreign[:3])}{', ...' if len(foreign) > 3 else ''}); "
                                        f"choose another folder or pass --force (they are kept either way)")
            work = Path(tempfile.mkdtemp(prefix=WORK_PREFIX, dir=out))
            try:
                (work / WORK_MARK).write_text("a bearingfe run's work folder; removed by the next run\n")
                yield work
                _commit(out, work, old or {}, keep)
            finally:
                shutil.rmtree(work, ignore_errors=True)
    except BaseException:
        if created:
            with contextlib.suppress(OSError):
                out.rmdir()  # only if still empty
        raise


def _written(work: Path) -> list[str]:
    files = []
    for root, dirs, names in os.walk(work):
        dirs.sort()
        for name in sorted(names):
            rel = (Path(root) / name).relative_to(work).as_posix()
            if rel != WORK_MARK:
                files.append(rel)
    return files


def _commit(out: Path, work: Path, old: dict[str, str], keep: set[Path]) -> None:
    new = {}
    for rel in _written(work):
        target = _safe(out, rel)
        if target is None:
            raise OutputFolderError(f"--out {out}: cannot write {rel!r} there")
        if target.resolve() in keep:
            raise OutputFolderError(f"--out {out}: an output is named {rel!r} like the scene file, which is "
                                    f"never overwritten; keep the scene file elsewhere")
        if (target.exists() or target.is_symlink()) and rel not in old:
            raise OutputFolderError(f"--out {out}: {rel} is there and was not written by bearingfe; it is never "
                                    f"overwritten: move it away or choose another folder")
        new[rel] = _sha256(work / rel)
    remove = {rel: sha for rel, sha in old.items() if rel not in new and (out / rel).resolve() not in keep}
    journal = {"work": work.name, "replace": sorted(new), "remove": remove, "manifest": new}
    with atomic_path(out / JOURNAL) as tmp:
        tmp.write_text(json.dumps(journal, indent=1))
    with _signals_held():
        _apply(out, journal)


@contextlib.contextmanager
def _signals_held() -> Iterator[None]:
    """Hold back SIGINT, SIGTERM and SIGHUP: record them and deliver them again on exit.

    The Python handlers are swapped (a blocked signal mask would not do: a
    process-directed signal then goes to another thread, and Python raises in
    the main thread anyway). Only from the main thread, where handlers live.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []
    before = {}
    for sig in (signal.SIGINT, signal.SIGTERM, getattr(signal, "SIGHUP", None)):
        if sig is not None and signal.getsignal(sig) is not None:
            before[sig] = signal.signal(sig, lambda signum, frame: caught.append(signum))
    try:
        yield
    finally:
        for sig, handler in before.items():
            signal.signal(sig, handler)
        for sig in dict.fromkeys(caught):
            signal.raise_signal(sig)


def _apply(out: Path, journal: dict) -> None:
    """Move the work folder's files into place, remove the old outputs, write the manifest."""
    work = out / journal["work"]
    for rel in journal["replace"]:
        src, dst = work / rel, _safe(out, rel)
        if dst is not None and src.is_file():
            dst.parent.mkdir(parents=True, exist_ok=True)
            os.replace(src, dst)
    for rel, sha in journal["remove"].items():
        path = _safe(out, rel)
        if path is not None and _is_ours(path, sha):
            path.unlink()
    with atomic_path(out / MANIFEST) as tmp:
        tmp.write_text(json.dumps({"written_by": f"bearingfe {__version__}", "files": journal["manifest"]},
                                  indent=1))
    (out / JOURNAL).unlink()
    shutil.rmtree(work, ignore_errors=True)


def _finish_journal(out: Path) -> None:
    """Finish a move into place that a killed run left half done (its journal is still there)."""
    try:
        journal = json.loads((out / JOURNAL).read_text())
    except FileNotFoundError:
        return
    except (OSError, ValueError):
        return  # not ours to read: left alone
    ok = (isinstance(journal, dict) and isinstance(journal.get("work"), str)
          and journal["work"].startswith(WORK_PREFIX) and "/" not in journal["work"]
          and isinstance(journal.get("replace"), list) and isinstance(journal.get("remove"), dict)
          and isinstance(journal.get("manifest"), dict) and (out / journal["work"] / WORK_MARK).is_file())
    if ok:
        with _signals_held():
            _apply(out, journal)
