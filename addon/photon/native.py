"""The native module _photon: the one place the add-on imports it. The add-on must still register
when the module is missing or built for another Python, so the panel (and a render) can say why
instead of Blender refusing to enable it: MODULE is then None and IMPORT_ERROR says why."""


def _import_error(exc):
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
    from . import _photon as MODULE
    IMPORT_ERROR = None
except Exception as exc:  # ImportError, or an undefined symbol from a stale build
    MODULE = None
    IMPORT_ERROR = _import_error(exc)


def native_module():
    """The native module; RuntimeError with IMPORT_ERROR when it did not load."""
    if MODULE is None:
        raise RuntimeError(IMPORT_ERROR)
    return MODULE
