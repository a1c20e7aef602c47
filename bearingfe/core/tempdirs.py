"""Private temporary folders that a killed process does not leave behind for good.

A ``with`` block's temporary folder is removed when the block ends, also on
Ctrl-C and SIGTERM (the command line turns it into KeyboardInterrupt); a
SIGKILL (or a power cut) ends the process before any clean-up can run. So
each folder made here carries its owner: its name is
``bearingfe-<kind>-<pid>-<random>`` in the system's temporary folder and it
holds a mark file naming its own inode. Every new folder first removes the
folders of earlier processes that are gone: only folders whose name has the
pattern, that belong to this user, whose mark names the folder's own inode
(made by this package, not copied or look-alike) and whose process no
longer runs. A folder of a running process is never touched.
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import shutil
import tempfile
from pathlib import Path
from typing import Iterator

__all__ = ["private_tempdir", "remove_stale_tempdirs"]

MARK = ".bearingfe-temporary"
_NAME = re.compile(r"bearingfe-([a-z]+)-([0-9]+)-[A-Za-z0-9_]+")


@contextlib.contextmanager
def private_tempdir(kind: str, parent: str | Path | None = None) -> Iterator[Path]:
    """A temporary folder ``bearingfe-<kind>-<pid>-<random>``, removed on exit; stale ones removed first.

    Parameters
    ----------
    kind : str
        Lower-case letters naming what it is for (``"mesh"``, ``"geo"``, ``"shoe"``).
    parent : path, optional
        Where to make it (default the system's temporary folder).
    """
    if not re.fullmatch(r"[a-z]+", kind):
        raise ValueError(f"kind must be lower-case letters, got {kind!r}")
    parent = Path(parent if parent is not None else tempfile.gettempdir())
    remove_stale_tempdirs(parent)
    folder = Path(tempfile.mkdtemp(prefix=f"bearingfe-{kind}-{os.getpid()}-", dir=parent))
    try:
        (folder / MARK).write_text(json.dumps({"inode": folder.stat().st_ino, "pid": os.getpid()}))
        yield folder
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def remove_stale_tempdirs(parent: str | Path | None = None) -> list[Path]:
    """Remove the folders of :func:`private_tempdir` whose process has ended; returns those removed."""
    parent = Path(parent if parent is not None else tempfile.gettempdir())
    removed = []
    try:
        entries = list(parent.iterdir())
    except OSError:
        return removed
    for path in entries:
        match = _NAME.fullmatch(path.name)
        if match is None or int(match.group(2)) == os.getpid():
            continue
        if _ours(path) and not _running(int(match.group(2))):
            shutil.rmtree(path, ignore_errors=True)
            removed.append(path)
    return removed


def _ours(path: Path) -> bool:
    """A real folder of this user whose mark names its own inode."""
    try:
        info = path.lstat()
        if path.is_symlink() or not path.is_dir() or info.st_uid != os.getuid():
            return False
        mark = json.loads((path / MARK).read_text())
        return isinstance(mark, dict) and mark.get("inode") == info.st_ino
    except (OSError, ValueError, RecursionError):
        return False


def _running(pid: int) -> bool:
    """True if a process ``pid`` exists (or may: a process of another user counts as running)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError, OSError):
        return True
    return True
