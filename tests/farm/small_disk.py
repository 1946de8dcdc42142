"""A small filesystem that fills up, for the farm tests: a tmpfs mounted by the test (as root;
a test skips with the reason where mounting is not permitted)."""

import os
import subprocess

import pytest


def mount_tmpfs(path, size):
    """A tmpfs of `size` (mount's size=, e.g. "512k") at `path`, or a skip saying why not."""
    if os.geteuid() != 0:
        pytest.skip("mounting a small tmpfs (a disk that fills) needs root")
    path.mkdir(parents=True, exist_ok=True)
    proc = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(path)],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {proc.stderr.strip()}")


def unmount(path):
    # Lazy: a process still holding a file there (a cancelled task) does not keep it mounted.
    subprocess.run(["umount", "-l", str(path)], capture_output=True)


def fill(folder, leave=0):
    """Writes folder/filler until the filesystem is full, then gives `leave` bytes back."""
    filler = folder / "filler"
    with open(filler, "wb", buffering=0) as f:
        try:
            while True:
                f.write(b"\0" * 4096)
        except OSError:
            pass
    os.truncate(filler, max(filler.stat().st_size - leave, 0))
