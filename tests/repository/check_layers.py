#!/usr/bin/env python3
"""Checks DESIGN.md's layering: a file of a layer (src/<layer>/, include/fastcorot/<layer>/)
includes headers of its own layer and the layers before it only, never one after it.

    check_layers.py REPOSITORY      exit 1 listing each upward include as FILE:LINE: what
    check_layers.py --self-test     checks the checker on a tree made to break it
"""

import pathlib
import re
import sys
import tempfile

LAYERS = ["core", "topology", "state", "fem", "mapping", "sim", "constraint", "softrobots", "collision", "io", "scene", "render"]
INCLUDE = re.compile(r'^\s*#\s*include\s+"fastcorot/([a-z_]+)/')


def problems(repository):
    repository = pathlib.Path(repository)
    found = []
    for layer in LAYERS:
        rank = LAYERS.index(layer)
        for folder in (repository / "src" / layer, repository / "include" / "fastcorot" / layer):
            for file in sorted(folder.rglob("*")):
                if file.suffix not in (".h", ".cpp", ".in"):
                    continue
                for number, line in enumerate(file.read_text().splitlines(), 1):
                    match = INCLUDE.match(line)
                    if not match:
                        continue
                    used = match.group(1)
                    if used not in LAYERS:
                        found.append(f"{file.relative_to(repository)}:{number}: includes an unknown layer '{used}'")
                    elif LAYERS.index(used) > rank:
                        found.append(f"{file.relative_to(repository)}:{number}: {layer} includes {used}, "
                                     f"a later layer")
    return found


def self_test():
    with tempfile.TemporaryDirectory() as folder:
        root = pathlib.Path(folder)
        (root / "src" / "io").mkdir(parents=True)
        (root / "include" / "fastcorot" / "sim").mkdir(parents=True)
        (root / "src" / "io" / "a.cpp").write_text('#include "fastcorot/sim/x.h"\n#include "fastcorot/scene/y.h"\n')
        (root / "include" / "fastcorot" / "sim" / "b.h").write_text('#include "fastcorot/core/z.h"\n'
                                                                     '  #include "fastcorot/render/w.h"\n')
        found = problems(root)
        if len(found) != 2 or "io includes scene" not in found[1] or "sim includes render" not in found[0]:
            print("self-test failed:", found)
            return 1
    print("self-test passed")
    return 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    found = problems(argv[1])
    for problem in found:
        print(problem)
    print(f"{len(found)} upward includes" if found else "every include goes down the layers")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
