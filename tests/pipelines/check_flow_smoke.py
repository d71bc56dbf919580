#!/usr/bin/env python3
"""check_flow_smoke.py CASE OUT_DIR SCENE SOURCE_DIR BUILD_DIR

Checks the smoke run of a flow pipeline (results.h5 and probes.csv in OUT_DIR) against the
case's stated tolerances; prints the measured numbers; exits 1 naming every failed check.
The constants (tank, column, depth, sway period, end time) are read from the scene, the
references from data/reference/. Only the standard library, h5dump and fsi-inspect are used.
"""
import csv
import json
import math
import re
import subprocess
import sys
import tomllib
from pathlib import Path

GRAVITY = 9.81  # m/s², the scenes' default (fluid.gravity = [])


class Checks:
    def __init__(self):
        self.failed = []

    def expect(self, ok, message):
        print(("ok    " if ok else "FAIL  ") + message)
        if not ok:
            self.failed.append(message)


def read_probes(out):
    """probes.csv as {column name: [values]}."""
    with open(out / "probes.csv", newline="") as f:
        rows = list(csv.reader(f))
    header, values = rows[0], [[float(v) for v in row] for row in rows[1:] if row]
    return {name: [row[c] for row in values] for c, name in enumerate(header)}


def ambient_when_dry(values):
    """A pressure column with its missing values (nan: no fluid at the probe) read as the ambient
    gauge pressure 0, as an experiment's dry sensor reads."""
    return [0.0 if math.isnan(v) else v for v in values]


def read_xy(path):
    """Two-column reference CSV with one header line."""
    with open(path, newline="") as f:
        return [(float(a), float(b)) for a, b in list(csv.reader(f))[1:]]


def interpolate(xy, x):
    """Linear interpolation in a table sorted by x, clamped at the ends."""
    if x <= xy[0][0]:
        return xy[0][1]
    for (x0, y0), (x1, y1) in zip(xy, xy[1:]):
        if x <= x1:
            return y0 + (x - x0) / (x1 - x0) * (y1 - y0)
    return xy[-1][1]


def first_crossing(xy, level):
    """First x where y rises through `level` (linear between samples), None if never."""
    for (x0, y0), (x1, y1) in zip(xy, xy[1:]):
        if y0 <= level < y1:
            return x0 + (x1 - x0) * (level - y0) / (y1 - y0)
    return None


def zero_crossings(t, s):
    out = []
    for k in range(1, len(s)):
        if (s[k - 1] > 0) != (s[k] > 0):
            out.append(t[k - 1] + (t[k] - t[k - 1]) * s[k - 1] / (s[k - 1] - s[k]))
    return out


def dataset(build, results, path):
    """A 1-D dataset of results.h5 through h5dump."""
    text = subprocess.run(["h5dump", "-y", "-w", "0", "-m", "%.17g", "-d", path, str(results)],
                          check=True, capture_output=True, text=True).stdout
    data = re.search(r"DATA \{(.*?)\}", text, re.S).group(1)
    return [float(v) for v in data.replace(",", " ").split()]


def inspect(build, results):
    text = subprocess.run([str(build / "stages/fsi-inspect/fsi-inspect"), "--json", str(results)],
                          check=True, capture_output=True, text=True).stdout
    return json.loads(text)


def check_run(c, scene, out, build):
    """Completed (no divergence) to the scene's end time; returns max |volume drift|."""
    results = out / "results.h5"
    attributes = inspect(build, results)["attributes"]
    end = scene["time"]["end"]
    c.expect(attributes["run_status"] == "completed",
             f"run_status = {attributes['run_status']!r} (expected 'completed'); "
             f"divergence report: {attributes['divergence_report']!r}")
    c.expect(abs(attributes["end_time"] - end) <= 1e-9 * end,
             f"end_time = {attributes['end_time']} s (scene: {end} s)")
    drift = max(abs(v) for v in dataset(build, results, "/monitors/volume_drift"))
    print(f"      {attributes['steps']} steps, {attributes['points']} points, "
          f"{attributes['wall_seconds']:.2f} s; max |volume drift| {100 * drift:.3f} %")
    return drift


