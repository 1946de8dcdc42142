"""Run inside Blender's GUI (under Xvfb): starts an F12 render shown in the image editor, waits
for a stage of it (photon.final.RENDER_STATUS), presses Esc there with xdotool, takes a
screenshot, and reports through stdout when Blender's render_cancel / render_complete handlers
fire.

Arguments after "--": screenshot=PATH esc_stage=TEXT (the start of the status Esc waits for)
esc_delay=SECONDS (after the stage starts) photons=N samples=N percent=N (resolution) irradiance_cache=0|1."""

import subprocess
import sys
import time

import bpy

from photon import final

args = dict(a.split("=", 1) for a in sys.argv[sys.argv.index("--") + 1:])
esc_stage = args.get("esc_stage", "")
esc_delay = float(args.get("esc_delay", 0.2))
POLL = 0.02
TIMEOUT = 240.0

bpy.context.preferences.view.render_display_type = "AREA"
scene = bpy.context.scene
scene.render.engine = 'PHOTON'
scene.photon.photons = int(args.get("photons", 100000))
scene.photon.samples = int(args.get("samples", 16))
scene.render.resolution_percentage = int(args.get("percent", 100))
scene.photon.irradiance_cache = args.get("irradiance_cache", "1") == "1"
# One render thread leaves Blender's main thread (its timers, this script) a core.
scene.photon.threads = 1
state = {"stage_seen": None, "ended": None}


def log(message):
    print(f"render_gui: {message}", flush=True)


def start():
    state["start"] = time.monotonic()
    log("render started")
    bpy.ops.render.render('INVOKE_DEFAULT')
    bpy.app.timers.register(watch, first_interval=POLL)


def in_stage(status):
    return status.get("status", "").startswith(esc_stage)


def watch():
    now = time.monotonic()
    status = dict(final.RENDER_STATUS)
    if state["ended"] is not None or now - state["start"] > TIMEOUT:
        finish()
        return None
    if state["stage_seen"] is None and status and in_stage(status):
        state["stage_seen"] = now
        log(f"stage '{status.get('status')}' at {now - state['start']:.3f} s, preview shown: "
            f"{status.get('preview_shown')}")
    if state["stage_seen"] is not None and "esc" not in state and \
            now - state["stage_seen"] >= esc_delay:
        bpy.ops.screen.screenshot(filepath=args["screenshot"] + ".running.png")
        # Keyboard focus follows the pointer without a window manager: point at the editor.
        subprocess.run(["xdotool", "mousemove", "500", "400", "key", "Escape"], check=True)
        state["esc"] = time.monotonic()
        log(f"Esc at {state['esc'] - state['start']:.3f} s during '{status.get('status')}'")
    return POLL


def finish():
    bpy.ops.screen.screenshot(filepath=args["screenshot"])
    bpy.ops.wm.quit_blender()


def on_cancel(*_args):
    state["ended"] = time.monotonic()
    log(f"cancelled {state['ended'] - state.get('esc', state['start']):.3f} s after Esc")


def on_complete(*_args):
    state["ended"] = time.monotonic()
    log(f"completed at {state['ended'] - state['start']:.3f} s")


bpy.app.handlers.render_cancel.append(on_cancel)
bpy.app.handlers.render_complete.append(on_complete)
# Blender's window needs a moment to open under Xvfb before the render starts.
bpy.app.timers.register(start, first_interval=2.0)
