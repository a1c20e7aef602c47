"""The kinds section of the benchmark page says what its own tables say.

``docs/benchmarks_parts/kinds.md`` is written by ``benchmarks/run_all.py`` (part ``kinds``,
:mod:`benchmarks.solver_kinds`). Expected values: the 4 GiB verdict of the linear P1 solve at 1e6 unknowns
and the largest peak of each memory breakdown are re-derived from the tables on the same page (timings and
memory are never asserted, only that the sentences follow the tables).
"""

import re

from tests.helpers import ROOT, markdown_table

PAGE = ROOT / "docs" / "benchmarks_parts" / "kinds.md"


def test_the_4_gib_verdict_follows_the_table():
    text = PAGE.read_text()
    _, rows = markdown_table(text, "| kind | dofs |")
    largest = [r for r in rows if r[0] == "linear P1" and r[1].isdigit() and int(r[1]) >= 9e5 and r[3] != "-"]
    assert largest, "the linear P1 solve must have run at 1e6 unknowns"
    match = re.search(r"Linear P1 at (\d+) unknowns: peak (\d+) MiB of the process, (within|over) the budget of "
                      r"(\d+) MiB", text)
    assert match
    assert match[1] == largest[0][1] and match[2] == largest[0][3]
    assert match[3] == ("within" if int(match[2]) <= int(match[4]) else "over")
    assert int(match[4]) == 4096


def test_the_largest_peaks_follow_the_breakdown():
    text = PAGE.read_text()
    head, rows = markdown_table(text, "| stage |")
    assert len(head) >= 3 and len(rows) >= 8  # P1 and P2 at two sizes; mesh .. result
    for j, column in enumerate(head[1:], start=1):
        name = column.split(":")[0]  # e.g. "P1 101025"
        peaks = {r[0]: float(r[j].split("/")[1]) for r in rows if r[j] != "-"}
        match = re.search(re.escape(name) + r": (\d+) MiB at the (.+?) \((\d+) bytes per unknown\)", text)
        assert match, name
        assert float(match[1]) == max(peaks.values())
        assert peaks[match[2].strip()] == max(peaks.values())
        dofs = int(name.split()[1])
        assert abs(int(match[3]) - float(match[1]) * 2**20 / dofs) <= 0.5 * 2**20 / dofs + 1