def dambreak_koshizuka(c, scene, out, source, build):
    drift = check_run(c, scene, out, build)
    # The volume drift (the half-density region, ldd/volume.hpp) falls at first order under
    # refinement: 3.5 % at L/20 (this smoke variant), 1.6 % at L/40, 0.5 % at L/80 to T = 3
    # (tests/ldd asserts the convergence); the smoke run is held to an envelope above L/20's.
    c.expect(drift < 0.05, f"max |volume drift| {100 * drift:.3f} % < 5 % (L/20)")
    L = scene["fluid"]["region"][0]["size"][0]  # column width [m]
    scale = math.sqrt(2 * GRAVITY / L)  # T = t·√(2g/L)
    p = read_probes(out)
    front = list(zip([t * scale for t in p["t [s]"]], [x / L for x in p["front.front [m]"]]))
    reference = source / "data/reference/dambreak_koshizuka_oka_1996"
    mps = read_xy(reference / "pysph_ko1996_mps_front.csv")
    experiment = read_xy(reference / "pysph_ko1996_experiment_front.csv")
    asserted = {1.0, 2.0, 2.9}  # MPS ends at T = 2.94 (Z = 4, the right wall)
    for T in (1.0, 1.5, 2.0, 2.5, 2.9, 3.0):
        z, z_mps, z_exp = interpolate(front, T), interpolate(mps, T), interpolate(experiment, T)
        e_mps, e_exp = z / z_mps - 1, z / z_exp - 1
        line = (f"T = {T:.1f}: front Z = {z:.3f} (MPS {z_mps:.3f}: {100 * e_mps:+.1f} %; "
                f"experiment {z_exp:.3f}: {100 * e_exp:+.1f} %)")
        if T in asserted:
            c.expect(abs(e_mps) < 0.08, line + " within 8 % of MPS")
        else:
            print("      " + line)


def running_mean(t, v, window):
    """Mean of the piecewise-constant signal (value v[k] over (t[k-1], t[k]]) over (t − window, t]."""
    out = []
    for k in range(len(t)):
        start, total, j = t[k] - window, 0.0, k
        while j > 0 and t[j - 1] > start:
            total += v[j] * (t[j] - t[j - 1])
            j -= 1
        if j > 0:
            total += v[j] * (t[j] - start)
        out.append(total / window)
    return out


def dambreak_lobovsky(c, scene, out, source, build):
    """Impact time (asserted) and the first-impact peaks of p1 and p3, per step and averaged over
    one contact window w = dx / (2√(gH)): the time the surge front (at the Ritter speed) takes to
    cross one point spacing. An incompressible impact arrives as one pressure impulse per point
    that reaches the wall, of height ≈ ρU²/C_u, so the per-step peak is set by the CFL number, not
    by the flow; over w the impulses average to the pressure of the flow, and w → 0 under
    refinement. The experiment is the median of ~100 repetitions."""
    check_run(c, scene, out, build)
    H = scene["fluid"]["region"][0]["size"][1]  # column height [m]
    dx = scene["fluid"]["dx"]
    rho_g_h = scene["fluid"]["density"] * GRAVITY * H
    scale = math.sqrt(GRAVITY / H)  # T = t·√(g/H)
    window = dx / (2 * math.sqrt(GRAVITY * H))
    p = read_probes(out)
    t = p["t [s]"]
    T = [x * scale for x in t]
    reference = source / "data/reference/dambreak_lobovsky_2014"
    sensors = {n: read_xy(reference / f"pysph_lobovsky2014_H300_sensor{n}.csv") for n in (1, 3)}
    p1 = list(zip(T, [v / rho_g_h for v in ambient_when_dry(p["p1.p [Pa]"])]))
    t_sim, t_exp = first_crossing(p1, 0.5), first_crossing(sensors[1], 0.5)
    c.expect(t_sim is not None, "p1 exceeds 0.5·ρgH")
    if t_sim is not None:
        c.expect(abs(t_sim / t_exp - 1) < 0.05,
                 f"impact: p1 first exceeds 0.5·ρgH at t·√(g/H) = {t_sim:.3f} "
                 f"(experiment {t_exp:.3f}: {100 * (t_sim / t_exp - 1):+.1f} %) within 5 %")
    first_impact = {1: (2.3, 2.7), 3: (2.5, 3.0)}  # T windows around the experiment's peaks
    for n in (1, 3):
        values = [v / rho_g_h for v in ambient_when_dry(p[f"p{n}.p [Pa]"])]
        lo, hi = first_impact[n]
        te, pe = max((q for q in sensors[n] if lo <= q[0] <= hi), key=lambda q: q[1])
        for label, signal in (("per step", values),
                              (f"over w = {1000 * window:.2f} ms", running_mean(t, values, window))):
            ks = [k for k in range(len(T)) if lo <= T[k] <= hi]
            if not ks:
                continue
            k = max(ks, key=lambda k: signal[k])
            print(f"      p{n} first-impact peak ({label}, T in [{lo}, {hi}]): {signal[k]:.2f} ρgH "
                  f"at {T[k]:.3f} (experiment {pe:.2f} at {te:.3f}: {100 * (signal[k] / pe - 1):+.0f} %,"
                  f" {100 * (T[k] / te - 1):+.1f} % in time)")


def sloshing_first_mode_period(length, depth):
    """Linear first-mode period of a rectangular tank [s]: ω² = (πg/L)·tanh(πH/L)."""
    k = math.pi / length
    return 2 * math.pi / math.sqrt(GRAVITY * k * math.tanh(k * depth))


