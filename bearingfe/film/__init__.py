"""One film state of the Reynolds equation: film models, weak forms, the compiled operator, superposition and results, and the finite-difference and finite-volume discretizations.

================  ============================================================
module            what it does
================  ============================================================
``thickness``     Film-thickness models.
``forms``         The Reynolds equation's weak forms and pointwise formulas, written once.
``compiled``      Compiled film operator: the film-independent linear maps of a mesh and element, built once.
``superposition`` One film state of the finite-element Reynolds equation: operators, condensed system, results.
``fd``            Finite-difference reference solver of the Reynolds equation (paper 004's method).
``finite_volume`` Mass-conserving cavitation: the Jakobsson-Floberg-Olsson (JFO) model in Elrod-Adams p-theta form.
================  ============================================================
"""
