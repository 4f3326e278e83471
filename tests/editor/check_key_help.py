#!/usr/bin/env python3
"""The F1 help names every key the editor handles.

Reads the editor's sources (editor/*.cpp) for the keys and mouse buttons they react to
(ImGui::IsKeyPressed / IsKeyDown / glfwGetKey with GLFW_KEY_*, the mouse wheel with or without Ctrl, mouse
buttons) and the help table (editor/key_help.cpp, which the F1 window shows row by row), and
fails naming each binding the table does not list.

Usage: check_key_help.py EDITOR_SOURCE_DIR
"""
import pathlib
import re
import sys

editor = pathlib.Path(sys.argv[1])
rows = re.findall(r'\{"([^"]*)", "([^"]*)", "([^"]*)"\}', (editor / "key_help.cpp").read_text())
if len(rows) < 10:
    sys.exit(f"check_key_help: only {len(rows)} rows read from key_help.cpp: the table's format changed?")
keys_columns = [keys for _, keys, _ in rows]

DISPLAY = {"LEFT_SHIFT": "Shift", "RIGHT_SHIFT": "Shift", "0": "1 .. 9"}
BUTTONS = {"0": "Left", "1": "Right", "2": "Middle"}


def listed(combo: str) -> bool:
    """A keys column holds the combination as whole words ("D" in "Right + W A S D")."""
    pattern = r"(^|[ +,])" + re.escape(combo) + r"($|[ ,])"
    return any(re.search(pattern, column) for column in keys_columns)


def prefixed(word: str) -> bool:
    return any(column.startswith(word) for column in keys_columns)


missing = []
bindings = 0
for source in sorted(editor.glob("*.cpp")):
    if source.name == "key_help.cpp":
        continue
    for number, line in enumerate(source.read_text().splitlines(), 1):
        where = f"{source.name}:{number}"
        ctrl = re.search(r"\bctrl\b|KeyCtrl", line) and "!io.KeyCtrl" not in line
        # A binding reads a key's state: ImGui's IsKeyPressed/IsKeyDown, glfwGetKey, or a
        # local key(...) helper; key tables (the input queue, the script's key names) are not.
        is_binding = re.search(r"IsKeyPressed\(|IsKeyDown\(|glfwGetKey\(|\bkey\(GLFW_KEY_", line)
        for key in re.findall(r"GLFW_KEY_(\w+)", line) if is_binding else []:
            name = DISPLAY.get(key, key)
            combos = [f"Ctrl + {name}" if ctrl else name]
            if "KeyShift" in line:
                combos.append(f"Ctrl + Shift + {name}" if ctrl else f"Shift + {name}")
            for combo in combos:
                bindings += 1
                if not listed(combo):
                    missing.append(f"{where}: `{combo}`")
        if "MouseWheel" in line and re.search(r"in\.dolly|viewer_\.zoom|zoom", line + " "):
            combo = "Ctrl + Wheel" if ctrl else "Wheel"
            bindings += 1
            if not listed(combo):
                missing.append(f"{where}: `{combo}`")
        for button in re.findall(r"IsMouse(?:Down|Clicked|Released)\((\d)\)", line):
            bindings += 1
            if not prefixed(BUTTONS[button]):
                missing.append(f"{where}: the {BUTTONS[button].lower()} mouse button")

if missing:
    print("the F1 help (editor/key_help.cpp) does not list:\n  " + "\n  ".join(missing))
    sys.exit(1)
print(f"the F1 help lists all {bindings} key and mouse bindings found in {editor}")