def sloshing_linear(c, scene, out, source, build):
    drift = check_run(c, scene, out, build)
    length = scene["wall"][0]["size"][0]
    depth = scene["fluid"]["region"][0]["size"][1]
    period = sloshing_first_mode_period(length, depth)  # also the pulse's duration (pulse.csv)
    p = read_probes(out)
    after = [k for k, t in enumerate(p["t [s]"]) if t >= period]
    t = [p["t [s]"][k] for k in after]
    s = [p["eta_left.eta [m]"][k] - p["eta_right.eta [m]"][k] for k in after]
    crossings = zero_crossings(t, s)
    c.expect(len(crossings) >= 5, f"{len(crossings)} zero crossings after the pulse (≥ 5)")
    if len(crossings) < 5:
        return
    whole = (len(crossings) - 1) // 2
    measured = (crossings[2 * whole] - crossings[0]) / whole
    swings = [max(abs(v) for tv, v in zip(t, s) if a <= tv <= b)
              for a, b in zip(crossings, crossings[1:])]
    print(f"      eta_left − eta_right half-swing peaks [mm]: "
          + ", ".join(f"{1000 * v:.1f}" for v in swings) + f"; max |volume drift| "
          f"{100 * drift:.3f} %")
    c.expect(abs(measured / period - 1) < 0.03,
             f"period {measured:.4f} s over {whole} whole periods against {period:.4f} s "
             f"({100 * (measured / period - 1):+.2f} %) within 3 %")


def sway_sloshing(c, scene, out, source, build):
    drift = check_run(c, scene, out, build)
    c.expect(drift < 0.02, f"max |volume drift| {100 * drift:.3f} % < 2 %")
    results = out / "results.h5"
    speed = max(dataset(build, results, "/monitors/max_speed"))
    escaped = dataset(build, results, "/monitors/escaped")[-1]
    c.expect(speed < 1.0, f"max fluid speed {speed:.3f} m/s < 1 m/s (wave orbital speed ωa ≈ 0.1)")
    c.expect(escaped == 0, f"{escaped:.0f} points escaped the tank (expected 0)")
    wall = scene["wall"][0]
    period = wall["sway_period"]
    count = round((scene["time"]["end"] - wall["motion_ramp"]) / period)
    start = wall["motion_ramp"] - period  # period 0 is the ramp's (the ramp lasts one period)
    p = read_probes(out)
    amplitude = []
    for k in range(count + 1):
        window = [i for i, t in enumerate(p["t [s]"])
                  if start + k * period - 1e-9 <= t <= start + (k + 1) * period + 1e-9]
        eta = [p["eta_left.eta [m]"][i] for i in window]
        pressure = ambient_when_dry([p["p_wall.p [Pa]"][i] for i in window])
        fx = [p["tank.fx [N]"][i] for i in window]
        amplitude.append((max(eta) - min(eta)) / 2)
        print(f"      period {k}{' (ramp)' if k == 0 else ''}: eta_left {min(eta):.4f} … "
              f"{max(eta):.4f} m (half range {1000 * amplitude[-1]:.1f} mm), p_wall "
              f"{min(pressure):.0f} … {max(pressure):.0f} Pa, tank.fx {min(fx):.1f} … "
              f"{max(fx):.1f} N/m")
    for k in range(1, len(amplitude)):
        c.expect(amplitude[k] > 1.1 * amplitude[k - 1],
                 f"resonance: eta_left half range grows from period {k - 1} to {k} by more than "
                 f"10 % ({1000 * amplitude[k - 1]:.1f} → {1000 * amplitude[k]:.1f} mm)")


def matrix(build, results, path):
    """A 2-D dataset of results.h5 as a list of rows."""
    text = subprocess.run(["h5dump", "-y", "-w", "0", "-m", "%.17g", "-d", path, str(results)],
                          check=True, capture_output=True, text=True).stdout
    dims = [int(v) for v in re.search(r"DATASPACE\s+SIMPLE\s+\{\s*\(\s*([\d,\s]+)\)",
                                       text).group(1).split(",")]
    values = dataset(build, results, path)
    return [values[r * dims[1]:(r + 1) * dims[1]] for r in range(dims[0])]


def check_coupling(c, out, build):
    """The coupled run's sub-iterations: at least 90 % of the steps below the tolerance."""
    results = out / "results.h5"
    residual = dataset(build, results, "/monitors/interface_residual")
    iterations = dataset(build, results, "/monitors/coupling_iterations")
    converged = sum(1 for r in residual if r <= 1e-3) / len(residual)
    print(f"      coupling: {sum(iterations) / len(iterations):.2f} PPE solves a step "
          f"(max {max(iterations):.0f}), {100 * converged:.1f} % of the steps converged")
    c.expect(converged >= 0.9, f"{100 * converged:.1f} % of the steps converged (at least 90 %)")


