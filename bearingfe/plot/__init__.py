"""Pictures: pyvista fields and matplotlib curves, imported lazily (never on ``import bearingfe``)."""
