"""`python3 -m fastcorot ARGS...`: the fastcorot command line (run, view, bench, probe, components),
with Python scene scripts as scenes: `python3 -m fastcorot run liver.py --steps 100` calls the
script's createScene(root) (SofaPython3's convention) and runs it as `fastcorot run` runs a .scn
file, calling its controllers around each step. The `fastcorot` program hands .py scenes here."""

import sys

from . import _core


def _load_script(script, strict):
    from Sofa import _script  # the SofaPython3 names, only for scripts

    return _script.load(script, strict)


def main(arguments=None):
    arguments = sys.argv[1:] if arguments is None else list(arguments)
    return _core.cli_main(["fastcorot", *arguments], _load_script)


if __name__ == "__main__":
    sys.exit(main())