def gate_added_mass(scene):
    """m_a/m_s of the gate's first mode from potential flow (LDD-SPEC §3.4: 14.5).

    The column (width A, depth H, free surface p = 0, rigid floor, far wall and the wall above
    the gate) sees the gate's face x = A, y ∈ [0, L] move with the Euler–Bernoulli clamped-free
    shape φ (clamped at y = L), mass-normalised (ρ_s t ∫φ² = 1): with k_n = (2n − 1)π/(2H),
    m_a = ρ H/2 Σ c_n² coth(k_n A)/k_n, c_n = (2/H) ∫ φ cos(k_n y) dy.
    """
    rho = scene["fluid"]["density"]
    region = scene["fluid"]["region"][0]
    width, depth = region["size"]
    thickness, length = scene["structure"]["geometry"]["size"]
    rho_s = scene["structure"]["material"]["density"]
    beta = 1.8751040687
    sigma = (math.cosh(beta) + math.cos(beta)) / (math.sinh(beta) + math.sin(beta))
    samples = 2000
    ys = [length * k / samples for k in range(samples + 1)]

    def shape(y):
        s = (length - y) / length * beta
        return math.cosh(s) - math.cos(s) - sigma * (math.sinh(s) - math.sin(s))

    def integral(f):
        v = [f(y) for y in ys]
        return (sum(v) - 0.5 * (v[0] + v[-1])) * length / samples

    norm = math.sqrt(rho_s * thickness * integral(lambda y: shape(y) ** 2))
    total = 0.0
    for n in range(1, 300):
        k = (2 * n - 1) * math.pi / (2 * depth)
        cn = 2 / depth * integral(lambda y: shape(y) / norm * math.cos(k * y))
        total += cn * cn / math.tanh(k * width) / k
    return rho * depth / 2 * total


def elastic_gate(c, scene, out, source, build):
    """Completed; early response of the first mode against its wet one-degree-of-freedom value.

    Right after the release the gate is loaded by the hydrostatic pressure and held back by the
    water's added mass: mode 1 alone answers y(t) = F(0⁺)/ω_w² (1 − cos ω_w t) with
    ω_w = ω_1/√(1 + m̂_11) and F(0⁺) the consistent start load (spec §3.5: 4.05 mm at the tip
    at 0.02 s on the prototype; the dry gate would move 16 times as far).
    """
    check_run(c, scene, out, build)
    check_coupling(c, out, build)
    results = out / "results.h5"
    t = dataset(build, results, "/modal/time")
    y = [row[0] for row in matrix(build, results, "/modal/coordinates")]
    force = matrix(build, results, "/modal/forces")[0][0]
    added = matrix(build, results, "/modal/added_mass_initial")[0][0]
    modes = inspect(build, out / "modes.h5")
    omega = 2 * math.pi * modes["frequencies_hz"][0]
    wet = omega / math.sqrt(1 + added)
    at = 0.02
    measured = interpolate(list(zip(t, y)), at)
    one_dof = force / wet ** 2 * (1 - math.cos(wet * at))
    probes = read_probes(out)
    tip = interpolate(list(zip(probes["t [s]"], probes["tip.ux [m]"])), at)
    print(f"      mode 1 at {at} s: y = {measured:.4g} against the wet one-DOF {one_dof:.4g} "
          f"({100 * (measured / one_dof - 1):+.1f} %); m_a/m_s = {added:.2f}; tip {1000 * tip:.2f} mm")
    c.expect(abs(measured / one_dof - 1) < 0.15,
             f"mode 1 at {at} s within 15 % of its wet one-DOF response")
    potential = gate_added_mass(scene)
    c.expect(abs(added / potential - 1) < 0.05,
             f"m_a/m_s of mode 1 = {added:.2f} within 5 % of potential flow {potential:.2f} "
             f"({100 * (added / potential - 1):+.1f} %)")


def dambreak_elastic_plate(c, scene, out, source, build):
    """Completed; the plate at rest until the surge arrives, then pushed downstream."""
    check_run(c, scene, out, build)
    check_coupling(c, out, build)
    probes = read_probes(out)
    t, ux = probes["t [s]"], probes["tip.ux [m]"]
    before = max(abs(u) for time, u in zip(t, ux) if time < 0.08)
    print(f"      tip before t = 0.08 s: max |ux| {1000 * before:.3f} mm; at {t[-1]} s: "
          f"{1000 * ux[-1]:.2f} mm")
    c.expect(before < 5e-4, f"max |tip ux| {1000 * before:.3f} mm before the surge (< 0.5 mm)")
    c.expect(ux[-1] > 1e-3, f"tip ux {1000 * ux[-1]:.2f} mm at {t[-1]} s (> 1 mm downstream)")


