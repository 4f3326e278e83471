#!/usr/bin/env python3
"""Editor soak: a seeded random walk of user actions on copies of content scenes, run as the
editor's own scripts (`twinlight --script`) under an X server, counting crashes, lost edits and
validation messages.

Actions: open another scene (answering the unsaved-work question: save, discard or cancel),
switch the lighting path, edit (add or delete a light, change a render setting, override an
albedo), undo, redo, bake the albedo, capture a frame, split the viewport (compare), drag in the
viewport, resize the window, reload the scene, save, and quit (the window's close button,
answered the same way; the walk goes on in a new editor).

The walk keeps a model of what the artist has and what each scene's files hold, and of the
editor's two undo histories (lighting and settings; albedo), undone latest first. It is checked
three ways:
- in the editor, after every action (expect-lights, expect-setting, expect-unsaved; a failed
  expectation stops that editor with exit code 1 and its line);
- after every editor, from `dump-state` written after every action: each light exactly as it was
  when it was made (a light is known by what it was when it first appeared), the setting, the
  albedo override's colour and the unsaved work's exact description;
- after every editor, the files themselves: the scene's lighting sidecar (every light), the albedo
  database's overrides and the render settings saved with the scene.
Every opening of a scene in a new editor is a reload of what was saved, so a save that lost
something shows as a light, a colour or a setting that differs from the walk's.

A crash is an editor that exits with neither 0 nor 1 (a signal included), one that does not end
within its time, or a sanitizer report. A lost edit is a failed expectation or a difference
between the model and a dump or a file. A validation message (or an `[error]` line) is counted
apart. The exit status is 0 only when there was none of these.

--inject-defect shows that the walk can fail: `skip-save` leaves the Ctrl+S out of the script
once (the model believes it saved), `kill` kills the first editor halfway (SIGKILL).

Usage: soak_editor.py --twinlight BIN --content DIR --out DIR [--actions N] [--seed S]
                      [--segment N] [--xvfb tests/editor/with_xvfb.sh] [--inject-defect kill|skip-save]
Prints one line per editor run and a summary: actions, editors run, crashes, lost edits,
validation messages, seconds.
"""
import argparse
import glob
import json
import math
import os
import random
import re
import shutil
import signal
import sqlite3
import subprocess
import sys
import threading
import time

SCENES = ["cornell", "lamps", "area_room", "courtyard", "atrium"]
PATHS = ["direct", "legacy", "rt", "reference"]
SHADOW_SIZES = [512, 1024, 2048, 4096]
DEFAULT_SHADOW = 2048
# The editor's own lines that fail a test (tests/cli/check_command.cmake forbids the same).
VALIDATION = re.compile(r"[Vv]alidation|VUID-|SYNC-HAZARD|\[error\]|\[critical\]")
SANITIZER = re.compile(r"ERROR: (?:AddressSanitizer|LeakSanitizer)|runtime error:|SUMMARY: \w+Sanitizer")


class Scene:
    """What the files of one scene hold."""

    def __init__(self, name, lights, instance):
        self.name = name
        self.instance = instance  # the instance the walk overrides
        self.saved_lights = list(lights)  # light tokens
        self.saved_override = None  # the colour saved in the database, or None
        self.saved_settings = None  # the shadow map size saved with the scene (File > Save), or None
        self.lighting_written = False  # the walk saved lighting: the sidecar is the editor's own
        self.db_opened = False


class History:
    """One of the editor's undo histories: steps (what, before, after, when made), `done` applied."""

    def __init__(self):
        self.steps, self.done = [], 0

    def push(self, what, before, after, when):
        del self.steps[self.done:]
        self.steps.append((what, before, after, when))
        self.done += 1

    def undo_time(self):
        return self.steps[self.done - 1][3] if self.done > 0 else None

    def redo_time(self):
        return self.steps[self.done][3] if self.done < len(self.steps) else None


def rgb_equal(a, b):
    if a is None or b is None:
        return a is None and b is None
    return all(abs(x - y) <= 1e-5 for x, y in zip(a, b))


