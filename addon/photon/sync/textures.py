"""Image Texture nodes to native textures: resolves each image to a file OpenImageIO can read
(external files as they are, packed images' bytes written out undecoded) or, for generated
images, to native pixel memory filled in place (one float copy, no reshape or flip: the native
side reads rows bottom-up), and adds each (image, colour space, extension, interpolation) to the
native scene once per render. The native side converts them to MIP-mapped textures in a
persistent cache keyed by content (native/src/photon/shading/texture_convert.h)."""

import os
import re
import shutil
import tempfile

import bpy
import numpy as np

# Colour spaces whose data Photon reads unchanged (scene-linear or plain data).
LINEAR_SPACES = {"Non-Color", "Linear", "Raw", "Linear ACES", "Linear ACEScg", "XYZ",
                 "Linear Rec.709", "Linear Rec.2020", "Linear CIE-XYZ E", "ACEScg"}
SRGB_SPACES = {"sRGB", "sRGB EOTF"}
EXTENSIONS = {'REPEAT', 'EXTEND', 'CLIP'}
INTERPOLATIONS = {'Closest': "Closest", 'Linear': "Linear", 'Cubic': "Cubic",
                  'Smart': "Cubic"}  # Smart is Cubic when magnified, as Cycles renders it
FILE_SUFFIX = {'PNG': ".png", 'JPEG': ".jpg", 'JPEG2000': ".jp2", 'TARGA': ".tga",
               'TARGA_RAW': ".tga", 'TIFF': ".tif", 'OPEN_EXR': ".exr",
               'OPEN_EXR_MULTILAYER': ".exr", 'HDR': ".hdr", 'BMP': ".bmp", 'WEBP': ".webp",
               'DPX': ".dpx", 'CINEON': ".cin", 'IRIS': ".rgb"}


def colour_space(image, where, reporter):
    """srgb flag for an image's colour space; spaces that are neither sRGB nor linear warn."""
    name = image.colorspace_settings.name
    if name in SRGB_SPACES:
        return True
    if name in LINEAR_SPACES:
        return False
    srgb = name == "Filmic sRGB"
    reporter.warning(f"{where}: image '{image.name}' uses colour space '{name}', which is not "
                     f"supported; reading it as {'sRGB' if srgb else 'linear'}")
    return srgb


def alpha_handling(image, node):
    """(alpha, unassociate) as Cycles loads and reads an image: colour images store their
    colour premultiplied by alpha ("ASSOCIATE", straight and premultiplied files alike), Non-Color
    and Channel Packed ones keep it ("KEEP"), alpha mode None makes alpha 1 ("IGNORE"); a node
    whose Alpha output is used divides the colour by alpha again (unassociate)."""
    mode = getattr(image, "alpha_mode", 'STRAIGHT')
    if mode == 'NONE':
        return "IGNORE", False
    if mode == 'CHANNEL_PACKED' or image.colorspace_settings.is_data:
        return "KEEP", False
    alpha = node.outputs.get("Alpha")
    return "ASSOCIATE", bool(alpha is not None and alpha.is_linked)


