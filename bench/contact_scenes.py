#!/usr/bin/env python3
"""Times SOFA's contact scenes in fastcorot and, where SOFA is built here, in SOFA, side by side.

By hand, never in CI:
    bench/contact_scenes.py [--fastcorot build-release/apps/fastcorot/fastcorot] [--runs 3]
        [--sofa /work/sofa-build-out/sofaContactRun] [--scenes ../shared/sofa-scenes/examples]
        [--only NAME ...]

SOFA built without OpenGL (../shared/sofa-build) cannot create OglModel, so each scene is written
again without its visual components: OglModel and the other Sofa.GL components, VisualStyle, the
mappings that fed a removed visual model, and the Sofa.GL plugins. Every other node stays, the
still obstacles (floors, fixed tori) included, since they carry collision models. Both programs run
the rewritten scene from the start for N steps on one thread; the figure is the median of the runs
(SOFA: its animate time; fastcorot: `--json` seconds, which also count the collision detection).
Prints one row per scene: seconds, the ratio, the ratio of the fastest runs (less moved by other
programs on a shared machine, which slow fastcorot's short runs more than SOFA's long ones), the
detection share and the contacts at the last step in each program.
"""
import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

# scene (relative to the examples folder), steps
SCENES = [
    ("Component/Collision/Geometry/TriangleModel.scn", 300),
    ("Component/Collision/Geometry/SphereModel.scn", 300),
    ("Component/Collision/Response/StickContactForceField.scn", 300),
    ("Component/SolidMechanics/FEM/TetrahedronFEMForceField_Chain.scn", 200),
    ("Component/AnimationLoop/FreeMotionAnimationLoop.scn", 200),
    ("Benchmark/Performance/TorusFall.scn", 100),
    ("Component/Mapping/Linear/BarycentricMapping.scn", 100),
]

VISUAL_TAGS = {"VisualStyle", "LightManager", "DirectionalLight", "PositionalLight", "SpotLight",
               "InteractiveCamera", "VisualGrid", "LineAxis", "TrailRenderer", "ClipPlane"}
MAPPING_SUFFIX = "Mapping"


def is_visual(element):
    return element.tag.startswith("Ogl") or element.tag in VISUAL_TAGS


def names_in(link):
    """The last path segment of each @link in an attribute value ("@../Visual" -> "Visual")."""
    return {word.lstrip("@").split("/")[-1] for word in link.split() if word.startswith("@")}


def strip_visuals(node, removed_names):
    """Removes visual components under node; returns whether node lost a visual model itself."""
    lost_model_here = False
    for child in list(node):
        if child.tag == "RequiredPlugin" and child.get("pluginName", child.get("name", "")).startswith("Sofa.GL"):
            node.remove(child)
        elif is_visual(child):
            if child.get("name"):
                removed_names.add(child.get("name"))
            lost_model_here = lost_model_here or child.tag.startswith("Ogl")
            node.remove(child)
        elif child.tag == "Node":
            strip_visuals(child, removed_names)
    has_state = any(child.tag == "MechanicalObject" for child in node)
    for child in list(node):
        if not child.tag.endswith(MAPPING_SUFFIX):
            continue
        output = child.get("output")
        feeds_removed = output is not None and names_in(output) & removed_names
        # A mapping with no output maps onto the node's own state: a removed visual model.
        implicit_output = output is None and lost_model_here and not has_state
        if feeds_removed or implicit_output:
            node.remove(child)
    return lost_model_here


def rewrite(scene, folder):
    tree = ET.parse(scene)
    strip_visuals(tree.getroot(), set())
    out = pathlib.Path(folder) / scene.name
    tree.write(out, encoding="unicode")
    return out


def run(command, env):
    result = subprocess.run(command, env=env, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"contact_scenes: {' '.join(map(str, command))} failed ({result.returncode}):\n"
                 f"{result.stderr[-2000:]}")
    return result.stdout


def time_fastcorot(program, scene, steps, env):
    stdout = run([program, "run", scene, "--steps", str(steps), "--threads", "1", "--quiet",
                  "--json"], env)
    report = json.loads(stdout)
    contacts = report.get("contacts", {})
    return report["seconds"], contacts.get("detection_seconds", 0.0), contacts.get("last_step", 0)


def time_sofa(program, scene, steps, env, plugins):
    stdout = run([program, scene, str(steps), "--plugins", plugins], env)
    line = next(l for l in stdout.splitlines() if l.startswith("SOFACONTACT"))
    fields = dict(word.split("=", 1) for word in line.split()[1:])
    return float(fields["animate_s"]), int(fields["last_contacts"])


def main():
    here = pathlib.Path(__file__).resolve().parent.parent
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fastcorot", default=here / "build-release/apps/fastcorot/fastcorot")
    parser.add_argument("--sofa", default="/work/sofa-build-out/sofaContactRun")
    parser.add_argument("--scenes", default=here.parent / "shared/sofa-scenes/examples")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--only", nargs="*", default=None, help="scene file names to keep")
    args = parser.parse_args()
    examples = pathlib.Path(args.scenes)
    data_path = f"{examples.parent / 'share'}:{examples}:{examples / 'Benchmark/Performance'}"
    env = dict(os.environ, SOFA_DATA_PATH=data_path, FASTCOROT_DATA_PATH=data_path)
    sofa = pathlib.Path(args.sofa)
    have_sofa = sofa.is_file()
    if have_sofa:
        env.setdefault("SOFA_ROOT", str(sofa.parent))
    plugins = str(sofa.parent / "lib")
    print(f"{'scene':34s} {'steps':>5s} {'SOFA s':>8s} {'ours s':>8s} {'x':>5s} {'x best':>6s} {'detect':>6s} "
          f"{'contacts SOFA/ours':>18s}")
    with tempfile.TemporaryDirectory() as folder:
        for relative, steps in SCENES:
            scene = examples / relative
            if args.only and scene.name not in args.only:
                continue
            rewritten = rewrite(scene, folder)
            ours, sofas = [], []
            for _ in range(args.runs):
                ours.append(time_fastcorot(args.fastcorot, rewritten, steps, env))
                if have_sofa:
                    sofas.append(time_sofa(sofa, rewritten, steps, env, plugins))
            ours_s = statistics.median(o[0] for o in ours)
            detection = statistics.median(o[1] for o in ours) / ours_s
            sofa_s = statistics.median(s[0] for s in sofas) if sofas else float("nan")
            sofa_best = min(s[0] for s in sofas) if sofas else float("nan")
            best = sofa_best / min(o[0] for o in ours)
            sofa_contacts = sofas[-1][1] if sofas else "-"
            print(f"{scene.stem[:34]:34s} {steps:5d} {sofa_s:8.3f} {ours_s:8.3f} {sofa_s / ours_s:5.1f} {best:6.1f} "
                  f"{detection:6.0%} {str(sofa_contacts) + '/' + str(ours[-1][2]):>18s}", flush=True)


if __name__ == "__main__":
    main()
