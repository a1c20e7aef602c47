"""Every internal link of the README and the documentation pages resolves: a relative path names a file
that exists, and an anchor ``#name`` names a heading (or an explicit target) of the page it points to.

External links (``http(s)://``, ``mailto:``) cannot be checked without a network and are left to the
site's link check; the Sphinx build (warnings as errors) also fails on a broken cross-reference, but
it does not read the README and takes minutes, so this fast check runs with the tests. Anchors follow
the heading slugs of GitHub and of MyST (``myst_heading_anchors`` in docs/conf.py: headings down to
that level get one): lower case, punctuation dropped, spaces to hyphens.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.helpers import ROOT

DOCS = ROOT / "docs"
#: Pages whose links are checked: the README and every Markdown page of the site (the generated
#: benchmark parts included), not the build's output.
PAGES = sorted([ROOT / "README.md", *(p for p in DOCS.rglob("*.md") if "_build" not in p.parts
                                      and "_generated" not in p.parts)])
#: Fragments that benchmarks/run_all.py pastes into docs/benchmarks.md: their links are relative to docs/.
FRAGMENTS = DOCS / "benchmarks_parts"
#: Written by the site build (the example gallery, docs/_ext/gallery.py), not kept in the repository.
GENERATED = DOCS / "_generated"
_EXTERNAL = re.compile(r"^[a-z][a-z0-9+.-]*:", re.I)  # http:, https:, mailto:, ...
_FENCE = re.compile(r"^(```|~~~).*?^\1", re.S | re.M)
_CODE = re.compile(r"`[^`\n]*`")
_INLINE = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
_REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+.*)?$", re.M)
_HTML = re.compile(r"""<(?:a|img)\s[^>]*?(?:href|src)\s*=\s*["']([^"']+)["']""", re.I)


def _prose(text: str) -> str:
    """The page without its fenced code blocks and inline code (their brackets are not links)."""
    return _CODE.sub("", _FENCE.sub("", text))


def links(text: str) -> list[str]:
    """Targets of the Markdown inline and reference links, images and HTML ``href``/``src`` of a page."""
    prose = _prose(text)
    return [m.group(1) for rx in (_INLINE, _REFERENCE, _HTML) for m in rx.finditer(prose)]


def slug(heading: str) -> str:
    """GitHub's (and MyST's) anchor of a heading: markup and punctuation dropped, lower case, spaces to
    hyphens."""
    text = re.sub(r"`([^`]*)`", r"\1", heading)
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link in a heading keeps its text
    text = re.sub(r"[^\w\- ]", "", text.strip().lower())
    return text.replace(" ", "-")


def anchors(path: Path) -> set[str]:
    """Anchors a page defines: its headings' slugs (repeats numbered ``-1``, ``-2`` as GitHub does;
    in docs/ only the levels MyST gives one), explicit MyST targets ``(name)=`` and HTML ``id``/``name``."""
    text = _FENCE.sub("", path.read_text(encoding="utf-8"))
    depth = 6 if path.parent == ROOT else _myst_depth()
    out, seen = set(), {}
    for hashes, heading in re.findall(r"^(#{1,6})\s+(.+?)\s*#*\s*$", text, flags=re.M):
        if len(hashes) > depth:
            continue
        s = slug(heading)
        n = seen.get(s, 0)
        out.add(s if n == 0 else f"{s}-{n}")
        seen[s] = n + 1
    out.update(re.findall(r"^\(([\w\-.:]+)\)=\s*$", text, flags=re.M))
    out.update(re.findall(r"""<[^>]+\s(?:id|name)\s*=\s*["']([^"']+)["']""", text, flags=re.I))
    return out


def _myst_depth() -> int:
    conf = (DOCS / "conf.py").read_text(encoding="utf-8")
    m = re.search(r"^myst_heading_anchors\s*=\s*(\d+)", conf, flags=re.M)
    return int(m.group(1)) if m else 0


def broken(page: Path) -> list[str]:
    """The internal links of ``page`` that do not resolve, each with the reason."""
    out = []
    for target in links(page.read_text(encoding="utf-8")):
        if _EXTERNAL.match(target):
            continue
        file, _, anchor = target.partition("#")
        base = DOCS if page.parent == FRAGMENTS else page.parent
        dest = page if not file else (base / file).resolve()
        if file and dest.is_relative_to(GENERATED.resolve()):
            continue
        if not dest.exists():
            out.append(f"{target}: no file {dest}")
        elif anchor and dest.suffix == ".md" and anchor not in anchors(dest):
            out.append(f"{target}: no heading or target #{anchor} in {dest.name}")
    return out


def test_the_checked_pages_are_the_site_and_the_readme():
    assert ROOT / "README.md" in PAGES and DOCS / "index.md" in PAGES and len(PAGES) > 20


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_every_internal_link_resolves(page):
    assert broken(page) == []


def test_the_check_finds_broken_links_and_anchors(tmp_path):
    """The checker on a page made for it: one good link of each kind, then each kind broken."""
    (tmp_path / "other.md").write_text("# Other page\n\n## Results: 2 cases (P2)\n\n## Results: 2 cases (P2)\n\n"
                                       "(a-label)=\n### Deep\n")
    (tmp_path / "pic.png").write_bytes(b"")
    page = tmp_path / "page.md"
    page.write_text("# Page\n\n## Local heading\n\n"
                    "[ok](other.md) [ok](other.md#results-2-cases-p2) [ok](other.md#results-2-cases-p2-1) "
                    "[ok](other.md#a-label) ![ok](pic.png) [ok](#local-heading) [ext](https://example.org/x) "
                    "`[code](missing.md)`\n\n```\n[fenced](missing.md)\n```\n\n"
                    "[bad](missing.md) [bad](other.md#nowhere) [bad](#no-such-heading) <img src=\"gone.png\">\n"
                    "[ref]: ../absent/file.md\n")
    found = broken(page)
    assert [f.split(":")[0] for f in found] == ["missing.md", "other.md#nowhere", "#no-such-heading",
                                                "../absent/file.md", "gone.png"]
