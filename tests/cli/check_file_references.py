#!/usr/bin/env python3
"""Every file a comment or a document names exists, and every heading a document links to.

check_file_references.py ROOT [FILE...]

Reads the comments of the sources (C++, GLSL, CMake, shell, Python) and the Markdown documents
tracked under ROOT (or the FILEs given, for the test of this script) and collects every name of
a file in the repository they mention: `engine/session/session.h`, `shared/frame.h`,
`lighting/common/pass_builders.{h,cpp}`, `frame_key.h`, `docs/user-guide.md#limits`. A name with
a folder resolves against ROOT, the engine/ and shaders/ include roots, tests/, the mentioning
file's folder and its parents; a bare file name against every tracked file's name. Prints each
name that resolves nowhere with where it is mentioned, and exits 1 when there is any.

What a user or a run writes (out/..., build/..., a capture's manifest.json, SCENE.lighting.json),
names with placeholders (CAPS, #, *, <>, $) and URLs are not repository files and are left out.
"""
import os
import re
import subprocess
import sys

# The endings a repository file of interest has; a word ending otherwise is not a file name.
EXTENSIONS = ("h", "cpp", "glsl", "comp", "frag", "vert", "rgen", "rchit", "rmiss", "rahit", "md", "sh", "py",
              "cmake", "txt", "gltf", "glb", "script", "sbatch", "yaml", "dict", "supp", "html")
EXT = "|".join(EXTENSIONS)
# path/like/name.ext, with an optional {a,b} ending group: lighting/common/pass_builders.{h,cpp}
NAME = re.compile(r"(?<![\w/.$<>{*-])((?:[\w.-]+/)*[\w-]+(?:\.(?:%s)\b|\.\{[\w,]+\}))(?![\w/])" % EXT)
# A Markdown link or image: [text](target) or ![alt](target), relative to the document, and a
# link to a heading: [text](my_doc.md#heading) or [text](#heading).
LINK = re.compile(r"\]\(([^)\s#]+)(?:#[^)]*)?\)")
ANCHOR = re.compile(r"\]\(([^)\s#]*\.md|)#([^)\s]+)\)")


