#!/usr/bin/env bash
# A crash loses at most the last autosave interval of work: an editor with unsaved lights, render
# settings and an albedo override is killed (SIGKILL) once it has written its recovery file; the
# next editor on the scene offers the work back, recovers it as unsaved edits and saves it; the one
# after offers nothing and opens the saved work.
# Usage: recovery.sh TWINLIGHT CONTENT_DIR OUT_DIR (under an X server: with_xvfb.sh)
set -uo pipefail
tl=$1 content=$2 out=$3
rm -rf "$out"
mkdir -p "$out/scene" "$out/config/twinlight"
cp "$content/lamps.gltf" "$content/lamps.bin" "$out/scene/"
printf '{"windowWidth": 800, "windowHeight": 500, "renderScale": 0.25, "autosaveSeconds": 1}\n' >"$out/config/twinlight/settings.json"
export XDG_CONFIG_HOME="$out/config"
scene="$out/scene/lamps.gltf"
fail() {
  echo "recovery.sh: $*"
  exit 1
}

# 1. Edits, then the editor is killed once they are in the recovery file.
cat >"$out/edit.txt" <<EOF
wait-loaded
wait 1
click-ui outliner.lights
wait 1
click-ui lights.add
wait 1
click-ui lights.add.point
wait 2
expect-lights 4
set shadowMapSize=1024
select floor
albedo-override 0.8 0.2 0.2
wait 1000000
EOF
"$tl" --script "$out/edit.txt" "$scene" >"$out/edit.log" 2>&1 &
editor=$!
for _ in $(seq 600); do
  grep -q "autosaved the unsaved work (the lighting, the render settings and the albedo overrides)" "$out/edit.log" && break
  kill -0 "$editor" 2>/dev/null || { cat "$out/edit.log"; fail "the editor ended before it autosaved"; }
  sleep 0.2
done
grep -q "autosaved the unsaved work (the lighting, the render settings and the albedo overrides)" "$out/edit.log" ||
  { cat "$out/edit.log"; kill -9 "$editor"; fail "no autosave within 120 s"; }
kill -9 "$editor"
wait "$editor" 2>/dev/null
cat "$out/edit.log"
ls "$out/config/twinlight/recovery/"*.recovery.json >/dev/null 2>&1 || fail "no recovery file after the kill"
echo "recovery.sh: killed the editor after its autosave"

# 2. The next editor offers the work back; recovered, it is unsaved until saved.
cat >"$out/recover.txt" <<EOF
wait-loaded
wait 1
expect-recovery the lighting, the render settings and 1 albedo override
click-ui recovery.recover
wait 2
expect-recovery none
expect-notice recovered the unsaved work
expect-lights 4
expect-setting shadowMapSize 1024
select floor
expect-albedo-source override
expect-unsaved the lighting, the render settings and the albedo overrides
expect-title lamps.gltf*
key ctrl+S
wait 2
expect-unsaved none
quit
EOF
"$tl" --script "$out/recover.txt" "$scene" >"$out/recover.log" 2>&1 || { cat "$out/recover.log"; fail "the recovering editor failed"; }
cat "$out/recover.log"
ls "$out/config/twinlight/recovery/"*.recovery.json >/dev/null 2>&1 && fail "the recovery file is still there after saving"

# 3. Saved: nothing to recover, the work is in the files.
cat >"$out/after.txt" <<EOF
wait-loaded
wait 1
expect-recovery none
expect-lights 4
expect-setting shadowMapSize 1024
select floor
expect-albedo-source override
expect-unsaved none
quit
EOF
"$tl" --script "$out/after.txt" "$scene" >"$out/after.log" 2>&1 || { cat "$out/after.log"; fail "the editor after saving failed"; }
cat "$out/after.log"
echo "recovery.sh: killed, recovered, saved, reopened"
