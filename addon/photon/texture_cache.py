"""The native texture cache folder when it cannot be written: image textures are converted into
a temporary folder instead, with one clear warning, rather than each falling back to its constant
colour with a reason that names a temporary file.

The native side converts every image to a MIP-mapped file in its cache folder
($PHOTON_TEXTURE_CACHE, else $XDG_CACHE_HOME/photon/textures, else ~/.cache/photon/textures;
native/src/photon/shading/textures.cpp), which it reads from the environment when a session
prepares its textures. When it cannot write there (a read-only or full disk, a folder it may not
write to, a path through a file) each image fails alone:

    Image '/x/wood.png' cannot be used (Could not open "/ro/7f...exr.812.0.tmp.exr"
    (Read-only file system)): its inputs use their fallback colour

So before a session starts, prepare() (called by the sync of a scene with image textures)
writes a probe file into the folder. When that fails, PHOTON_TEXTURE_CACHE is pointed at a
temporary folder (<temp>/photon-textures-<uid>, the native side's own last resort) for this
Blender process, holding links to the files the unwritable folder already has, so a read-only
cache filled beforehand (a render farm's, say) still serves them. After the session, explain()
adds one warning naming the folder, the reason and the temporary folder when textures had to be
converted there, and replaces the warnings of images that failed all the same (both folders
unwritable, or a disk that filled during the conversion) with one per folder.
"""

import errno
import os
import re
import shutil
import tempfile
import time

ENV = "PHOTON_TEXTURE_CACHE"
REMEDY = ("make the folder writable or free space on its disk, or set the environment variable "
          "PHOTON_TEXTURE_CACHE to a writable folder before starting Blender")
# The native warnings of an image texture it could not convert, or whose converted file it
# could not open (textures.cpp).
_UNUSABLE = re.compile(r"^(?P<image>.+?) cannot be used \((?P<reason>.*)\): its inputs use "
                       r"their fallback colour$", re.DOTALL)
# (OpenImageIO's error after the colon may run over several lines.)
_UNOPENABLE = re.compile(r"^(?P<image>.+?) cannot be opened as a texture: (?P<reason>.*)$",
                         re.DOTALL)
# A file of the cache folder: the converted "<key>.exr", its "<key>.exr.stats", or the
# temporary "<key>.exr.<pid>.<n>.tmp.exr" (texture_convert.cpp), quoted by OpenImageIO's errors
# or after "cannot write ".
_CACHE_FILE = re.compile(r'(?:"|cannot write )(?P<path>[^"]*?[0-9a-f]{16}\.exr'
                         r'(?:\.\d+\.\d+\.tmp\.exr|\.stats)?)(?="|$)')
# A converted texture and its stats file (what the native side reuses).
_CONVERTED = re.compile(r"[0-9a-f]{16}\.exr(?:\.stats)?")
_CONVERTED_TEXTURE = re.compile(r"[0-9a-f]{16}\.exr")
PROBE_BYTES = 1 << 16  # a small converted texture's size: a full disk refuses it
NAMES_SHOWN = 3

# While PHOTON_TEXTURE_CACHE points at a temporary folder: "to" is that folder and "user" the
# value the user had set (None: unset), which the next prepare() starts from again.
_redirect = {"user": None, "to": None}
# Folders a session could not write although their probe passed (a disk that filled up during
# a conversion), with the reason: the next syncs of this process go to the temporary folder.
_trouble = {}


def cache_folder(configured=None):
    """The folder the native side converts into with PHOTON_TEXTURE_CACHE=`configured` (None:
    unset), as TextureSet::cache_directory() finds it."""
    if configured:
        return configured
    if os.environ.get("XDG_CACHE_HOME"):
        return os.path.join(os.environ["XDG_CACHE_HOME"], "photon", "textures")
    if os.environ.get("HOME"):
        return os.path.join(os.environ["HOME"], ".cache", "photon", "textures")
    return fallback_folder()


def fallback_folder():
    """The temporary folder that stands in for a cache folder that cannot be written."""
    return os.path.join(tempfile.gettempdir(), f"photon-textures-{os.getuid()}")


class Redirect:
    """The configured cache `folder` cannot be written (`reason`): this sync's textures are
    converted into `fallback`."""

    def __init__(self, folder, fallback, reason):
        self.folder = folder
        self.fallback = fallback
        self.reason = reason
        self.since = time.time() - 1.0  # (file systems with 1 s modification times)

    def converted(self):
        """How many converted textures in the temporary folder (not links to the configured
        folder's) were written or reused since prepare(): the native side refreshes a file's
        modification time on every reuse."""
        count = 0
        try:
            with os.scandir(self.fallback) as entries:
                for entry in entries:
                    if (_CONVERTED_TEXTURE.fullmatch(entry.name) and not entry.is_symlink()
                            and entry.stat().st_mtime >= self.since):
                        count += 1
        except OSError:
            pass
        return count

    def warning(self):
        """The warning after a session that converted textures into the temporary folder, or
        None when the configured folder held every texture it used."""
        count = self.converted()
        if not count:
            return None
        textures = "1 image texture is" if count == 1 else f"{count} image textures are"
        return (f"the texture cache folder '{self.folder}' cannot be written ({self.reason}), "
                f"so {textures} converted into the temporary folder '{self.fallback}' instead; "
                f"{REMEDY}")


