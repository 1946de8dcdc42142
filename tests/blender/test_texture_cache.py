"""A texture cache folder that cannot be written (read-only, full, a path through a file) no
longer drops every image texture with a reason naming a temporary file: the textures are
converted into a temporary folder instead and render as usual, with one warning naming the
folder, the reason and the remedy; when the temporary folder cannot be written either, one
warning per folder says which textures fall back to their colour. A read-only cache filled
beforehand renders as usual, without a warning.

Root ignores permission bits, so read-only and full folders are tmpfs mounts (root only; a
non-root run makes the read-only folder with chmod and skips the others)."""

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "scripts"))
from harness import read_image  # noqa: E402

REMEDY = ("make the folder writable or free space on its disk, or set the environment variable "
          "PHOTON_TEXTURE_CACHE to a writable folder before starting Blender")


@pytest.fixture(scope="module")
def blend(blender, tmp_path_factory):
    """A plane whose Base Color is a generated 16 x 16 UV grid, lit by a sun."""
    path = tmp_path_factory.mktemp("texture_cache") / "grid.blend"
    result, _ = blender.run_script("make_texture_scene.py", "grid", 16, path)
    assert "exception" not in result, result["exception"]
    return path


def render(blender, tmp_path, blend, cache, temp=None):
    """Renders frame 1 with PHOTON_TEXTURE_CACHE=cache and TMPDIR=temp (tmp_path/tmp, made,
    by default); returns (process, pixels)."""
    env = blender.env()
    env["PHOTON_TEXTURE_CACHE"] = str(cache)
    if temp is None:
        temp = tmp_path / "tmp"
        temp.mkdir(exist_ok=True)
    env["TMPDIR"] = str(temp)
    out = tmp_path / "out_####"
    cmd = [blender.executable, "-b", "--factory-startup", "--python-use-system-env", "--addons", "photon", str(blend),
           "-E", "PHOTON", "-o", str(out), "-F", "OPEN_EXR", "-x", "1", "-f", "1"]
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=300,
                          stdin=subprocess.DEVNULL)
    proc.log = f"$ {' '.join(cmd)}\n{proc.stdout}\n{proc.stderr}"
    assert proc.returncode == 0, proc.log
    assert "Photon: rendered frame 1" in proc.stdout, proc.log
    assert "Traceback" not in proc.stdout + proc.stderr, proc.log
    return proc, read_image(tmp_path / "out_0001.exr")


@pytest.fixture(scope="module")
def textured(blender, blend, tmp_path_factory):
    """The frame rendered with a writable cache folder: the grid's texture on the plane."""
    tmp_path = tmp_path_factory.mktemp("textured")
    proc, pixels = render(blender, tmp_path, blend, tmp_path / "cache")
    assert cache_warnings(proc) == [], proc.log
    # The grid shows: far from one colour (its fallback colour would be).
    assert pixels[:, :, :3].std(axis=(0, 1)).min() > 0.02, proc.log
    return pixels


def cache_warnings(proc):
    return [line for line in proc.stdout.splitlines()
            if line.startswith("Photon: warning:") and ("cache" in line or "Grid" in line)]


def fallback(tmp_path):
    return tmp_path / "tmp" / f"photon-textures-{os.getuid()}"


def assert_converted_in_the_temporary_folder(proc, pixels, textured, tmp_path, folder, reason):
    """One warning, naming the folder, the reason, the temporary folder and the remedy; the
    texture renders as with a writable cache."""
    expected = (f"Photon: warning: the texture cache folder '{folder}' cannot be written "
                f"({reason}), so 1 image texture is converted into the temporary folder "
                f"'{fallback(tmp_path)}' instead; {REMEDY}")
    assert cache_warnings(proc) == [expected], proc.log
    assert ".tmp.exr" not in proc.stdout, proc.log  # the old per-texture reason
    assert "(1, 0 cached)" in proc.stdout, proc.log  # converted, not read from elsewhere
    assert np.array_equal(pixels, textured), proc.log


