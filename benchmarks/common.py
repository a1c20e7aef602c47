"""Shared helpers of the benchmark scripts: machine record, timing, tables, plots."""

from __future__ import annotations

import datetime
import math
import os
import platform
import resource
import time
from pathlib import Path
from typing import Callable, Sequence

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
IMG = DOCS / "img"


def machine() -> dict[str, str]:
    """CPU model, cores, memory, Python and library versions, date."""
    import scipy
    import skfem

    import numpy

    cpu = platform.processor() or "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    mem = "unknown"
    try:
        kb = int(next(l for l in Path("/proc/meminfo").read_text().splitlines() if l.startswith("MemTotal")).split()[1])
        mem = f"{kb / 2**20:.1f} GiB"
    except (OSError, StopIteration, ValueError):
        pass
    try:
        import gmsh
        gmsh_version = gmsh.__version__
    except Exception:  # pragma: no cover - gmsh is a core dependency
        gmsh_version = "?"
    return {
        "date": datetime.datetime.now().strftime("%Y-%m-%d %H:%M"),
        "cpu": cpu,
        "cores": str(len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()),
        "memory": mem,
        "os": platform.platform(),
        "python": platform.python_version(),
        "numpy": numpy.__version__,
        "scipy": scipy.__version__,
        "scikit-fem": skfem.__version__,
        "gmsh": gmsh_version,
    }


#: Grid of the yardstick's Laplacian: YARDSTICK_GRID**2 = 90 000 unknowns.
YARDSTICK_GRID = 300


def yardstick_matrix():
    """The 5-point Laplacian on a ``YARDSTICK_GRID`` x ``YARDSTICK_GRID`` grid (CSC, 90 000 unknowns)."""
    import scipy.sparse as sp

    n = YARDSTICK_GRID
    t = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(n, n))
    eye = sp.identity(n)
    return (sp.kron(t, eye) + sp.kron(eye, t)).tocsc()


def host_speed(runs: int = 3) -> float:
    """The host's speed: CPU seconds (``time.process_time``) of one SuperLU factorization (``splu``, COLAMD) of
    :func:`yardstick_matrix` on one BLAS thread, the fastest of ``runs``.

    Stamped on every generated page, before and after its runs: the same code on the same kind of machine reads
    differently when the host behind it is slower, although the container is idle, and an absolute criterion
    (seconds) follows the host, not the code. Two pages' absolute times compare when their host speeds do."""
    from scipy.sparse.linalg import splu

    from bearingfe.core.linalg import dense_threads

    if runs < 1:
        raise ValueError(f"runs must be at least 1, got {runs}")
    a = yardstick_matrix()
    best = math.inf
    with dense_threads(1):
        for _ in range(runs):
            t = time.process_time()
            splu(a)
            best = min(best, time.process_time() - t)
    return best


def host_speed_text(before: float, after: float) -> str:
    """The page's words for :func:`host_speed` measured before and after its runs [s]."""
    return (f"host speed {before:.3f} s before and {after:.3f} s after the runs (CPU time of one SuperLU "
            f"factorization of the {YARDSTICK_GRID} x {YARDSTICK_GRID} Laplacian on one thread: higher is a slower "
            "host; absolute times compare between pages of similar host speed)")


def optional_versions() -> dict[str, str]:
    out = {}
    for mod, name in (("pyamg", "pyamg"), ("pypardiso", "pypardiso"), ("cholespy", "cholespy"),
                      ("sksparse", "scikit-sparse")):
        try:
            m = __import__(mod)
            out[name] = getattr(m, "__version__", "installed")
        except ImportError:
            out[name] = "not installed"
    return out


def timed(fn: Callable, *args, repeat: int = 1, **kwargs):
    """Run ``fn`` ``repeat`` times; return (last result, best wall time [s])."""
    best, out = np.inf, None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn(*args, **kwargs)
        best = min(best, time.perf_counter() - t)
    return out, best


def peak_rss_mib() -> float:
    """Peak resident set size of this process so far [MiB] (Linux: ru_maxrss in KiB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def proc_status_mib(key: str) -> float:
    """A memory line of ``/proc/self/status`` (``VmHWM``: the peak, ``VmRSS``: now) [MiB]; NaN if absent."""
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith(key + ":"):
            return int(line.split()[1]) / 1024.0
    return math.nan


def md_table(header: Sequence[str], rows: Sequence[Sequence]) -> str:
    """A GitHub-markdown table; floats printed with 3 significant digits."""
    def fmt(v):
        if isinstance(v, float):
            if not np.isfinite(v):
                return "-"
            return f"{v:.3g}"
        return str(v)
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(fmt(v) for v in r) + " |" for r in rows]
    return "\n".join(lines)


def loglog_plot(path: Path, series: dict[str, tuple[Sequence[float], Sequence[float]]], *, xlabel: str,
                ylabel: str, title: str) -> str:
    """Write a log-log line plot of ``{label: (x, y)}``; return the path relative to docs/."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    markers = "os^vD<>ph*x+"
    for k, (label, (x, y)) in enumerate(series.items()):
        x, y = np.asarray(x, float), np.asarray(y, float)
        ok = np.isfinite(x) & np.isfinite(y) & (x > 0) & (y > 0)
        if ok.any():
            ax.loglog(x[ok], y[ok], marker=markers[k % len(markers)], label=label,
                      linestyle="--" if label.startswith("FD") else "-")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return str(path.relative_to(DOCS))


def time_at_error(times: Sequence[float], errors: Sequence[float], target: float) -> float:
    """Wall time a method needs for ``target`` error, by log-log interpolation
    between its measured points (NaN if the target is outside their range)."""
    t, e = np.asarray(times, float), np.asarray(errors, float)
    ok = np.isfinite(t) & np.isfinite(e) & (e > 0)
    t, e = t[ok], e[ok]
    if t.size == 0:
        return np.nan
    # walk from cheap to expensive; first segment that brackets the target
    order = np.argsort(t)
    t, e = t[order], e[order]
    if e.min() > target:
        return np.nan
    for i in range(t.size):
        if e[i] <= target:
            if i == 0:
                return float(t[0])
            a, b = np.log(e[i - 1]), np.log(e[i])
            w = (np.log(target) - a) / (b - a) if b != a else 1.0
            return float(np.exp(np.log(t[i - 1]) + w * (np.log(t[i]) - np.log(t[i - 1]))))
    return np.nan


def laplace_floor(meshes, element: str, repeats: int = 5) -> float:
    """Seconds of one film state on ``meshes`` (SupportMesh): the LU and four solves of each mesh's condensed
    matrix (a Laplacian of its mesh and element, Dirichlet on its whole boundary: the pattern and size of the
    film's matrix, ``factorize_splu_sym``), best of ``repeats``: what any method must spend at least once."""
    import skfem
    from skfem.models.poisson import laplace

    from bearingfe.core.linalg import factorize_splu_sym

    e = skfem.ElementTriP2() if element == "P2" else skfem.ElementTriP1()
    systems = []
    for m in meshes:
        basis = skfem.Basis(m.mesh, e)
        A = laplace.assemble(basis)
        interior = basis.complement_dofs(basis.get_dofs())
        systems.append(A[interior][:, interior].tocsc())
    best = math.inf
    for _ in range(repeats):
        t = time.perf_counter()
        for A in systems:
            factorize_splu_sym(A)(np.ones((A.shape[0], 4)))
        best = min(best, time.perf_counter() - t)
    return best
