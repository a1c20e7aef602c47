"""Pictures: pyvista fields and matplotlib curves, imported lazily (never on ``import bearingfe``).

===============  ==============================================================
module           what it draws
===============  ==============================================================
``fields``       pressure and film fields on the surface (pyvista, off-screen)
``curves``       trajectories, orbits and other curves (matplotlib)
``maps``         field maps side by side, P2 fields on a refined display mesh (matplotlib)
``mechanisms``   the crank and rotor models' curves (matplotlib)
``figures``      fixed margins in inches (no layout-engine pass); saving at the package's resolution
``colour_bars``  colour bars as a few artists beside a map (no axes of their own)
===============  ==============================================================
"""

__all__ = ["preload"]


def preload():
    """Import matplotlib's figure machinery (figure, triangulations, the Agg backend), PIL's image formats and
    this package's picture modules in a background thread; returns the thread (join it before the process
    forks or draws).

    The import costs about half a second; a scene starts it while its physics runs in the main thread
    (which spends much of its time in compiled code that releases the interpreter), so the pictures, and the
    processes forked to draw them, find the modules loaded. Nothing is drawn and no global state is set (the
    garbage collector is off while the modules load, :func:`bearingfe.core.lazy.without_collections`, and
    restored after).
    """
    import threading

    def load() -> None:
        from ..core.lazy import without_collections

        with without_collections():  # the modules live as long as the process: nothing to collect meanwhile
            _load()

    def _load() -> None:
        import matplotlib.figure  # noqa: F401
        import matplotlib.tri  # noqa: F401
        from matplotlib.backends import backend_agg  # noqa: F401
        from matplotlib import _qhull, _tri  # noqa: F401  (the triangulations' compiled helpers, else on first use)
        from PIL import Image

        from . import colour_bars, curves, fields, maps  # noqa: F401  (fields: its numpy part; pyvista loads on use)

        Image.preinit()  # the image formats PIL registers on its first save

    thread = threading.Thread(target=load, name="bearingfe-preload-pictures", daemon=True)
    thread.start()
    return thread
