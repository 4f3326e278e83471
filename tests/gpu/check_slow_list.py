#!/usr/bin/env python3
"""check_slow_list.py TL_GPU_TESTS SLOW_LIST: every pattern of the slow list (tests/gpu/slow_tests.txt)
names at least one test of the GPU suite. Lists the tests without running them (no device)."""
import fnmatch
import subprocess
import sys


def tests(binary, pattern):
    out = subprocess.run([binary, "--gtest_list_tests", "--gtest_filter=" + pattern], capture_output=True, text=True,
                         check=True).stdout
    names, suite = [], None
    for line in out.split("\n"):
        if not line.strip():
            continue
        if not line.startswith(" "):
            suite = line.split("#")[0].strip()
        else:
            names.append(suite + line.split("#")[0].strip())
    return names


def main():
    binary, listing = sys.argv[1], sys.argv[2]
    patterns = [l.strip() for l in open(listing) if l.strip() and not l.startswith("#")]
    everything = tests(binary, "*")
    empty, named = [], set()
    for p in patterns:
        found = [t for t in everything if fnmatch.fnmatchcase(t, p)]  # gtest's * and ? are fnmatch's
        if not found:
            empty.append(p)
        named.update(found)
    for p in empty:
        print("slow_tests.txt: `%s` names no test of the GPU suite (renamed or removed?)" % p)
    print("%d patterns name %d slow tests of %d" % (len(patterns), len(named), len(everything)))
    return 1 if empty else 0


if __name__ == "__main__":
    sys.exit(main())
