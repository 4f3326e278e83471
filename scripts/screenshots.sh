#!/usr/bin/env bash
# Regenerates the editor screenshots in docs/images/ (a real window under Xvfb, default
# layout, 1600x900), then crops each panel out of the overview for the user guide.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
config="$(mktemp -d)"
trap 'rm -rf "$config"' EXIT
rm -rf out/screenshots
XDG_CONFIG_HOME="$config" xvfb-run -a -s "-screen 0 1600x900x24" \
  "${TWINLIGHT_BUILD_DIR:-$root/build}/editor/twinlight" --script docs/screenshots.script
XDG_CONFIG_HOME="$config" xvfb-run -a -s "-screen 0 1600x900x24" \
  "${TWINLIGHT_BUILD_DIR:-$root/build}/editor/twinlight" --script docs/screenshots_views.script
XDG_CONFIG_HOME="$config" xvfb-run -a -s "-screen 0 1600x900x24" \
  "${TWINLIGHT_BUILD_DIR:-$root/build}/editor/twinlight" --script docs/screenshots_tune.script
rm -rf out/screenshots
crop() { oiiotool docs/images/editor_overview.png --cut "$2" -o "docs/images/panel_$1.png"; }
crop outliner 300x420+0+20
crop inspector 300x440+0+440
crop viewport 960x856+300+20
crop lighting 340x380+1260+20
crop timing 340x220+1260+400
crop status 1600x24+0+876
oiiotool docs/images/editor_albedo.png --cut 340x256+1260+620 -o docs/images/panel_albedo.png
oiiotool docs/images/editor_albedo.png --cut 300x440+0+440 -o docs/images/panel_inspector_albedo.png
oiiotool docs/images/editor_buffers.png --cut 470x720+300+20 -o docs/images/panel_buffers.png
oiiotool docs/images/editor_compare.png --cut 360x300+320+420 -o docs/images/panel_compare.png
oiiotool docs/images/editor_presets.png --cut 340x380+1260+20 -o docs/images/panel_presets.png
oiiotool docs/images/editor_tune.png --cut 340x380+1260+20 -o docs/images/panel_tune.png
oiiotool docs/images/editor_compare_band.png --cut 380x360+318+415 -o docs/images/panel_compare_band.png
oiiotool docs/images/editor_help.png --cut 480x360+560+270 -o docs/images/panel_help.png
oiiotool docs/images/editor_browser.png --cut 560x460+520+220 -o docs/images/panel_browser.png
echo "screenshots in docs/images/"
