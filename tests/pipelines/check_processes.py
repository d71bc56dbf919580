#!/usr/bin/env python3
"""check_processes.py ONE MANY SCENE [--until-impact] [--scatter TIGHT]: a flow run over several processes against
the same run as one process. Both folders hold results.h5 and probes.csv of the same scene.
Every sample of MANY must be at the time of ONE's (to 10x the tolerance relative: the steps
follow the largest speed) and every value within 10x the
PPE tolerance (the scene's solver.ppe_tolerance, default 1e-6) of the probe's largest
magnitude (a force probe's: of its vector); a value missing in one (no fluid at the probe) must be missing in the other. With
--until-impact, only the samples before the impact are held to that — the first sample at which
a pressure probe of ONE sees fluid — as the flow after a violent impact is chaotic: the time at
which the runs part and their largest differences after it are printed. Exit 1 with the failed
columns otherwise.

With --scatter TIGHT (ONE's run again at a 10x tighter PPE tolerance), a probe's bound is the
larger of that and twice ONE's own distance from TIGHT over the run: where a relative residual of
the tolerance leaves ONE itself further than 10x the tolerance from the converged answer (a
force integrated over a wall), MANY is held to be as close to it as ONE is (by the triangle
inequality, two answers each that far from the converged one lie within twice of each other)."""
import csv
import math
import subprocess
import sys
import tomllib


def read_probes(folder):
    with open(f"{folder}/probes.csv", newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(x) for x in row] for row in rows[1:]]


def run_status(folder):
    out = subprocess.run(["h5dump", "-a", "/run_status", f"{folder}/results.h5"],
                         capture_output=True, text=True, check=True).stdout
    return "completed" if '"completed"' in out else out


def probe_scale(header, rows, column):
    """The largest magnitude of the probe a column belongs to: of the vector of a force probe's
    components (a component that vanishes by symmetry is held to the force's scale), else of the
    column's values."""
    probe = header[column].rsplit(".", 1)[0]
    group = [c for c in range(1, len(header)) if header[c].rsplit(".", 1)[0] == probe]
    largest = 0.0
    for row in rows:
        values = [row[c] for c in group if not math.isnan(row[c])]
        largest = max(largest, math.sqrt(sum(v * v for v in values)))
    return largest


def impact_time(header, rows):
    """The first sample time at which a pressure column holds a value (the fluid arrived)."""
    pressure = [c for c in range(1, len(header)) if "[Pa]" in header[c]]
    for row in rows:
        if any(not math.isnan(row[c]) for c in pressure):
            return row[0]
    return math.inf


def main():
    one, many, scene = sys.argv[1:4]
    options = sys.argv[4:]
    until_impact = "--until-impact" in options
    tight = options[options.index("--scatter") + 1] if "--scatter" in options else None
    with open(scene, "rb") as f:
        tolerance = tomllib.load(f).get("solver", {}).get("ppe_tolerance", 1e-6)
    header, a = read_probes(one)
    header_many, b = read_probes(many)
    c_tight = read_probes(tight)[1] if tight else None
    failures = []
    if header != header_many:
        failures.append(f"columns differ: {header} against {header_many}")
    end = impact_time(header, a) if until_impact else math.inf
    held = [(ra, rb) for ra, rb in zip(a, b) if ra[0] < end]
    if len(a) != len(b) and not until_impact:
        failures.append(f"{len(a)} samples against {len(b)}")
    for ra, rb in held:
        if abs(ra[0] - rb[0]) > 10 * tolerance * max(ra[0], 1e-3):  # Δt from u_max
            failures.append(f"sample at t = {ra[0]} s against t = {rb[0]} s")
            break
    status = run_status(many)
    if status != "completed":
        failures.append(f"the run over processes did not complete: {status}")
    if until_impact:
        print(f"compared up to the impact at t = {end:.6g} s ({len(held)} of {len(a)} samples)")
    parted = math.inf  # the first time a column leaves its bound
    for c in range(1, len(header)):
        scale = probe_scale(header, a, c)
        bound = 10 * tolerance * scale
        own = ""
        if c_tight is not None:  # ONE's own distance from the converged answer
            scatter = max((abs(ra[c] - rt[c]) for ra, rt in zip(a, c_tight)
                           if not (math.isnan(ra[c]) or math.isnan(rt[c]))), default=0.0)
            own = f"; one process off its tighter-tolerance run by {scatter:.3g}"
            bound = max(bound, 2 * scatter)
        worst = 0.0
        for ra, rb in held:
            if math.isnan(ra[c]) != math.isnan(rb[c]):
                failures.append(f"{header[c]} at t = {ra[0]} s: missing in one run only")
                break
            if not math.isnan(ra[c]):
                worst = max(worst, abs(ra[c] - rb[c]))
        after = 0.0
        for ra, rb in zip(a, b):
            if math.isnan(ra[c]) or math.isnan(rb[c]):
                continue
            if abs(ra[c] - rb[c]) > bound:
                parted = min(parted, ra[0])
            if ra[0] >= end:
                after = max(after, abs(ra[c] - rb[c]))
        print(f"{header[c]}: largest difference {worst:.3g} (bound {bound:.3g}, "
              f"{worst / scale if scale else 0:.3g} of the largest value {scale:.4g}{own})"
              + (f"; after the impact {after:.3g} ({after / scale if scale else 0:.3g})"
                 if until_impact else ""))
        if worst > bound:
            failures.append(f"{header[c]} differs by {worst:.3g} > {bound:.3g}")
    if until_impact:
        print(f"the runs part at t = {parted:.6g} s" if parted < math.inf else
              "the runs never part")
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