def cantilever_plate_f1(scene):
    """First bending frequency [Hz] of the baffle as a clamped-free strip, Euler–Bernoulli:
    f1 = 1.8751²/(2π L²)·√(EI/(ρA)) with EI/(ρA) = E t²/(12 ρ), thickness t along x, length L
    along the last axis (up); returned as (beam, plate) with E and with the plate modulus
    E/(1 − ν²) (2-D plane strain: the plate value)."""
    size = scene["structure"]["geometry"]["size"]
    thickness, length = size[0], size[-1]
    material = scene["structure"]["material"]
    E, nu, rho = material["youngs_modulus"], material["poisson_ratio"], material["density"]
    f = 1.8751040687 ** 2 / (2 * math.pi * length ** 2) * math.sqrt(E * thickness ** 2 / (12 * rho))
    return f, f / math.sqrt(1 - nu * nu)


def check_dry_f1(c, scene, out, build):
    """The mode count asked for, and the dry f1 in the bracket of the clamped-free beam (E) and
    plate (E/(1 − ν²)) estimates, 3 % margin each side (a strip b/t = 24, b/L = 0.8, or a plane-
    strain beam: neither estimate is exact)."""
    frequencies = inspect(build, out / "modes.h5")["frequencies_hz"]
    c.expect(len(frequencies) == scene["modes"]["count"],
             f"{len(frequencies)} modes (scene: {scene['modes']['count']})")
    beam, plate = cantilever_plate_f1(scene)
    c.expect(0.97 * beam <= frequencies[0] <= 1.03 * plate,
             f"dry f1 = {frequencies[0]:.3f} Hz within [0.97·{beam:.3f}, 1.03·{plate:.3f}] Hz "
             f"(Euler–Bernoulli with E, with E/(1 − ν²); {100 * (frequencies[0] / beam - 1):+.1f} % "
             f"/ {100 * (frequencies[0] / plate - 1):+.1f} %)")


def check_hydrostatic_probe(c, scene, probes, name):
    """The pressure probe `name` at t = 0 (fluid at rest) within 10 % of ρg·depth below the still
    surface of the first region (the probe averages over a sphere cut by the floor or surface)."""
    region = scene["fluid"]["region"][0]
    probe = next(p for p in scene["probe"] if p["name"] == name)
    up = scene["case"]["dimension"] - 1
    depth = region["origin"][up] + region["size"][up] - probe["position"][up]
    expected = scene["fluid"]["density"] * GRAVITY * depth
    p0 = probes[f"{name}.p [Pa]"][0]
    c.expect(abs(p0 / expected - 1) < 0.10,
             f"{name} at t = {probes['t [s]'][0]} s: {p0:.0f} Pa against ρg·d = {expected:.0f} Pa "
             f"({100 * (p0 / expected - 1):+.1f} %) within 10 %")


def hydrostatic_tank(c, scene, out, source, build):
    """Water at rest (2-D or 3-D): at every probe row, each pressure probe within 1 % of ρgH of
    ρg·depth when its averaging ball (radius h = 2.5 dx) lies inside the water; a ball cut by the
    floor, a wall or the surface averages around a centroid moved by up to 3h/8 (a half ball), so
    then within ρg·3h/8. Each elevation probe within dx/4 of the still surface, the tank's
    vertical force within 1 % of −ρgH·(floor area); the volume kept within 0.5 %; nothing
    escaped."""
    drift = check_run(c, scene, out, build)
    c.expect(drift < 0.005, f"max |volume drift| {100 * drift:.3f} % < 0.5 %")
    escaped = dataset(build, out / "results.h5", "/monitors/escaped")[-1]
    c.expect(escaped == 0, f"{escaped:.0f} points escaped the tank (expected 0)")
    probes = read_probes(out)
    up = scene["case"]["dimension"] - 1
    region = scene["fluid"]["region"][0]
    surface = region["origin"][up] + region["size"][up]
    rho, dx = scene["fluid"]["density"], scene["fluid"]["dx"]
    rho_g_h = rho * GRAVITY * region["size"][up]
    for probe in scene["probe"]:
        name = probe["name"]
        if probe["kind"] == "pressure":
            expected = rho * GRAVITY * (surface - probe["position"][up])
            h = probe.get("radius", 0.0) or 2.5 * dx
            x, lo = probe["position"], region["origin"]
            inside = all(lo[a] + h <= x[a] <= lo[a] + region["size"][a] - h for a in range(up + 1))
            bound = 0.01 * rho_g_h if inside else rho * GRAVITY * 3 * h / 8
            values = probes[f"{name}.p [Pa]"]
            c.expect(not any(math.isnan(p) for p in values), f"{name}: a value at every row")
            worst = max(abs(p - expected) for p in ambient_when_dry(values))
            c.expect(worst < bound,
                     f"{name}: max |p − ρg·d| {worst:.1f} Pa < {bound:.1f} Pa "
                     f"({'1 % of ρgH' if inside else 'ρg·3h/8: the ball is cut'}); "
                     f"ρg·d = {expected:.1f} Pa")
        elif probe["kind"] == "elevation":
            worst = max(abs(e - surface) for e in probes[f"{name}.eta [m]"])
            c.expect(worst < 0.25 * dx, f"{name}: max |η − H| {1000 * worst:.2f} mm < dx/4")
        elif probe["kind"] == "force":
            floor = math.prod(region["size"][:up])
            expected = -rho_g_h * floor
            force = probes[f"{name}.f{'xyz'[up]} [N]"][-1]
            c.expect(abs(force / expected - 1) < 0.01,
                     f"{name}.f{'xyz'[up]} at the end {force:.2f} N against −ρgH·A = "
                     f"{expected:.2f} N within 1 %")


