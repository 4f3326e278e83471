#!/usr/bin/env bash
# A tune's folder holds runs measured on its scenes as they were: the same command after the
# scene file was edited (here one material's colour) is refused by name, not resumed on stale
# figures; the unedited scene resumes. Prints "tune scene edited: ok".
#
#   tune_scene_edited.sh TWINLIGHT CONTENT_DIR OUT
set -euo pipefail
tl="$1" content="$2" out="$3"
rm -rf "$out"
mkdir -p "$out/scene"
cp "$content/cornell.gltf" "$content/cornell.bin" "$out/scene/"
fail() { echo "tune scene edited: $*" >&2; exit 1; }
tiny=(--scene "$out/scene/cornell.gltf" --size 32x18 --candidates 2 --rungs 1 --frames 4 --spp 8 --budget 1000ms
  --cache "$out/cache" --out "$out/tune")

"$tl" tune "${tiny[@]}" >"$out/first.log" 2>&1 || { cat "$out/first.log"; fail "the first tune failed"; }
"$tl" tune "${tiny[@]}" >"$out/again.log" 2>&1 || { cat "$out/again.log"; fail "the unedited scene did not resume"; }
python3 - "$out/scene/cornell.gltf" <<'PY'
import json, sys
g = json.load(open(sys.argv[1]))
g["materials"][0].setdefault("pbrMetallicRoughness", {})["baseColorFactor"] = [0.2, 0.6, 0.9, 1.0]
json.dump(g, open(sys.argv[1], "w"))
PY
if "$tl" tune "${tiny[@]}" >"$out/edited.log" 2>&1; then cat "$out/edited.log"; fail "the edited scene resumed the old runs"; fi
grep -q "cornell.gltf changed since this folder's runs were measured" "$out/edited.log" || { cat "$out/edited.log"; fail "no clear refusal"; }
echo "tune scene edited: ok"
