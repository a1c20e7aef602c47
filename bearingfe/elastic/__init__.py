"""Elastic supports: compliances and the coupled (EHD) film.

================  ============================================================
module            what it does
================  ============================================================
``coupled``       Elastic support: compliance of the film surfaces and the coupled (EHD) film.
``shoe``          The real shoe body: a 3-D gmsh mesh of the shoe, linear elasticity, condensed to the film dofs.
================  ============================================================
"""

from __future__ import annotations
from .coupled import (Compliance, DeflectedFilm, ElasticError, ElasticSolution, combined_modulus, half_space, shoe_body, body_compliance, rectangle_deflection, solve_elastic, balance_load, ElasticBalance, pressure_sensitivity, newton, check_dense_size, ChordBalance)
from .shoe import (ShoeMesh, mesh_shoe, shoe_compliance, condense, overlay, BODY_ORDERS)

__all__ = ['Compliance', 'DeflectedFilm', 'ElasticError', 'ElasticSolution', 'combined_modulus', 'half_space', 'shoe_body', 'body_compliance', 'rectangle_deflection', 'solve_elastic', 'balance_load', 'ElasticBalance', 'pressure_sensitivity', 'newton', 'check_dense_size', 'ChordBalance', 'ShoeMesh', 'mesh_shoe', 'shoe_compliance', 'condense', 'overlay', 'BODY_ORDERS']
