"""The host-speed stamp of the generated pages (``benchmarks.common.host_speed``): what it factorizes, how it
times, and where the parts write it. No timing is asserted, only what is timed and where it is written."""

import json

import pytest

from benchmarks import common, run_all


def test_the_yardstick_matrix_is_the_five_point_laplacian():
    a = common.yardstick_matrix()
    n = common.YARDSTICK_GRID
    assert a.shape == (n * n, n * n)
    # 5 entries per row less one per missing neighbour on the border: 5 n^2 - 4 n
    assert a.nnz == 5 * n * n - 4 * n
    assert a.diagonal().min() == a.diagonal().max() == 4.0
    assert abs(a - a.T).max() == 0.0


def test_host_speed_is_the_fastest_cpu_time_of_its_runs(monkeypatch):
    ticks = iter([0.0, 0.5, 1.0, 1.3, 2.0, 2.4])  # runs of 0.5, 0.3, 0.4 s of CPU
    calls = []
    monkeypatch.setattr(common.time, "process_time", lambda: next(ticks))
    monkeypatch.setattr(common, "yardstick_matrix", lambda: "A")
    import scipy.sparse.linalg
    monkeypatch.setattr(scipy.sparse.linalg, "splu", lambda a: calls.append(a))
    assert common.host_speed(runs=3) == pytest.approx(0.3, abs=1e-15)
    assert calls == ["A"] * 3


def test_host_speed_needs_a_run():
    with pytest.raises(ValueError, match="runs must be at least 1, got 0"):
        common.host_speed(runs=0)


def test_a_part_is_stamped_with_the_host_speed_before_and_after(monkeypatch, tmp_path):
    monkeypatch.setattr(run_all, "PARTS_DIR", tmp_path)
    run_all._store("demo", "text\n", {"x": 1.0}, 12.0, False, 0.01, speed=(0.412, 0.437))
    stamp, blank, rest = (tmp_path / "demo.md").read_text().split("\n", 2)
    assert "host speed 0.412 s before and 0.437 s after the runs" in stamp
    assert stamp.startswith("*Part `demo`") and stamp.endswith(".*") and blank == "" and rest == "text\n"
    facts = json.loads((tmp_path / "demo.json").read_text())
    assert (facts["host_speed_before"], facts["host_speed_after"], facts["x"]) == (0.412, 0.437, 1.0)
    run_all._store("plain", "text\n", {}, 1.0, False, 0.0)  # without a measurement: no words about it
    assert "host speed" not in (tmp_path / "plain.md").read_text()