def prepare():
    """Chooses where the native side converts the image textures of the session about to
    start (it reads PHOTON_TEXTURE_CACHE then): the configured folder when a probe file can be
    written there, else the temporary folder (Redirect returned), else the configured folder
    all the same (explain() reports the images that fail)."""
    current = os.environ.get(ENV) or None
    ours = _redirect["to"] is not None and current == _redirect["to"]
    user = _redirect["user"] if ours else current
    folder = cache_folder(user)
    reason = write_problem(folder) or _trouble.get(folder)
    fallback = fallback_folder()
    if (reason is None or _same(folder, fallback) or write_problem(fallback) is not None):
        _point_at(user, None)
        return None
    _point_at(user, fallback)
    _link_converted(folder, fallback)
    return Redirect(folder, fallback, reason)


def _point_at(user, fallback):
    """PHOTON_TEXTURE_CACHE set to `fallback`, or back to the user's value without one."""
    _redirect["user"], _redirect["to"] = user, fallback
    value = fallback or user
    if os.environ.get(ENV) == value:
        return  # (changing the environment while native threads may read it is avoided)
    if value is None:
        os.environ.pop(ENV, None)
    else:
        os.environ[ENV] = value


def _same(a, b):
    return os.path.abspath(a) == os.path.abspath(b)


def _link_converted(folder, fallback):
    """Links in `fallback` to the converted textures of `folder` it does not have, so the
    native side reuses them (it only reads them: their modification times stay)."""
    try:
        names = os.listdir(folder)
    except OSError:
        return
    for name in names:
        if not _CONVERTED.fullmatch(name):
            continue
        link = os.path.join(fallback, name)
        if os.path.lexists(link):
            continue
        try:
            os.symlink(os.path.join(os.path.abspath(folder), name), link)
        except OSError:
            return  # the texture is converted again instead


def explain(warnings, redirect=None):
    """The session's `warnings` with the images that failed because a cache folder could not
    be written replaced by one warning per folder (after the others), and `redirect`'s warning
    (prepare()'s) when textures had to go to the temporary folder."""
    kept, failed, problems = [], {}, {}  # failed: folder -> ([image names], native reason)
    for message in warnings:
        failure = _write_failure(message, problems)
        if failure is None:
            kept.append(message)
            continue
        image, folder, native_reason = failure
        failed.setdefault(folder, ([], native_reason))[0].append(image)
    if redirect is not None:
        message = redirect.warning()
        if message is not None:
            kept.append(message)
    for folder, (images, native_reason) in failed.items():
        reason = problems[folder]
        later = ""
        if reason is None:  # the probe passes: a disk that filled up during the conversion
            reason = f"{native_reason}; {_free_mb(folder):.1f} MB free on its disk"
            _trouble[folder] = reason
            fallback = fallback_folder()
            if not _same(folder, fallback) and write_problem(fallback) is None:
                later = (f"; the next renders of this Blender session convert image textures "
                         f"into the temporary folder '{fallback}' instead")
        stood_in = (redirect if redirect is not None and _same(folder, redirect.fallback)
                    else None)
        kept.append(unwritable_warning(folder, images, reason, stood_in) + later)
    return kept


def _write_failure(message, problems):
    """(image, cache folder, native reason) when `message` is the native warning of an image
    that failed for want of writing the cache folder, else None. `problems` keeps each
    folder's write_problem()."""
    match = _UNUSABLE.match(message) or _UNOPENABLE.match(message)
    found = match and _CACHE_FILE.search(match["reason"])
    if not found:
        return None
    folder = os.path.dirname(found["path"])
    if folder not in problems:
        problems[folder] = write_problem(folder)
    # A converted file that does not open is the folder's fault only when the folder cannot
    # be written: a full disk can leave an empty file where a small texture went.
    if match.re is _UNOPENABLE and problems[folder] is None:
        return None
    return match["image"], folder, match["reason"]


def unwritable_warning(folder, images, reason, redirect=None):
    """The warning for the image textures (their native names) a cache folder that cannot be
    written (for `reason`) made fall back to their constant colour; `redirect` when `folder`
    is the temporary folder standing in for the configured one."""
    shown = ", ".join(images[:NAMES_SHOWN])
    if len(images) > NAMES_SHOWN:
        shown += f" and {len(images) - NAMES_SHOWN} more"
    textures = ("1 image texture uses its" if len(images) == 1 else
                f"{len(images)} image textures use their")
    if redirect is not None:
        which = (f"the texture cache folder '{redirect.folder}' cannot be written "
                 f"({redirect.reason}), nor can the temporary folder '{folder}' standing in "
                 f"for it ({reason})")
    else:
        which = f"the texture cache folder '{folder}' cannot be written ({reason})"
    return f"{which}, so {textures} fallback colour ({shown}); {REMEDY}"


def write_problem(folder):
    """Why a converted texture cannot be written into `folder` ("read-only file system", "no
    space left on device", ...), found by writing a probe file there; None when it can."""
    try:
        os.makedirs(folder, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=folder, prefix=".photon-probe-") as probe:
            probe.write(bytes(PROBE_BYTES))
            probe.flush()
    except OSError as exc:
        if exc.errno in (errno.ENOTDIR, errno.EEXIST):
            return f"'{_file_on_path(folder)}' is a file, not a folder"
        return (exc.strerror or str(exc)).lower()
    return None


def _free_mb(folder):
    try:
        return shutil.disk_usage(folder).free / 1e6
    except OSError:
        return 0.0


def _file_on_path(folder):
    """The file that stands where `folder` or one of its parents should be a folder."""
    path = os.path.abspath(folder)
    while not os.path.exists(path) and os.path.dirname(path) != path:
        path = os.path.dirname(path)
    return path
