"""The test suite of bearingfe, laid out like the package.

``tests/<part>/`` holds the tests of ``bearingfe/<part>/`` (core, geometry, film, cavitation, elastic,
bearings, transient, mechanisms, sweep, scenes, io, plot); ``tests/test_<module>*.py`` those of a
top-level module ``bearingfe/<module>.py`` (``reynolds``, ``adaptivity``, ``cli``). The whole-package
checks have folders of their own: ``package/`` (import graph, package tables), ``docs/`` (README
blocks, examples, generated pages) and ``hostile/`` (hostile inputs and outputs across the layers).
A file that tests two layers sits with its main subject.

``conftest.py`` holds the shared fixtures, ``helpers.py`` the repository root and the scene-file
writer. Every folder is a package (an ``__init__.py``), so files of the same name in different
folders (``transient/test_jfo.py``, ...) import as distinct modules (``tests.transient.test_jfo``).
"""
