"""A final render's progress as Blender shows it: one progress bar for the whole render, and
the stats line above the image. Blender's bar must only move forward, but a render runs several
stages (photon tracing, radiance precompute, irradiance cache, tiles) whose own fractions each
start again at 0, and whose lengths are not known in advance."""

import re
import time

# Share of the bar given to the preparation stages of an integrator that prepares (photon
# mapping, radiosity); the tiles fill the rest. Each new preparation stage takes half of what is
# left of that share, so the bar never goes back and never passes the tiles' start.
PREPARE_SHARE = 0.5
# A fraction this small gives no useful rate for a time-left estimate.
MIN_FRACTION_FOR_ESTIMATE = 0.02


def stage_key(status):
    """The stage a status line belongs to: its text before the first digit or colon
    ('Tracing photons 1.2M of 4M' -> 'Tracing photons')."""
    return re.split(r"[0-9:]", status, maxsplit=1)[0].strip()


def format_seconds(seconds):
    seconds = max(0, int(round(seconds)))
    return f"{seconds // 60:02d}:{seconds % 60:02d}"


class RenderProgress:
    def __init__(self, prepares):
        self.prepare_share = PREPARE_SHARE if prepares else 0.0
        self.value = 0.0
        self._stage = None
        self._stage_start_value = 0.0
        self._stage_span = 0.0
        self._stage_started = 0.0
        self._tiles_started = None

    def update(self, status, preparing, fraction, now):
        """Takes the session's status, whether it prepares, its fraction of the current stage
        and the time; returns (bar fraction, text saying the time left or '')."""
        fraction = min(max(float(fraction), 0.0), 1.0)
        if preparing or self._tiles_started is None and not status.startswith("Rendering"):
            key = stage_key(status)
            if key != self._stage:
                self._stage = key
                self._stage_start_value = self.value
                self._stage_span = (self.prepare_share - self.value) / 2.0
                self._stage_started = now
            target = self._stage_start_value + self._stage_span * fraction
            left = self._time_left(now - self._stage_started, fraction)
            text = f"{format_seconds(left)} left in this stage" if left is not None else ""
        else:
            if self._tiles_started is None:
                self._tiles_started = now
            target = self.prepare_share + (1.0 - self.prepare_share) * fraction
            left = self._time_left(now - self._tiles_started, fraction)
            text = f"Remaining {format_seconds(left)}" if left is not None else ""
        self.value = max(self.value, min(target, 1.0))
        return self.value, text

    @staticmethod
    def _time_left(elapsed, fraction):
        if fraction < MIN_FRACTION_FOR_ESTIMATE or fraction >= 1.0:
            return None
        return elapsed * (1.0 - fraction) / fraction


def stats_line(status, sync_stats, tiles_done, tiles_total, t_start, time_left=""):
    """The render's stats line: stage, tiles, the synced scene's size, time and time left."""
    left = f" | {time_left}" if time_left else ""
    return (f"Photon | {status} | Tiles {tiles_done}/{tiles_total} | "
            f"Triangles {sync_stats.triangles:,} | Instances {sync_stats.instances:,} | "
            f"Lights {sync_stats.lights} | Time {time.perf_counter() - t_start:.1f} s{left}")
