"""The ``"pump"`` scene: the plunger shoe over the pump cycle, pocket against plain.

Scene file::

    kind = "pump"
    title = "..."                                    # optional
    [pump]
    mechanism = "../mechanisms/eccentric_pump.toml"  # relative to the scene file
    compare_plain = true                             # also run the shoe without its pockets
    [run]
    revolutions = 1.0
    start = "periodic"                               # periodic | steady
    mesh_size = 0.15                                 # element size [R0]
    element = "P2"                                   # P1 | P2 (P2 on a curved mesh)
    rtol = 1e-6
    frames = 12                                      # pressure fields in the PVD series
    cavitation = "none"                              # none | reynolds | gumbel | jfo (jfo: element P1)
    [elastic]
    enabled = false                                  # also run every design on an elastic support
    model = "half-space"                             # half-space | block | shoe (see below)
    dynamics = "squeeze"                             # squeeze | quasi-static (see below)
    [limits]                                         # optional design limits, flagged per design (SI)
    min_film = 8e-6                                  # smallest film [m]
    max_pressure = 35e6                              # peak pressure [Pa]
    max_friction_power = 500.0                       # mean friction power [W]
    max_leakage = 1e-6                               # mean inflow from the pocket [m^3/s]
    [output]
    pictures = ["trajectory", "orbit", "pocket", "pressure", "film", "deflection", "summary"]
    [thermal]
    enabled = false                                  # level-1 heat balance over the cycle (see below)
    grade = "VG 46"                                  # the oil: the [oil] fields of the journal scene
    kinematic_viscosity_100C = 6.8e-6
    supply_temperature_C = 46.0                      # optional: default where the oil has the file's viscosity

Every output is SI (angles in degrees); the solver's non-dimensional values
are kept beside, named as such. Writes ``trajectory_pocket.csv`` and
``trajectory_plain.csv`` (headers ``"name [unit]"``,
:func:`bearingfe.transient.trajectory.report_columns`: with the pocket pressure
[Pa], the restrictor's flow when the pocket is fed through one, and the power
lost at each sample [W]); ``trajectory.png`` and
``orbit.png`` with both designs, the smallest film of each marked;
``pocket.png`` (:func:`bearingfe.plot.curves.pocket_plot`): the chamber and
pocket pressures, the restrictor, pocket and side flows and the friction and
pumping power over the cycle;
``pressure.png`` and ``film.png``: every design at its most loaded state (the
largest plunger force) and at its thinnest film, P2 fields sampled on a
refined display mesh (:mod:`bearingfe.plot.maps`), each map titled with the
design, the shaft angle, the peak pressure [MPa] and the smallest film [um];
``summary.png``, one page for a report (the smallest film of both designs over
the cycle, their pressure at the most loaded state, the figures and the
limits' verdicts); ``pressure.pvd`` with its VTU frames over the cycle
(pressure in Pa, film in m, on the unwrapped surface in metres; time in s,
shaft angle in degrees as field data); and ``summary.json``. The printed
table gives per design the smallest film [um] and where, the peak pressure
[Pa] (the largest over the pictured states and :data:`PEAK_SAMPLES` more),
the mean friction power [W] (mean friction moment times shaft speed, as a
design study's ``friction_loss``), the leakage [l/min] (mean inflow from the
pocket) and side leakage, then the leakage and the power lost over the cycle
(:func:`bearingfe.transient.trajectory.cycle_losses`; ``results.<design>.losses``
in the summary): the pocket pressure (mean, peak) [Pa], the restrictor's,
the pocket's (into the film) and the side flows (mean, peak) [l/min], and the
mean power [W] split into friction and pumping, the pumping being the
restrictor's loss (its flow times its pressure drop, chamber to pocket) and the
film's (the pocket's outflow times the pocket pressure, dropped to the
surroundings); the total is friction plus pumping. Then each set limit with ``ok`` or ``VIOLATED``
(:data:`bearingfe.core.schema.LIMITS`; ``results.<design>.limits`` in the
summary). When the process may use two cores, the designs' rigid runs (each
in a forked process while this one loads the picture modules) and then the
pictures and the PVD frames are shared with forked processes
(:func:`bearingfe.core.parallel.in_processes`; the results are the same).

With ``[elastic] enabled`` every design is run again on the elastic support
(materials ``[shoe.material]`` and ``[eccentric.material]`` of the mechanism
file): ``trajectory_pocket_elastic.csv``, ``trajectory_plain_elastic.csv``,
``pressure_elastic.png``, ``film_elastic.png`` and ``deflection.png`` (the film
opening in um), and the summary compares the smallest film rigid against
elastic, with and without the pocket. ``deflection`` is drawn only then.
``model`` chooses the compliance: ``"half-space"`` (both surfaces elastic
half-spaces, :func:`bearingfe.elastic.half_space`), ``"block"`` (a flat
block of ``[shoe] thickness`` clamped over its back,
:func:`bearingfe.elastic.block_compliance`; ``"body"`` is its old name) or
``"shoe"`` (the real shoe body of the mechanism file: bore, back, seat on
the plunger, lining; gmsh tetrahedra, :func:`bearingfe.elastic.shoe.shoe_compliance`),
the last two with the eccentric as a half-space.
With ``[thermal] enabled`` every rigid design is run again at the
viscosity of its level-1 effective temperature
(:func:`bearingfe.thermal.cycle_temperature`: the cycle-mean heat balance of
the film, the fields of :data:`bearingfe.thermal.files.OIL`, or, when ``[thermal]`` names no
lubricant, the whole ``[oil]`` table of the mechanism file; without
``supply_temperature_C`` the oil is fed at the temperature where it has the
mechanism file's viscosity, so the isothermal run is the shipped model), and
the summary's ``thermal`` table has, per design, the effective and peak film
temperatures, the temperature rise over the cycle and the smallest film with
and without the thermal model. Off by default (the paper's isothermal model).
``dynamics = "squeeze"`` (default) integrates the pressure as a state so that
the rate of the deflection squeezes the film
(:func:`bearingfe.transient.elastic.simulate_elastic`; cavitation "none"
only); ``"quasi-static"`` lets the deflection follow the pressure
(``simulate(elastic=...)``, any cavitation model), which on the shipped pump
closes the plain shoe's film after the inner dead centre.
"""

