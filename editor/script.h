// `twinlight --script FILE`: editor actions, one a line, run as a person would use the
// editor (one action per frame; `wait` lets frames pass). A failed action or expectation
// stops the editor with exit code 1 and the line number. Each command is a function in the
// table of editor/script_commands.h.
//
//   open PATH              load a scene (relative: to the working directory, else the project)
//   wait-loaded            wait until the scene has loaded
//   path NAME              switch the lighting path
//   click X Y              left click at window pixel (X, Y)
//   click-viewport U V     left click at a fraction (U, V) of the viewport panel
//   select NAME            select the instance called NAME
//   expect-selected NAME   fail unless NAME (or `none`) is selected
//   preview RESOURCE       show a resource of the frame in the viewport (`final` for the image)
//   render-scale S         engine resolution relative to the viewport
//   help on|off, browser on|off
//   wait N                 let N engine frames finish (UI frames when nothing renders)
//   measure N              run N passes of the UI loop and print its rate (the UI's frame
//                          rate: each pass takes the input and runs the panels), the window
//                          frames presented (a pass that changes nothing on screen is not
//                          drawn again) and the engine's frame rate
//   screenshot FILE        save the whole window as PNG
//   capture [DIR]          write every buffer of the next frame (EXR + manifest.json) into DIR
//   snapshot               remember the viewport image of the next frame
//   expect-viewport-changed [D]  fail unless the viewport differs from the snapshot by a mean
//                          absolute difference of at least D (default 0.01; more for a noisy path)
//   albedo-db PATH         open (or create) the albedo database
//   albedo-bake            bake the scene into it (one batch a frame) and wait until done
//   albedo-override R G B  override the selected instance's albedo (linear RGB)
//   albedo-undo, albedo-redo, albedo-save
//   expect-scene-warnings N  fail unless the scene has N import warnings (and the Scene panel is open); lists them
//   expect-scene-report TEXT  fail unless the Scene panel is open and a line of its report holds TEXT
//   expect-orphans N       fail unless N overrides are orphaned (their mesh + material is gone); lists them
//   orphan-reapply I [selected]  re-apply orphan I (0 = first listed) to its new key, or to the selection
//   orphan-delete I        delete orphan I (removed from the database on albedo-save)
//   albedo-impact          remember this image and show what later albedo edits change
//   expect-albedo-source S fail unless the selected instance's albedo comes from S
//                          (override, baked, texture average)
//   buffers on|off         the Buffers panel
//   view RESOURCE          show a resource through the viewer (range fitted); `final` for the image
//   view-channel C         rgb, r, g, b, a or luminance
//   view-meaning on|off    what a decoded resource means (default) or its stored values
//   expect-meaning TEXT    fail unless the viewer shows a meaning containing TEXT (`stored values`
//                          when raw), with its range fitted; prints the range
//   view-false-colour on|off, view-zoom Z U V (zoom Z around source UV), view-slice N
//   expect-slice TEXT      fail unless the 3D image's slice is named TEXT ("level 1, world z voxel 5 of 64")
//   expect-square-texels   fail unless the viewed resource's texels show square in the viewport
//                          (its true aspect); prints the shown window
//   keep-b, show-b on|off  A/B against a kept copy
//   view-probe X Y         probe texel (X, Y) as if hovered
//   expect-probe X Y TEXT  fail unless texel (X, Y) (in a volume, of the slice on view) has raw or decoded
//                          lines containing TEXT (or one of A|B)
//   expect-viewer-matches-capture DIR  the viewer's read-back equals DIR/<resource>.exr
//   append-line FILE TEXT  append a line to a file (tests: break a shader under TWINLIGHT_SHADER_SOURCES)
//   expect-shader-error T  wait (up to 120 frames) for a hot-reload error containing T
//   open-capture DIR       reopen a capture (its buffers, without the scene); close-capture
//   renderdoc-capture      capture the next frame in RenderDoc (fails with the reason outside it)
//   compare LEFT RIGHT     split the viewport between two lighting paths (Compare panel); compare off
//   compare-mode wipe|difference, compare-wipe F (0..1 of the width)
//   animation play|pause|T play or pause the scene's morph animations, or pause at T seconds
//   expect-compare-errors  fail unless every side has a finite relMSE and FLIP against the reference
//   camera-move X Y Z      move the camera X, Y, Z metres along its right, up and forward axes
//   expect-reference-restarted PART  fail unless the Compare panel's reference started over since
//                          the last camera-move, PART (a frame-key part, e.g. camera.position)
//                          among its causes, and now holds fewer samples than it did then
//   mouse-click X Y        a person's left click at window pixel (X, Y), through the window's input
//   click-ui NAME, double-click-ui NAME   the same on a named control (ui_helpers.h trackItem)
//   mouse-wheel X Y STEPS  the wheel turned STEPS (negative: down, scrolls a panel's contents up) at (X, Y)
//   key [ctrl+][shift+]K   a quick tap of key K (F1, Z, Enter, ...), pressed and released in one frame
//   type TEXT              characters typed into the focused text field
//   expect-compare-mode M  fail unless the compare view shows M (wipe or difference)
//   expect-viewing R       fail unless the viewport shows resource R (`final` for the image)
//   expect-notice TEXT     fail unless a status-bar message contains TEXT
//   expect-labels-fit      fail when a panel's label was cut off by its window last frame
//   set NAME=VALUE         change a render setting (what the Lighting panel's widget for it does)
//   undo, redo             Ctrl+Z / Ctrl+Y: the latest settings, lighting or albedo edit
//   preset NAME            a preset of the current path (Fast, Balanced, Reference-like) or your own
//   save-preset NAME       write every panel setting to the presets folder as NAME.json
//   expect-setting NAME V  fail unless the setting's value reads V ("512", "clay", "true")
//   copy-file SRC DST      copy SRC over DST as an exporter does (a temporary, then a rename)
//   expect-reload          wait (up to 60 s) until the scene reloaded after the last
//                          copy-file, and fail unless the camera is where it was then
//   save-image FILE        File > Save image: the last frame as .png or .exr
//   drag-ui NAME DX DY [U V]  press on a named control or viewport handle (gizmo.move.x, gizmo.aim,
//                          light.icon.N), at the fraction U, V of its box (its centre by default),
//                          move by DX, DY pixels over eight frames, release
//   expect-lights N        fail unless the scene has N lights besides the sun; lists them
//   expect-light I TEXT    fail unless light I's line ("name (type) at x y z aim dx dy dz I unit
//                          [hidden]") holds TEXT
//   expect-lights-apart I J  fail unless lights I and J stand apart (not at one point)
//   expect-gizmo-followed  fail unless the last gizmo drag moved the light along its arrow alone,
//                          as far as the mouse went along it (or aimed its knob under the mouse)
//   expect-selected-light NAME  fail unless the light NAME (or `none`) is selected
//   save-lighting          File > Save lighting: the lights into the glTF, all into SCENE.lighting.json
//   expect-sun TEXT        fail unless the sun's line ("sun E r g b towards x y z") holds TEXT
// The artist's work (script_work.cpp):
//   reload                 File > Reload scene (wait-loaded waits for it)
//   close-window           the window's close button (File > Quit): asks first when work is unsaved
//   expect-question TEXT   fail unless the unsaved-work question is asked and holds TEXT (`none`: not
//                          asked); click-ui unsaved.save, unsaved.discard or unsaved.cancel answers it
//   expect-unsaved TEXT    fail unless the unsaved work's description holds TEXT (`none`: nothing unsaved)
//   expect-title TEXT      fail unless the window's title holds TEXT
//   expect-recovery TEXT   fail unless a recovery is offered and its text holds TEXT (`none`: not
//                          offered); click-ui recovery.recover or recovery.discard answers it
//   autosave-every S       write unsaved work to the recovery file every S seconds (1 to 60)
//   expect-stopped TEXT    fail unless what the last scene change stopped holds TEXT (`none`: nothing)
//   tune-view BUDGET [WxH CANDIDATES RUNGS FRAMES SPP]
//                          Lighting › Tune for this view (a child `twinlight tune`; the button's sizes
//                          by default: 320x180 81 3 32 256)
//   wait-tune [SECONDS]    hold the next line until the tune ends (default 600 s; fails after)
//   stop-tune              stop the running tune (its measurements stay in its folder)
//   expect-tune TEXT       fail unless what the last tune did holds TEXT ("finished: 1 preset(s)")
//   resize W H             resize the window to W x H pixels, as a person dragging its corner
//   expect-viewport-uncovered  fail when a panel (not a dialog) lies over the viewport
//   dump-state DIR TAG     write what the scene opened as (lighting, settings, history, selection,
//                          camera, database, albedo overrides, title) to DIR/<scene file>.TAG.json,
//                          to compare ways of opening (and for the soak walk to check its edits)
//   quit                   quit at once; unsaved work is discarded (close-window asks)
#pragma once

#include "script_commands.h"

#include <filesystem>
#include <string>
#include <vector>

namespace tl::editor {

class EditorApp;

class Script {
 public:
  explicit Script(const std::filesystem::path& file);
  void step(EditorApp& app);
  bool failed() const { return !failure_.empty(); }
  const std::string& failure() const { return failure_; }

 private:
  void fail(EditorApp& app, const std::string& why);
  std::filesystem::path file_;
  std::vector<std::string> lines_;
  size_t next_ = 0;
  std::string failure_;
  ScriptState state_;
};

}  // namespace tl::editor
