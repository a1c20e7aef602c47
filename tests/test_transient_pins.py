"""The pump transients give the same numbers as before their driver was rewritten (one stepping loop).

Every expected value in :data:`EXPECTED` was printed by the pre-refactor code at commit
``4e84691699d5f0abf05709b5e731a9be65368192`` (three transient drivers: ``transient/quasi_static.py``,
``transient/jfo.py``, ``transient/elastic.py``) on this file's runs: the shipped pump
(``mechanisms/eccentric_pump.toml``) and, where its film never ruptures so that a cavitation model
would be idle, the shoe widened to +-1.4 rad, on small meshes so that each run takes a second or two.

What is pinned: the status, the number of samples, the start state and the periodic-start figures,
the smallest film and the sample where it occurs, the state at the last sample, and every SI column of
:meth:`bearingfe.Trajectory.columns` at five samples spread over the run; the film re-solved at one
sample by ``state_result``; and the counters of the run (right sides, factorizations, steps,
Jacobians), which are deterministic: the same arithmetic takes the same steps.

Tolerances: ``1e-9`` of the largest value of each column over the pinned samples (a quantity that
passes through zero, such as a flow at a dead centre, is compared at the scale of the column, not to
its own tiny value; the mass balance, a round-off difference of the flows, at the scale of the largest
flow), and ``1e-9`` relative on states, smallest films and angles. Round-off and
platform noise move these by about ``1e-13`` (the integrators' error control sees differences of
round-off only); a behavioural change (another step, another rate) moves them by ``1e-6`` or more.
The periodic residual is a difference of two states of order 1: it is compared to ``1e-12`` absolute.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import bearingfe as bf
from bearingfe import transient
from bearingfe.elastic import half_space

#: Relative tolerance of the pins (see the module docstring).
RTOL = 1e-9
#: Absolute tolerance of the periodic residual (a difference of states of order 1).
RESIDUAL_ATOL = 1e-12
#: Columns compared at the pinned samples.
COLUMNS = ("gamma", "delta", "gamma_rate", "delta_rate", "h_min", "friction_moment", "flow_inlet", "flow_side",
           "flow_arc", "flow_squeeze", "mass_balance", "max_deflection")
#: The flow columns [m^3/s]: their largest value is the scale of the mass balance.
FLOWS = ("flow_inlet", "flow_side", "flow_arc", "flow_squeeze")
#: Counters compared exactly.
COUNTERS = ("nfev", "factorizations", "steps", "jacobians", "newton_iterations")


def _wide(pump):
    """The shipped shoe widened to +-1.4 rad: its diverging ends rupture during suction."""
    return dataclasses.replace(pump, surface=bf.Surface(arc=(-1.4, 1.4), half_width=pump.surface.half_width))


def _compliance(pump, mesh):
    return half_space(mesh, pump.scale, (pump.shoe_material, pump.eccentric_material))


def _rigid_defaults(pump):
    traj = bf.simulate(pump)
    mesh = transient.pump_mesh(pump, 0.2, order=2)  # the default mesh of simulate
    return traj, transient.state_result(pump, mesh, traj, 33)


def _rk23_periodic(pump):
    traj = bf.simulate(pump, start="periodic", method="RK23", rtol=1e-3)
    return traj, transient.state_result(pump, transient.pump_mesh(pump, 0.2, order=2), traj, 33)


def _cavitating(model: str):
    def run(pump):
        mesh = transient.pump_mesh(pump, 0.15)
        traj = bf.simulate(pump, mesh, 0.25, start="steady", cavitation=model, points_per_revolution=72)
        return traj, transient.state_result(pump, mesh, traj, 10, model)
    return run


def _cavitating_wide(model: str):
    def run(pump):
        wide = _wide(pump)
        mesh = transient.pump_mesh(wide, 0.2)
        traj = bf.simulate(wide, mesh, 0.5, beta0=math.pi / 2, start="steady", cavitation=model,
                           points_per_revolution=24)
        return traj, transient.state_result(wide, mesh, traj, 10, model)
    return run


def _jfo(pump):
    mesh = transient.pump_mesh(pump, 0.15)
    traj = bf.simulate(pump, mesh, 0.05, start="steady", cavitation="jfo")
    return traj, transient.state_result(pump, mesh, traj, 5, "jfo")


def _jfo_periodic(pump):
    mesh = transient.pump_mesh(pump, 0.3)
    traj = bf.simulate(pump, mesh, 0.05, start="periodic", cavitation="jfo", points_per_revolution=36)
    return traj, transient.state_result(pump, mesh, traj, 1, "jfo")


def _quasi_static_elastic(pump):
    mesh = transient.pump_mesh(pump, 0.3)
    C = _compliance(pump, mesh)
    traj = bf.simulate(pump, mesh, 0.1, start="steady", elastic=C)
    return traj, transient.state_result(pump, mesh, traj, 10, elastic=C)


def _elastic_squeeze(pump):
    mesh = transient.pump_mesh(pump, 0.3)
    C = _compliance(pump, mesh)
    traj = transient.simulate_elastic(pump, C, 0.1, start="steady")
    return traj, transient.state_result(pump, mesh, traj, 10, elastic=C)


def _elastic_periodic(pump):
    mesh = transient.pump_mesh(pump, 0.3)
    C = _compliance(pump, mesh)
    traj = transient.simulate_elastic(pump, C, 1.0, start="periodic", points_per_revolution=72)
    return traj, transient.state_result(pump, mesh, traj, 37, elastic=C)


#: The pinned runs by name: ``pump -> (Trajectory, ReynoldsResult of one sample)``.
RUNS = {
    "rigid defaults": _rigid_defaults,
    "rigid RK23 rtol 1e-3 periodic": _rk23_periodic,
    "reynolds": _cavitating("reynolds"),
    "gumbel": _cavitating("gumbel"),
    "reynolds wide": _cavitating_wide("reynolds"),
    "gumbel wide": _cavitating_wide("gumbel"),
    "jfo": _jfo,
    "jfo periodic": _jfo_periodic,
    "quasi-static elastic": _quasi_static_elastic,
    "elastic squeeze": _elastic_squeeze,
    "elastic squeeze periodic": _elastic_periodic,
}


def pinned(traj, result) -> dict:
    """The pinned figures of one run (the same function printed :data:`EXPECTED`)."""
    n = traj.beta.size
    samples = sorted({0, n // 4, n // 2, (3 * n) // 4, n - 1})
    cols = traj.columns()
    k = int(np.argmin(traj.h_min))
    return {
        "status": traj.status, "samples": n, "beta_end": float(traj.beta[-1]),
        "start": [float(v) for v in traj.start], "periodic_iterations": int(traj.periodic_iterations),
        "periodic_residual": float(traj.periodic_residual),
        "smallest_film": traj.smallest_film, "smallest_index": k, "smallest_beta": float(traj.beta[k]),
        "end": [float(traj.gamma[-1]), float(traj.delta[-1])],
        "at": samples,
        "columns": {name: [float(cols[name][i]) for i in samples] for name in COLUMNS if name in cols},
        "counters": {name: int(traj.stats[name]) for name in COUNTERS if name in traj.stats},
        "state": {"max_pressure": float(result.max_pressure), "force": [float(v) for v in result.force],
                  "h_min": float(result.h_min), "friction": float(result.friction)},
    }


#: Printed by :func:`pinned` on the pre-refactor code (commit 4e84691, see the module docstring).
EXPECTED: dict = {
    'rigid defaults': {
        'status': 'completed',
        'samples': 181,
        'beta_end': 6.283185307179586,
        'start': [0.06289118837105973, 4.518481741725367],
        'periodic_iterations': 0,
        'periodic_residual': math.nan,
        'smallest_film': 9.607213484755022e-06,
        'smallest_index': 104,
        'smallest_beta': 3.6302848441482056,
        'end': [0.4548575167440972, 4.9070771429129705],
        'at': [0, 45, 90, 135, 180],
        'columns': {
            'gamma': [0.06289118837105973, 0.3851978270265494, 0.5133033421365136, 0.5127125944401487,
                      0.4548575167440972],
            'delta': [4.518481741725367, 3.389480096378934, 3.5650607642380368, 4.2451522955982615,
                      4.9070771429129705],
            'gamma_rate': [2.4259478480640625e-17, 0.1397555330749391, 0.03921557198926805, -0.01612529726712637,
                           -0.05696750772561518],
            'delta_rate': [-4.462028761835806e-17, 0.11397105733190246, 0.09054651391564782, 0.4458648163345384,
                           0.412108810482103],
            'h_min': [1.9103048469178073e-05, 1.2296043459469012e-05, 9.733933157269727e-06, 1.1018604068128848e-05,
                      1.6412944937043287e-05],
            'friction_moment': [1.2383812832834602, 1.9875595724552182, 2.4642723592798292, 1.6931011641413154,
                                1.1574189211251196],
            'flow_inlet': [-3.8959119873857144e-08, 7.688138155304949e-07, 4.030805850211216e-07,
                           -1.8264122465205691e-07, -1.8544360916607821e-07],
            'flow_side': [1.0880738801810597e-07, 1.281509172541274e-06, 8.4579854459692e-07,
                          5.9565840918592376e-08, 1.5069732143583883e-07],
            'flow_arc': [-1.4776676571321346e-07, 2.7846671679406764e-07, -3.37175948974872e-07,
                         -1.5832427000300555e-06, -1.4330821268968277e-06],
            'flow_squeeze': [-4.713036175180865e-23, -7.912618607208538e-07, -1.0565679452000873e-07,
                             1.341026434315621e-06, 1.0969269601119286e-06],
            'mass_balance': [2.5782125024492576e-13, 9.978691600718055e-11, 1.1478391908233606e-10,
                             9.200143785486934e-12, 1.423618298221846e-11],
        },
        'counters': {
            'nfev': 190,
            'factorizations': 211,
            'steps': 85,
        },
        'state': {
            'max_pressure': 1.0864977448406723,
            'force': [0.42084957769543496, 0.0],
            'h_min': 0.6836375839618472,
            'friction': 1.2105273820763305,
        },
    },
    'rigid RK23 rtol 1e-3 periodic': {
        'status': 'completed',
        'samples': 181,
        'beta_end': 6.283185307179586,
        'start': [0.44438366494842285, 4.881997103705826],
        'periodic_iterations': 5,
        'periodic_residual': 9.623013497161992e-10,
        'smallest_film': 9.914355518696205e-06,
        'smallest_index': 106,
        'smallest_beta': 3.7000980142279785,
        'end': [0.44438366520551, 4.881997102743525],
        'at': [0, 45, 90, 135, 180],
        'columns': {
            'gamma': [0.44438366494842285, 0.3387893467576142, 0.49573881128922576, 0.49839055321518766,
                      0.44438366520551],
            'delta': [4.881997103705826, 3.414296646743239, 3.5372776867192717, 4.222055697073232,
                      4.881997102743525],
            'gamma_rate': [-0.0539633108762759, 0.16419820252040335, 0.05310125396208369, -0.014572410163960967,
                           -0.053963310843331294],
            'delta_rate': [0.40966565340168043, -0.0025448869461180937, 0.09654816400849547, 0.44542324521598997,
                           0.40966565340099365],
            'h_min': [1.6291822973432478e-05, 1.3224213064847718e-05, 1.0085223774215484e-05,
                      1.1160734498120482e-05, 1.6291822963514562e-05],
            'friction_moment': [1.170065207201608, 1.8610223432340813, 2.4086885664261772, 1.695408469892629,
                                1.1700652076425546],
            'flow_inlet': [-1.8166904562557427e-07, 9.689291091074542e-07, 4.414863389646012e-07,
                           -1.755806809394581e-07, -1.8166904572769796e-07],
            'flow_side': [1.4553277313568616e-07, 1.5651014864450143e-06, 8.851723951769147e-07,
                          5.83812323428088e-08, 1.4553277300610479e-07],
            'flow_arc': [-1.407894748600437e-06, 4.084901487028584e-07, -2.499659372585943e-07,
                         -1.5200478827304572e-06, -1.4078947497773653e-06],
            'flow_squeeze': [1.0806794236226462e-06, -1.0047646998971598e-06, -1.938311770088319e-07,
                             1.286077578364207e-06, 1.0806794248270163e-06],
            'mass_balance': [1.3506216530348319e-11, 1.0217385674100085e-10, 1.110580551126915e-10,
                             8.391083983432099e-12, 1.350621654647971e-11],
        },
        'counters': {
            'nfev': 615,
            'factorizations': 635,
            'steps': 27,
        },
        'state': {
            'max_pressure': 1.0864977448406723,
            'force': [0.42084957769543496, 0.0],
            'h_min': 0.739220413643348,
            'friction': 1.123524680762485,
        },
    },
    'reynolds': {
        'status': 'completed',
        'samples': 19,
        'beta_end': 1.5707963267948966,
        'start': [0.06822682070573481, 4.501456409149565],
        'periodic_iterations': 0,
        'periodic_residual': math.nan,
        'smallest_film': 1.2018470413704215e-05,
        'smallest_index': 18,
        'smallest_beta': 1.5707963267948966,
        'end': [0.3990764793147893, 3.383469218566804],
        'at': [0, 4, 9, 14, 18],
        'columns': {
            'gamma': [0.06822682070573481, 0.1067196903268333, 0.24553644879167086, 0.34261743060960814,
                      0.3990764793147893],
            'delta': [4.501456409149565, 3.6017980403008876, 3.3303257791637932, 3.3474192377896217,
                      3.383469218566804],
            'gamma_rate': [-3.4597364784891044e-18, 0.3460598065465894, 0.2664070408510207, 0.18483693212934207,
                           0.1410058290330193],
            'delta_rate': [-1.4235193486314078e-16, -2.2964067297178006, -0.05439903630459339, 0.08926844312389984,
                           0.11252543213038729],
            'h_min': [1.9010806800532323e-05, 1.7865606193463335e-05, 1.5089271024166582e-05,
                      1.3147651387807838e-05, 1.2018470413704215e-05],
            'friction_moment': [1.2499010987787846, 1.3712961056718773, 1.6233963478864113, 1.8645891485038637,
                                2.043425004236915],
            'flow_inlet': [-4.56600312008836e-08, 2.3796590820095646e-06, 1.3871316153577391e-06,
                           9.102558539024705e-07, 6.931632496977807e-07],
            'flow_side': [1.1480048343150542e-07, 3.641390796109199e-06, 2.2252286317036837e-06,
                          1.5429738114826956e-06, 1.2369214462402385e-06],
            'flow_arc': [-1.6046458852832022e-07, 1.4165780852692988e-06, 8.515161910695569e-07,
                         4.847907663377854e-07, 2.6339076108627876e-07],
            'flow_squeeze': [-5.608092365678333e-23, -2.6779242621661823e-06, -1.6888505648408675e-06,
                             -1.1167144843547576e-06, -8.064130117481366e-07],
            'mass_balance': [4.073895931314237e-12, -3.855372027506703e-10, -7.626425746341313e-10,
                             -7.942395632530388e-10, -7.35945880599888e-10],
        },
        'counters': {
            'nfev': 105,
            'factorizations': 124,
            'steps': 49,
        },
        'state': {
            'max_pressure': 1.086497744840672,
            'force': [0.42084957769543485, 2.5632705909017724e-18],
            'h_min': 0.7320771184376571,
            'friction': 1.1359549255608552,
        },
    },
    'gumbel': {
        'status': 'completed',
        'samples': 19,
        'beta_end': 1.5707963267948966,
        'start': [0.06822682070573481, 4.501456409149565],
        'periodic_iterations': 0,
        'periodic_residual': math.nan,
        'smallest_film': 1.2018470413704215e-05,
        'smallest_index': 18,
        'smallest_beta': 1.5707963267948966,
        'end': [0.3990764793147893, 3.383469218566804],
        'at': [0, 4, 9, 14, 18],
        'columns': {
            'gamma': [0.06822682070573481, 0.1067196903268333, 0.24553644879167086, 0.34261743060960814,
                      0.3990764793147893],
            'delta': [4.501456409149565, 3.6017980403008876, 3.3303257791637932, 3.3474192377896217,
                      3.383469218566804],
            'gamma_rate': [-3.4597364784891044e-18, 0.3460598065465894, 0.2664070408510207, 0.18483693212934207,
                           0.1410058290330193],
            'delta_rate': [-1.4235193486314078e-16, -2.2964067297178006, -0.05439903630459339, 0.08926844312389984,
                           0.11252543213038729],
            'h_min': [1.9010806800532323e-05, 1.7865606193463335e-05, 1.5089271024166582e-05,
                      1.3147651387807838e-05, 1.2018470413704215e-05],
            'friction_moment': [1.2499010987787846, 1.3712961056718773, 1.6233963478864113, 1.8645891485038637,
                                2.043425004236915],
            'flow_inlet': [-4.5660031200883584e-08, 2.379659082009565e-06, 1.3871316153577391e-06,
                           9.102558539024707e-07, 6.931632496977807e-07],
            'flow_side': [1.148004834315054e-07, 3.641390796109199e-06, 2.225228631703684e-06,
                          1.5429738114826958e-06, 1.2369214462402385e-06],
            'flow_arc': [-1.6046458852832022e-07, 1.4165780852692988e-06, 8.515161910695569e-07,
                         4.847907663377854e-07, 2.633907610862785e-07],
            'flow_squeeze': [-5.608092365678333e-23, -2.6779242621661823e-06, -1.6888505648408675e-06,
                             -1.1167144843547576e-06, -8.064130117481366e-07],
            'mass_balance': [4.073895931327862e-12, -3.8553720275023433e-10, -7.626425746345672e-10,
                             -7.942395632528207e-10, -7.359458805996699e-10],
        },
        'counters': {
            'nfev': 105,
            'factorizations': 124,
            'steps': 49,
        },
        'state': {
            'max_pressure': 1.086497744840672,
            'force': [0.42084957769543485, 5.707456891109735e-18],
            'h_min': 0.7320771184376571,
            'friction': 1.135954925560855,
        },
    },
    'reynolds wide': {
        'status': 'completed',
        'samples': 13,
        'beta_end': 4.71238898038469,
        'start': [0.5677448543602521, 4.036710887687551],
        'periodic_iterations': 0,
        'periodic_residual': math.nan,
        'smallest_film': 8.645102912794957e-06,
        'smallest_index': 0,
        'smallest_beta': 1.5707963267948966,
        'end': [0.5393119270744943, 4.661122076939688],
        'at': [0, 3, 6, 9, 12],
        'columns': {
            'gamma': [0.5677448543602521, 0.5501983959020206, 0.544664362211766, 0.5431329914050655,
                      0.5393119270744943],
            'delta': [4.036710887687551, 3.9938436067447776, 3.9710227648567438, 4.275929934038282,
                      4.661122076939688],
            'gamma_rate': [-0.03445367676328721, -0.01270327923174688, -0.002843105654186654,
                           -0.0023891069403916346, -0.007760668684151616],
            'delta_rate': [-0.06836174266412183, -0.040360619538721845, -0.020697383309985135, 0.5006603314535005,
                           0.4799799346048153],
            'h_min': [8.645102912794957e-06, 8.99603208195959e-06, 9.106712755764681e-06, 9.13734017189869e-06,
                      9.290722783852645e-06],
            'friction_moment': [5.267177570809999, 5.351576540610117, 5.4091496194340065, 4.742390146047708,
                                3.9161594108010194],
            'flow_inlet': [0.0, 0.0, 0.0, 0.0, 0.0],
            'flow_side': [2.695507450645535e-06, 2.5788414022640153e-06, 2.506133105119954e-06,
                          6.574140994405506e-08, 1.1595291355970908e-07],
            'flow_arc': [-2.2663029635519128e-06, -2.195050745126367e-06, -2.165117698765338e-06,
                         -3.1230569314050634e-06, -3.312913748590022e-06],
            'flow_squeeze': [-1.0818399796438617e-07, -1.0344820349807554e-07, -7.918669155932068e-08,
                             3.0642202170726058e-06, 3.206299227022155e-06],
            'mass_balance': [-4.281876855625834e-09, -4.4718036831129835e-09, -4.563662915908062e-09,
                             -3.380084535960149e-11, 6.672664382816155e-11],
        },
        'counters': {
            'nfev': 82,
            'factorizations': 101,
            'steps': 35,
        },
        'state': {
            'max_pressure': 0.01078404551974419,
            'force': [0.006636244362101684, 6.162164691275035e-19],
            'h_min': 0.4576837006039197,
            'friction': 3.03516022748845,
        },
    },
    'gumbel wide': {
        'status': 'completed',
        'samples': 13,
        'beta_end': 4.71238898038469,
        'start': [0.5677448543602521, 4.036710887687551],
        'periodic_iterations': 0,
        'periodic_residual': math.nan,
        'smallest_film': 8.64510291279496e-06,
        'smallest_index': 0,
        'smallest_beta': 1.5707963267948966,
        'end': [0.54726536265227, 4.681546982531468],
        'at': [0, 3, 6, 9, 12],
        'columns': {
            'gamma': [0.567744854360252, 0.5561437309726368, 0.5523957183834569, 0.5509759434725299,
                      0.54726536265227],
            'delta': [4.036710887687551, 4.0046258256947285, 3.9899582241912697, 4.2963120928890834,
                      4.681546982531468],
            'gamma_rate': [-0.02329785972631497, -0.008287590406038697, -0.0022416688567389828,
                           -0.00229078272651632, -0.007650946540740838],
            'delta_rate': [-0.05531418897381458, -0.02748416984404099, -0.01274205189350664, 0.500785828574068,
                           0.4799199082900537],
            'h_min': [8.64510291279496e-06, 8.877125380547265e-06, 8.952085632330862e-06, 8.980481130549403e-06,
                      9.161711930538035e-06],
            'friction_moment': [5.267177570824032, 5.379960569801189, 5.440614051141623, 4.7485602862136895,
                                3.9018574845123175],
            'flow_inlet': [0.0, 0.0, 0.0, 0.0, 0.0],
            'flow_side': [2.679057930897337e-06, 2.579424866608238e-06, 2.5307978775315295e-06,
                          6.697218994898332e-08, 1.1845439985552353e-07],
            'flow_arc': [-2.28380828956609e-06, -2.2582197535254016e-06, -2.25070175501425e-06,
                         -3.1980204349600995e-06, -3.365064991760657e-06],
            'flow_squeeze': [-1.2300777466004837e-07, -7.709825545812254e-08, -4.703498191226438e-08,
                             3.13681771119473e-06, 3.2538281704838045e-06],
            'mass_balance': [1.0732331273295542e-08, 2.596870852356554e-09, 1.5269693691385417e-08,
                             2.0283910967520953e-10, 1.3260185742959408e-09],
        },
        'counters': {
            'nfev': 84,
            'factorizations': 103,
            'steps': 36,
        },
        'state': {
            'max_pressure': 0.011202121993759343,
            'force': [0.006636244362101683, 1.362452495658542e-18],
            'h_min': 0.4498077258069715,
            'friction': 3.03391198476693,
        },
    },
    'jfo': {
        'status': 'completed',
        'samples': 10,
        'beta_end': 0.3141592653589793,
        'start': [0.06822682070573481, 4.501456409149565],
        'periodic_iterations': 0,
        'periodic_residual': math.nan,
        'smallest_film': 1.7987829975813865e-05,
        'smallest_index': 9,
        'smallest_beta': 0.3141592653589793,
        'end': [0.10060867142613585, 3.665499915055908],
        'at': [0, 2, 5, 7, 9],
        'columns': {
            'gamma': [0.06822682070573481, 0.06808160481797346, 0.07027642841254977, 0.08071484881001412,
                      0.10060867142613585],
            'delta': [4.501456409149565, 4.468447903744324, 4.194810256832583, 3.9016446939763223,
                      3.665499915055908],
            'gamma_rate': [-3.4597364784891044e-18, -0.0031261844137544233, 0.05048569125795311,
                           0.18731021313855725, 0.31094097707080365],
            'delta_rate': [-1.4235193486314078e-16, -0.7526248322153214, -3.593313053485088, -4.212759440891338,
                           -3.0241885420237207],
            'h_min': [1.9010806800532323e-05, 1.8982496107608366e-05, 1.8736369524032482e-05,
                      1.8406335367887947e-05, 1.7987829975813865e-05],
            'friction_moment': [1.2499012270998215, 1.2544823980487765, 1.284534643582112, 1.3191948541072926,
                                1.3595796289645192],
            'flow_inlet': [-4.56998618276528e-08, 2.5219409791101043e-07, 1.428947730322751e-06,
                           2.1273237715715676e-06, 2.3885923927646724e-06],
            'flow_side': [1.1483331986032119e-07, 5.443410791718438e-07, 2.2436515396038175e-06,
                          3.259990173459741e-06, 3.6491963506069332e-06],
            'flow_arc': [-1.6053318168797344e-07, 2.2405547616922097e-08, 7.578756776480063e-07,
                         1.2128433931799649e-06, 1.4062368047196151e-06],
            'flow_squeeze': [-5.608092365678333e-23, -3.1455252887775375e-07, -1.5725794869290754e-06,
                             -2.3455097950681407e-06, -2.6668407625618754e-06],
            'mass_balance': [-6.523923650012202e-22, -1.6894363037229316e-21, 2.6159013735064747e-21,
                             2.6159013735064747e-21, -4.359835622510791e-22],
        },
        'counters': {
            'nfev': 90,
            'factorizations': 90,
            'steps': 9,
            'newton_iterations': 27,
        },
        'state': {
            'max_pressure': 0.5483418305992767,
            'force': [0.21353479419426008, -0.00023824048851806446],
            'h_min': 0.9368184762016241,
            'friction': 0.8722752828272171,
        },
    },
    'jfo periodic': {
        'status': 'completed',
        'samples': 3,
        'beta_end': 0.3141592653589793,
        'start': [0.42400429727192523, 4.886484819445155],
        'periodic_iterations': 1,
        'periodic_residual': 0.38681835827400146,
        'smallest_film': 1.6496500499695026e-05,
        'smallest_index': 0,
        'smallest_beta': 0.0,
        'end': [0.24692667496186058, 4.630991784879249],
        'at': [0, 1, 2],
        'columns': {
            'gamma': [0.42400429727192523, 0.34681770436473375, 0.24692667496186058],
            'delta': [4.886484819445155, 4.854121775789239, 4.630991784879249],
            'gamma_rate': [-0.06249275037089318, -0.49138511206405405, -0.6359260440002049],
            'delta_rate': [0.3897858781582196, -0.20602953485350908, -1.42048964021499],
            'h_min': [1.6496500499695026e-05, 1.6931393259447167e-05, 1.688932229253712e-05],
            'friction_moment': [1.1774576220135433, 1.2405521930924956, 1.342175978834637],
            'flow_inlet': [-1.741456981685e-07, 1.4452359414134135e-06, 2.894134347568955e-06],
            'flow_side': [1.5478597676796881e-07, 2.504677312464673e-06, 4.558518685443152e-06],
            'flow_arc': [-1.3326220128361464e-06, -6.42243504817837e-08, 1.146508779616898e-06],
            'flow_squeeze': [1.0036903378996763e-06, -9.952170205694748e-07, -2.8108931174910953e-06],
            'mass_balance': [1.3079506867532374e-21, -1.3079506867532374e-21, 0.0],
        },
        'counters': {
            'nfev': 26,
            'factorizations': 26,
            'steps': 2,
            'newton_iterations': 8,
        },
        'state': {
            'max_pressure': 0.4641556980466876,
            'force': [0.17992063731997543, -0.00020977552379632792],
            'h_min': 0.8465696629723584,
            'friction': 0.8421611879624085,
        },
    },
    'quasi-static elastic': {
        'status': 'completed',
        'samples': 19,
        'beta_end': 0.6283185307179586,
        'start': [0.06905501676532175, 4.499666461171153],
        'periodic_iterations': 0,
        'periodic_residual': math.nan,
        'smallest_film': 1.7976971738807996e-05,
        'smallest_index': 18,
        'smallest_beta': 0.6283185307179586,
        'end': [0.23400493130495434, 2.504368219145434],
        'at': [0, 4, 9, 14, 18],
        'columns': {
            'gamma': [0.06905501676532175, 0.05805802164472278, 0.08339980699207825, 0.17338443540109974,
                      0.23400493130495434],
            'delta': [4.499666461171153, 4.288319016665654, 2.806398197181702, 2.5234635543174613,
                      2.504368219145434],
            'gamma_rate': [-0.007351124808972458, -0.17487120903415346, 0.5209360444693046, 0.4709542782583384,
                           0.40138575181129954],
            'delta_rate': [-0.028658969921269473, -4.857063688680963, -4.449915629996894, -0.38153077475154,
                           0.015211576560089899],
            'h_min': [1.9041468589924105e-05, 1.995495371775105e-05, 2.0981743997177452e-05, 1.918734130553004e-05,
                      1.7976971738807996e-05],
            'friction_moment': [1.244816737259124, 1.1546648484766842, 1.0326331237099524, 1.0614115437845604,
                                1.0975865673946852],
            'flow_inlet': [-4.693207544628072e-08, 1.55315790919292e-06, 7.294075981386289e-06,
                           6.6326458805481136e-06, 5.935293009157501e-06],
            'flow_side': [1.172443490112652e-07, 2.07771713659128e-06, 7.09036635781721e-06, 6.295247523563417e-06,
                          5.5697984203884165e-06],
            'flow_arc': [-1.6173149242009459e-07, 6.584718880311294e-07, 2.56814582463242e-06,
                         2.5459339339428453e-06, 2.4414219329735403e-06],
            'flow_squeeze': [-2.4449320756150204e-09, -1.1830311154594167e-06, -2.364436201047802e-06,
                             -2.2085355769011063e-06, -2.0759273441252025e-06],
            'mass_balance': [3.816371468034883e-17, 2.99270016718197e-17, -1.5539326125752962e-17,
                             -5.704234535068218e-17, -7.925309194600116e-17],
            'max_deflection': [1.1806120375483342e-07, 3.0880732088625742e-06, 8.499912300299364e-06,
                               8.708685565484567e-06, 8.708142762908332e-06],
        },
        'counters': {
            'nfev': 95,
            'factorizations': 619,
            'steps': 45,
            'jacobians': 14,
        },
        'state': {
            'max_pressure': 1.086497744840672,
            'force': [0.420849577691231, -4.382554649046133e-12],
            'h_min': 1.0317285809210364,
            'friction': 0.7011750231909251,
        },
    },
    'elastic squeeze': {
        'status': 'completed',
        'samples': 19,
        'beta_end': 0.6283185307179586,
        'start': [0.06905501676532175, 4.499666461171153],
        'periodic_iterations': 0,
        'periodic_residual': math.nan,
        'smallest_film': 1.4779263223542987e-05,
        'smallest_index': 18,
        'smallest_beta': 0.6283185307179586,
        'end': [0.41141971207111705, 2.8364221684764375],
        'at': [0, 4, 9, 14, 18],
        'columns': {
            'gamma': [0.06905501676532175, 0.13594063922107846, 0.33697995099244316, 0.37823132885659794,
                      0.41141971207111705],
            'delta': [4.499666461171153, 3.5639296482240694, 3.1145081316683236, 2.9283224305396334,
                      2.8364221684764375],
            'gamma_rate': [-0.007350526867400473, 1.1842305229552599, 0.561230665635303, 0.22687712833644108,
                           0.24437998408955824],
            'delta_rate': [-0.028699055841867757, -5.656496699329964, -1.307162828010041, -0.8142509016920472,
                           -0.5229633981873341],
            'h_min': [1.904146858992483e-05, 1.828138594454273e-05, 1.6931434456648867e-05, 1.564706252261892e-05,
                      1.4779263223542987e-05],
            'friction_moment': [1.244816737259153, 1.2648730494417117, 1.3039088136499541, 1.3211538587498464,
                                1.345354884353149],
            'flow_inlet': [-4.6931841188705996e-08, 1.5613777968132744e-06, 3.93349310995815e-06,
                           3.6473736793130413e-06, 3.4274118336825028e-06],
            'flow_side': [9.325093257268088e-08, 1.901696427627873e-06, 3.539456846990715e-06,
                          3.254472675459664e-06, 3.046243805736721e-06],
            'flow_arc': [-1.3773753570140765e-07, 8.036518510099113e-07, 1.3711000825868064e-06,
                         1.3942816988772636e-06, 1.4586083129019323e-06],
            'flow_squeeze': [-2.4452380981414608e-09, -1.1439704818560269e-06, -9.770638196142055e-07,
                             -1.0013806949784415e-06, -1.0774402848857865e-06],
            'mass_balance': [3.816220491695846e-17, 3.1517033723349385e-17, -5.165206257879097e-18,
                             -4.544474661124123e-17, -7.036404108704504e-17],
            'max_deflection': [1.1806120376012538e-07, 3.0580732595063657e-06, 8.494942269797284e-06,
                               8.714820227331784e-06, 8.713602355088791e-06],
        },
        'counters': {
            'nfev': 203,
            'factorizations': 19,
            'steps': 64,
            'jacobians': 3,
        },
        'state': {
            'max_pressure': 1.086497744840672,
            'force': [0.4208550011441723, 4.180403625382909e-12],
            'h_min': 0.8306692989698312,
            'friction': 0.8872239718943624,
        },
    },
    'elastic squeeze periodic': {
        'status': 'completed',
        'samples': 73,
        'beta_end': 6.283185307179586,
        'start': [0.7637961731618897, 3.9392743679704725],
        'periodic_iterations': 6,
        'periodic_residual': 1.4007101700741487e-06,
        'smallest_film': 4.06901971203724e-06,
        'smallest_index': 37,
        'smallest_beta': 3.2288591161895095,
        'end': [0.7637968362383997, 3.9392729672603024],
        'at': [0, 18, 36, 54, 72],
        'columns': {
            'gamma': [0.7637961731618897, 0.676737611969645, 0.9451623878020211, 0.7703796675877629,
                      0.7637968362383997],
            'delta': [3.9392743679704725, 3.03603675239171, 2.74878710414987, 3.201452073727507,
                      3.9392729672603024],
            'gamma_rate': [-0.011973094454926713, 0.07122085665568038, 0.20887362227082545, 0.0003111898766712548,
                           -0.011973554204685],
            'delta_rate': [0.45357615729575246, -0.434563423184408, -0.020791203946801767, 0.4862833358285395,
                           0.4535766961876565],
            'h_min': [5.063954584016609e-06, 1.0506193483148739e-05, 4.205072555295312e-06, 4.667630402476427e-06,
                      5.063937545703118e-06],
            'friction_moment': [2.8398942182423426, 1.992682734908925, 3.1740278479532926, 4.5817339645240285,
                                2.8399021770196504],
            'flow_inlet': [-1.9020096235455125e-07, 1.3090868032512388e-06, 6.584729619097822e-07,
                           -1.6757170219709147e-08, -1.9020090061348744e-07],
            'flow_side': [-1.7207216491930357e-07, 9.86653281509725e-07, 4.782490650714618e-07,
                          -1.3788481648256932e-08, -1.720719576111858e-07],
            'flow_arc': [-1.656779293558595e-06, 5.782296626763896e-07, 1.3729615114150964e-06,
                         -1.445846674970647e-07, -1.6567787415144537e-06],
            'flow_squeeze': [1.6386504958142606e-06, -2.5579614089302644e-07, -1.1927376143551913e-06,
                             1.4161597889854832e-07, 1.6386497982030648e-06],
            'mass_balance': [3.090868405976234e-16, -4.184929916924714e-17, -2.215847216620507e-16,
                             2.706414285927063e-17, 3.090874945729668e-16],
            'max_deflection': [1.2024450910709085e-07, 8.739719977147561e-06, 8.747859448948386e-06,
                               1.1863919711008607e-07, 1.2024473729898071e-07],
        },
        'counters': {
            'nfev': 4333,
            'factorizations': 420,
            'steps': 1158,
            'jacobians': 152,
        },
        'state': {
            'max_pressure': 0.9288755268950138,
            'force': [0.3601912457504614, 1.3922912565541436e-12],
            'h_min': 0.2034509856018621,
            'friction': 2.261668330010082,
        },
    },
}


def _close(actual, expected, rtol, what, scale=None):
    actual, expected = np.asarray(actual, float), np.asarray(expected, float)
    scale = np.max(np.abs(expected)) if scale is None else scale
    assert actual.shape == expected.shape, what
    assert np.all(np.isnan(actual) == np.isnan(expected)), what
    ok = ~np.isnan(expected)
    assert np.all(np.abs(actual[ok] - expected[ok]) <= rtol * scale), (what, actual, expected)


@pytest.fixture(scope="module")
def shipped_pump(root):
    return bf.load_mechanism(root / "mechanisms" / "eccentric_pump.toml")


@pytest.mark.parametrize("name", list(RUNS))
def test_same_numbers_as_before_the_refactor(name, shipped_pump):
    got = pinned(*RUNS[name](shipped_pump))
    want = EXPECTED[name]
    for key in ("status", "samples", "periodic_iterations", "smallest_index", "at", "counters"):
        assert got[key] == want[key], (key, got[key], want[key])
    for key in ("beta_end", "start", "smallest_film", "smallest_beta", "end"):
        _close(got[key], want[key], RTOL, key)
    _close(got["periodic_residual"], want["periodic_residual"], 1.0, "periodic_residual", scale=RESIDUAL_ATOL)
    assert set(got["columns"]) == set(want["columns"])
    flows = max(np.max(np.abs(want["columns"][name])) for name in FLOWS)
    for column, values in want["columns"].items():
        # the mass balance is a round-off difference of the flows: measured at their scale
        _close(got["columns"][column], values, RTOL, column, scale=flows if column == "mass_balance" else None)
    for key, value in want["state"].items():
        _close(got["state"][key], value, RTOL, f"state_result {key}")
