#!/usr/bin/env python3
"""The randomized interior corpus covers what it promises (content/generator/corpus.h), and a
seed draws the same files every time.

  check_corpus.py GENERATOR OUT_DIR SEED COUNT

Draws COUNT interiors from SEED twice and once from SEED + 1: the two draws from SEED must be
byte-identical and the other seed's must differ; over the draw, the scale must span the promised
0.5 m to 500 m (at least a decade at each end), and every shape, opening, light kind, albedo
class and wall kind must occur, and sealed rooms beside lit ones.
"""
import filecmp
import json
import shutil
import subprocess
import sys
from pathlib import Path


def draw(gen, folder, seed, count):
    subprocess.run([gen, "--corpus", str(folder), str(seed), "0", str(count)], check=True, stdout=subprocess.DEVNULL)
    return json.loads((folder / "corpus.json").read_text())


def main():
    gen, out, seed, count = sys.argv[1], Path(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
    shutil.rmtree(out, ignore_errors=True)  # no file left from an earlier draw
    first = draw(gen, out / "a", seed, count)
    draw(gen, out / "b", seed, count)
    other = draw(gen, out / "c", seed + 1, count)
    failures = []
    names = sorted(p.relative_to(out / "a") for p in (out / "a").rglob("*") if p.is_file())
    for name in names:
        if not filecmp.cmp(out / "a" / name, out / "b" / name, shallow=False):
            failures.append(f"seed {seed} drew {name} differently the second time")
    if first["scenes"] == other["scenes"]:
        failures.append(f"seeds {seed} and {seed + 1} drew the same corpus")

    scenes = first["scenes"]
    if len(scenes) != count:
        failures.append(f"{len(scenes)} interiors listed, {count} asked for")
    sizes = [s["size_m"] for s in scenes]
    if min(sizes) > 5.0 or max(sizes) < 50.0:
        failures.append(f"sizes {min(sizes):.3g} to {max(sizes):.3g} m do not span 0.5 to 500 m")
    if min(sizes) < 0.5 or max(sizes) > 500.0:
        failures.append(f"sizes {min(sizes):.3g} to {max(sizes):.3g} m leave 0.5 to 500 m")
    promised = {
        "shape": {"box", "hall", "corridor", "l_shape", "suite"},
        "openings": {"none", "door", "windows", "slits", "skylight"},
        "albedo": {"white", "grey", "saturated"},
        "walls": {"quads", "thick"},
    }
    for key, kinds in promised.items():
        seen = {s[key] for s in scenes}
        if kinds - seen:
            failures.append(f"no interior with {key} {sorted(kinds - seen)}")
    lights = {kind for s in scenes for kind in s["lights"].split("+")}
    for kind in ("sun", "sky", "hdri", "panels", "emitter", "lamps", "spots"):
        if kind not in lights:
            failures.append(f"no interior lit by {kind}")
    for s in scenes:
        if s["openings"] == "none" and not set(s["lights"].split("+")) & {"panels", "emitter", "lamps", "spots"}:
            failures.append(f"{s['name']} is closed and has no light of its own")
        if "hdri" in s["lights"] and not (out / "a" / f"{s['name']}.lighting.json").is_file():
            failures.append(f"{s['name']} is lit by an HDRI without a lighting sidecar")
    if not any(s["sealed_room"] for s in scenes):
        failures.append("no sealed room")
    if not any(s["triangles"] >= 10000 for s in scenes):
        failures.append("no interior of 10k+ triangles")

    for f in failures:
        print("corpus:", f)
    if failures:
        return 1
    print(f"corpus of {count} from seed {seed}: sizes {min(sizes):.3g} to {max(sizes):.3g} m, "
          f"{len(lights)} light kinds, {sum(s['sealed_room'] for s in scenes)} sealed rooms, same files twice")
    return 0


if __name__ == "__main__":
    sys.exit(main())