def sloshing_baffle(c, scene, out, source, build):
    """Completed; coupling converged; volume kept; the dry first mode against the cantilever
    strip; the hydrostatic pressure at t = 0; D1 moved, and stayed within the linear range."""
    drift = check_run(c, scene, out, build)
    check_coupling(c, out, build)
    c.expect(drift < 0.03, f"max |volume drift| {100 * drift:.3f} % < 3 %")
    results = out / "results.h5"
    escaped = dataset(build, results, "/monitors/escaped")[-1]
    c.expect(escaped == 0, f"{escaped:.0f} points escaped the tank (expected 0)")
    check_dry_f1(c, scene, out, build)
    probes = read_probes(out)
    check_hydrostatic_probe(c, scene, probes, "p_floor")
    # D1 (the baffle's top corner): it moves (the tank's acceleration alone bends the dry baffle
    # quasi-statically by ρ_s t Aω² L⁴/(8EI)), and stays bounded below the baffle's height. At
    # the paper's E = 38.4 MPa the water bends it beyond the linear range (11 % of the height at
    # 1 s, the stretch monitor warns), so this is a stability bound, not an accuracy one.
    height = scene["structure"]["geometry"]["size"][2]
    ux = probes["D1.ux [m]"]
    peak = max(abs(u) for u in ux)
    wall = next(w for w in scene["wall"] if w["name"] == scene["coupling"]["moves_with"])
    material = scene["structure"]["material"]
    thickness = scene["structure"]["geometry"]["size"][0]
    omega = 2 * math.pi / wall["sway_period"]
    dry = (material["density"] * thickness * wall["sway_amplitude"] * omega ** 2 * height ** 4
           / (8 * material["youngs_modulus"] * thickness ** 3 / 12))
    print(f"      D1: max |ux| {1000 * peak:.3f} mm (dry quasi-static base-excitation peak "
          f"{1000 * dry:.2f} mm); at {probes['t [s]'][-1]} s: {1000 * ux[-1]:.3f} mm")
    c.expect(peak > 1e-5, f"D1 max |ux| {1000 * peak:.3f} mm > 0.01 mm (the baffle responds)")
    c.expect(peak < height,
             f"D1 max |ux| {1000 * peak:.3f} mm < {1000 * height:.1f} mm (the baffle's height)")


def wedge_geometry(source, case="wedge_entry"):
    """Keel height and deadrise β [rad] of pipelines/<case>/wedge.geo (Points 1 and 2: the keel
    and the right chine; (x, y) in 2-D, (x, y, z) in 3-D with the section in x–z), and the
    prism's length along y in 3-D (its Extrude), 1 m (per metre) in 2-D."""
    text = (source / f"pipelines/{case}/wedge.geo").read_text()
    number = r"([-\d.e]+)"
    points = {int(m[0]): tuple(float(v) for v in m[1:] if v) for m in
              re.findall(rf"Point\((\d+)\) = \{{{number}, {number}, {number}\}}", text)}
    (x1, *up1), (x2, *up2) = points[1], points[2]
    keel, chine = (up1[0], up2[0]) if up1[1] == 0 and up2[1] == 0 else (up1[1], up2[1])
    extrude = re.search(rf"Extrude \{{0, {number}, 0\}}", text)
    return keel, math.atan2(chine - keel, x2 - x1), float(extrude[1]) if extrude else 1.0


