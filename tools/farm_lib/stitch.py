"""Assembles a frame from its horizontal bands with OpenImageIO (Debian's python3-openimageio):
each band file is a full-size render with Blender's border on one band (crop off), so its own
rows are exactly the full render's; every channel of every subimage is copied, each written back
in its own stored type (Blender's half-float EXRs keep float32 Depth and Normal).

Copies are exact: band values are read as float32, which holds every half, 8- and 16-bit value,
and written back to the type they came from.
"""

from pathlib import Path

from . import files

# Formats OIIO writes from a stitched buffer; JPEG bands are rendered as PNG (lossless, same
# display-referred 8 bits) and the stitched frame is encoded once.
OIIO_FORMATS = {"OPEN_EXR": "openexr", "OPEN_EXR_MULTILAYER": "openexr", "PNG": "png",
                "TIFF": "tiff", "BMP": "bmp", "TARGA_RAW": "targa", "HDR": "hdr",
                "JPEG": "jpeg"}
BAND_FORMAT = {"JPEG": "PNG"}

# Blender's own run metadata that describes one band's render, not the frame.
_DROP_ATTRIBUTES = ("RenderTime", "Date", "oiio:subimages")


class StitchError(RuntimeError):
    pass


def _read_subimages(path):
    import OpenImageIO as oiio
    try:
        # OpenImageIO would wait for ever on a FIFO.
        files.require_regular(path, "band")
    except files.FileError as exc:
        raise StitchError(str(exc)) from None
    inp = oiio.ImageInput.open(str(path))
    if inp is None:
        raise StitchError(f"cannot open band {path}: {oiio.geterror()}")
    images = []
    try:
        index = 0
        while inp.seek_subimage(index, 0):
            spec = inp.spec()
            pixels = inp.read_image(oiio.FLOAT)
            if pixels is None:
                raise StitchError(f"cannot read band {path}: {inp.geterror()}")
            images.append((oiio.ImageSpec(spec), pixels))
            index += 1
    finally:
        inp.close()
    return images


def _same_layout(a, b):
    return (a.width, a.height, a.nchannels, list(a.channelnames)) == \
        (b.width, b.height, b.nchannels, list(b.channelnames))


def stitch(band_paths, rows, out_path, file_format, quality=90):
    """Writes out_path (through a temporary name, read back and renamed when complete) from band
    files whose rows rows[k] = (y0, y1) (top row first) belong to band k."""
    import OpenImageIO as oiio
    if len(band_paths) != len(rows):
        raise StitchError("one band file per row range expected")
    bands = [_read_subimages(p) for p in band_paths]
    first = bands[0]
    for path, band in zip(band_paths, bands):
        if len(band) != len(first) or not all(_same_layout(s, f[0]) for (s, _), f in
                                                zip(band, first)):
            raise StitchError(f"band {path} does not have the layout of {band_paths[0]}")
    specs, images = [], []
    for index, (spec, _) in enumerate(first):
        pixels = first[index][1].copy()
        for band, (y0, y1) in zip(bands, rows):
            pixels[y0:y1] = band[index][1][y0:y1]
        out_spec = oiio.ImageSpec(spec)
        for name in _DROP_ATTRIBUTES:
            out_spec.erase_attribute(name)
        if file_format == "JPEG":
            out_spec.attribute("Compression", f"jpeg:{int(quality)}")
        specs.append(out_spec)
        images.append(pixels)

    out_path = Path(out_path)
    # Same extension, so OIIO picks the same format; renamed only once written and read back.
    tmp = files.temporary_name(out_path)
    try:
        _write(tmp, file_format, specs, images)
        # Read back: a full disk can make OpenEXR's writes fail while OIIO still says done.
        layouts = files.check_image(tmp, "stitched frame", specs[0].width, specs[0].height)
        if layouts != [list(spec.channelnames) for spec in specs]:
            raise StitchError(f"{tmp} reads back with other channels than were written")
        files.move(tmp, out_path, "frame")
    except files.FileError as exc:
        raise StitchError(str(exc)) from None
    finally:
        files.discard(tmp)


def _write(tmp, file_format, specs, images):
    import OpenImageIO as oiio
    out = oiio.ImageOutput.create(OIIO_FORMATS.get(file_format, str(tmp)))
    if out is None:
        raise StitchError(f"OpenImageIO cannot write {file_format}: {oiio.geterror()}")
    if len(specs) > 1:
        ok = out.open(str(tmp), tuple(specs))
    else:
        ok = out.open(str(tmp), specs[0], "create")
    if not ok:
        raise StitchError(f"cannot write {tmp}: {out.geterror()}")
    try:
        for index, (spec, pixels) in enumerate(zip(specs, images)):
            if index and not out.open(str(tmp), spec, "appendsubimage"):
                raise StitchError(f"cannot append subimage to {tmp}: {out.geterror()}")
            if not out.write_image(pixels):
                raise StitchError(f"cannot write {tmp}: {out.geterror()}")
    finally:
        closed = out.close()
    if not closed:
        raise StitchError(f"cannot finish {tmp}: {out.geterror()}")