from __future__ import annotations

import dataclasses
import gc
import time
from pathlib import Path
from typing import Callable

import numpy as np

from ..core.limits import check_limit
from ..core.parameters import ELEMENTS
from ..core.schema import (LIMITS_TABLE, NONNEGATIVE, REQUIRED, SchemaError, Table, anything, build, choice, choices, flag, integer,
                     path_text, positive_number, read_table, text)

__all__ = ["run", "settings", "simulate_design", "pocket_gain", "SPEC", "PICTURES"]

PICTURES = ("trajectory", "orbit", "pocket", "pressure", "film", "deflection", "summary")
#: Support compliances of :mod:`bearingfe.elastic.coupled` by name.
ELASTIC_MODELS = ("half-space", "block", "shoe", "body")
#: How the deflection enters the squeeze term: its rate, or not at all (quasi-static).
DYNAMICS = ("squeeze", "quasi-static")


def _cavitation_models() -> tuple[str, ...]:
    from ..cavitation import MODELS

    return tuple(MODELS)


def _starts() -> tuple[str, ...]:
    from ..transient import STARTS

    return tuple(STARTS)


def _thermal_fields() -> dict:
    from ..thermal.files import OIL

    return {"enabled": (flag, False, "run the level-1 heat balance over the cycle"), **OIL}


#: The ``"pump"`` scene file: ``{name: (check, default) | Table}`` (see :mod:`bearingfe.core.schema`).
SPEC = {
    "kind": (anything, REQUIRED, "the scene kind (this section's name)"),
    "title": (text, None, "title of the pictures and tables (default: the file name)"),
    "pump": Table({"mechanism": (path_text, "../mechanisms/eccentric_pump.toml",
                                 "machine file of the pump (.toml), relative to the scene file"),
                   "compare_plain": (flag, True, "also run the shoe without its pockets")}),
    "run": Table({"revolutions": (positive_number, 1.0, "shaft revolutions to simulate"),
                  "start": (choice(_starts), "periodic", "initial state: the periodic orbit or the steady state"),
                  "mesh_size": (positive_number, 0.08, "element size [R0]"),
                  "rtol": (positive_number, 1e-6, "relative tolerance of the integrator [-]"),
                  "periodic_tol": (positive_number, 1e-6,
                                   "periodic start: largest change of (gamma, delta) over a revolution [-] (a fed "
                                   "pocket on a cavitating film integrates the search at rtol <= periodic_tol / 10)"),
                  "frames": (integer(NONNEGATIVE), 12, "pressure fields in the PVD series"),
                  "cavitation": (choice(_cavitation_models), "none", "cavitation model"),
                  "element": (choice(ELEMENTS), "P2", "finite element (P2 on a curved mesh)")}),
    "elastic": Table({"enabled": (flag, False, "also run every design on an elastic support"),
                      "model": (choice(ELASTIC_MODELS), "half-space", "compliance of the support"),
                      "dynamics": (choice(DYNAMICS), "squeeze", "the deflection's rate squeezes the film, or follows the pressure")}),
    "limits": LIMITS_TABLE,
    "output": Table({"pictures": (choices(PICTURES), PICTURES, "pictures to draw")}),
    "thermal": Table(_thermal_fields()),
}


def settings(data: dict, label: str, base_dir: Path | None = None) -> dict:
    """All validated settings of a ``"pump"`` scene."""
    s = read_table(data, label, "", SPEC)
    path = Path(s["pump"]["mechanism"])
    if not path.is_absolute():
        path = (base_dir or Path.cwd()) / path
    if path.suffix != ".toml":
        raise SchemaError(f"{label}: [pump] mechanism: must name a mechanism file (.toml), got {path.name!r}")
    if not path.is_file():
        raise SchemaError(f"{label}: [pump] mechanism: file not found: {path}")
    if "deflection" in data.get("output", {}).get("pictures", ()) and not s["elastic"]["enabled"]:
        raise SchemaError(f"{label}: [output] pictures: 'deflection' needs [elastic] enabled = true")
    if s["elastic"]["enabled"] and s["elastic"]["dynamics"] == "squeeze" and s["run"]["cavitation"] != "none":
        raise SchemaError(f"{label}: [elastic] dynamics: 'squeeze' needs [run] cavitation = 'none' (the pressure "
                          f"is a state variable); got cavitation {s['run']['cavitation']!r}: use 'quasi-static'")
    thermal = s["thermal"]
    if thermal["enabled"]:
        from ..mechanisms.files import mechanism_oil, oil_given
        from ..thermal.files import check_oil

        if not oil_given(thermal):  # the oil of the mechanism file's [oil] table, if it has one
            machine = build(label, "pump", mechanism_oil, path)
            if machine is None:
                raise SchemaError(f"{label}: [thermal]: names no lubricant (grade with kinematic_viscosity_100C, "
                                  f"kinematic_viscosity or vogel) and the mechanism file has no [oil] table")
            thermal = {**machine, "enabled": True}
        check_oil(thermal, label, "thermal", need_supply=False)
    return {"title": label if s["title"] is None else s["title"], "mechanism": path,
            "compare_plain": s["pump"]["compare_plain"], "run": s["run"], "output": s["output"],
            "elastic": s["elastic"], "limits": s["limits"], "thermal": thermal}


