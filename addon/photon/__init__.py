# SPDX-License-Identifier: GPL-2.0-or-later
"""Photon: a photon-mapping render engine for Blender (engine id PHOTON, settings at scene.photon)."""

bl_info = {
    "name": "Photon",
    "author": "Photon developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Render Properties > Render Engine > Photon",
    "description": "Photon mapping, ray tracing and radiosity render engine",
    "category": "Render",
}

# The native module may be missing or built for another Python: the add-on must still register
# so the panel can say why instead of Blender refusing to enable it.
def _native_import_error(exc):
    """What the user needs to know about a failed import of _photon: a missing file is
    reported as missing (Python's own message then blames a circular import), anything else
    with the loader's message."""
    import importlib.machinery
    import os
    import sys
    here = os.path.dirname(__file__)
    if not any(name.startswith("_photon") and name.endswith(tuple(
            importlib.machinery.EXTENSION_SUFFIXES)) for name in os.listdir(here)):
        expected = "_photon" + importlib.machinery.EXTENSION_SUFFIXES[0]
        return (f"the native module {expected} is not installed in {here}: build and install "
                f"the add-on with tools/setup_and_demo.sh (it must be built for Blender's "
                f"Python {sys.version_info.major}.{sys.version_info.minor})")
    return f"the native module _photon failed to load: {type(exc).__name__}: {exc}"


try:
    from . import _photon  # noqa: F401
    NATIVE_IMPORT_ERROR = None
except Exception as exc:  # ImportError, or an undefined symbol from a stale build
    _photon = None
    NATIVE_IMPORT_ERROR = _native_import_error(exc)

from . import engine, properties, ui  # noqa: E402
from .bake import operators as bake_ops  # noqa: E402

_modules = (properties, engine, ui, bake_ops)


def register():
    for module in _modules:
        module.register()


def unregister():
    for module in reversed(_modules):
        module.unregister()
