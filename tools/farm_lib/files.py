"""Checked file access for the farm.

Reading: a file is opened without blocking and checked on the open descriptor to be a regular
file, so a FIFO put where a manifest or marker belongs never hangs a task, and a folder or a
device is refused with a message instead of a traceback.

Writing: every file goes to a temporary name beside its destination, is flushed to the disk
(fsync: a full or over-quota disk may refuse the blocks only then), read back and compared, and
only then renamed over the destination, which must be a regular file or absent. Images the farm
did not write itself (Blender's frames and bands) are checked the same way before they are
renamed: opened with OpenImageIO, every subimage's size and channels checked and its pixels
read. Blender reports "Saved" and exits 0 even when the disk filled while it wrote the file.

Every failure raises FileError, whose message names the file, what it is for and the reason.
"""

import json
import os
import shutil
import stat
from pathlib import Path


class FileError(RuntimeError):
    pass


# Channels a Blender image of each colour mode holds at least (an EXR adds Z, a multilayer EXR
# its passes; a BW EXR or HDR is stored as RGB).
MIN_CHANNELS = {"BW": 1, "RGB": 3, "RGBA": 4}

# Header of a Photon prepared-state file (native/.../prepared_state_file.h): magic, format
# version (u32), integrator (u32), fingerprint (u64), payload size (u64), checksum (u64).
_STATE_MAGIC = b"PHOTPREP"
_STATE_HEADER_BYTES = 40
_STATE_SIZE_OFFSET = 24


def _kind(mode):
    for test, name in ((stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO"),
                       (stat.S_ISSOCK, "a socket"), (stat.S_ISCHR, "a character device"),
                       (stat.S_ISBLK, "a block device"), (stat.S_ISLNK, "a symbolic link")):
        if test(mode):
            return name
    return "not a regular file"


def _reason(exc):
    return exc.strerror or str(exc)


def is_regular(path):
    """Whether `path` is a regular file (following links). stat() never blocks on a FIFO."""
    try:
        return stat.S_ISREG(os.stat(path).st_mode)
    except OSError:
        return False


def require_regular(path, what):
    """Raises FileError unless `path` is a regular file (following links)."""
    try:
        mode = os.stat(path).st_mode
    except OSError as exc:
        raise FileError(f"cannot read {what} {path}: {_reason(exc)}") from None
    if not stat.S_ISREG(mode):
        raise FileError(f"{what} {path} is {_kind(mode)}, not a regular file; refusing it")


def read_bytes(path, what):
    # O_NONBLOCK: opening a FIFO with no writer returns at once instead of waiting for one.
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError as exc:
        raise FileError(f"cannot read {what} {path}: {_reason(exc)}") from None
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            raise FileError(f"{what} {path} is {_kind(mode)}, not a regular file; refusing it")
        os.set_blocking(fd, True)
        chunks = []
        while True:
            chunk = os.read(fd, 1 << 20)
            if not chunk:
                return b"".join(chunks)
            chunks.append(chunk)
    except OSError as exc:
        raise FileError(f"cannot read {what} {path}: {_reason(exc)}") from None
    finally:
        os.close(fd)


def read_text(path, what):
    return read_bytes(path, what).decode("utf-8", errors="replace")


def read_json(path, what):
    try:
        return json.loads(read_bytes(path, what))
    except ValueError as exc:
        raise FileError(f"{what} {path} is not valid JSON: {exc}") from None


def check_replaceable(path, what):
    """Raises FileError when `path` exists and is not a regular file: renaming over a folder
    fails, and renaming over a FIFO, device or link would silently destroy it."""
    try:
        mode = os.lstat(path).st_mode
    except FileNotFoundError:
        return
    except OSError as exc:
        raise FileError(f"cannot write {what} {path}: {_reason(exc)}") from None
    if not stat.S_ISREG(mode):
        raise FileError(f"{what} {path} exists and is {_kind(mode)}; refusing to replace it")


def temporary_name(path):
    """A name beside `path`, hidden, that no other process uses; same extension, so a writer
    that picks the format by the name (OpenImageIO) picks the destination's."""
    path = Path(path)
    return path.with_name(f".{path.stem}.partial-{os.getpid()}{path.suffix}")


def discard(path):
    """Removes a temporary file if it is there; never raises."""
    try:
        if os.path.lexists(path) and not os.path.isdir(path):
            os.unlink(path)
    except OSError:
        pass


def write_bytes(path, data, what, mode=0o644):
    """Writes `data` to `path` through a temporary file that is read back before the rename.
    Raises FileError; a failed write leaves `path` as it was and no temporary file."""
    path = Path(path)
    check_replaceable(path, what)
    tmp = temporary_name(path)
    discard(tmp)
    try:
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_CLOEXEC, mode)
        try:
            view = memoryview(data)
            while view:
                view = view[os.write(fd, view):]
            os.fsync(fd)
        finally:
            os.close(fd)
        if read_bytes(tmp, what) != bytes(data):
            raise FileError(f"cannot write {what} {path}: it reads back differently")
        check_replaceable(path, what)
        os.replace(tmp, path)
    except OSError as exc:
        raise FileError(f"cannot write {what} {path}: {_reason(exc)}") from None
    finally:
        discard(tmp)


