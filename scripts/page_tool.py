"""What every page script does at the end: write the generated page, or check that the committed one is it.

Used by the ``scripts/make_*`` page generators (``--check``: exit 1 if the committed page is stale)."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Callable

ROOT = Path(__file__).resolve().parents[1]


def page_main(page: Path, make: Callable[[], str], description: str, argv: list[str] | None = None) -> int:
    """Parse ``--check``; write ``make()`` to ``page`` (0), or compare it with the committed page (1 if stale)."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--check", action="store_true", help="exit 1 if the committed page is stale")
    args = parser.parse_args(argv)
    text = make()
    if args.check:
        stale = not page.is_file() or page.read_text(encoding="utf-8") != text
        print(f"{page.relative_to(ROOT)}: {'stale' if stale else 'current'}")
        return 1 if stale else 0
    page.write_text(text, encoding="utf-8")
    print(f"wrote {page.relative_to(ROOT)}")
    return 0