class TextureTable:
    """Native texture indices for images, added to `native_scene` once per render. Packed and
    generated images are written to a temporary folder that release() deletes (after the
    render: the native texture cache reads files lazily)."""

    def __init__(self, native_scene, reporter, pixels_type=None):
        self._scene = native_scene
        self._reporter = reporter
        self._pixels_type = pixels_type  # _photon.TexturePixels(width, height, is_float)
        self._index = {}     # (path, srgb, extension, interpolation, alpha...) -> index
        self._files = {}     # image name_full -> resolved path (None: unusable)
        self._temp_dir = None
        self.paths = []      # native index -> path (for tests and stats)

    @property
    def temp_dir(self):
        """Folder of the packed and generated images written for this render (or None)."""
        return self._temp_dir

    def release(self):
        if self._temp_dir is not None:
            shutil.rmtree(self._temp_dir, ignore_errors=True)
            self._temp_dir = None

    def _temp_path(self, image, suffix):
        if self._temp_dir is None:
            self._temp_dir = tempfile.mkdtemp(prefix="photon_textures_")
        stem = re.sub(r"[^A-Za-z0-9_.-]", "_", image.name)[:64]
        return os.path.join(self._temp_dir, f"{len(self._files)}_{stem}{suffix}")

    def texture(self, node, where):
        """Native texture index for an Image Texture node, or None (the caller falls back to a
        constant); every problem is reported naming `where` (material and node)."""
        image = node.image
        if image is None:
            self._reporter.warning(f"{where} has no image; using a constant instead")
            return None
        path = self._files.get(image.name_full, "")
        if path == "":
            path = self._resolve(image, where)
            self._files[image.name_full] = path
        if path is None:
            return None
        srgb = colour_space(image, where, self._reporter)
        # Environment textures wrap around horizontally (Cycles reads them with REPEAT).
        extension = getattr(node, "extension", 'REPEAT')
        if extension not in EXTENSIONS:
            self._reporter.warning(f"{where}: extension '{extension}' is not supported; "
                                   f"using REPEAT")
            extension = 'REPEAT'
        interpolation = INTERPOLATIONS.get(node.interpolation, "Linear")
        alpha, unassociate = alpha_handling(image, node)
        key = (path if isinstance(path, str) else id(path), srgb, extension, interpolation,
               alpha, unassociate)
        found = self._index.get(key)
        if found is None:
            if isinstance(path, str):
                found = int(self._scene.add_texture(path, srgb=srgb, extension=extension,
                                                    interpolation=interpolation, alpha=alpha,
                                                    unassociate=unassociate))
            else:  # a generated image's pixels
                found = int(self._scene.add_texture_pixels(path, image.name, srgb=srgb,
                                                           extension=extension,
                                                           interpolation=interpolation,
                                                           alpha=alpha,
                                                           unassociate=unassociate))
            self._index[key] = found
            self.paths.append(path if isinstance(path, str) else image.name)
        return found

    def _resolve(self, image, where):
        source = image.source
        if image.packed_file is not None and source in {'FILE', 'SEQUENCE'}:
            return self._write_packed(image)
        if source == 'GENERATED':
            return self._write_generated(image, where)
        if source not in {'FILE', 'TILED'}:
            self._reporter.warning(f"{where}: image '{image.name}' of type {source.title()} "
                                   f"is not supported; using a constant instead")
            return None
        path = bpy.path.abspath(image.filepath, library=image.library)
        if source == 'TILED':
            self._reporter.warning(f"{where}: UDIM image '{image.name}' is not supported; "
                                   f"using its tile 1001 only")
            path = path.replace("<UDIM>", "1001")
        path = os.path.normpath(path)
        if not os.path.isfile(path):
            self._reporter.warning(f"{where}: image file '{path}' is missing; using a "
                                   f"constant instead")
            return None
        if image.is_dirty:
            self._reporter.warning(f"{where}: image '{image.name}' has unsaved changes; "
                                   f"rendering the file on disk")
        return path

    def _write_packed(self, image):
        # The packed bytes are the original file: write them as-is (no decode, no re-encode).
        suffix = os.path.splitext(image.filepath)[1] or FILE_SUFFIX.get(image.file_format, "")
        path = self._temp_path(image, suffix)
        with open(path, "wb") as f:
            f.write(image.packed_file.data)
        return path

    def _write_generated(self, image, where):
        width, height = image.size
        if self._pixels_type is None or width <= 0 or height <= 0:
            self._reporter.warning(f"{where}: generated image '{image.name}' cannot be "
                                   f"read; using a constant instead")
            return None
        # Generated byte images hold their colour-space values (sRGB-encoded), float ones hold
        # linear values: the native side keeps them and the colour space flag decodes them.
        # foreach_get fills native memory directly: the only full-size copy of the image.
        pixels = self._pixels_type(width, height, bool(image.is_float))
        view = pixels.array
        image.pixels.foreach_get(view)
        del view
        return pixels