def write_text(path, text, what, mode=0o644):
    write_bytes(path, text.encode("utf-8"), what, mode)


def write_json(path, value, what):
    write_text(path, json.dumps(value, indent=1), what)


def _sync(path, what):
    """fsync a file another process wrote, so a disk that refuses its blocks late says so now."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)
    except OSError as exc:
        raise FileError(f"cannot write {what} {path}: {_reason(exc)}") from None


def check_image(path, what, width, height, min_channels=1):
    """Raises FileError unless `path` is an image whose every subimage is width x height with
    at least `min_channels` channels and whose pixels all read. Returns the subimages'
    (channel names) for comparing layouts."""
    import OpenImageIO as oiio
    require_regular(path, what)
    _sync(path, what)
    inp = oiio.ImageInput.open(str(path))
    if inp is None:
        raise FileError(f"{what} {path} is not a readable image: {oiio.geterror()}")
    layouts = []
    try:
        while inp.seek_subimage(len(layouts), 0):
            spec = inp.spec()
            if (spec.width, spec.height) != (width, height):
                raise FileError(f"{what} {path} is {spec.width}x{spec.height}, not "
                                f"{width}x{height}")
            if spec.nchannels < min_channels:
                raise FileError(f"{what} {path} has {spec.nchannels} channel(s), fewer than "
                                f"{min_channels}")
            if inp.read_image(oiio.FLOAT) is None:
                raise FileError(f"{what} {path} is damaged or incomplete (its pixels do not "
                                f"read: {inp.geterror() or 'no reason given'})")
            layouts.append(list(spec.channelnames))
    finally:
        inp.close()
    if not layouts:
        raise FileError(f"{what} {path} holds no image")
    return layouts


def place_image(src, dest, what, width, height, min_channels=1):
    """Checks the image `src` (check_image) and renames it to `dest`."""
    check_image(src, what, width, height, min_channels)
    move(src, dest, what)


def move(src, dest, what):
    """Renames `src` over `dest`, which must be a regular file or absent."""
    dest = Path(dest)
    try:
        dest.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise FileError(f"cannot write {what} {dest}: {_reason(exc)}") from None
    check_replaceable(dest, what)
    try:
        os.replace(src, dest)
    except OSError as exc:
        raise FileError(f"cannot write {what} {dest}: {_reason(exc)}") from None


def check_state_file(path, what="prepared state"):
    """Raises FileError unless `path` is a prepared-state file whose size is what its header
    says. (Photon checks the checksum when it loads it; this catches a truncated file early.)"""
    require_regular(path, what)
    _sync(path, what)
    try:
        with open(path, "rb") as f:
            header = f.read(_STATE_HEADER_BYTES)
            size = os.fstat(f.fileno()).st_size
    except OSError as exc:
        raise FileError(f"cannot read {what} {path}: {_reason(exc)}") from None
    if len(header) < _STATE_HEADER_BYTES or not header.startswith(_STATE_MAGIC):
        raise FileError(f"{what} {path} is not a prepared-state file (or is truncated)")
    payload = int.from_bytes(header[_STATE_SIZE_OFFSET:_STATE_SIZE_OFFSET + 8], "little")
    if size != _STATE_HEADER_BYTES + payload:
        raise FileError(f"{what} {path} holds {size} bytes, its header says "
                        f"{_STATE_HEADER_BYTES + payload}")


def remove(path, what):
    """Removes the file `path` (absent is fine). Raises FileError for anything but a regular file
    or a link, which the farm did not make and leaves alone."""
    try:
        mode = os.lstat(path).st_mode
    except FileNotFoundError:
        return
    except OSError as exc:
        raise FileError(f"cannot remove {what} {path}: {_reason(exc)}") from None
    if not (stat.S_ISREG(mode) or stat.S_ISLNK(mode)):
        raise FileError(f"{what} {path} is {_kind(mode)}, not a file; left in place")
    try:
        os.unlink(path)
    except OSError as exc:
        raise FileError(f"cannot remove {what} {path}: {_reason(exc)}") from None


def fresh_dir(path):
    """An empty folder at `path`, whatever was there (a previous attempt's files, or a file)."""
    path = Path(path)
    try:
        if path.is_dir() and not path.is_symlink():
            shutil.rmtree(path)
        elif os.path.lexists(path):
            path.unlink()
        path.mkdir(parents=True)
    except OSError as exc:
        raise FileError(f"cannot make the folder {path}: {_reason(exc)}") from None
    return path
