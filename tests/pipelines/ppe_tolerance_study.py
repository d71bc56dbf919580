#!/usr/bin/env python3
"""ppe_tolerance_study.py SOURCE_DIR BUILD_DIR [--tolerances 1e-6,1e-5,1e-4,1e-3] [--jobs 2]

Issue 17, point 4: does a looser PPE tolerance (`solver.ppe_tolerance`, the solve warm-started
from the last step's pressure) move the answers? Runs three cases at each tolerance, with the
case's full scene and the default solver, through the case's own pipeline
(`make -C pipelines/<case> simulate VARIANT=ppe_tol_<tol> SET=...`, outputs in
out/<case>/ppe_tol_<tol>/), then prints, per case and tolerance, the numbers
tests/pipelines/check_flow_smoke.py prints for the case, the PPE iterations a step and the wall
time:
  - hydrostatic_tank (dx = 0.01 m, 2 s): every probe's pressure against ρg·depth, the force, the
    volume drift;
  - dambreak_koshizuka (L/80) to T = t·√(2g/L) = 3: the surge front against MPS at T = 1 … 3;
  - dambreak_lobovsky (H/80) to t = 0.5 s: sensor 1's impact time and the first-impact peaks;
  - in 3-D (`--cases hydrostatic_tank_3d,wedge_entry_3d`): the 3-D tank at rest (dx = 0.0125 m,
    2 s) and the wedge prism's water entry (dx = 0.05 m, to 0.34 s: the force peak, the keel
    pressures, the velocity against the momentum models).
Runs one thread each, `--jobs` side by side; a finished run is not rerun (the pipeline's
staleness), so a second call only tabulates. The wall times compare within one call on a quiet
machine. Exit 1 when a run fails.
"""
import argparse
import contextlib
import io
import json
import os
import subprocess
import sys
import tomllib
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import check_flow_smoke as checks  # noqa: E402

CASES = {
    "hydrostatic_tank": [],
    "dambreak_koshizuka": ["time.end=0.2602"],  # T = t·√(2g/L) = 3 with L = 0.146 m
    "dambreak_lobovsky": ["time.end=0.5"],  # past sensor 1's impact (t·√(g/H) = 2.45, t = 0.43 s)
}
CASES_3D = {"hydrostatic_tank_3d": [], "wedge_entry_3d": []}
ALL_CASES = CASES | CASES_3D
# The check function of a case (check_flow_smoke.py checks the 3-D tank as the 2-D one).
CHECK_OF = {"hydrostatic_tank_3d": "hydrostatic_tank"}


def variant(tolerance):
    return "ppe_tol_" + tolerance


def settings(case, tolerance):
    return [f"solver.ppe_tolerance={tolerance}"] + ALL_CASES[case]


def run(source, build, case, tolerance):
    command = ["make", "-s", "-C", str(source / "pipelines" / case), "simulate",
               f"VARIANT={variant(tolerance)}", f"HM_BUILD={build}",
               "SET=" + " ".join(settings(case, tolerance))]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    done = subprocess.run(command, env=env, capture_output=True, text=True)
    if done.returncode != 0:
        print(f"{case} at {tolerance}: make failed ({done.returncode})\n{done.stderr[-2000:]}")
    return done.returncode


def scene_with_settings(source, case, tolerance):
    """The case's scene as the run saw it (the SET values applied to the dict the checks read)."""
    with open(source / "pipelines" / case / "scene.toml", "rb") as f:
        scene = tomllib.load(f)
    for setting in settings(case, tolerance):
        key, value = setting.split("=")
        section, name = key.split(".")
        scene.setdefault(section, {})[name] = float(value)
    return scene


def summary(source, build, case, tolerance):
    out = source / "out" / case / variant(tolerance)
    results = out / "results.h5"
    attributes = checks.inspect(build, results)["attributes"]
    iterations = checks.dataset(build, results, "/monitors/ppe_iterations")
    passes = checks.dataset(build, results, "/monitors/ppe_passes")
    residual = checks.dataset(build, results, "/monitors/ppe_residual")
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        getattr(checks, CHECK_OF.get(case, case))(checks.Checks(), scene_with_settings(source, case, tolerance), out,
                              source, build)
    return {
        "case": case, "tolerance": float(tolerance), "steps": attributes["steps"],
        "wall_seconds": attributes["wall_seconds"],
        "ppe_iterations_per_step": sum(iterations) / len(iterations),
        "ppe_iterations_per_pass": sum(iterations) / sum(passes),
        "largest_ppe_residual": max(residual),
        "measured": [line.strip()[6:] if line.startswith(("ok    ", "FAIL  ")) else line.strip()
                     for line in printed.getvalue().splitlines() if line.strip()],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[2])
    parser.add_argument("source", type=Path)
    parser.add_argument("build", type=Path)
    parser.add_argument("--tolerances", default="1e-6,1e-5,1e-4,1e-3")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--cases", default=",".join(CASES))
    args = parser.parse_args()
    source, build = args.source.resolve(), args.build.resolve()
    tolerances = args.tolerances.split(",")
    runs = [(case, tol) for case in args.cases.split(",") for tol in tolerances]
    with ThreadPoolExecutor(args.jobs) as pool:
        codes = list(pool.map(lambda r: run(source, build, *r), runs))
    table = [summary(source, build, *r) for r, code in zip(runs, codes) if code == 0]
    for row in table:
        print(f"\n## {row['case']} at ppe_tolerance = {row['tolerance']:g}: {row['steps']} steps, "
              f"{row['wall_seconds']:.1f} s, {row['ppe_iterations_per_step']:.1f} PPE iterations "
              f"a step ({row['ppe_iterations_per_pass']:.1f} a solve), largest residual "
              f"{row['largest_ppe_residual']:.2g}")
        for line in row["measured"]:
            print("    " + line)
    (source / "out" / "ppe_tolerance_study.json").write_text(json.dumps(table, indent=1))
    return 1 if any(codes) else 0


if __name__ == "__main__":
    sys.exit(main())
