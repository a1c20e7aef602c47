"""Output folders: replace only what this package wrote there, all at once, one run at a time.

:func:`output_folder` is how ``bearingfe run --out DIR`` writes:

- a run writes into a hidden work folder ``DIR/.bearingfe-work-XXXXXXXX``
  (marked as the package's by a file ``.bearingfe-work`` inside it); the
  files are moved into ``DIR`` only when all of them are written, so ``DIR``
  holds either the previous results or the new ones;
- ``DIR/.bearingfe-manifest.json`` lists the files a run wrote with their
  SHA-256, size and inode; the next run replaces or removes those files
  only, and only while they are still the very files the package wrote
  (same inode, same content). A manifest entry that does not match (edited,
  copied from another folder, forged, or a path leaving ``DIR``) is not
  acted on: that file is the user's. Every other file in
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
  finishes the move first. The journal names its work folder by inode: a
  journal that does not match a work folder this package made in ``DIR`` is
  refused (:class:`OutputFolderError`), never acted on. Work folders left by
  a killed run are removed by the next run (only folders whose mark names
  their own inode: a copied or look-alike folder is left alone);
- ``own`` names sub-folders the caller writes directly and keeps between
  runs (a sweep's ``cache``): such a folder holding only files whose names
  the package makes is not foreign; a link or a file in its place is refused.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import shutil
import signal
import tempfile
import re
import threading
from pathlib import Path, PurePosixPath
from typing import Iterable, Iterator, Mapping

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


def _entry(path: Path) -> dict:
    """What a manifest records of a file the package wrote: SHA-256, size [bytes] and inode."""
    info = path.stat()
    return {"sha256": _sha256(path), "size": info.st_size, "inode": info.st_ino}


def _is_ours(path: Path, entry) -> bool:
    """True if ``path`` is a regular file (not a link) that is the very file ``entry`` records.

    Inode, size and SHA-256 must all match: the same content in another file
    (a folder copied from someone else, a forged manifest that lists the
    hash of a user's file) is not the package's file.
    """
    if not (isinstance(entry, dict) and isinstance(entry.get("sha256"), str)
            and all(isinstance(entry.get(k), int) and not isinstance(entry.get(k), bool) for k in ("size", "inode"))):
        return False
    try:
        if not path.is_file() or path.is_symlink():
            return False
        info = path.stat()
        return (info.st_ino == entry["inode"] and info.st_size == entry["size"]
                and _sha256(path) == entry["sha256"])
    except OSError:
        return False


def read_manifest(folder: str | Path) -> dict[str, dict] | None:
    """Files of the previous run still as it wrote them: ``{relative path: entry}``.

    None if ``folder`` has no readable manifest. Entries that leave the
    folder, are not files, are not the file the package wrote (another
    inode: copied or forged) or were changed since are dropped (they are not
    the package's to replace or remove).
    """
    folder = Path(folder)
    try:
        data = json.loads((folder / MANIFEST).read_text())
        files = data["files"]
        if not isinstance(files, dict):
            return None
    except (OSError, ValueError, KeyError, TypeError, RecursionError):
        return None
    return {rel: entry for rel, entry in files.items()
            if (p := _safe(folder, rel)) is not None and _is_ours(p, entry)}


# -- the folder ----------------------------------------------------------------------

def _is_work(path: Path) -> bool:
    """True if ``path`` is a work folder this package made here: its mark names the folder's own inode."""
    try:
        if not (path.name.startswith(WORK_PREFIX) and path.is_dir() and not path.is_symlink()):
            return False
        mark = json.loads((path / WORK_MARK).read_text())
        return isinstance(mark, dict) and mark.get("inode") == path.stat().st_ino
    except (OSError, ValueError, RecursionError):
        return False


def _work_folders(folder: Path) -> list[Path]:
    return [p for p in folder.iterdir() if _is_work(p)]


def _own_folder_is_ours(path: Path, names: re.Pattern) -> bool:
    """True if ``path`` is a real folder holding only regular files whose names match ``names``."""
    try:
        return all(names.fullmatch(p.name) and p.is_file() and not p.is_symlink() for p in path.iterdir())
    except OSError:
        return False


def _check_own(out: Path, own: Mapping[str, re.Pattern]) -> None:
    for name in own:
        path = out / name
        if (path.exists() or path.is_symlink()) and (path.is_symlink() or not path.is_dir()):
            raise OutputFolderError(f"--out {out}: {name} is there and is not a folder bearingfe made "
                                    f"(a link or a file); move it away or choose another folder")


def _foreign(folder: Path, own: Mapping[str, re.Pattern] = {}) -> list[str]:
    work = set(_work_folders(folder))
    return sorted(p.name for p in folder.iterdir() if p.name not in _OURS and p not in work
                  and not (p.name in own and _own_folder_is_ours(p, own[p.name])))


@contextlib.contextmanager
def output_folder(out: str | Path, *, force: bool = False, keep: Iterable[str | Path] = (),
                  own: Mapping[str, re.Pattern] = {}) -> Iterator[Path]:
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
    own : mapping of str to compiled pattern
        Sub-folders of ``out`` the caller writes directly (not through the
        work folder) and keeps between runs, with the pattern of the file
        names the package makes there (a sweep's ``cache``). Such a folder
        holding only such files does not make ``out`` foreign.

    Raises
    ------
    OutputFolderError
        ``out`` holds foreign files (without ``force``), a new output's name
        is taken by a file the package did not write or by a ``keep`` file,
        an ``own`` name is a link or a file, a commit journal does not match
        a run of this package in ``out``, or another run holds the folder's lock.
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
            _check_own(out, own)
            old = read_manifest(out)
            foreign = _foreign(out, own)
            if old is None and foreign and not force:
                raise OutputFolderError(f"--out {out} holds files that are not a bearingfe output "
                                        f"({', '.join(foreign[:3])}{', ...' if len(foreign) > 3 else ''}); "
                                        f"choose another folder or pass --force (they are kept either way)")
            work = Path(tempfile.mkdtemp(prefix=WORK_PREFIX, dir=out))
            try:
                (work / WORK_MARK).write_text(json.dumps({"inode": work.stat().st_ino, "note": "a bearingfe "
                                                          "run's work folder; removed by the next run"}))
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


def _commit(out: Path, work: Path, old: dict[str, dict], keep: set[Path]) -> None:
    new = {}
    for rel in _written(work):
        target = _safe(out, rel)
        if target is None:
            raise OutputFolderError(f"--out {out}: cannot write {rel!r} there")
        if target.resolve() in keep:
            raise OutputFolderError(f"--out {out}: an output is named {rel!r} like the scene file, which is "
                                    f"never overwritten; keep the scene file elsewhere")
        if (target.exists() or target.is_symlink()) and rel not in old:
            raise OutputFolderError(f"--out {out}: {rel} is there and was not written by bearingfe (or it was "
                                    f"edited since, copied from another folder, or listed by the manifest of an "
                                    f"older version); it is never overwritten: move it away or choose another folder")
        new[rel] = _entry(work / rel)  # os.replace keeps the inode: the entry holds for the moved file
    remove = {rel: entry for rel, entry in old.items() if rel not in new and (out / rel).resolve() not in keep}
    journal = {"work": work.name, "work_inode": work.stat().st_ino, "replace": sorted(new),
               "old": {rel: old[rel] for rel in new if rel in old}, "remove": remove, "manifest": new}
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
    """Move the work folder's files into place, remove the old outputs, write the manifest.

    A target is replaced only if it is absent, is the package's previous
    output (``journal["old"]``) or already the new file (a move finished
    before a kill); a file to remove only while it is the one the package wrote.
    """
    work = out / journal["work"]
    for rel in journal["replace"]:
        src, dst = work / rel, _safe(out, rel)
        if dst is None or not src.is_file() or src.is_symlink():
            continue
        taken = dst.exists() or dst.is_symlink()
        if taken and not _is_ours(dst, journal["old"].get(rel)):
            continue  # not the package's file: never overwritten
        dst.parent.mkdir(parents=True, exist_ok=True)
        os.replace(src, dst)
    for rel, entry in journal["remove"].items():
        path = _safe(out, rel)
        if path is not None and _is_ours(path, entry):
            path.unlink()
    manifest = {rel: entry for rel, entry in journal["manifest"].items()
                if (p := _safe(out, rel)) is not None and _is_ours(p, entry)}
    with atomic_path(out / MANIFEST) as tmp:
        tmp.write_text(json.dumps({"written_by": f"bearingfe {__version__}", "files": manifest}, indent=1))
    (out / JOURNAL).unlink()
    shutil.rmtree(work, ignore_errors=True)


def _finish_journal(out: Path) -> None:
    """Finish a move into place that a killed run left half done (its journal is still there).

    The journal is acted on only if it names a work folder this package made
    in ``out`` by its inode; any other journal (copied, forged, damaged) is
    refused with :class:`OutputFolderError` and left for the user to remove.
    """
    path = out / JOURNAL
    if not (path.exists() or path.is_symlink()):
        return
    try:
        journal = json.loads(path.read_text()) if path.is_file() and not path.is_symlink() else None
    except (OSError, ValueError, RecursionError):
        journal = None
    ok = (isinstance(journal, dict) and isinstance(journal.get("work"), str)
          and _safe(out, journal["work"]) is not None and "/" not in journal["work"]
          and _is_work(out / journal["work"]) and journal.get("work_inode") == (out / journal["work"]).stat().st_ino
          and isinstance(journal.get("replace"), list) and all(isinstance(r, str) for r in journal["replace"])
          and all(isinstance(journal.get(k), dict) for k in ("old", "remove", "manifest")))
    if not ok:
        raise OutputFolderError(f"--out {out}: {JOURNAL} does not match an unfinished run of bearingfe in this "
                                f"folder (copied, edited or damaged); it is not acted on: remove it to go on")
    with _signals_held():
        _apply(out, journal)