def wedge_momentum_model(v0, mass, keel, surface, beta, factor, t_end, rho):
    """Velocity [m/s] at t_end of a 2-D wedge by momentum theory: d/dt[(M + ρπc²/2)V] = −Mg +
    ρg ζ²/tan β (weight, buoyancy), c = factor·ζ/tan β the wetted half-width at penetration ζ:
    factor 1 is von Kármán's (the still-water width, too narrow), π/2 Wagner's (the splash-up
    width, too wide at 25°); the true wetted width lies between them. M per metre."""
    dt, t, z, momentum = 1e-5, 0.0, keel, mass * v0
    v = v0
    while t < t_end:
        zeta = max(surface - z, 0.0)
        c = factor * zeta / math.tan(beta)
        momentum += dt * (-mass * GRAVITY + rho * GRAVITY * zeta * zeta / math.tan(beta))
        v = momentum / (mass + rho * math.pi * c * c / 2)
        z += dt * v
        t += dt
    return v


def check_wedge_drop(c, scene, out, source, build, case, between_models):
    """A free-falling elastic wedge (structure.free_translation), 2-D section or 3-D prism: the
    exact fall before contact, the fluid's impulse equal to the body's momentum change, and the
    velocity after impact against the von Kármán and Wagner momentum models (per metre of the
    prism in 3-D: strip theory); reports the pressure peak and the deformation."""
    check_run(c, scene, out, build)
    check_coupling(c, out, build)
    results = out / "results.h5"
    attributes = inspect(build, results)
    attributes = attributes.get("attributes", attributes)
    mass = attributes["body_mass"]
    keel, beta, length = wedge_geometry(source, case)
    up = scene["case"]["dimension"] - 1
    region = scene["fluid"]["region"][0]
    surface = region["origin"][up] + region["size"][up]
    rho, dx = scene["fluid"]["density"], scene["fluid"]["dx"]
    v0 = scene["structure"]["initial_velocity"]
    t = dataset(build, results, "/modal/time")
    z = dataset(build, results, "/body/position")
    v = dataset(build, results, "/body/velocity")
    # Before the fluid can feel the wedge (keel above the surface by more than h = 2.5 dx): the
    # exact parabola (CFPI integrates the translation's constant load exactly).
    air = [k for k in range(len(t)) if keel + z[k] > surface + 2.5 * dx]
    fall = max((abs(z[k] - (v0 * t[k] - 0.5 * GRAVITY * t[k] ** 2)) for k in air), default=0)
    c.expect(len(air) > 0 and fall < 1e-9,
             f"free fall through the air ({len(air)} rows): max error {fall:.2e} m < 1e-9 m")
    # Momentum: ∫(F_up − Mg) dt over the probe rows (the force probe "wedge") = M Δv; exact when a
    # row ends every step (the load is linear in each step); a step cut short for an output time
    # leaves a row out (0.44 % at dx = 0.01 m). A wrong mass, thickness or weight is off by O(1).
    probes = read_probes(out)
    tp, fup = probes["t [s]"], probes[f"wedge.f{'xyz'[up]} [N]"]
    impulse = sum(0.5 * (fup[k] + fup[k + 1] - 2 * mass * GRAVITY) * (tp[k + 1] - tp[k])
                  for k in range(len(tp) - 1))
    change = mass * (v[-1] - v[0])
    c.expect(abs(impulse - change) < 1e-2 * abs(change),
             f"impulse of the fluid and the weight {impulse:.4f} N·s = M Δv {change:.4f} N·s "
             f"(within 1 %)")
    # After the impact: between the momentum models (strip theory per metre in 3-D).
    karman = wedge_momentum_model(v0, mass / length, keel, surface, beta, 1.0, t[-1], rho)
    wagner = wedge_momentum_model(v0, mass / length, keel, surface, beta, math.pi / 2, t[-1], rho)
    inside = min(karman, wagner) <= v[-1] <= max(karman, wagner)
    text = (f"velocity at {t[-1]} s {v[-1]:.3f} m/s between von Kármán {karman:.3f} and Wagner "
            f"{wagner:.3f} m/s")
    if between_models:
        c.expect(inside, text)
    else:
        print(f"      {text}: {'yes' if inside else 'no'} (reported, not checked at this dx)")
    peak = attributes["max_structure_pressure"]
    contact = max((abs(v[k]) for k in range(len(t)) if keel + z[k] > surface), default=abs(v0))
    wagner_cp = math.pi ** 2 / (4 * math.tan(beta) ** 2)
    print(f"      pressure peak {peak:.0f} Pa = {peak / (0.5 * rho * contact ** 2):.2f}·½ρV² at the "
          f"contact speed {contact:.3f} m/s (Wagner's small-deadrise limit {wagner_cp:.2f}); "
          f"largest deformation {1000 * attributes['max_structure_deformation']:.3f} mm")
    c.expect(peak > 0, f"a pressure peak on the wedge ({peak:.0f} Pa > 0)")
    c.expect(attributes["max_structure_deformation"] > 0,
             f"the wedge deforms ({attributes['max_structure_deformation']:.2e} m > 0)")