def slug(heading):
    """A heading's anchor as GitHub makes it: lower case, letters, digits, `-` and `_` kept,
    other punctuation dropped, spaces made hyphens; a repeated one gets -1, -2."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


def anchors(text):
    found, counts, fenced = set(), {}, False
    for line in text.split("\n"):
        if line.startswith("```"):
            fenced = not fenced
            continue
        m = None if fenced else re.match(r"^#{1,6}\s+(.*)$", line)
        if m:
            s = slug(m.group(1))
            n = counts.get(s, 0)
            counts[s] = n + 1
            found.add(s if n == 0 else "%s-%d" % (s, n))
    return found
# Files written by runs and users, and words that only look like file names.
GENERATED = re.compile(r"^(out|build|fuzz-ci|shots|corpus|crashes)/|^(manifest|report|shard|bench|compare|"
                       r"CMakeLists|LastTest|CTestTestfile)\.(json|html|txt|log)$|^[A-Z_]+\.|lighting\.json$")
# Names the documents use as examples of the reader's own files: any whose name starts with
# `my` (docs/plugins.md's mygi, a new pass's my_blur.comp, my-pvc.yaml), a scene, a shader
# list's stand-ins, an output; and folders in capitals (DIR/, OUT/: placeholders).
EXAMPLES = re.compile(r"(^|/)(my[\w.-]*|scene\.gltf|big\.gltf|x\.gltf|a\.comp|b\.frag|figures\.txt)$|"
                      r"(^|/)[A-Z][A-Z_]*/")
# Headers of the system's libraries a comment may name (tinygltf's, MikkTSpace's).
SYSTEM_INCLUDE = "/usr/include"
SOURCE_ENDINGS = {".cpp": "//", ".h": "//", ".glsl": "//", ".comp": "//", ".frag": "//", ".vert": "//",
                  ".rgen": "//", ".rchit": "//", ".rmiss": "//", ".rahit": "//", ".cmake": "#", ".sh": "#",
                  ".py": "#", ".txt": "#", ".sbatch": "#", ".yaml": "#"}


def tracked(root):
    out = subprocess.run(["git", "-C", root, "ls-files", "-co", "--exclude-standard"], capture_output=True, text=True,
                         check=True).stdout.split("\n")
    return [f for f in out if f and os.path.isfile(os.path.join(root, f))]


def comment_text(path, text):
    """The comment lines of a source file (the part after its comment marker), by line number."""
    ending = os.path.splitext(path)[1]
    marker = SOURCE_ENDINGS.get(ending)
    if os.path.basename(path) == "CMakeLists.txt":
        marker = "#"
    if path.endswith(".md"):
        return list(enumerate(text.split("\n"), 1))
    if marker is None:
        return []
    lines = []
    for number, line in enumerate(text.split("\n"), 1):
        at = line.find(marker)
        if at >= 0 and not (marker == "#" and line.lstrip().startswith("#!")):
            lines.append((number, line[at + len(marker):]))
        elif marker == "//" and line.lstrip().startswith("*"):
            lines.append((number, line))
    return lines


def expand(name):
    """pass_builders.{h,cpp} -> pass_builders.h, pass_builders.cpp."""
    m = re.match(r"^(.*)\.\{([\w,]+)\}$", name)
    if not m:
        return [name]
    return ["%s.%s" % (m.group(1), e) for e in m.group(2).split(",") if e]


def resolves(name, mentioned_in, files, basenames):
    if os.path.isfile(os.path.join(SYSTEM_INCLUDE, name)):
        return True
    if "/" not in name:
        return name in basenames
    folder = os.path.dirname(mentioned_in)
    if name.startswith("./") or name.startswith("../"):  # relative to the mentioning file only
        return os.path.normpath(os.path.join(folder, name)) in files
    bases = ["", "engine/", "engine/lighting/", "shaders/", "tests/", "editor/", "content/", "docs/"]
    while True:
        bases.append(folder + "/" if folder else "")
        if not folder:
            break
        folder = os.path.dirname(folder)
    for base in bases:
        candidate = os.path.normpath(base + name)
        if candidate in files:
            return True
        # A folder named like a file is not one; a tracked folder prefix is (docs/design/).
    return any(f.startswith(name.rstrip("/") + "/") for f in files)


def main():
    if len(sys.argv) < 2:
        print("usage: check_file_references.py ROOT [FILE...]", file=sys.stderr)
        return 2
    root = sys.argv[1]
    files = set(tracked(root))
    basenames = {os.path.basename(f) for f in files}
    scanned = sys.argv[2:] or sorted(files)
    missing = []
    names = 0
    heading_cache = {}
    for path in scanned:
        full = path if os.path.isabs(path) else os.path.join(root, path)
        rel = os.path.relpath(full, root)
        if rel.startswith("tests/cli/data/file_references/") and not sys.argv[2:]:
            continue  # this script's own test cases name missing files on purpose
        try:
            with open(full, encoding="utf-8") as f:
                text = f.read()
        except (UnicodeDecodeError, OSError):
            continue
        for number, line in comment_text(rel, text):
            if rel.endswith(".md"):
                for target in LINK.findall(line):
                    if re.match(r"^[a-z]+:", target):
                        continue  # a URL
                    names += 1
                    if os.path.normpath(os.path.join(os.path.dirname(rel), target)) not in files and \
                            not any(f.startswith(os.path.normpath(os.path.join(os.path.dirname(rel), target)) + "/") for f in files):
                        missing.append("%s:%d: %s (a link)" % (rel, number, target))
                for target, anchor in ANCHOR.findall(line):
                    doc = os.path.normpath(os.path.join(os.path.dirname(rel), target)) if target else rel
                    if doc not in files:
                        continue  # a missing document is reported above
                    if doc not in heading_cache:
                        with open(os.path.join(root, doc), encoding="utf-8") as f:
                            heading_cache[doc] = anchors(f.read())
                    names += 1
                    if anchor not in heading_cache[doc]:
                        missing.append("%s:%d: %s#%s (no such heading)" % (rel, number, target or rel, anchor))
            line = re.sub(r"https?://\S+", "", line)
            for m in NAME.finditer(line):
                for name in expand(m.group(1).split("#")[0]):
                    stem = os.path.splitext(os.path.basename(name))[0]
                    if GENERATED.search(name) or EXAMPLES.search(name) or name.startswith("/") or len(stem) <= 2:
                        continue  # a run's output, an example, or a product like n.h (n . h)
                    names += 1
                    if not resolves(name, rel, files, basenames):
                        missing.append("%s:%d: %s" % (rel, number, name))
    for m in missing:
        print("no such file: " + m)
    print("%d file names in %d files checked, %d name nothing in the repository" % (names, len(scanned), len(missing)))
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
