#!/usr/bin/env bash
# After editor.lights: the CLI renders what the artist saved. `twinlight render --lighting`
# with the saved sidecar gives the editor's own image (same camera, path, size and the diffuse
# material mode the editor saved it in: lights.txt says why) within
# 0.01 on all but 0.1% of the pixels, while the scene without the sidecar does not; the glTF
# alone holds the four punctual lights (KHR_lights_punctual) that other tools read.
# Usage: check_saved_lighting.sh TWINLIGHT DIR
set -euo pipefail
tl=$1
dir=$2
size=$(oiiotool --info "$dir/editor.exr" | sed -E 's/.*: *([0-9]+) x +([0-9]+),.*/\1x\2/')
"$tl" render --scene "$dir/lamps.gltf" --lighting "$dir/lamps.lighting.json" --path direct --size "$size" --frames 4 \
  --materials diffuse --out "$dir/cli.exr"
"$tl" render --scene "$dir/lamps.gltf" --path direct --size "$size" --frames 4 --materials diffuse --out "$dir/cli_gltf_only.exr"
"$tl" info --scene "$dir/lamps.gltf" | grep -q "lights: 4 (2 point, 2 spot)" || { echo "the glTF does not hold the 4 saved lights"; exit 1; }
if ! oiiotool "$dir/editor.exr" "$dir/cli.exr" --fail 0.01 --failpercent 0.1 --diff; then
  echo "the CLI's render with the saved lighting differs from the editor's image"
  exit 1
fi
if oiiotool "$dir/editor.exr" "$dir/cli_gltf_only.exr" --fail 0.01 --failpercent 0.1 --diff >/dev/null; then
  echo "the render without the sidecar equals the editor's image: the comparison cannot tell lighting apart"
  exit 1
fi
echo "the CLI renders the saved lighting ($size)"
