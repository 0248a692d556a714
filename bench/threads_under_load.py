#!/usr/bin/python3
"""Steps per second of the two beams on 1 and 2 threads, with both cores free and with one core
kept busy by another process, as a user running fastcorot beside other work sees them
(docs/performance.md, "Threads on a busy machine").

Run by hand (a few minutes, never in CI), after scripts/build --release:
    bench/threads_under_load.py
    bench/threads_under_load.py --baseline /tmp/old/fastcorot --rounds 7 --json figures.json

The busy core is a shell loop (`while :; do :; done`) that the script starts before the loaded
measurements and kills after them, whatever happens. Each figure is `fastcorot bench --beam B
--steps S --threads T --json` (the step loop alone, scene loading left out); configurations take
turns within each round, so that drifts of the host touch them all alike, and the table shows
the median of the rounds with the range. `--baseline` times another build the same way in the
same rounds (e.g. the previous commit's), since the host's placement of the VM's two cores
changes from run to run and only figures from one run compare. `--threads 0` stands for the
program's default (no --threads given).
"""
import argparse
import json
import os
import pathlib
import signal
import statistics
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
BEAMS = {"40x10x10": 300, "76x16x16": 40}  # timed steps each
BUSY_LOOP = ["/bin/sh", "-c", "while :; do :; done"]


def steps_per_second(program, beam, steps, threads):
    command = [str(program), "bench", "--beam", beam, "--steps", str(steps), "--warmup", "3", "--json"]
    if threads > 0:
        command += ["--threads", str(threads)]
    result = subprocess.run(command, capture_output=True, text=True, check=False)
    if result.returncode != 0:
        sys.exit(f"threads_under_load: {' '.join(command)} failed ({result.returncode}):\n{result.stderr}")
    return json.loads(result.stdout)["steps_per_second"]


class BusyCore:
    """One core kept busy by a shell loop while the block runs; killed on the way out."""

    def __enter__(self):
        self.process = subprocess.Popen(BUSY_LOOP, start_new_session=True)
        return self

    def __exit__(self, *exc):
        os.killpg(self.process.pid, signal.SIGKILL)
        self.process.wait()


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--program", default=ROOT / "build-release/apps/fastcorot/fastcorot", type=pathlib.Path)
    parser.add_argument("--baseline", type=pathlib.Path, help="another build's fastcorot, timed in the same rounds")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--beams", nargs="+", default=list(BEAMS), choices=list(BEAMS))
    parser.add_argument("--json", type=pathlib.Path, help="write every figure to this file")
    args = parser.parse_args()
    programs = {"this build": args.program}
    if args.baseline:
        programs["baseline"] = args.baseline
    for name, program in programs.items():
        if not program.is_file():
            sys.exit(f"threads_under_load: {name} {program} not found (scripts/build --release makes it)")

    configurations = [(load, beam, name, threads) for load in ("free", "one core busy") for beam in args.beams
                      for name in programs for threads in args.threads]
    figures = {configuration: [] for configuration in configurations}
    for round_number in range(args.rounds):
        for load in ("free", "one core busy"):
            chosen = [c for c in configurations if c[0] == load]
            # Alternate the order from round to round: a configuration is not always first after
            # the busy loop starts.
            if round_number % 2:
                chosen.reverse()
            if load == "free":
                for configuration in chosen:
                    figures[configuration].append(steps_per_second(programs[configuration[2]], configuration[1],
                                                                   BEAMS[configuration[1]], configuration[3]))
            else:
                with BusyCore():
                    for configuration in chosen:
                        figures[configuration].append(steps_per_second(programs[configuration[2]], configuration[1],
                                                                       BEAMS[configuration[1]], configuration[3]))
        print(f"round {round_number + 1} of {args.rounds} done", file=sys.stderr)

    thread_label = {0: "default"}
    print(f"steps/s, medians of {args.rounds} rounds (range); fastcorot bench --beam B --steps S --json, "
          f"S = {', '.join(f'{s} for {b}' for b, s in BEAMS.items() if b in args.beams)}")
    print()
    header = ["load", "beam", "build"] + [f"{thread_label.get(t, t)} thread{'s' if t != 1 else ''}" for t in args.threads]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for load in ("free", "one core busy"):
        for beam in args.beams:
            for name in programs:
                cells = []
                for threads in args.threads:
                    values = figures[(load, beam, name, threads)]
                    cells.append(f"{statistics.median(values):.0f} ({min(values):.0f}–{max(values):.0f})")
                print(f"| {load} | {beam} | {name} | " + " | ".join(cells) + " |")
    if args.json:
        args.json.write_text(json.dumps([{"load": c[0], "beam": c[1], "build": c[2], "threads": c[3],
                                          "steps_per_second": v} for c, v in figures.items()], indent=1))


if __name__ == "__main__":
    main()
