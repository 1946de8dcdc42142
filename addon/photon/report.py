"""Collects warnings during sync and render, and hands each distinct one to Blender once."""

import sys


class SceneError(Exception):
    """A scene Photon cannot render meaningfully (e.g. a camera with a NaN transform): the
    render stops with this message as its error, and no image is written."""


class Reporter:
    def __init__(self, engine=None):
        self._engine = engine
        self._seen = set()
        self.warnings = []

    def warning(self, message):
        if message in self._seen:
            return
        self._seen.add(message)
        self.warnings.append(message)
        # Printed too: in background mode RenderEngine.report does not reach the terminal, and
        # tests and render farms read stdout.
        print(f"Photon: warning: {message}", flush=True)
        if self._engine is not None:
            self._engine.report({'WARNING'}, f"Photon: {message}")

    def info(self, message):
        print(f"Photon: {message}", flush=True)
        if self._engine is not None:
            self._engine.report({'INFO'}, f"Photon: {message}")

    def error(self, message):
        print(f"Photon: error: {message}", file=sys.stderr, flush=True)
        if self._engine is not None:
            self._engine.report({'ERROR'}, f"Photon: {message}")