def mount_tmpfs(folder, options):
    """Mounts a tmpfs at `folder` (root only), or skips the test."""
    folder.mkdir(parents=True, exist_ok=True)
    if os.geteuid() != 0:
        pytest.skip("mounting a tmpfs needs root")
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", str(folder)],
                          capture_output=True, text=True)
    if done.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs: {done.stderr.strip()}")


@pytest.fixture
def mounts():
    """Folders mounted during the test, unmounted after it."""
    mounted = []
    yield mounted
    for folder in reversed(mounted):
        subprocess.run(["umount", str(folder)], check=False)


def read_only_folder(folder, mounts, options="ro,size=1m"):
    """An empty read-only folder: a read-only tmpfs as root, chmod 555 otherwise; returns the
    reason the warning gives."""
    if os.geteuid() != 0:
        folder.mkdir(parents=True, exist_ok=True)
        folder.chmod(0o555)
        return "permission denied"
    mount_tmpfs(folder, options)
    mounts.append(folder)
    return "read-only file system"


def test_cache_folder_under_a_file_falls_back_to_a_temporary_folder(blender, tmp_path, blend,
                                                                    textured):
    (tmp_path / "not_a_folder").write_text("a file")
    folder = tmp_path / "not_a_folder" / "textures"
    proc, pixels = render(blender, tmp_path, blend, folder)
    assert_converted_in_the_temporary_folder(
        proc, pixels, textured, tmp_path, folder,
        f"'{tmp_path / 'not_a_folder'}' is a file, not a folder")


def test_read_only_cache_folder_falls_back_to_a_temporary_folder(blender, tmp_path, blend,
                                                                 textured, mounts):
    folder = tmp_path / "read_only"
    reason = read_only_folder(folder, mounts)
    proc, pixels = render(blender, tmp_path, blend, folder)
    assert_converted_in_the_temporary_folder(proc, pixels, textured, tmp_path, folder, reason)
    # The next render (another Blender) reuses the temporary folder's texture, and says so.
    proc, again = render(blender, tmp_path, blend, folder)
    assert "(1, 1 cached)" in proc.stdout, proc.log
    assert len(cache_warnings(proc)) == 1 and "temporary folder" in proc.stdout, proc.log
    assert np.array_equal(again, textured), proc.log


def test_full_cache_folder_falls_back_to_a_temporary_folder(blender, tmp_path, blend, textured,
                                                            mounts):
    folder = tmp_path / "full"
    mount_tmpfs(folder, "size=64k")
    mounts.append(folder)
    with open(folder / "filler", "wb", buffering=0) as filler:  # every byte the tmpfs has
        try:
            while True:
                filler.write(bytes(4096))
        except OSError:
            pass
    proc, pixels = render(blender, tmp_path, blend, folder)
    assert_converted_in_the_temporary_folder(proc, pixels, textured, tmp_path, folder,
                                             "no space left on device")


def test_both_folders_unwritable_are_reported_once(blender, tmp_path, blend, textured):
    # The cache folder lies under a file, and so does the temporary folder (a file stands
    # where it would be): the texture falls back to its colour, with one warning.
    (tmp_path / "not_a_folder").write_text("a file")
    folder = tmp_path / "not_a_folder" / "textures"
    (tmp_path / "tmp").mkdir()
    fallback(tmp_path).write_text("a file")
    proc, pixels = render(blender, tmp_path, blend, folder)
    expected = (f"Photon: warning: the texture cache folder '{folder}' cannot be written "
                f"('{tmp_path / 'not_a_folder'}' is a file, not a folder), so 1 image texture "
                f"uses its fallback colour (Generated image 'Grid'); {REMEDY}")
    assert cache_warnings(proc) == [expected], proc.log
    assert ".tmp.exr" not in proc.stdout, proc.log
    assert not np.array_equal(pixels, textured), proc.log


