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

# The native module (native.py) may be missing or built for another Python: the add-on still
# registers so the panel can say why. Scripts and tests read its state off the package.
from .native import IMPORT_ERROR as NATIVE_IMPORT_ERROR, MODULE as _photon  # noqa: E402, F401

from . import engine, properties, ui  # noqa: E402
from .bake import operators as bake_ops  # noqa: E402

_modules = (properties, engine, ui, bake_ops)


def register():
    for module in _modules:
        module.register()


def unregister():
    for module in reversed(_modules):
        module.unregister()