def wedge_entry(c, scene, out, source, build):
    """The 2-D wedge section (paper §4.6): check_wedge_drop, velocity between the models."""
    check_wedge_drop(c, scene, out, source, build, "wedge_entry", between_models=True)


def wedge_entry_3d(c, scene, out, source, build):
    """The 3-D wedge prism: check_wedge_drop; at the smoke's dx = 0.1 m (the half-breadth 4.7 dx)
    the velocity against the strip models is reported, not checked."""
    check_wedge_drop(c, scene, out, source, build, "wedge_entry_3d", between_models=False)


def oil_beam_rolling_tank(c, scene, out, source, build):
    """A beam on a rolling tank (the rotating carrier): completed; coupling converged; volume
    kept; the dry first mode against the cantilever; the hydrostatic pressure at t = 0; the tip
    moved and stayed bounded."""
    drift = check_run(c, scene, out, build)
    check_coupling(c, out, build)
    c.expect(drift < 0.03, f"max |volume drift| {100 * drift:.3f} % < 3 %")
    check_dry_f1(c, scene, out, build)
    probes = read_probes(out)
    check_hydrostatic_probe(c, scene, probes, "p_floor")
    height = scene["structure"]["geometry"]["size"][1]
    peak = max(abs(u) for u in probes["tip.ux [m]"])
    c.expect(1e-5 < peak < height,
             f"tip max |ux| {1000 * peak:.3f} mm in (0.01 mm, {1000 * height:.1f} mm): the beam "
             f"responds and stays bounded")


def dambreak_cantilever(c, scene, out, source, build):
    """The gate's strip standing on the floor under a dam break (paper §4.5): completed; coupling
    converged; volume kept; the dry first mode against the cantilever; the surge bends the tip
    downstream (> 1 mm) and it stays bounded (below the beam's length)."""
    drift = check_run(c, scene, out, build)
    check_coupling(c, out, build)
    # A dam break of 560 points splashing over the beam: the bound of the K&O L/20 smoke run.
    c.expect(drift < 0.05, f"max |volume drift| {100 * drift:.3f} % < 5 % (coarse dam break)")
    check_dry_f1(c, scene, out, build)
    probes = read_probes(out)
    length = scene["structure"]["geometry"]["size"][1]
    ux = probes["tip.ux [m]"]
    c.expect(max(ux) > 1e-3, f"tip max ux {1000 * max(ux):.2f} mm > 1 mm (the surge bends it downstream)")
    c.expect(max(abs(u) for u in ux) < length,
             f"tip max |ux| {1000 * max(abs(u) for u in ux):.2f} mm < {1000 * length:.0f} mm")


def rhee_sloshing(c, scene, out, source, build):
    """Rhee's swayed tank (paper §4.1.1): completed; volume kept; no point escaped; at t = 0 the
    floor probe P1 is hydrostatic and the tank carries the water's weight."""
    drift = check_run(c, scene, out, build)
    c.expect(drift < 0.03, f"max |volume drift| {100 * drift:.3f} % < 3 %")
    escaped = dataset(build, out / "results.h5", "/monitors/escaped")[-1]
    c.expect(escaped == 0, f"{escaped:.0f} points escaped the tank (expected 0)")
    probes = read_probes(out)
    check_hydrostatic_probe(c, scene, probes, "P1")
    region = scene["fluid"]["region"][0]
    weight = scene["fluid"]["density"] * GRAVITY * math.prod(region["size"])
    fz = probes["tank.fz [N]"][0]
    c.expect(abs(-fz / weight - 1) < 0.02,
             f"tank fz at t = 0: {fz:.1f} N against −ρgV = {-weight:.1f} N within 2 %")


def main():
    if len(sys.argv) != 6:
        sys.exit(__doc__)
    case, out, scene_file, source, build = sys.argv[1:]
    checks = {f.__name__: f for f in (hydrostatic_tank, dambreak_koshizuka, dambreak_lobovsky, sloshing_linear,
                                      sway_sloshing, elastic_gate, dambreak_elastic_plate,
                                      sloshing_baffle, wedge_entry, wedge_entry_3d,
                                      oil_beam_rolling_tank,
                                      dambreak_cantilever, rhee_sloshing)}
    checks["hydrostatic_tank_3d"] = hydrostatic_tank  # the same checks in 3-D
    if case not in checks:
        sys.exit(f"check_flow_smoke.py: unknown case {case!r}; expected one of {sorted(checks)}")
    with open(scene_file, "rb") as f:
        scene = tomllib.load(f)
    c = Checks()
    checks[case](c, scene, Path(out), Path(source), Path(build))
    if c.failed:
        print(f"{case}: {len(c.failed)} check(s) failed")
        sys.exit(1)
    print(f"{case}: all checks passed")


if __name__ == "__main__":
    main()
