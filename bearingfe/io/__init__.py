"""Outputs at the edge: VTU/PVD, CSV and JSON writers and output folders.

================  ============================================================
module            what it does
================  ============================================================
``writers``       Files users open elsewhere: VTU/PVD for ParaView, CSV trajectories, JSON summaries, ROSS bearings.
``outfolder``     Output folders: replace only what this package wrote there, all at once, one run at a time.
================  ============================================================
"""

from __future__ import annotations
from .writers import (atomic_path, umask, write_vtu, write_pvd, read_pvd, write_csv, write_json, write_ross_bearings,
                      write_ross3_bearing, read_ross_bearing)
from .outfolder import (MANIFEST, OutputFolderError, lock_folder, output_folder, read_manifest)

__all__ = ['atomic_path', 'umask', 'write_vtu', 'write_pvd', 'read_pvd', 'write_csv', 'write_json', 'write_ross_bearings', 'write_ross3_bearing', 'read_ross_bearing', 'MANIFEST', 'OutputFolderError', 'lock_folder', 'output_folder', 'read_manifest']