def test_read_only_cache_filled_beforehand_serves_its_textures(blender, tmp_path, blend,
                                                               textured, mounts):
    # A farm may share a cache converted once: reading it needs no write, and warns of none.
    folder = tmp_path / "shared"
    mount_tmpfs(folder, "size=4m")
    mounts.append(folder)
    _, first = render(blender, tmp_path, blend, folder)
    subprocess.run(["mount", "-o", "remount,ro", str(folder)], check=True)
    proc, again = render(blender, tmp_path, blend, folder)
    assert cache_warnings(proc) == [], proc.log
    assert "textures " in proc.stdout and "(1, 1 cached)" in proc.stdout, proc.log
    assert np.array_equal(again, first) and np.array_equal(again, textured), proc.log
    # Served through links to it: nothing was converted again.
    converted = sorted(path.name for path in fallback(tmp_path).glob("*.exr")
                       if not path.is_symlink())
    assert converted == [], converted


@pytest.fixture
def texture_cache(blender, monkeypatch, tmp_path):
    """The staged add-on's texture_cache module (standard library only), loaded outside
    Blender, with its temporary folder under tmp_path/tmp and PHOTON_TEXTURE_CACHE restored
    after the test."""
    path = blender.stage / "addons" / "photon" / "texture_cache.py"
    spec = importlib.util.spec_from_file_location("photon_texture_cache", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    (tmp_path / "tmp").mkdir()
    monkeypatch.setattr(module, "fallback_folder", lambda: str(fallback(tmp_path)))
    monkeypatch.setenv("PHOTON_TEXTURE_CACHE", "")  # prepare() changes it: undone after
    return module


def test_images_failed_by_one_folder_make_one_warning_after_the_others(texture_cache,
                                                                       tmp_path):
    (tmp_path / "file").write_text("a file")
    folder = tmp_path / "file" / "textures"
    failures = [f"Image '/art/{name}.png' cannot be used (Could not open \"{folder}/"
                f"{key:016x}.exr.812.{key}.tmp.exr\" (Not a directory)): its inputs use their "
                f"fallback colour" for key, name in enumerate(["a", "b", "c", "d", "e"])]
    others = ["Image '/art/gone.png' cannot be used (file not found): its inputs use their "
              "fallback colour", "Material 'M': something else"]
    explained = texture_cache.explain([failures[0], others[0], *failures[1:], others[1]])
    assert explained == others + [
        f"the texture cache folder '{folder}' cannot be written ('{tmp_path / 'file'}' is a "
        f"file, not a folder), so 5 image textures use their fallback colour (Image "
        f"'/art/a.png', Image '/art/b.png', Image '/art/c.png' and 2 more); {REMEDY}"]


def test_prepare_points_the_native_side_at_a_writable_folder(texture_cache, tmp_path,
                                                             monkeypatch):
    env = os.environ
    cache = tmp_path / "cache"
    monkeypatch.setenv("PHOTON_TEXTURE_CACHE", str(cache))
    # Writable: left as it is.
    assert texture_cache.prepare() is None
    assert env["PHOTON_TEXTURE_CACHE"] == str(cache)
    # Two converted files there (a texture and its stats), then the folder cannot be written:
    # the native side is pointed at the temporary folder, which links to them.
    (cache / f"{7:016x}.exr").write_text("converted")
    (cache / f"{7:016x}.exr.stats").write_text("stats")
    (cache / "unrelated.txt").write_text("not a texture")
    probe = texture_cache.write_problem
    monkeypatch.setattr(texture_cache, "write_problem",
                        lambda folder: "read-only file system" if folder == str(cache)
                        else probe(folder))
    redirect = texture_cache.prepare()
    assert (redirect.folder, redirect.reason) == (str(cache), "read-only file system")
    assert env["PHOTON_TEXTURE_CACHE"] == str(fallback(tmp_path))
    linked = sorted(p.name for p in fallback(tmp_path).iterdir())
    assert linked == [f"{7:016x}.exr", f"{7:016x}.exr.stats"]
    assert all((fallback(tmp_path) / name).resolve() == cache / name for name in linked)
    assert redirect.warning() is None  # nothing converted into the temporary folder yet
    # Prepared again (the next render): the user's folder still counts, not the temporary one.
    assert texture_cache.prepare().folder == str(cache)
    # A texture converted into the temporary folder is reported.
    (fallback(tmp_path) / f"{8:016x}.exr").write_text("converted here")
    assert redirect.warning() == (
        f"the texture cache folder '{cache}' cannot be written (read-only file system), so 1 "
        f"image texture is converted into the temporary folder '{fallback(tmp_path)}' "
        f"instead; {REMEDY}")
    # The folder can be written again: back to it.
    monkeypatch.setattr(texture_cache, "write_problem", probe)
    assert texture_cache.prepare() is None
    assert env["PHOTON_TEXTURE_CACHE"] == str(cache)
    # The user's variable unset: the native default folder, unset again after a redirect.
    monkeypatch.delenv("PHOTON_TEXTURE_CACHE")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "file"))
    (tmp_path / "file").write_text("a file")
    assert texture_cache.prepare().folder == str(tmp_path / "file" / "photon" / "textures")
    assert env["PHOTON_TEXTURE_CACHE"] == str(fallback(tmp_path))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert texture_cache.prepare() is None
    assert "PHOTON_TEXTURE_CACHE" not in env