def light_fields(light):
    """A light as the walk compares it: the node it was saved to is bookkeeping, not an edit."""
    return {k: v for k, v in light.items() if "node" not in k}


def describe_light(fields):
    """light_fields as one line, for a message."""
    return json.dumps(fields, sort_keys=True)


def same_light(a, b):
    """Two light_fields that are the same light, numbers within float rounding (as the editor
    compares them: a light added again at the orbit's pivot lands there through other sums)."""
    def near(x, y):
        if isinstance(x, list) and isinstance(y, list):
            return len(x) == len(y) and math.dist(x, y) <= 1e-6 * max(math.hypot(*x), math.hypot(*y), 1e-30)
        if isinstance(x, (int, float)) and isinstance(y, (int, float)) and not isinstance(x, bool):
            return abs(x - y) <= 1e-6 * max(abs(x), abs(y))
        return x == y
    return a.keys() == b.keys() and all(near(a[k], b[k]) for k in a)


class Walk:
    def __init__(self, args):
        self.args = args
        self.rng = random.Random(args.seed)
        self.out = os.path.abspath(args.out)
        self.scene_dir = os.path.join(self.out, "scenes")
        self.dump_dir = os.path.join(self.out, "dumps")
        self.config = os.path.join(self.out, "config")
        self.scenes = {}
        self.next_id = 0
        self.bound = {}  # light token -> the light as it first appeared (light_fields)
        self.lines = []
        self.expected = []  # (tag, scene name, expected state) for the dumps of one editor
        self.current = None
        self.lights, self.override, self.shadow = [], None, DEFAULT_SHADOW
        self.baseline_shadow = DEFAULT_SHADOW  # the settings as opened or last saved
        self.lh, self.ah = History(), History()  # lighting and settings; albedo
        self.clock = 0  # orders the edits as the editor's steady clock does
        # A new light is known by what the editor makes it from (addLight): its kind, its name
        # (the kind and how many lights of that kind there are) and its place. The editor puts it
        # at the orbit camera's pivot (0.3 of the scene's diagonal in front of it, where orbiting
        # keeps it), stepped a quarter of that to the camera's right past any light within a
        # fifth of it. The walk follows the camera's yaw through its drags (0.005 rad a pixel) and
        # keeps each light it added at its place (in units of that distance, about the pivot), so
        # the same add from the same state makes the same light again, and the editor (which
        # compares lights by what they cast) calls it the light it replaced, saved or not. The
        # scene's own lights stand elsewhere: they take no place.
        self.yaw = 0.0  # radians from the opening camera's
        self.adds = {}  # (kind, name, scene, place) -> the light token it made
        self.kind = {}  # light token -> its kind
        self.place = {}  # token of an added light -> (x, z) about the pivot
        self.path = "direct"
        self.compare = False
        self.actions = 0
        self.saves_skipped = 0

    # --- set-up ---------------------------------------------------------------------------
    def prepare(self):
        for d in (self.scene_dir, self.dump_dir, self.config, os.path.join(self.out, "dbs")):
            shutil.rmtree(d, ignore_errors=True)
        os.makedirs(self.scene_dir)
        os.makedirs(self.dump_dir)
        os.makedirs(os.path.join(self.config, "twinlight"))
        os.makedirs(os.path.join(self.out, "dbs"))
        content = self.args.content
        for folder in ("environments", "textures"):
            shutil.copytree(os.path.join(content, folder), os.path.join(self.scene_dir, folder))
        self.bound = {}
        for name in SCENES:
            for ext in (".gltf", ".bin", ".lighting.json"):
                src = os.path.join(content, name + ext)
                if os.path.exists(src):
                    shutil.copy(src, self.scene_dir)
            gltf = json.load(open(os.path.join(self.scene_dir, name + ".gltf")))
            # The lights the scene opens with are learnt from its first dump (bound then).
            tokens = []
            for kind in self.opening_light_kinds(name, gltf):
                tokens.append(self.new_id())
                self.kind[tokens[-1]] = kind
            instance = next(n["name"] for n in gltf["nodes"] if "mesh" in n and "name" in n)
            self.scenes[name] = Scene(name, tokens, instance)
        # A small window at a quarter of its resolution: the walk is about the editor's work, not its pixels.
        settings = {"renderScale": 0.25, "autosaveSeconds": 5, "windowWidth": 1280, "windowHeight": 720}
        json.dump(settings, open(os.path.join(self.config, "twinlight", "settings.json"), "w"))

    def opening_light_kinds(self, name, gltf):
        """The kinds of the lights the scene opens with (its sidecar's, else its glTF's but the sun)."""
        sidecar = os.path.join(self.scene_dir, name + ".lighting.json")
        if os.path.exists(sidecar):
            return [light.get("type", "point") for light in json.load(open(sidecar)).get("lights", [])]
        lights = gltf.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
        used = sorted({n["extensions"]["KHR_lights_punctual"]["light"] for n in gltf["nodes"]
                       if "KHR_lights_punctual" in n.get("extensions", {})})
        kinds = [lights[i].get("type", "point") for i in used if i < len(lights)]
        # The first directional light of the file is the sun, not one of the listed lights.
        if "directional" in kinds:
            kinds.remove("directional")
        return kinds

    def new_id(self):
        self.next_id += 1
        return self.next_id

    def scene_file(self, name):
        return os.path.join(self.scene_dir, name + ".gltf")

    # --- the model --------------------------------------------------------------------------
    def unsaved(self):
        s = self.current
        parts = []
        if self.lights != s.saved_lights:
            parts.append("the lighting")
        if self.shadow != self.baseline_shadow:
            parts.append("the render settings")
        if not rgb_equal(self.override, s.saved_override):
            parts.append("the albedo overrides")
        if not parts:
            return "none"
        return parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + " and " + parts[-1]

    def opened(self, scene, fresh_process):
        """The model after `scene` opens: what its files hold; the settings carried (or the defaults)."""
        self.current = scene
        self.lights = list(scene.saved_lights)
        self.override = scene.saved_override
        if fresh_process:
            self.shadow = DEFAULT_SHADOW
        if scene.saved_settings is not None:
            self.shadow = scene.saved_settings
        self.baseline_shadow = self.shadow
        self.lh, self.ah = History(), History()
        self.yaw = 0.0

    def saved(self):
        s = self.current
        if self.lights != s.saved_lights:
            s.lighting_written = True
        s.saved_lights = list(self.lights)
        s.saved_override = self.override
        if self.shadow != self.baseline_shadow:
            s.saved_settings = self.shadow
        self.baseline_shadow = self.shadow

    def edited(self, history, what, before, after):
        self.clock += 1
        history.push(what, before, after, self.clock)

    def step(self, history, forward):
        what, before, after, _ = history.steps[history.done if forward else history.done - 1]
        history.done += 1 if forward else -1
        value = after if forward else before
        if what == "lights":
            self.lights = list(value)
        elif what == "shadow":
            self.shadow = value
        else:
            self.override = value

    # --- script lines -----------------------------------------------------------------------
    def emit(self, *lines):
        self.lines.extend(lines)

    def checks(self):
        self.emit(f"expect-lights {len(self.lights)}", f"expect-setting shadowMapSize {self.shadow}",
                  f"expect-unsaved {self.unsaved()}")
        if self.override is not None:
            self.emit(f"select {self.current.instance}", "expect-albedo-source override")
        tag = f"a{self.actions:05d}"
        self.emit(f"dump-state {self.dump_dir} {tag}")
        self.expected.append((tag, self.current.name, {
            "lights": list(self.lights), "shadow": self.shadow, "override": self.override, "unsaved": self.unsaved()}))

    def after_open(self):
        if not self.current.db_opened:
            # The scene's database from its first opening on (remembered by the editor).
            self.emit(f"albedo-db {os.path.join(self.out, 'dbs', self.current.name + '.db')}")
            self.current.db_opened = True
        self.emit("wait 1", "expect-recovery none")
        self.checks()

    def answer(self, question):
        a = self.rng.choices(["save", "discard", "cancel"], [5, 3, 2])[0]
        self.emit("wait 2", f"expect-question {question}", "wait 1", f"click-ui unsaved.{a}", "wait 2")
        return a

    def save_keys(self):
        """The lines of File > Save (Ctrl+S); the injected defect leaves them out once."""
        if self.args.inject_defect == "skip-save" and self.saves_skipped == 0 and self.unsaved() != "none":
            self.saves_skipped += 1
            self.emit("# injected defect: this save is left out")
            return
        self.emit("key ctrl+S", "wait 2")

    # --- actions ----------------------------------------------------------------------------
    def open_scene(self):
        name = self.rng.choice([n for n in SCENES if n != self.current.name])
        scene = self.scenes[name]
        self.emit(f"open {self.scene_file(name)}")
        if self.unsaved() != "none":
            a = self.answer(f"Save it before opening {name}.gltf")
            if a == "cancel":
                self.emit("expect-question none")
                self.checks()
                return
            if a == "save":
                self.saved()
            else:
                self.shadow = self.baseline_shadow  # a discarded settings edit does not follow
        self.emit("wait-loaded")
        self.opened(scene, False)
        self.after_open()

    def switch_path(self):
        self.path = self.rng.choice([p for p in PATHS if p != self.path])
        self.emit(f"path {self.path}", "wait 1")
        self.checks()

    def edit(self):
        kind = self.rng.choice(["add", "add", "delete", "setting", "override", "override"])
        if kind == "delete" and not self.lights:
            kind = "add"
        before = list(self.lights)
        if kind == "add":
            kind_of_light = self.rng.choice(["point", "spot", "rect"])
            self.emit("click-ui outliner.lights", "wait 1", "click-ui lights.add", "wait 1",
                      f"click-ui lights.add.{kind_of_light}", "wait 1")
            name = 1 + sum(1 for t in self.lights if self.kind[t] == kind_of_light)
            right = (math.cos(self.yaw), -math.sin(self.yaw))
            place = (0.0, 0.0)
            for _ in range(64):
                if not any(math.dist(self.place[t], place) < 0.2 for t in self.lights if t in self.place):
                    break
                place = (place[0] + 0.25 * right[0], place[1] + 0.25 * right[1])
            made = (kind_of_light, name, self.current.name, (round(place[0], 6), round(place[1], 6)))
            if made not in self.adds:
                self.adds[made] = self.new_id()
                self.kind[self.adds[made]] = kind_of_light
                self.place[self.adds[made]] = place
            self.lights.append(self.adds[made])
            self.edited(self.lh, "lights", before, list(self.lights))
        elif kind == "delete":
            row = self.rng.randrange(len(self.lights))
            self.emit("click-ui outliner.lights", "wait 1", f"click-ui lights.row.{row}", "wait 1", "click-ui lights.delete", "wait 1")
            self.lights.pop(row)
            self.edited(self.lh, "lights", before, list(self.lights))
        elif kind == "setting":
            old = self.shadow
            self.shadow = self.rng.choice([s for s in SHADOW_SIZES if s != self.shadow])
            self.emit(f"set shadowMapSize={self.shadow}", "wait 1")
            self.edited(self.lh, "shadow", old, self.shadow)
        else:
            rgb = tuple(round(self.rng.uniform(0.05, 0.95), 3) for _ in range(3))
            self.emit(f"select {self.current.instance}", "albedo-override {} {} {}".format(*rgb), "wait 1")
            old = self.override
            self.override = rgb
            self.edited(self.ah, "override", old, rgb)
        self.checks()

    def undo_redo(self):
        """Ctrl+Z or Ctrl+Y: the latest edit of either history is undone first; redone in reverse."""
        if self.rng.random() < 0.65:
            self.emit("key ctrl+Z", "wait 1")
            la, aa = self.lh.undo_time(), self.ah.undo_time()
            if aa is not None and (la is None or aa > la):
                self.step(self.ah, False)
            elif la is not None:
                self.step(self.lh, False)
        else:
            self.emit("key ctrl+Y", "wait 1")
            lr, ar = self.lh.redo_time(), self.ah.redo_time()
            if ar is not None and (lr is None or ar < lr):
                self.step(self.ah, True)
            elif lr is not None:
                self.step(self.lh, True)
        self.checks()

    def bake(self):
        self.emit("wait 1", "click-ui " + self.rng.choice(["albedo.bake", "albedo.rebake"]), "wait 2")
        self.checks()

    def capture(self):
        self.emit(f"capture {os.path.join(self.out, 'capture')}", "wait 2")
        self.checks()

    def compare_view(self):
        self.compare = not self.compare
        self.emit("compare direct rt" if self.compare else "compare off", "wait 2")
        self.checks()

    def drag(self):
        """The camera orbited: a drag in the viewport from its lower left, with an instance selected
        (a drag on a selected light's gizmo or on a light's icon would move the light; new lights
        stand in the middle of the view and to its right), ending inside the viewport. drag-ui
        moves the mouse in 8 equal steps; the orbit starts with the first step more than 3 px
        from the press, and each step from then on turns the yaw by 0.005 rad a pixel."""
        dx, dy = self.rng.randint(-120, 120), self.rng.randint(-60, 60)
        u, v = round(self.rng.uniform(0.25, 0.4), 2), round(self.rng.uniform(0.6, 0.85), 2)
        self.emit(f"select {self.current.instance}", f"drag-ui viewport {dx} {dy} {u} {v}", "wait 1")
        step = math.hypot(dx, dy) / 8
        turning = sum(1 for i in range(1, 9) if i * step > 3.0)
        self.yaw -= 0.005 * (dx / 8) * turning
        self.checks()

    def resize(self):
        w, h = self.rng.choice([(1280, 720), (1024, 640), (1440, 810), (1200, 675)])
        self.emit(f"resize {w} {h}", "wait 2")
        self.checks()

    def reload(self):
        self.emit("reload", "wait-loaded", "wait 1")
        # The edits stay (unsaved); the lighting history starts again, and the albedo history
        # holds an unsaved override put back as one edit (the database is attached again).
        self.lh = History()
        self.ah = History()
        if not rgb_equal(self.override, self.current.saved_override):
            self.edited(self.ah, "override", self.current.saved_override, self.override)
        self.checks()

    def save(self):
        self.save_keys()
        self.saved()
        self.checks()

    def quit(self):
        """Returns True when the editor quits (the segment ends)."""
        self.emit("close-window")
        if self.unsaved() != "none":
            a = self.answer("Save it before quitting")
            if a == "cancel":
                self.emit("expect-question none")
                self.checks()
                return False
            if a == "save":
                self.saved()
        self.emit("wait 100")  # the editor ends within this
        return True

    ACTIONS = [("open_scene", 8), ("switch_path", 7), ("edit", 26), ("undo_redo", 14), ("bake", 4), ("capture", 2),
               ("compare_view", 4), ("drag", 6), ("resize", 3), ("reload", 4), ("save", 7), ("quit", 3)]

    # --- running ----------------------------------------------------------------------------
    def run_editor(self, index, start_scene):
        script = os.path.join(self.out, f"run{index:03d}.txt")
        with open(script, "w") as f:
            f.write("\n".join(self.lines) + "\n")
        env = dict(os.environ, XDG_CONFIG_HOME=self.config, LP_NUM_THREADS=os.environ.get("LP_NUM_THREADS", "2"))
        env.setdefault("TWINLIGHT_VALIDATION", "1")
        log = os.path.join(self.out, f"run{index:03d}.log")
        command = [self.args.twinlight, "--script", script, self.scene_file(start_scene)]
        if self.args.xvfb:
            command = ["bash", self.args.xvfb] + command
        start = time.time()
        actions = sum(1 for line in self.lines if line.startswith("# action"))
        limit = 120 + 20 * actions
        killed = []
        with open(log, "w") as out:
            proc = subprocess.Popen(command, stdout=out, stderr=subprocess.STDOUT, env=env, cwd=self.out,
                                    start_new_session=True)
            if self.args.inject_defect == "kill" and index == 1:
                # The injected defect: the editor dies halfway (as a crash would end it).
                def kill_editor():
                    time.sleep(max(5.0, self.args.kill_after))
                    for p in subprocess.run(["pgrep", "-s", str(proc.pid), "-x", "twinlight"], capture_output=True,
                                            text=True).stdout.split():
                        os.kill(int(p), signal.SIGKILL)
                        killed.append(p)
                threading.Thread(target=kill_editor, daemon=True).start()
            try:
                code = proc.wait(timeout=limit)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
                code = "timeout"
        text = open(log, errors="replace").read()
        if killed:
            text += "\n(soak: killed the editor, injected defect)\n"
        return code, text, time.time() - start, log

    def check_dumps(self):
        """The state written after every action against the model. Returns the first difference."""
        for tag, scene, want in self.expected:
            files = glob.glob(os.path.join(self.dump_dir, f"{scene}.gltf.{tag}.json"))
            if not files:
                return f"{tag}: no state written for {scene} (the editor did not get there)"
            have = json.load(open(files[0]))
            lights = have["lighting"]["lights"]
            if len(lights) != len(want["lights"]):
                return f"{tag} on {scene}: {len(lights)} lights, the walk has {len(want['lights'])}"
            for token, light in zip(want["lights"], lights):
                fields = light_fields(light)
                if token not in self.bound:
                    self.bound[token] = fields
                elif not same_light(self.bound[token], fields):
                    return f"{tag} on {scene}: a light changed: {describe_light(fields)} was " \
                           f"{describe_light(self.bound[token])}"
            if have["settings"].get("shadowMapSize") != want["shadow"]:
                return f"{tag} on {scene}: shadowMapSize {have['settings'].get('shadowMapSize')}, the walk has {want['shadow']}"
            overrides = list(have.get("overrides", {}).values())
            if want["override"] is None and overrides:
                return f"{tag} on {scene}: overrides {overrides}, the walk has none"
            if want["override"] is not None and (len(overrides) != 1 or not rgb_equal(overrides[0], want["override"])):
                return f"{tag} on {scene}: overrides {overrides}, the walk has {want['override']}"
            unsaved = have["unsaved"] or "none"
            if unsaved != want["unsaved"]:
                return f"{tag} on {scene}: unsaved `{unsaved}`, the walk has `{want['unsaved']}`"
        return None

    def check_files(self):
        """What each scene's files hold against what the walk saved. Returns the first difference."""
        settings = json.load(open(os.path.join(self.config, "twinlight", "settings.json")))
        for name, s in self.scenes.items():
            sidecar = os.path.join(self.scene_dir, name + ".lighting.json")
            # A sidecar the walk never wrote is the content's own, written by hand (kelvin, not
            # colours): what the editor read from it is checked in the dumps instead.
            if s.lighting_written:
                if not os.path.exists(sidecar):
                    return f"{name}: no lighting sidecar, the walk saved its lighting"
                lights = json.load(open(sidecar))["lights"]
                if len(lights) != len(s.saved_lights):
                    return f"{name}.lighting.json holds {len(lights)} lights, the walk saved {len(s.saved_lights)}"
                for token, light in zip(s.saved_lights, lights):
                    fields = light_fields(light)
                    if token in self.bound and not same_light(self.bound[token], fields):
                        return f"{name}.lighting.json: a light changed: {describe_light(fields)} " \
                               f"was {describe_light(self.bound[token])}"
            db = os.path.join(self.out, "dbs", name + ".db")
            if os.path.exists(db):
                con = sqlite3.connect(db)
                rows = [tuple(r) for r in con.execute("SELECT r, g, b FROM overrides")]
                con.close()
                want = [] if s.saved_override is None else [s.saved_override]
                if len(rows) != len(want) or (want and not rgb_equal(rows[0], want[0])):
                    return f"{name}.db holds the overrides {rows}, the walk saved {want}"
            elif s.saved_override is not None:
                return f"{name}: no albedo database, the walk saved the override {s.saved_override}"
            saved = [v for k, v in settings.get("sceneSettings", {}).items() if os.path.basename(k) == name + ".gltf"]
            have = saved[0].get("shadowMapSize") if saved else None
            if have != s.saved_settings:
                return f"the settings saved with {name} have shadowMapSize {have}, the walk saved {s.saved_settings}"
        return None

    def walk(self):
        self.prepare()
        weights = [w for _, w in self.ACTIONS]
        names = [n for n, _ in self.ACTIONS]
        totals = {"crashes": 0, "lost": 0, "validation": 0, "walk": 0}
        runs = 0
        started = time.time()
        start_scene = "cornell"
        while self.actions < self.args.actions:
            # One editor: a segment of the walk, until it quits (or the segment is long enough).
            self.lines, self.expected = [], []
            self.opened(self.scenes[start_scene], True)
            self.emit("wait-loaded", "path direct")
            self.path = "direct"
            self.compare = False
            self.after_open()
            quitted = False
            done = 0
            while self.actions < self.args.actions and done < self.args.segment:
                action = self.rng.choices(names, weights)[0]
                self.actions += 1
                done += 1
                self.emit(f"# action {self.actions}: {action}")
                if action == "quit":
                    if self.quit():
                        quitted = True
                        break
                else:
                    getattr(self, action)()
            if not quitted:
                # The walk's end (or the segment's): saved, then closed, so the next editor opens it.
                self.emit("# end of the segment: save and close")
                self.save_keys()
                self.saved()
                self.emit("close-window", "wait 100")
            runs += 1
            code, text, seconds, log = self.run_editor(runs, start_scene)
            sanitizer = SANITIZER.search(text)
            validation = VALIDATION.search(text)
            failure = re.search(r"twinlight: error: script: (.*)", text)
            crashed = code not in (0, 1) or bool(sanitizer)
            problem = None
            if crashed:
                totals["crashes"] += 1
                problem = f"CRASH (exit {code}{', ' + sanitizer.group(0) if sanitizer else ''})"
            elif failure and re.search(r":\d+: (expected|[0-9]+ lights, expected|unsaved work|.* is `|light \d)", failure.group(1)):
                totals["lost"] += 1
                problem = "LOST EDIT: " + failure.group(1)
            elif failure:
                totals["walk"] += 1
                problem = "WALK ERROR: " + failure.group(1)
            elif validation:
                totals["validation"] += 1
                problem = "LAYER MESSAGE: " + text[max(0, validation.start() - 80):validation.end() + 80].replace("\n", " ")
            elif code != 0:
                totals["crashes"] += 1
                problem = f"exit {code}"
            else:
                difference = self.check_dumps() or self.check_files()
                if difference:
                    totals["lost"] += 1
                    problem = "LOST EDIT: " + difference
            end_scene = self.current.name
            print(f"editor {runs}: {done} actions (to {self.actions}) on {start_scene}..{end_scene}, exit {code}, "
                  f"{seconds:.0f} s{': ' + problem + ' (log ' + log + ')' if problem else ''}", flush=True)
            if problem:
                # The model no longer knows what the files hold: go on from fresh copies.
                self.prepare()
                start_scene = "cornell"
            else:
                start_scene = end_scene
            shutil.rmtree(self.dump_dir, ignore_errors=True)
            os.makedirs(self.dump_dir)
        seconds = time.time() - started
        print(f"soak: seed {self.args.seed}, {self.actions} actions in {runs} editors, {totals['crashes']} crashes, "
              f"{totals['lost']} lost edits, {totals['validation']} with messages of the layers, "
              f"{totals['walk']} walk errors, {seconds:.0f} s")
        return 0 if not any(totals.values()) else 1


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--twinlight", required=True)
    p.add_argument("--content", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--actions", type=int, default=200)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--segment", type=int, default=150, help="most actions one editor runs before it is closed")
    p.add_argument("--xvfb", help="run each editor through this wrapper (tests/editor/with_xvfb.sh)")
    p.add_argument("--inject-defect", choices=["kill", "skip-save"], help="a defect the walk must find")
    p.add_argument("--kill-after", type=float, default=30.0, help="seconds into the first editor that `kill` kills it")
    args = p.parse_args()
    # Each editor runs in the walk's folder: the paths given are made absolute first.
    args.twinlight = os.path.abspath(args.twinlight)
    args.content = os.path.abspath(args.content)
    if args.xvfb:
        args.xvfb = os.path.abspath(args.xvfb)
    sys.exit(Walk(args).walk())


if __name__ == "__main__":
    main()
