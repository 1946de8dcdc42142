"""Sharing a frame's photon-mapping preparation between renders (a render farm's bands of one
frame), driven by the environment of the Blender process so that a farm sets it per task
without changing the .blend:

    PHOTON_PREPARED_SAVE=FILE   save the preparation (photon maps, radiance records, irradiance
                                cache) to FILE once prepared
    PHOTON_PREPARED_LOAD=FILE   load it from FILE instead of preparing
    PHOTON_PREPARE_ONLY=1       end each render once prepared (and saved): no pixels are
                                rendered (Blender still writes its empty image)

The last run of '#' in FILE's name (not its folders) becomes the frame number, zero-padded to
the run's length, as in Blender's output paths. A file prepared for another scene, frame or setting (anything but the render
border, threads and tile size), or a damaged one, is refused with a warning and the render
prepares as usual. Only the PHOTON_MAP integrator shares its preparation; the others warn and
ignore the variables. A frame with several view layers or views renders each with its own
preparation: they would all save to (and load from) the same FILE.
"""

import os
import re

SAVE = "PHOTON_PREPARED_SAVE"
LOAD = "PHOTON_PREPARED_LOAD"
PREPARE_ONLY = "PHOTON_PREPARE_ONLY"


def frame_path(path, frame):
    """`path` with the last run of '#' in its file name replaced by the zero-padded frame
    number."""
    folder, name = os.path.split(path)
    runs = list(re.finditer(r"#+", name))
    if not runs:
        return path
    run = runs[-1]
    name = name[:run.start()] + str(frame).zfill(len(run.group())) + name[run.end():]
    return os.path.join(folder, name)


def from_environment(frame, environ=None):
    """{'load', 'save', 'prepare_only'} for RenderSession.set_prepared_state, or None when no
    variable is set."""
    environ = os.environ if environ is None else environ
    load = environ.get(LOAD, "")
    save = environ.get(SAVE, "")
    prepare_only = environ.get(PREPARE_ONLY, "").strip().lower() not in ("", "0", "false", "no")
    if not (load or save or prepare_only):
        return None
    return {"load": frame_path(load, frame) if load else "",
            "save": frame_path(save, frame) if save else "",
            "prepare_only": prepare_only}


def report(reporter, files, stats):
    """Info lines on what the render did with the files (RenderStats.prepared_state); the
    native session has already warned about any file it refused or could not write."""
    state = stats.prepared_state
    if state.loaded:
        reporter.info(f"prepared state loaded from {files['load']} "
                      f"({state.bytes / 1e6:.1f} MB in {state.load_seconds:.3f} s); the "
                      f"photon and cache figures below are the saved preparation's")
    if state.saved:
        reporter.info(f"prepared state saved to {files['save']} "
                      f"({state.bytes / 1e6:.1f} MB in {state.save_seconds:.3f} s)")