def run(data: dict, label: str, out_dir: Path, progress: Callable | None = None,
                   base_dir: Path | None = None) -> dict:
    """Simulate the pump (and its plain-shoe twin, and both on an elastic support), draw and write the results.

    The objects alive when the run forks its processes are frozen for the garbage collector (``gc.freeze``,
    as Python advises before a fork: the collections of every process then skip the imported modules, a
    tenth of a second of CPU per collection of the oldest generation) and released when the run ends,
    unless something else froze objects before it."""
    mine = gc.get_freeze_count() == 0
    try:
        return _run(data, label, out_dir, progress, base_dir, freeze=gc.freeze if mine else (lambda: None))
    finally:
        if mine:
            gc.unfreeze()


def _run(data: dict, label: str, out_dir: Path, progress: Callable | None, base_dir: Path | None,
         freeze: Callable[[], None]) -> dict:
    from ..core.lazy import without_collections

    with without_collections():  # the modules of the run load with the collector off
        from ..geometry.surface import Surface
        from ..io.writers import write_csv, write_json
        from ..mechanisms.files import load_mechanism
        from ..transient import simulate, simulate_elastic
        from ..transient.trajectory import report_columns

    s = settings(data, label, base_dir)
    check_limit("revolutions", s["run"]["revolutions"])  # before any work (simulate checks it, too)
    check_limit("frames", s["run"]["frames"])
    pump = build(label, "pump", load_mechanism, path=s["mechanism"])
    if s["elastic"]["enabled"] and s["elastic"]["dynamics"] == "squeeze" and pump.shoe_supply is not None:
        raise SchemaError(f"{label}: [elastic] dynamics: 'squeeze' holds the pocket at the chamber pressure; the "
                          "mechanism feeds it through a restrictor ([shoe.supply]): use dynamics = 'quasi-static'")
    designs = {"pocket": pump}
    if s["compare_plain"] and pump.surface.inlets:
        plain = Surface(arc=pump.surface.arc, half_width=pump.surface.half_width)
        designs["plain"] = dataclasses.replace(pump, surface=plain, shoe_supply=None)  # no pocket to feed
    run, pictures, elastic = s["run"], s["output"]["pictures"], s["elastic"]["enabled"]
    if not elastic:
        pictures = tuple(p for p in pictures if p != "deflection")
    steps = len(designs) * (2 if elastic else 1) + len(pictures) + 2
    tick = progress or (lambda done, total, what: None)
    start = time.perf_counter()
    runs, meshes, balance, compliances = {}, {}, {}, {}
    done = 0
    from ..core.parallel import in_processes
    from ..plot import preload

    tick(done, steps, f"simulating: {', '.join(designs)}")
    # the designs are independent: on two free cores each in its own process (the same results); the picture
    # modules load in a thread of this process meanwhile (after the fork: a child must not inherit the import).
    # With pictures, every design goes to a child and this process only loads them: the three share the two
    # cores as the system schedules them, so the import no longer delays one design's run (scene wall A/B 0.97
    # best, 0.88 median); on one core the plainest design (the cheapest run) here, beside the import thread
    loading = []
    order = sorted(designs, key=lambda n: len(designs[n].surface.inlets))
    jobs = [lambda p=designs[n]: _design(p, run) for n in order]
    if pictures and _workers(len(jobs) + 1) > 1:
        jobs.insert(0, lambda: None)  # this process's share: the import thread alone
    freeze()  # before the forks: the collector then skips the imported modules
    results = in_processes(jobs, processes=len(jobs) if len(jobs) > len(order) else None,
                           after_fork=(lambda: loading.append(preload())) if pictures else None)
    rigid = dict(zip(order, results[len(results) - len(order):]))
    states, solved = {}, {}  # the pictured film states by run; the film states re-solved, by sample
    for name, p in designs.items():
        meshes[name], runs[name], states[name], solved[name] = rigid[name]
        balance[name] = runs[name].stats["balance_ratio"]  # simulate checks it before integrating
        done += 1
        if elastic:
            tick(done, steps, f"simulating: {name} on the elastic support")
            compliances[name] = _compliance(p, meshes[name], run["element"], s["elastic"]["model"])
            if s["elastic"]["dynamics"] == "squeeze":
                runs[f"{name}_elastic"] = simulate_elastic(p, compliances[name], run["revolutions"],
                                                           start=run["start"], rtol=run["rtol"])
            else:
                runs[f"{name}_elastic"] = simulate(p, meshes[name], run["revolutions"], start=run["start"],
                                                   rtol=run["rtol"], periodic_tol=run["periodic_tol"],
                                                   cavitation=run["cavitation"],
                                                   element=run["element"], elastic=compliances[name])
            done += 1
    tick(done, steps, "files")
    files = []
    for name, traj in runs.items():
        cols = report_columns(traj, pump.scale, pump.drive.omega)
        files.append(write_csv(cols, out_dir / f"trajectory_{name}.csv", fields=list(cols)).name)
    pumps = {name: designs[name.removesuffix("_elastic")] for name in runs}
    for name, traj in runs.items():  # the elastic runs' (the rigid designs' came with their runs)
        if name not in states:
            solved[name] = {}
            states[name] = _states(pumps[name], meshes[name.removesuffix("_elastic")], traj, run,
                                   compliances[name.removesuffix("_elastic")], solved[name])
    states = {name: states[name] for name in runs}
    tick(done + 1, steps, f"pictures: {', '.join(pictures)}")
    for thread in loading:  # loaded before the pictures fork
        thread.join()
    # the pictures and the PVD frames, shared among the processes by their measured cost (the dearest first,
    # each to the least loaded process; this process is one of them)
    jobs = {name: (lambda name=name: _draw(name, pumps, runs, states, s, out_dir)) for name in pictures}
    if run["frames"] > 0:
        jobs["frames"] = lambda: _frames(pump, meshes["pocket"], runs["pocket"], run, out_dir, solved["pocket"])
    groups = _shares(list(jobs), _workers(len(jobs)))
    freeze()  # the picture modules and the runs too: a picture's collections no longer walk them
    done_jobs = in_processes([lambda g=g: [jobs[name]() for name in g] for g in groups])
    drawn = {name: written for g, out in zip(groups, done_jobs) for name, written in zip(g, out)}
    files += [f for name in (*pictures, "frames") if name in drawn for f in drawn[name]]
    summary = _summary(s, runs, balance, meshes, time.perf_counter() - start, pumps, states)
    if s["thermal"]["enabled"]:
        tick(done, steps, "thermal: level-1 heat balance over the cycle")
        summary["thermal"] = _thermal(s, label, pump, designs, meshes)
        summary["table"][-1:-1] = [row for name, th in summary["thermal"].items() for row in (
            (f"{name}: effective film temperature (level 1)", th["effective_temperature_C"], "degC"),
            (f"{name}: temperature rise over the cycle", th["temperature_rise_K"], "K"),
            (f"{name}: smallest film, level 1", th["smallest_film_m"] * 1e6, "um"))]
    summary["files"] = files + ["summary.json"]
    write_json(summary, out_dir / "summary.json")
    tick(steps, steps, "done")
    return summary


