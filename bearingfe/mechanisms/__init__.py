"""The machines around the bearings: crank drives, efficiency, rotors on frames, machine files.

================  ============================================================
module            what it does
================  ============================================================
``machines``      Shared parameter objects for the machine models (SI units, frozen, validated).
``crank``         Kinematics and inertia forces of the central crank-slider (paper 000).
``efficiency``    Efficiency of a crank-slider with joint and guide friction (paper 003, cold pilger mill).
``rotor``         Unbalanced rotor on an elastic frame and the column-height design method (paper 002).
``sections``      Beam sections as data: Soviet hot-rolled I-beams No. 20 ... 24a.
``files``         Read mechanism descriptions (TOML) into the parameter objects of :mod:`bearingfe.mechanisms.machines
================  ============================================================
"""
