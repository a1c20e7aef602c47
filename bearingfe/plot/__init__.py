"""Pictures: pyvista fields and matplotlib curves, imported lazily (never on ``import bearingfe``).

==============  ==============================================================
module          what it draws
==============  ==============================================================
``fields``      pressure and film fields on the surface (pyvista, off-screen)
``curves``      trajectories, orbits and other curves (matplotlib)
``maps``        field maps side by side, P2 fields on a refined display mesh (matplotlib)
``mechanisms``  the crank and rotor models' curves (matplotlib)
``figures``     fixed margins in inches (no layout-engine pass); saving at the package's resolution
==============  ==============================================================
"""
