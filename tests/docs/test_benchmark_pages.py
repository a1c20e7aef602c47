"""The generated benchmark pages say what their own tables say.

``docs/benchmarks.md`` and ``docs/benchmarks_pump.md`` are written by
``benchmarks/run_all.py`` and ``benchmarks/pump_revolution.py``; these tests
re-derive the sentences and verdicts that quote numbers from the tables on
the same page, so a page edited by hand or a script that words a verdict
wrongly fails here (timings themselves are never asserted).
"""

import re

import pytest
from tests.helpers import ROOT, markdown_table

DOCS = ROOT / "docs"


def _rows(text: str, header_start: str) -> list[list[str]]:
    return markdown_table(text, header_start)[1]


def test_pump_page_names_its_cheapest_run_within_a_tenth_of_a_percent():
    text = (DOCS / "benchmarks_pump.md").read_text()
    rows = _rows(text, "| element | mesh size")
    ok = [r for r in rows if float(r[7]) < 1e-3]
    match = re.search(r"Cheapest run within 0\.1 % of the converged smallest film: (P\d) on mesh ([\d.]+) R0 "
                      r"\((\d+) nodes\), (\w+) rtol ([\de.+-]+): \*\*([\d.]+) s per revolution", text)
    if not ok:
        assert "No case reached 0.1 %" in text
        return
    assert match, "the page must name the cheapest run within 0.1 %"
    best = min(ok, key=lambda r: float(r[5]))
    assert (match[1], match[2], match[4]) == (best[0], best[1], best[3])
    assert float(match[5]) == pytest.approx(float(best[4]))
    assert float(match[6]) == pytest.approx(float(best[5]))


def test_target_verdicts_follow_the_measured_numbers():
    text = (DOCS / "benchmarks.md").read_text()
    rows = _rows(text, "| target |")
    assert len(rows) >= 5
    for what, goal, measured, verdict, _ in rows:
        number = re.match(r"([\d.e+-]+)", measured)
        if "not measured" in measured.split("(")[0] or number is None:
            assert verdict in ("not measured", "no goal"), what
            continue
        value = float(number[1])
        bound = re.match(r"<= ([\d.]+) (?:s|yardsticks)$", goal)  # seconds, or the scene's yardsticks
        if bound:
            assert verdict == ("met" if value <= float(bound[1]) else "NOT met"), what
        factor = re.match(r">= ([\d.]+)x", goal)
        if factor:
            speedups = [float(x) for x in re.findall(r"([\d.]+)x", measured)]
            assert verdict == ("met" if max(speedups) >= float(factor[1]) else "NOT met"), what
        if goal.startswith("5x faster"):
            speedup = float(re.search(r"([\d.]+)x$", measured)[1])  # "(more than) N x" at the end
            assert verdict == ("met" if speedup >= 5 else "NOT met"), what
        if goal == "within 0.1 %":
            error = float(re.search(r"error ([\d.e+-]+)", measured)[1])
            assert verdict == ("met" if error < 1e-3 else "NOT met"), what


def test_the_scaling_page_is_the_kinds_part():
    # docs/scaling.md is written by benchmarks/run_all.py from the stored part `kinds` (OWN_PAGES): the same text
    # under its own heading, so the page and the benchmark page's section cannot drift apart
    from benchmarks.run_all import OWN_PAGES, own_page

    page_name, heading = OWN_PAGES["kinds"]
    stored = (DOCS / "benchmarks_parts" / "kinds.md").read_text()
    assert (DOCS / page_name).read_text() == own_page("kinds", heading, stored)
    assert "time exponent" in stored and "where it stops" in stored and "scaling_kinds_time.png" in stored