#: The periodic start's tolerance when the run settings do not give one (the transient's default).
PERIODIC_TOL = 1e-6


#: CPU cost of each picture and of the PVD frames [ms] (shipped scene, each alone in a process forked after the
#: picture modules loaded, its first-use costs included, best of five; "deflection" taken as "pressure"): how
#: :func:`run` shares them among processes; the frames reuse the states already solved.
_COSTS = {"pressure": 189.0, "film": 174.0, "deflection": 189.0, "summary": 181.0, "trajectory": 133.0,
          "pocket": 110.0, "orbit": 65.0, "frames": 10.0}
#: Up to this many assignments (``workers ** jobs``) the shares are the best of them all; above,
#: the dearest first to the least loaded share.
_EXACT_SHARES_UP_TO = 4096


def _workers(jobs: int) -> int:
    """The processes :func:`bearingfe.core.parallel.in_processes` would use for ``jobs`` jobs."""
    from ..core import parallel

    return max(1, min(jobs, parallel.cores() if parallel.PROCESSES is None else int(parallel.PROCESSES)))


def _shares(names: list[str], workers: int) -> list[list[str]]:
    """``names`` in ``workers`` groups whose dearest costs least (:data:`_COSTS`): the best assignment
    where there are few, else the dearest first to the least loaded group. Each group dearest first; the
    cheapest group first (this process's: it also forks and collects the others)."""
    cost = {n: _COSTS.get(n, 100.0) for n in names}
    ordered = sorted(names, key=lambda n: -cost[n])
    workers = max(1, min(workers, len(names))) if names else 1
    if workers ** len(names) <= _EXACT_SHARES_UP_TO:
        best = None
        for code in range(workers ** len(names)):
            which = [(code // workers ** i) % workers for i in range(len(names))]
            load = [0.0] * workers
            for n, k in zip(ordered, which):
                load[k] += cost[n]
            if best is None or max(load) < best[0] - 1e-9:
                best = (max(load), which)
        which = best[1]
    else:
        load, which = [0.0] * workers, []
        for n in ordered:
            k = load.index(min(load))
            which.append(k)
            load[k] += cost[n]
    groups = [[n for n, k in zip(ordered, which) if k == g] for g in range(workers)]
    return sorted((g for g in groups if g), key=lambda g: sum(cost[n] for n in g))


def _frames(pump, mesh, traj, run: dict, out_dir: Path, solved: dict) -> list[str]:
    """The PVD series of the pocket design: ``run["frames"]`` pressure fields spread over the run (the
    states :func:`_states` re-solved, ``solved`` by sample, are not solved again)."""
    from ..io.writers import write_pvd
    from ..transient import state_result

    frames = np.unique(np.linspace(0, traj.beta.size - 1, int(run["frames"])).astype(int))
    results = [solved[k] if k in solved else state_result(pump, mesh, traj, k, run["cavitation"], run["element"])
               for k in frames]
    write_pvd(results, traj.t[frames], out_dir / "pressure.pvd", scale=pump.scale, angles=np.degrees(traj.beta[frames]))
    return ["pressure.pvd"]


def simulate_design(pump, run: dict):
    """The mesh and the rigid run of one design with a scene's ``[run]`` settings: the one computation behind
    the scene's comparison, the documented pocket gain and the pump example.

    Parameters
    ----------
    pump : EccentricPump
    run : dict
        ``mesh_size`` [R0], ``element``, ``revolutions``, ``start``, ``rtol`` and ``cavitation`` (as
        ``settings(...)["run"]`` reads them from a scene file).

    Returns
    -------
    (SupportMesh, Trajectory)
    """
    from ..transient import pump_mesh, simulate

    mesh = pump_mesh(pump, run["mesh_size"], order=2 if run["element"] == "P2" else 1)
    return mesh, simulate(pump, mesh, run["revolutions"], start=run["start"], rtol=run["rtol"],
                          cavitation=run["cavitation"], element=run["element"],
                          periodic_tol=run.get("periodic_tol", PERIODIC_TOL))


def _design(pump, run: dict):
    """:func:`simulate_design` and the run's pictured film states (:func:`_states`, with the film states it
    re-solved by sample): one design's share of the scene, made where the design runs."""
    mesh, traj = simulate_design(pump, run)
    solved: dict = {}
    return mesh, traj, _states(pump, mesh, traj, run, None, solved), solved


def pocket_gain(pocket, plain) -> float:
    """Relative gain of the smallest film over the cycle, ``pocket / plain - 1`` [-], of two completed runs."""
    ratio, row = _film_ratio(pocket, plain, "")
    if ratio is None:
        raise ValueError(f"pocket gain {row[0]}")
    return ratio - 1.0


def _thermal(s: dict, label: str, pump, designs: dict, meshes: dict) -> dict:
    """Every rigid design at its level-1 effective temperature (:func:`bearingfe.thermal.cycle_temperature`)."""
    from ..thermal import celsius, cycle_temperature
    from ..thermal.files import balance_of, lubricant_of

    th, run = s["thermal"], s["run"]
    oil = lubricant_of(th, label, "thermal")
    supply = None
    if th["supply_temperature_C"] is None:  # where the oil has the mechanism file's viscosity
        supply = build(label, "thermal", oil.temperature_at, pump.viscosity)
    balance = balance_of(th, label, "thermal", supply)
    out = {}
    for name, p in designs.items():
        r = cycle_temperature(p, meshes[name], oil, balance, revolutions=run["revolutions"], start=run["start"],
                              rtol=run["rtol"], cavitation=run["cavitation"], element=run["element"])
        out[name] = {"effective_temperature_C": celsius(r.temperature),
                     "supply_temperature_C": celsius(r.supply_temperature),
                     "temperature_rise_K": r.temperature_rise, "peak_temperature_C": celsius(r.peak_temperature),
                     "effective_viscosity_Pa_s": r.viscosity, "supply_viscosity_Pa_s": r.supply_viscosity,
                     "mean_power_W": r.friction_power, "smallest_film_m": r.smallest_film,
                     "isothermal_smallest_film_m": r.isothermal_smallest_film, "evaluations": r.evaluations}
    return out


def _compliance(pump, mesh, element: str, model: str):
    from ..elastic import NEEDS_BODY, compliance_of

    model = "block" if model == "body" else model  # "body" is the block's old name
    if model in NEEDS_BODY and pump.shoe_body is None:
        raise ValueError(f"[elastic] model {model!r} needs the shoe's depth: [shoe] thickness in the mechanism file")
    return compliance_of(model, mesh, pump.scale, pump.shoe_material, counterpart=pump.eccentric_material,
                         body=pump.shoe_body, element=element)


#: Pictured states of every run: key -> what it is.
STATES = {"loaded": "most loaded", "thinnest": "thinnest film"}

#: States spread over the cycle (besides the pictured ones) whose largest pressure is the run's peak
#: pressure (as a design study's ``peak_pressure``, :class:`bearingfe.sweep.cases.PumpOutcome`).
PEAK_SAMPLES = 12


def _states(pump, mesh, traj, run: dict, compliance=None, solved: dict | None = None) -> dict:
    """The pictured film states of a run (most loaded: the largest plunger force; thinnest film), re-solved,
    with their SI figures, and the run's peak pressure over them and :data:`PEAK_SAMPLES` more. The film
    results are kept in ``solved`` by sample, if given (of a rigid run: the PVD frames' states)."""
    from ..transient import state_result

    elastic = compliance if traj.max_deflection is not None else None

    def solve(k):
        res = state_result(pump, mesh, traj, int(k), run["cavitation"], run["element"], elastic=elastic)
        if solved is not None and elastic is None:
            solved[int(k)] = res
        return res

    sc = pump.scale
    out = {}
    for key, k in (("loaded", int(np.argmax(np.abs(traj.load[:, 0])))), ("thinnest", int(np.argmin(traj.h_min)))):
        res = solve(k)
        d = res.basis.doflocs
        at = int(np.argmin(np.asarray(res.film.thickness(d[0], d[1]))))
        out[key] = {"result": res, "sample": k, "beta_deg": float(np.degrees(traj.beta[k]) % 360.0),
                    "load_N": float(sc.to_force(abs(traj.load[k, 0]))),
                    "chamber_pressure_Pa": float(traj.chamber_pressure[k]),
                    "film_m": float(sc.to_thickness(res.h_min)),
                    "pressure_at_thinnest_Pa": float(sc.to_pressure(float(res.pressure[at]))),
                    "thinnest_on_edge": bool(np.isin(at, res.basis.get_dofs().all())),  # prescribed pressure
                    "peak_pressure_Pa": float(sc.to_pressure(res.max_pressure)),
                    "deflection_m": float(sc.to_thickness(res.max_deflection))}
    spread = np.unique(np.linspace(0, traj.beta.size - 1, PEAK_SAMPLES).astype(int))
    peaks = [st["peak_pressure_Pa"] for st in out.values()]
    peaks += [sc.to_pressure(solve(k).max_pressure) for k in spread if k not in {st["sample"] for st in out.values()}]
    out["peak_pressure_Pa"] = float(max(peaks))
    out["peak_states"] = len(peaks)
    return out


def _heading(design: str, key: str, st: dict) -> str:
    return (f"{design}, {STATES[key]}: beta = {st['beta_deg']:.0f} deg\n"
            f"p_max = {st['peak_pressure_Pa'] / 1e6:.3g} MPa, h_min = {st['film_m'] * 1e6:.3g} um")


def _panels(kind: str, names: list[str], pumps: dict, states: dict) -> list[list]:
    """Rows: the pictured states (most loaded, thinnest film); columns: the designs ``names``."""
    from ..plot.maps import Panel

    sc = next(iter(pumps.values())).scale
    unit = {"pressure": (sc.pressure / 1e6, "MPa"), "film": (sc.clearance * 1e6, "um"),
            "deflection": (sc.clearance * 1e6, "um")}[kind]
    return [[Panel(states[n][key]["result"], kind, *unit, radius=sc.radius, title=_heading(n, key, states[n][key]),
                   surface=pumps[n].surface) for n in names] for key in STATES]


def _draw(name: str, pumps: dict, runs: dict, states: dict, s: dict, out_dir: Path) -> list[str]:
    """One picture kind: every design's curves, fields of every design at its pictured states (rigid, and
    elastic when run), or the one-page summary."""
    from ..plot import curves, maps

    title = s["title"]
    rigid = [n for n in runs if not n.endswith("_elastic")]
    elastic = [n for n in runs if n.endswith("_elastic")]
    if name == "trajectory":
        curves.trajectory_plot({n: runs[n] for n in runs}, out_dir / "trajectory.png", title=title)
        return ["trajectory.png"]
    if name == "orbit":
        curves.orbit_plot({n: runs[n] for n in runs}, out_dir / "orbit.png", title=title)
        return ["orbit.png"]
    if name == "pocket":
        pump = next(iter(pumps.values()))
        curves.pocket_plot({n: runs[n] for n in runs}, pump.scale, pump.drive.omega, out_dir / "pocket.png",
                           title=f"{title}: pocket pressure, leakage and power loss")
        return ["pocket.png"]
    if name == "summary":
        _summary_page(pumps, runs, states, s, out_dir / "summary.png")
        return ["summary.png"]
    written = []
    groups = [(elastic, "")] if name == "deflection" else [(rigid, ""), (elastic, "_elastic")]
    for names, suffix in groups:
        if not names:
            continue
        file = f"{name}{suffix}.png"
        what = {"pressure": "film pressure", "film": "film thickness", "deflection": "film opening by the support"}
        support = "elastic support" if names[0].endswith("_elastic") else "rigid support"
        maps.field_panels(_panels(name, names, pumps, states), out_dir / file,
                          title=f"{title}: {what[name]} ({support})")
        written.append(file)
    return written


def _summary_page(pumps: dict, runs: dict, states: dict, s: dict, path: Path):
    """One page for a report: the smallest film over the cycle of every design, the pressure of each
    rigid design at its most loaded state, and the table of figures with the limits' verdicts."""
    from matplotlib.figure import Figure

    from ..plot import maps
    from ..plot.curves import DESIGN_COLORS
    from ..plot.figures import frame, ruled_table, save, title as set_title

    rigid = [n for n in runs if not n.endswith("_elastic")]
    fig = Figure(figsize=(8.27, 11.69))  # A4 portrait; bands from the top [in]: curves, maps, table
    ax = fig.add_subplot(frame(fig, top=0.85, bottom=7.3, left=0.8, right=0.5)[0, 0])
    maps_grid = frame(fig, ncols=len(rigid), top=5.0, bottom=3.8, left=0.8, right=0.5, wgap=1.1)
    for (n, traj), color in zip(runs.items(), DESIGN_COLORS):
        deg = np.degrees(traj.beta)
        ax.plot(deg, traj.h_min * 1e6, color=color, label=n)
        i = int(np.argmin(traj.h_min))
        ax.plot(deg[i], traj.h_min[i] * 1e6, "o", color=color, markeredgecolor="k",
                label=f"{n}: min {traj.h_min[i] * 1e6:.3g} um at {deg[i] % 360:.0f} deg")
    if s["limits"]["min_film"] is not None:
        ax.axhline(s["limits"]["min_film"] * 1e6, color="red", ls=":", label="limit min_film")
    ax.set_ylim(bottom=0.0)
    ax.set_xticks(np.arange(0, 361, 45))
    ax.set_xlabel("shaft angle beta [deg]")
    ax.set_ylabel("smallest film [um]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    set_title(ax, "smallest film over the cycle")
    for j, panel in enumerate(_panels("pressure", rigid, pumps, states)[0]):
        maps.field_axes(fig.add_subplot(maps_grid[0, j]), panel)
    table = fig.add_subplot(frame(fig, top=8.2, bottom=0.2, left=0.8, right=0.5)[0, 0])
    names = list(runs)
    ruled_table(table, _comparison(runs, pumps, states, s["limits"]), ["", *names, "unit"],
                [0.4] + [0.5 / (len(names) + 1)] * len(names) + [0.1], fontsize=9,
                emphasis=lambda text: {"color": "red", "weight": "bold"} if text == "VIOLATED" else None)
    if "plain" in runs:
        ratio, row = _film_ratio(runs["pocket"], runs["plain"], "")
        gain = f"{(ratio - 1) * 100:+.0f} %" if ratio is not None else row[0]
        set_title(table, f"smallest film pocket/plain: {gain}", fontsize="medium")
    fig.suptitle(s["title"])
    return save(fig, path)


def _comparison(runs: dict, pumps: dict, states: dict, limits: dict) -> list[list[str]]:
    """Rows ``[quantity, value of each run..., unit]`` of the summary page."""
    from ..core.schema import LIMITS, check_limits

    from ..transient.trajectory import cycle_losses

    figures = {n: _design_figures(traj, pumps[n], states[n]) for n, traj in runs.items()}
    verdicts = {n: check_limits(f, limits) for n, f in figures.items()}
    losses = {n: cycle_losses(traj, pumps[n]) for n, traj in runs.items()}
    rows = [("smallest film", lambda n: f"{figures[n]['min_film'] * 1e6:.3g}", "um"),
            ("  at shaft angle", lambda n: f"{states[n]['thinnest']['beta_deg']:.0f}", "deg"),
            ("peak pressure", lambda n: f"{figures[n]['max_pressure'] / 1e6:.3g}", "MPa"),
            ("mean friction power", lambda n: f"{figures[n]['max_friction_power']:.3g}", "W"),
            ("leakage (inflow from the pocket)", lambda n: f"{figures[n]['max_leakage'] * LITRES_PER_MINUTE:.3g}",
             "l/min"),
            ("side leakage", lambda n: f"{np.mean(runs[n].flow_side) * LITRES_PER_MINUTE:.3g}", "l/min"),
            ("restrictor flow (mean)", lambda n: "-" if losses[n].restrictor_flow_mean is None else
             f"{losses[n].restrictor_flow_mean * LITRES_PER_MINUTE:.3g}", "l/min"),
            ("pumping power (restrictor + film)", lambda n: f"{losses[n].pumping_power:.3g}", "W"),
            ("total power loss", lambda n: f"{losses[n].total_power:.3g}", "W"),
            ("status", lambda n: runs[n].status, "")]
    for limit, value in limits.items():
        if value is not None:
            spec = LIMITS[limit]
            shown, unit = {"m": (value * 1e6, "um"), "Pa": (value / 1e6, "MPa")}.get(spec.unit, (value, spec.unit))
            rows.append((f"{spec.quantity} {spec.relation} {shown:.4g} {unit}",
                         lambda n, limit=limit: "ok" if verdicts[n][limit]["ok"] else "VIOLATED", ""))
    return [[q, *(f(n) for n in runs), u] for q, f, u in rows]


#: m^3/s -> l/min.
LITRES_PER_MINUTE = 6e4


def _design_figures(traj, pump, states: dict) -> dict:
    """What the limits of :data:`bearingfe.core.schema.LIMITS` are checked against, SI, by limit name."""
    return {"min_film": traj.smallest_film, "max_pressure": states["peak_pressure_Pa"],
            "max_friction_power": float(np.mean(traj.friction_moment)) * pump.drive.omega,
            "max_leakage": float(np.mean(traj.flow_inlet))}


def _film_ratio(pocket, plain, suffix: str) -> tuple[float | None, tuple]:
    """Smallest film pocket/plain, or ``None`` and the reason when a run did not complete (the smallest
    film of a stopped run is where it stopped, not a film of the cycle)."""
    statuses = {f"pocket{suffix}": pocket.status, f"plain{suffix}": plain.status}
    if all(status == "completed" for status in statuses.values()):
        ratio = pocket.smallest_film / plain.smallest_film
        return ratio, (ratio, "-")
    return None, ("not computed: " + ", ".join(f"{n} {st}" for n, st in statuses.items()), "")


def _losses(name: str, losses, has_pocket: bool) -> tuple[list[tuple], dict]:
    """The leakage and power rows of one run's summary table, and its ``losses`` entry of ``summary.json`` [SI]."""
    lpm = LITRES_PER_MINUTE
    rows = []
    if has_pocket:
        rows += [(f"{name}: pocket pressure (mean)", losses.pocket_pressure_mean, "Pa"),
                 (f"{name}: pocket pressure (peak)", losses.pocket_pressure_peak, "Pa")]
    if losses.restrictor_flow_mean is not None:
        rows += [(f"{name}: restrictor flow (mean)", losses.restrictor_flow_mean * lpm, "l/min"),
                 (f"{name}: restrictor flow (peak)", losses.restrictor_flow_peak * lpm, "l/min")]
    if has_pocket:
        rows.append((f"{name}: pocket flow into the film (peak)", losses.pocket_flow_peak * lpm, "l/min"))
    rows += [(f"{name}: side leakage (peak)", losses.side_flow_peak * lpm, "l/min"),
             (f"{name}: power loss: restrictor (mean)", losses.restrictor_power, "W"),
             (f"{name}: power loss: film leakage (mean)", losses.film_power, "W"),
             (f"{name}: pumping power (restrictor + film, mean)", losses.pumping_power, "W"),
             (f"{name}: total power loss (friction + pumping, mean)", losses.total_power, "W")]
    entry = {"pocket_pressure_mean_Pa": losses.pocket_pressure_mean if has_pocket else None,
             "pocket_pressure_peak_Pa": losses.pocket_pressure_peak if has_pocket else None,
             "restrictor_flow_mean_m3s": losses.restrictor_flow_mean,
             "restrictor_flow_peak_m3s": losses.restrictor_flow_peak,
             "pocket_flow_mean_m3s": losses.pocket_flow_mean, "pocket_flow_peak_m3s": losses.pocket_flow_peak,
             "side_flow_mean_m3s": losses.side_flow_mean, "side_flow_peak_m3s": losses.side_flow_peak,
             "friction_power_W": losses.friction_power, "restrictor_power_W": losses.restrictor_power,
             "film_power_W": losses.film_power, "pumping_power_W": losses.pumping_power,
             "total_power_W": losses.total_power}
    return rows, entry


def _summary(s: dict, runs: dict, balance: dict, meshes: dict, seconds: float, pumps: dict, states: dict) -> dict:
    from ..core.schema import check_limits
    from ..transient.trajectory import cycle_losses

    table = []
    results = {}
    for name, traj in runs.items():
        design = name.removesuffix("_elastic")
        figures = _design_figures(traj, pumps[name], states[name])
        verdicts = check_limits(figures, s["limits"])
        thin = states[name]["thinnest"]
        table += [(f"{name}: smallest film", traj.smallest_film * 1e6, "um"),
                  (f"{name}: smallest film at beta", thin["beta_deg"], "deg"),
                  (f"{name}: peak pressure", figures["max_pressure"], "Pa"),
                  (f"{name}: mean friction moment", float(np.mean(traj.friction_moment)), "N m"),
                  (f"{name}: mean friction power", figures["max_friction_power"], "W"),
                  (f"{name}: leakage (mean inflow from the pocket)", figures["max_leakage"] * LITRES_PER_MINUTE,
                   "l/min"),
                  (f"{name}: side leakage (mean)", float(np.mean(traj.flow_side)) * LITRES_PER_MINUTE, "l/min")]
        loss_rows, loss_entry = _losses(name, cycle_losses(traj, pumps[name]), bool(pumps[name].surface.inlets))
        table += loss_rows + [
                  (f"{name}: balance ratio", balance[design], "-"),
                  (f"{name}: mass balance (relative)", traj.mass_balance_relative, "-"),
                  (f"{name}: status", traj.status, "")]
        for limit, v in verdicts.items():
            table.append((f"{name}: limit {limit}: {v['value']:.4g} {v['relation']} {v['limit']:.4g} {v['unit']}",
                          "ok" if v["ok"] else "VIOLATED", ""))
        results[name] = {"smallest_film_m": traj.smallest_film, "balance_ratio": balance[design],
                         "status": traj.status, "message": traj.message, "nodes": meshes[design].n_nodes,
                         "mean_friction_moment_Nm": float(np.mean(traj.friction_moment)),
                         "mean_friction_power_W": figures["max_friction_power"],
                         "mean_inlet_flow_m3s": figures["max_leakage"],
                         "mean_side_flow_m3s": float(np.mean(traj.flow_side)),
                         "peak_pressure_Pa": figures["max_pressure"],
                         "peak_pressure_states": states[name]["peak_states"],
                         "mass_balance_relative": traj.mass_balance_relative,
                         "periodic_iterations": traj.periodic_iterations,
                         "limits": verdicts, "within_limits": all(v["ok"] for v in verdicts.values()),
                         "losses": loss_entry}
        if traj.max_deflection is not None:
            largest = float(np.max(traj.max_deflection))
            table.append((f"{name}: largest deflection", largest * 1e6, "um"))
            results[name]["largest_deflection_m"] = largest
        for key in STATES:
            st = states[name][key]
            results[name][f"{key}_state"] = {k: v for k, v in st.items() if k != "result"}
        loaded = states[name]["loaded"]
        table.append((f"{name}: most loaded state at beta ({loaded['load_N'] / 1e3:.4g} kN)", loaded["beta_deg"],
                      "deg"))
        if name == "pocket":
            table.append((f"{name}: pressure at the thinnest film"
                          + (" (on a boundary of the film: its prescribed pressure)" if thin["thinnest_on_edge"]
                             else ""), thin["pressure_at_thinnest_Pa"], "Pa"))
    for suffix, what in (("", ""), ("_elastic", ", elastic support")):
        if f"plain{suffix}" in runs:
            ratio, row = _film_ratio(runs[f"pocket{suffix}"], runs[f"plain{suffix}"], suffix)
            table.append((f"smallest film ratio pocket/plain{what}", *row))
            if ratio is not None:  # the pocket's gain as the README and docs/papers.md quote it
                table.append((f"pocket gain (smallest film){what}", f"{100 * (ratio - 1):+.0f} %", ""))
            results[f"film_ratio{suffix}"] = ratio
    table.append(("seconds", seconds, "s"))
    return {"kind": "pump", "title": s["title"], "mechanism": str(s["mechanism"]), "run": s["run"],
            "elastic": s["elastic"], "limits": s["limits"], "results": results, "table": table}
