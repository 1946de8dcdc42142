#!/usr/bin/env bash
# Installs what is missing, builds Photon, installs the add-on into your Blender user scripts
# (enabled in Preferences), and renders the demo Cornell box to out/cornell_box.png.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

install_packages
build

# Blender's per-user folder (e.g. ~/.config/blender/3.4); add-ons live in scripts/addons there.
USER_DIR="$(blender -b --factory-startup --python-expr \
  'import bpy; print("PHOTON_USER_DIR=" + bpy.utils.resource_path("USER"))' 2>/dev/null |
  sed -n 's/^PHOTON_USER_DIR=//p')"
cmake --install "$BUILD" --prefix "$USER_DIR/scripts" --component addon >/dev/null
echo "== add-on installed in $USER_DIR/scripts/addons/photon"
blender -b --python-expr \
  'import addon_utils, bpy; addon_utils.enable("photon", default_set=True); bpy.ops.wm.save_userpref()' \
  >/dev/null 2>&1 && echo "== add-on enabled in Blender's preferences"
cmake --build "$BUILD" --target photon_addon_zip >/dev/null
echo "== installable zip: $BUILD/photon-addon.zip"

mkdir -p "$REPO/out"
blender -b "$REPO/test_scenes/cornell_box.blend" --addons photon -E PHOTON \
  -o "$REPO/out/cornell_box_####" -F PNG -x 1 -f 1 | grep -E "^Photon|Saved"
mv -f "$REPO/out/cornell_box_0001.png" "$REPO/out/cornell_box.png"
echo "== demo render: $REPO/out/cornell_box.png"
