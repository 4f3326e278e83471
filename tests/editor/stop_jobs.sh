#!/usr/bin/env bash
# Background work belongs to the scene it works for: another scene opened, or the editor quit,
# while it runs stops it first and waits for it. For one JOB, 10 times each: the scene is
# changed while the job runs (one editor), and the editor is closed while it runs (10 editors);
# each must exit 0. Opening another scene or the file changing on disk during a bake used to
# crash the editor (SIGSEGV), and quitting during one to abort it (SIGABRT in vkWaitSemaphores).
#
# Usage: stop_jobs.sh TWINLIGHT CONTENT_DIR SHADER_COPY OUT_DIR JOB [TIMES]   (under an X server)
# JOB: bake (the albedo bake of a 400-key scene), reference (the reference path's frames),
# compare (the Compare panel: its sides, the reference and its FLIP), shader (a shader edited: hot
# reload), watch (the scene's file rewritten: the reload it starts).
set -uo pipefail
tl=$1 content=$2 shaders=$3 out=$4 job=$5 times=${6:-10}
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"
mkdir -p "$out/config/twinlight" "$out/watched"
printf '{"renderScale": 0.25}\n' >"$out/config/twinlight/settings.json"
export XDG_CONFIG_HOME="$out/config"
other="$content/plane.gltf"
fail() {
  echo "stop_jobs.sh ($job): $*"
  exit 1
}

scene="$content/cornell.gltf"
case "$job" in
  bake)
    python3 "$here/../../scripts/make_many_keys_scene.py" "$out/many_keys.gltf" 400 >/dev/null || fail "cannot make the scene"
    scene="$out/many_keys.gltf"
    start="albedo-db $out/bake.db
wait 1
click-ui albedo.rebake"
    stopped="expect-stopped the albedo bake" ;;
  reference)
    start="path reference"
    stopped="" ;;
  compare)
    start="compare direct rt"
    stopped="" ;;
  shader)
    [ -d "$shaders" ] || fail "no shader copy at $shaders"
    export TWINLIGHT_SHADER_SOURCES="$shaders"
    start="append-line $shaders/common/tonemap.comp // edited while the scene changes"
    stopped="" ;;
  watch)
    cp "$content/cornell.gltf" "$content/cornell.bin" "$out/watched/"
    scene="$out/watched/cornell.gltf"
    start="copy-file $content/cornell.gltf $out/watched/cornell.gltf"
    stopped="" ;;
  *) fail "unknown job (bake, reference, compare, shader, watch)" ;;
esac

# The scene changed while the job runs, $times times in one editor (each a little later in it).
{
  for i in $(seq "$times"); do
    printf 'open %s\nwait-loaded\n%s\nwait %d\nopen %s\nwait-loaded\n%s\npath direct\ncompare off\n' \
      "$scene" "$start" $((i % 4)) "$other" "$stopped"
  done
  echo quit
} >"$out/change.txt"
"$tl" --script "$out/change.txt" >"$out/change.log" 2>&1
status=$?
[ "$status" -eq 0 ] || { cat "$out/change.log"; fail "the editor changing scenes exited $status"; }
echo "stop_jobs.sh ($job): changed the scene $times times while it ran"
grep -E "^stopped" "$out/change.log" | sort | uniq -c | sed 's/^/  /'

# The window closed while the job runs, $times editors.
for i in $(seq "$times"); do
  printf '%s\nwait %d\nclose-window\nwait 100\n' "$start" $((i % 4)) >"$out/quit.txt"
  "$tl" --script "$out/quit.txt" "$scene" >"$out/quit.log" 2>&1
  status=$?
  [ "$status" -eq 0 ] || { cat "$out/quit.log"; fail "the editor closed during the job exited $status (run $i)"; }
  if [ "$job" = bake ]; then
    grep -q "stopped the albedo bake .* for quitting" "$out/quit.log" || { cat "$out/quit.log"; fail "quitting did not say it stopped the bake (run $i)"; }
  fi
  grep -E "^stopped" "$out/quit.log" >>"$out/quit_stopped.log"
done
echo "stop_jobs.sh ($job): closed the editor $times times while it ran"
[ -f "$out/quit_stopped.log" ] && sort "$out/quit_stopped.log" | sed 's/ in [0-9.]* s$//' | uniq -c | sed 's/^/  /'
exit 0