def test_a_folder_that_filled_up_during_a_render_is_left_for_the_next(texture_cache, tmp_path,
                                                                      monkeypatch):
    # The probe passed but the conversion failed (a disk that filled up meanwhile): the
    # warning says so, and the next sync converts into the temporary folder.
    cache = tmp_path / "cache"
    cache.mkdir()
    monkeypatch.setenv("PHOTON_TEXTURE_CACHE", str(cache))
    failure = (f"Generated image 'Grid' cannot be used (Could not open \"{cache}/"
               f"{9:016x}.exr.812.0.tmp.exr\" (No space left on device)): its inputs use "
               f"their fallback colour")
    [warning] = texture_cache.explain([failure])
    assert warning.startswith(f"the texture cache folder '{cache}' cannot be written (Could not "
                              f"open"), warning
    assert "MB free on its disk), so 1 image texture uses its fallback colour" in warning
    assert warning.endswith(f"{REMEDY}; the next renders of this Blender session convert image "
                            f"textures into the temporary folder '{fallback(tmp_path)}' "
                            f"instead"), warning
    redirect = texture_cache.prepare()
    assert redirect is not None and redirect.folder == str(cache)
    assert os.environ["PHOTON_TEXTURE_CACHE"] == str(fallback(tmp_path))


def test_a_temporary_folder_that_fails_too_names_both(texture_cache, tmp_path):
    # Textures redirected to the temporary folder, whose disk then filled up: the warning
    # names the user's folder and the temporary one, each with its reason.
    fallback(tmp_path).write_text("a file")  # (so that its probe fails as well)
    redirect = texture_cache.Redirect("/farm/cache", str(fallback(tmp_path)),
                                      "read-only file system")
    failure = (f"Image '/art/a.png' cannot be used (Could not open \"{fallback(tmp_path)}/"
               f"{5:016x}.exr.812.0.tmp.exr\" (No space left on device)): its inputs use "
               f"their fallback colour")
    assert texture_cache.explain([failure], redirect) == [
        f"the texture cache folder '/farm/cache' cannot be written (read-only file system), nor "
        f"can the temporary folder '{fallback(tmp_path)}' standing in for it ('"
        f"{fallback(tmp_path)}' is a file, not a folder), so 1 image texture uses its fallback "
        f"colour (Image '/art/a.png'); {REMEDY}"]
