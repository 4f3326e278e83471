#!/usr/bin/env bash
# One way to open a scene: every scene of content/ opened at start-up (named on the command
# line), by File > Open after another scene, and by File > Reload describes the same state
# (lighting and lights with their sidecar applied, render settings, undo history, unsaved work,
# selection, camera, albedo database, title: the script's dump-state). The start-up used to skip
# the sidecar, the announcement and the history reset: courtyard opened black, area_room without
# its lights, and its first Ctrl+Z undid the scene's lighting.
# Usage: open_ways.sh TWINLIGHT CONTENT_DIR OUT_DIR (under an X server: with_xvfb.sh)
set -euo pipefail
tl=$1 content=$2 out=$3
rm -rf "$out"
mkdir -p "$out/dumps"
# A small window: these runs compare state, not images.
config() {
  mkdir -p "$1/twinlight"
  printf '{"windowWidth": 640, "windowHeight": 400, "renderScale": 0.25}\n' >"$1/twinlight/settings.json"
}
config "$out/config-open"
scenes=("$content"/*.gltf "$content"/*.glb)
# OPEN_WAYS_SCENES="a.gltf b.gltf": only these (a quick look while working on one).
if [ -n "${OPEN_WAYS_SCENES:-}" ]; then
  scenes=()
  for name in $OPEN_WAYS_SCENES; do scenes+=("$content/$name"); done
fi

# File > Open of each scene after the one before, then File > Reload: one editor.
{
  for s in "${scenes[@]}"; do
    printf 'open %s\nwait-loaded\ndump-state %s open\nreload\nwait-loaded\ndump-state %s reload\n' "$s" "$out/dumps" "$out/dumps"
  done
  echo quit
} >"$out/open.txt"
XDG_CONFIG_HOME="$out/config-open" "$tl" --script "$out/open.txt" >"$out/open.log" 2>&1 || {
  cat "$out/open.log"
  echo "open_ways.sh: the File > Open editor failed"
  exit 1
}

# At start-up, each scene named on the command line: one editor each.
printf 'dump-state %s startup\nquit\n' "$out/dumps" >"$out/startup.txt"
for s in "${scenes[@]}"; do
  config "$out/config-startup"
  XDG_CONFIG_HOME="$out/config-startup" "$tl" --script "$out/startup.txt" "$s" >>"$out/startup.log" 2>&1 || {
    cat "$out/startup.log"
    echo "open_ways.sh: the editor started on $s failed"
    exit 1
  }
done

different=0
for s in "${scenes[@]}"; do
  name=$(basename "$s")
  for way in open reload; do
    if ! diff -u "$out/dumps/$name.startup.json" "$out/dumps/$name.$way.json" >"$out/$name.$way.diff"; then
      echo "$name: opened by $way differs from the start-up:"
      cat "$out/$name.$way.diff"
      different=$((different + 1))
    fi
  done
done
if [ "$different" -ne 0 ]; then
  echo "open_ways.sh: $different opening(s) differ"
  exit 1
fi
echo "open_ways.sh: ${#scenes[@]} scenes opened at start-up, by File > Open and by reload: the same state each way"
