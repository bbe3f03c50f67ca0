"""Cost per sea state and fairlead tension std: moorlife (time domain) against RAFT (frequency domain).

RAFT (``openraft``, NREL's Response Amplitudes of Floating Turbines) is the model floating-wind
users pick for speed. This script runs, in one process on the same WAMIT coefficients, the same
platform, the same MS2 lines and the same sea states:

* **moorlife**: ``simulate.simulate_batch`` of one sea state (JONSWAP waves, steady or turbulent wind,
  first-order + Newman slow-drift loads, Cummins with the radiation convolution, Morison drag on
  the relative velocity, thrust of the relative wind from the Ct table, dynamic lumped-mass or
  quasi-static lines, statistics and fatigue), the record ``--transient`` + ``--record`` s as
  the study runs it;
* **RAFT**: ``Model.analyzeCases`` of the same sea state (statics, iterated drag linearisation,
  CCBlade rotor derivatives, the full WAMIT difference-frequency QTF, spectral statistics), with
  MoorPy's quasi-static mooring (``moorMod`` 0, tension from the line-end Jacobian) and with its
  frequency-domain lumped-mass lines for the tensions (``moorMod`` 1).

RAFT is an anchor for cost, not a reference for accuracy: it is linear (drag linearised
stochastically, mooring linearised about the mean offset, slow drift only as the Gaussian
response to the QTF's force spectrum, rotor by the thrust derivatives of CCBlade at fixed pitch
and speed); moorlife integrates the nonlinear equations in time (Morison drag on the relative
velocity, thrust of the relative wind, lumped-mass lines with seabed contact). The tension
standard deviations are printed side by side to show where the two agree, not to score either.

Wind (``--wind``): by default steady on both sides, because openraft 2.0.4 computes the rotor's
turbulent excitation but does not apply it (the block is commented out in
``Model.solveDynamics``; RAFT issue 84, "Turbulence doesn't play a role"): RAFT's wind is the
CCBlade mean thrust plus the aerodynamic damping dT/dU, moorlife's the Ct-table thrust of the
relative wind (its damping included). ``--wind kaimal`` gives both inputs a Kaimal spectrum with
RAFT's IEC normal turbulence model, sigma = I_ref (0.75 U + 5.6), L_u = config
``simulation.wind.length_scale`` (8.1 x 42 = 340.2 m, RAFT's value above 60 m hub height): only
moorlife responds to it. Waves: JONSWAP with the gamma of config ``simulation.gamma`` on both
sides (the DNV rule = RAFT's IEC 61400-3 default). Directions: nautical "from" in the sea-state
table, converted to RAFT's propagation headings with ``moorlife.conventions``. The WAMIT
``.12d`` holds one heading: moorlife rotates its horizontal drift with the waves, and RAFT is given
the same rotation as data (``raft_wamit``).

The RAFT design is ``benchmarks/data/oc4semi_raft.yaml`` (RAFT's own OC4 example, see its header)
with the hull, masses, drag and mooring replaced from config/ (``raft_design``).

Usage (both sides read the WAMIT files; without them the script says so and stops)::

    nice -n 5 .venv/bin/python benchmarks/bench_raft.py --wamit ../shared/reference/oc4/marin_semi \\
        [--record 3600] [--transient 600] [--wind steady] [--rows 6 16 30 35] [--moormod1]
"""

from __future__ import annotations

import argparse
import contextlib
import copy
import gc
import io
import os
import platform as pyplatform
import sys
import tempfile
import time
import warnings
from importlib import metadata
from pathlib import Path

import numpy as np
import yaml

from moorlife import conventions
from moorlife import environment as env
from moorlife import mooring as moor
from moorlife import simulate as sim
from moorlife.io import read_mooring_systems, read_study_config
from moorlife.io.platform import read_platform_config
from moorlife.io.wamit import read_wamit_dataset

ROOT = Path(__file__).resolve().parents[1]
DESIGN = ROOT / "benchmarks/data/oc4semi_raft.yaml"
SHARED_WAMIT = ROOT.parent / "shared/reference/oc4/marin_semi"

#: Rows of the paper's Table 6 (the 35-bin scatter matrix; Barrera et al. 2019, restated in the
#: project's methodology notes): row -> (Hs m, Tp s, wave from deg, W m/s, wind from deg).
TABLE6 = {
    2: (1.0, 8.0, 320.0, 4.0, 320.0),
    6: (1.0, 8.0, 310.0, 9.5, 90.0),
    16: (2.1, 14.0, 340.0, 4.2, 330.0),
    19: (2.1, 10.5, 310.0, 10.5, 270.0),
    28: (3.6, 14.5, 310.0, 10.8, 270.0),
    30: (3.6, 10.5, 310.0, 17.5, 270.0),
    31: (3.6, 14.0, 310.0, 17.5, 270.0),
    35: (5.4, 15.0, 310.0, 21.0, 270.0),
}
KEYS = ("hs", "tp", "wave_dir", "wind_speed", "wind_dir")


def sea_states(cfg: dict, rows: list[int], sensitivity: bool = True) -> list[tuple[str, dict]]:
    """The Table 6 rows asked for, and config lifecycle.sensitivity.sea_state (paper section 4.2)."""
    out = [(f"T6#{r}", dict(zip(KEYS, TABLE6[r], strict=True))) for r in rows]
    if sensitivity:
        sens = cfg["lifecycle"]["sensitivity"]["sea_state"]
        out.insert(min(2, len(out)), ("sens.", {k: float(sens[k]) for k in KEYS}))
    return out


def heading_deg(nautical_from: float) -> float:
    """RAFT's heading (deg, counter-clockwise from +x, direction of travel) of a nautical 'from'."""
    return float(np.degrees(conventions.propagation_angle(nautical_from))) % 360.0


def wind_sigma(u: float, iref: float) -> float:
    """IEC 61400-1 normal turbulence model, the sigma RAFT's ``IECKaimal`` uses for a float ``turbulence``."""
    return iref * (0.75 * u + 5.6)


# ------------------------------------------------------------------------------------- RAFT side
def raft_members(pcfg: dict) -> list[dict]:
    """config/platform.yaml members as RAFT members: same geometry, drag; weightless; BEM inertia."""
    out = []
    for m in pcfg["members"]:
        axial = float(m.get("axial_cd", 0.0))
        out.append(
            {
                "name": m["name"],
                "type": "rigid",
                "rA": [float(v) for v in m["a"]],
                "rB": [float(v) for v in m["b"]],
                "shape": "circ",
                "potMod": True,  # hydrodynamic inertia and excitation from the WAMIT coefficients
                "stations": [0.0, 1.0],
                "d": float(m["diameter"]),
                "t": 0.01,
                "rho_shell": 0.0,  # the masses are the point inertias of config/platform.yaml
                "Cd": float(m["cd"]),
                "Ca": 0.0,
                "CdEnd": [axial, 0.0],  # moorlife: axial drag on the full disk at end a only
                "CaEnd": 0.0,
            }
        )
    return out


def point_inertia(block: dict) -> dict:
    ixx, iyy, izz = (float(v) for v in block["inertia_cm"])
    return {
        "type": "point_inertia",
        "mass": float(block["mass"]),
        "moments_of_inertia": [ixx, iyy, izz, 0.0, 0.0, 0.0],
        "location": [float(v) for v in block["cm"]],
    }


def raft_mooring(cfg: dict, row: dict, moor_mod: int) -> dict:
    """The MS2 lines and the OC4 layout of config/ in RAFT's (MoorPy's) YAML layout."""
    props = moor.line_properties(row, water_density=cfg["mooring"]["water_density"], gravity=cfg["mooring"]["gravity"])
    layout = moor.oc4_layout(cfg)
    ms = moor.mooring_settings(cfg)
    points, lines = [], []
    for i in range(layout.n_lines):
        points.append({"name": f"anchor{i + 1}", "type": "fixed", "location": layout.anchors[i].tolist()})
        points.append({"name": f"fairlead{i + 1}", "type": "vessel", "location": layout.fairleads_body[i].tolist()})
        lines.append(
            {
                "name": f"M{i + 1}",
                "endA": f"anchor{i + 1}",
                "endB": f"fairlead{i + 1}",
                "type": "chain",
                "length": float(layout.length),
            }
        )
    return {
        "water_depth": float(layout.depth),
        "water_density": float(ms.water_density),
        "moorMod": int(moor_mod),
        "points": points,
        "lines": lines,
        "line_types": [
            {
                "name": "chain",
                "diameter": float(props.equivalent_diameter),  # MoorPy: volume-equivalent diameter
                "mass_density": float(props.mass),
                "stiffness": float(props.EA),
                "breaking_load": float(props.MBS),
                "transverse_drag": float(ms.cd_normal),
                "tangential_drag": float(ms.cd_axial),
                "transverse_added_mass": float(ms.ca_normal),
                "tangential_added_mass": float(ms.ca_axial),
            }
        ],
    }


def raft_design(base: dict, cfg: dict, pcfg: dict, row: dict, hydro_prefix: str, moor_mod: int) -> dict:
    """RAFT's OC4 design with moorlife's hull, masses, drag, site and MS2 mooring (see the data file)."""
    d = copy.deepcopy(base)
    envc = pcfg["environment"]
    d["site"].update(
        water_depth=float(envc["water_depth"]),
        rho_water=float(envc["rho_water"]),
        rho_air=float(envc["rho_air"]),
        g=float(envc["gravity"]),
    )
    p = d["platform"]
    p["members"] = raft_members(pcfg)
    p["hydroPath"] = hydro_prefix
    p["potFirstOrder"] = 1
    p["potSecOrder"] = 2
    p["dlsMax"] = float(cfg["simulation"]["drag_strip_length"])
    p["additional_effects"] = [point_inertia(pcfg["platform"]), point_inertia(pcfg["tower"])]
    t = d["turbine"]
    rna = pcfg["rna"]
    t.update(
        mRNA=float(rna["mass"]),
        IxRNA=float(rna["inertia_cm"][0]),
        IrRNA=float(rna["inertia_cm"][1]),
        xCG_RNA=float(rna["cm"][0]),
    )
    t["tower"]["rho_shell"] = 0.0  # the tower's mass is its point inertia
    d["mooring"] = raft_mooring(cfg, row, moor_mod)
    return d


def raft_case(state: dict, gamma: float, iref: float | None) -> list:
    """One row of RAFT's ``cases`` table (turbulence 0 = steady wind)."""
    return [
        state["wind_speed"],
        heading_deg(state["wind_dir"]),
        0.0 if iref is None else iref,
        "operating",
        0.0,
        "JONSWAP",
        state["tp"],
        state["hs"],
        heading_deg(state["wave_dir"]),
        0.0,
        float(gamma),
    ]


@contextlib.contextmanager
def raft_quiet():
    """RAFT prints progress with print(); keep the benchmark's output readable."""
    with contextlib.redirect_stdout(io.StringIO()), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        yield


def raft_model(design: dict):
    """A RAFT model trimmed like moorlife's: even keel at the design draft with the lines at rest."""
    import raft

    with raft_quiet():
        probe = raft.Model(copy.deepcopy(design))
        fowt = probe.fowtList[0]
        fowt.setPosition(np.zeros(fowt.nDOF))  # solves the lines at rest, sets F_moor0
        fowt.calcStatics()
        net = fowt.W_struc[:6] + fowt.W_hydro[:6] + fowt.F_moor0[:6]
        trim = np.zeros(6)
        trim[[2, 3, 4]] = -net[[2, 3, 4]]
        design = copy.deepcopy(design)
        design["platform"]["additional_effects"].append(
            {"type": "mean_load", "location": [0.0, 0.0, 0.0], "load": trim.tolist()}
        )
        del probe, fowt
        gc.collect()
        model = raft.Model(design)
        model.analyzeUnloaded()
    return model, net


def raft_run(model, cases: list[list]) -> tuple[float, list[dict]]:
    """CPU s of one ``analyzeCases`` over ``cases``; per case the fairlead tension mean/std and thrust."""
    model.design["cases"]["data"] = cases
    with raft_quiet():
        t0 = time.process_time()
        model.analyzeCases()
        cpu = time.process_time() - t0
    n = len(model.fowtList[0].ms.lineList)
    out = []
    for i in range(len(cases)):
        r = model.results["case_metrics"][i][0]
        out.append({"mean": np.asarray(r["Tmoor_avg"][n:]), "std": np.asarray(r["Tmoor_std"][n:])})
    rotor = model.fowtList[0].rotorList[0]
    out[-1]["thrust"] = float(np.linalg.norm(rotor.f0[:3]))  # of the last case analysed
    out[-1]["offset"] = np.asarray(model.results["case_metrics"][len(cases) - 1][0]["surge_avg"], dtype=float).ravel()
    return cpu, out


# --------------------------------------------------------------------------------- moorlife side
def ours_models(cfg: dict, pcfg: dict, row: dict, wamit: str) -> dict[str, sim.ModelInputs]:
    """The simulator's inputs for dynamic and quasi-static lines, prepared as the simulate rule does."""
    ds = read_wamit_dataset(
        wamit,
        rho=float(pcfg["environment"]["rho_water"]),
        g=float(pcfg["environment"]["gravity"]),
        water_depth=float(pcfg["environment"]["water_depth"]),
    )
    return {
        kind: sim.prepare_model(ds, pcfg, row, {**cfg["mooring"], "model": kind}, cfg["simulation"])
        for kind in ("dynamic", "quasistatic")
    }


def ours_run(model, cfg: dict, state: dict, iref: float | None, record: float, transient: float, seed: int):
    """CPU s of ``simulate_batch`` for one sea state and its statistics (``iref`` None: steady wind)."""
    u = state["wind_speed"]
    wind = dict(cfg["simulation"]["wind"])
    if iref is None:
        wind["spectrum"] = "none"
    else:
        wind.update(spectrum="kaimal", turbulence_intensity=wind_sigma(u, iref) / u)
    sim_cfg = {**cfg["simulation"], "duration": record, "transient": transient, "wind": wind}
    cases = {k: np.array([state[k]]) for k in KEYS}
    t0 = time.process_time()
    out = sim.simulate_batch(
        cases,
        case_ids=np.arange(1),
        mooring_system="MS2",
        seed=seed,
        model_inputs=model,
        sim_cfg=sim_cfg,
        fatigue_cfg=cfg["fatigue"],
        stats_cfg=cfg["statistics"],
    )
    return time.process_time() - t0, out


def warm_up(model, cfg: dict) -> None:
    """Compile the Numba kernels once (excluded from every timing, as in bench_simulate.py)."""
    state = dict(zip(KEYS, (2.0, 8.0, 270.0, 8.0, 270.0), strict=True))
    ours_run(model, cfg, state, 0.14, 300.0, 0.0, 1)


def versions() -> str:
    names = ("numpy", "scipy", "numba", "openraft", "moorpy", "wisdem", "openmdao", "pyhams")
    v = ", ".join(f"{n} {metadata.version(n)}" for n in names)
    return f"python {pyplatform.python_version()}, {v}, machine {pyplatform.machine()}"


def raft_wamit(prefix: str, tmp: str, headings: list[float]) -> str:
    """The WAMIT files for RAFT in ``tmp``: ``.1`` and ``.3`` linked, ``.12d`` rewritten.

    RAFT reads ``.12d`` with ``numpy.loadtxt`` (no text header) and, with a single QTF heading,
    applies that heading's QTF in the global frame whatever the waves' heading. moorlife rotates
    the horizontal drift of a single-heading file with the waves (``io.wamit._drift_on_grid``);
    RAFT gets the same approximation as data: the QTF rows at each RAFT wave heading, surge and
    sway rotated, the other DOFs as in the file. A file with several headings is passed as is.
    """
    src = Path(prefix)
    dst = Path(tmp) / src.name
    for ext in (".1", ".3"):
        os.symlink(src.with_name(src.name + ext).resolve(), dst.with_name(dst.name + ext))
    text = src.with_name(src.name + ".12d").read_text().splitlines()
    data = np.array([[float(v) for v in ln.split()] for ln in text if ln.strip() and not ln.lstrip()[0].isalpha()])
    heads = np.unique(data[:, 2])
    if heads.size == 1 and np.all(data[:, 2] == data[:, 3]):
        order = np.lexsort((data[:, 4], data[:, 1], data[:, 0]))
        per_pair = data[order].reshape(-1, 6, 9)  # (frequency pair, dof 1..6, column)
        if not np.all(per_pair[:, :, 4] == np.arange(1, 7)):
            raise ValueError(f"{src}.12d: expected the 6 DOFs for every frequency pair")
        q = per_pair[:, :, 7] + 1j * per_pair[:, :, 8]
        blocks = []
        for h in sorted(set(headings)):
            rot = np.deg2rad(h - heads[0])
            qr = q.copy()
            qr[:, 0] = q[:, 0] * np.cos(rot) - q[:, 1] * np.sin(rot)
            qr[:, 1] = q[:, 0] * np.sin(rot) + q[:, 1] * np.cos(rot)
            b = per_pair.copy()
            b[:, :, 2] = b[:, :, 3] = h
            b[:, :, 5], b[:, :, 6] = np.abs(qr), np.degrees(np.angle(qr))
            b[:, :, 7], b[:, :, 8] = qr.real, qr.imag
            blocks.append(b.reshape(-1, 9))
        data = np.concatenate(blocks)
    np.savetxt(dst.with_name(dst.name + ".12d"), data, fmt="%.9E")
    return str(dst)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument(
        "--wamit",
        default=str(SHARED_WAMIT),
        help="WAMIT prefix (.1 .3 .hst .12d), read by both sides (default: the OC4 files in ../shared)",
    )
    ap.add_argument("--record", type=float, default=3600.0, help="moorlife: kept record per sea state, s")
    ap.add_argument("--transient", type=float, default=None, help="moorlife: transient, s (default: config)")
    ap.add_argument(
        "--wind",
        choices=("steady", "kaimal"),
        default="steady",
        help="steady: both sides without turbulence (openraft 2.0.4 does not apply the rotor's turbulent "
        "excitation); kaimal: IEC NTM turbulence on both inputs",
    )
    ap.add_argument("--iref", type=float, default=0.14, help="--wind kaimal: IEC reference turbulence intensity")
    ap.add_argument("--rows", type=int, nargs="+", default=[6, 16, 30, 35], choices=sorted(TABLE6))
    ap.add_argument("--no-sensitivity", action="store_true", help="without config lifecycle.sensitivity.sea_state")
    ap.add_argument("--seed", type=int, default=None, help="moorlife's random phases (default: config seed)")
    ap.add_argument(
        "--moormod1",
        action="store_true",
        help="also RAFT's dynamic line tensions (moorMod 1; unfinished after about 40 CPU-s on one state here)",
    )
    args = ap.parse_args()
    iref = None if args.wind == "steady" else args.iref
    missing = [e for e in (".1", ".3", ".hst", ".12d") if not Path(args.wamit + e).exists()]
    if missing:
        print(f"bench_raft: skipped, no WAMIT files {args.wamit}{{{','.join(missing)}}}; pass --wamit PREFIX")
        return

    cfg = read_study_config(ROOT / "config/config.yaml", [], schema=ROOT / "workflow/schemas/config.schema.yaml")
    pcfg = read_platform_config(ROOT / "config/platform.yaml")
    table = read_mooring_systems(ROOT / "config/mooring_systems.tsv")
    row = {k: (v.item() if hasattr(v, "item") else v) for k, v in table.loc["MS2"].items()}
    row["mooring_system"] = "MS2"
    transient = float(cfg["simulation"]["transient"] if args.transient is None else args.transient)
    seed = int(cfg["seed"] if args.seed is None else args.seed)
    states = sea_states(cfg, args.rows, not args.no_sensitivity)
    gammas = [float(env.resolve_gamma(cfg["simulation"]["gamma"], s["hs"], s["tp"])) for _, s in states]
    mods = (0, 1) if args.moormod1 else (0,)

    print(versions())
    wind = "steady (no turbulence on either side)" if iref is None else f"Kaimal, IEC NTM I_ref {iref}"
    print(
        f"MS2 lines, WAMIT {Path(args.wamit).name}; moorlife record {transient:.0f} s transient + "
        f"{args.record:.0f} s, dt {cfg['simulation']['dt']} s, seed {seed}; wind {wind}"
    )
    print("CPU seconds (time.process_time), one process; set-up (file reading, model building, JIT) apart", flush=True)

    t0 = time.process_time()
    ours = ours_models(cfg, pcfg, row, args.wamit)
    setup_ours = time.process_time() - t0
    t0 = time.process_time()
    for m in ours.values():
        warm_up(m, cfg)
    jit = time.process_time() - t0

    base = yaml.safe_load(DESIGN.read_text())
    with tempfile.TemporaryDirectory() as tmp:
        prefix = raft_wamit(args.wamit, tmp, [heading_deg(s["wave_dir"]) for _, s in states])
        cwd = os.getcwd()
        os.chdir(tmp)  # RAFT may write files beside itself
        try:
            raft_models, setup_raft = {}, {}
            for mod in mods:
                t0 = time.process_time()
                raft_models[mod], net = raft_model(raft_design(base, cfg, pcfg, row, prefix, mod))
                setup_raft[mod] = time.process_time() - t0
            with raft_quiet():
                t0 = time.process_time()
                raft_models[0].fowtList[0].readHydro()
                reread = time.process_time() - t0
            print(
                f"set-up: moorlife WAMIT read + 2 models {setup_ours:.1f} CPU-s, JIT warm-up {jit:.1f} CPU-s; "
                + ", ".join(f"RAFT moorMod {k} model {v:.1f} CPU-s" for k, v in setup_raft.items())
            )
            print(
                f"RAFT trim (its net static load at rest, removed as moorlife does): heave {net[2] / 1e3:.0f} kN, "
                f"roll {net[3] / 1e3:.0f} kN m, pitch {net[4] / 1e3:.0f} kN m",
                flush=True,
            )
            rows, failed = [], {}
            for (label, s), g in zip(states, gammas, strict=True):
                m_dyn = ours["dynamic"]
                r = {"label": label, "state": s, "gamma": g}
                r["ours_thrust"] = float(np.interp(s["wind_speed"], m_dyn.thrust_speed, m_dyn.thrust_force))
                for kind, m in ours.items():
                    r[kind] = ours_run(m, cfg, s, iref, args.record, transient, seed)
                for mod, m in list(raft_models.items()):
                    try:
                        r[f"raft{mod}"] = raft_run(m, [raft_case(s, g, iref)])
                    except Exception as exc:  # print RAFT's own error rather than stop the comparison
                        failed[mod] = f"{label}: {type(exc).__name__}: {exc}"
                        del raft_models[mod]
                rows.append(r)
                progress(r)
        finally:
            os.chdir(cwd)
    for mod, err in failed.items():
        print(f"RAFT moorMod {mod} failed ({err}); left out of the tables")
    report(rows, tuple(m for m in mods if m not in failed), args.record + transient, reread)


def progress(r: dict) -> None:
    """One line per finished sea state (CPU-s, fairlead tension std in kN), before the tables."""
    keys = [k for k in ("dynamic", "quasistatic", "raft0", "raft1") if k in r]
    cost = ", ".join(f"{k} {r[k][0]:.2f}" for k in keys)
    std = "; ".join(f"{k} " + " ".join(f"{tension(r, k, i)[1]:.1f}" for i in range(3)) for k in keys)
    print(f"done {r['label']}: CPU-s {cost}; tension std M1 M2 M3 {std}", flush=True)


def report(rows: list[dict], mods: tuple, simulated: float, reread: float) -> None:
    n = len(rows)
    print()
    print("sea states (nautical 'from' directions; JONSWAP gamma from config simulation.gamma, both sides):")
    for r in rows:
        s = r["state"]
        mis = float(conventions.circular_difference(s["wave_dir"], s["wind_dir"]))
        print(
            f"  {r['label']:<6s} Hs {s['hs']:4.2f} m  Tp {s['tp']:5.2f} s  waves from {s['wave_dir']:6.2f}  "
            f"W {s['wind_speed']:5.2f} m/s from {s['wind_dir']:6.2f}  misaligned {mis:5.1f} deg  gamma {r['gamma']:.2f}"
        )
    print()
    print(f"cost per sea state, CPU-s (moorlife: {simulated:.0f} s simulated, as the study runs a state;")
    print("RAFT: one analyzeCases call per state; m0/m1 = moorMod 0 quasi-static / 1 dynamic line tensions)")
    head = f"  {'state':<6s} {'ours dyn':>9s} {'ours qs':>8s}" + "".join(f" {'RAFT m' + str(m):>8s}" for m in mods)
    head += "".join(f" {'m' + str(m) + '/ours dyn':>13s}" for m in mods)
    print(head)
    tot = {k: sum(r[k][0] for r in rows) for k in ("dynamic", "quasistatic", *(f"raft{m}" for m in mods))}
    for r in rows:
        line = f"  {r['label']:<6s} {r['dynamic'][0]:9.2f} {r['quasistatic'][0]:8.2f}"
        line += "".join(f" {r[f'raft{m}'][0]:8.2f}" for m in mods)
        line += "".join(f" {r[f'raft{m}'][0] / r['dynamic'][0]:12.1f}x" for m in mods)
        print(line)
    line = f"  {'mean':<6s} {tot['dynamic'] / n:9.2f} {tot['quasistatic'] / n:8.2f}"
    line += "".join(f" {tot[f'raft{m}'] / n:8.2f}" for m in mods)
    line += "".join(f" {tot[f'raft{m}'] / tot['dynamic']:12.1f}x" for m in mods)
    print(line)
    no_read = (tot["raft0"] / n - reread) / (tot["dynamic"] / n)
    print(
        f"  each RAFT call re-reads the WAMIT files (calcBEM -> readHydro, {reread:.2f} CPU-s); "
        f"without it RAFT m0 / ours dyn = {no_read:.1f}x"
    )
    per_h = 3600.0 / simulated
    print(
        f"  moorlife per simulated hour: dynamic {tot['dynamic'] / n * per_h:.2f}, "
        f"quasi-static {tot['quasistatic'] / n * per_h:.2f} CPU-s/h"
    )
    print()
    print("fairlead tension, kN, mean / standard deviation (M1 bearing 30 deg, M2 270 deg (west), M3 150 deg)")
    cols = [("ours dyn", "dynamic"), ("ours qs", "quasistatic")] + [(f"RAFT m{m}", f"raft{m}") for m in mods]
    for r in rows:
        print(
            f"  {r['label']}: mean thrust ours (Ct table) {r['ours_thrust'] / 1e3:.0f} kN, "
            f"RAFT (CCBlade) {r['raft0'][1][0]['thrust'] / 1e3:.0f} kN; mean surge ours "
            f"{float(r['dynamic'][1]['surge_mean'][0]):.2f} m, RAFT {r['raft0'][1][0]['offset'][0]:.2f} m"
        )
        for i in range(3):
            parts = [f"{name} {tension(r, key, i)[0]:5.0f} / {tension(r, key, i)[1]:5.1f}" for name, key in cols]
            ref = tension(r, "dynamic", i)[1]
            parts += [f"m{m} {100 * (tension(r, f'raft{m}', i)[1] / ref - 1):+4.0f} %" for m in mods]
            print(
                f"    M{i + 1}  "
                + "   ".join(parts[: len(cols)])
                + "   std vs ours dyn: "
                + ", ".join(parts[len(cols) :])
            )
    print()
    print(
        "RAFT is linear: drag linearised, lines linearised about the mean offset (m0 quasi-static; m1 MoorPy\n"
        "lumped-mass lines in the frequency domain, wave-driven motion only), slow drift as the linear response\n"
        "to the QTF's force spectrum, rotor by CCBlade derivatives at fixed pitch and speed (openraft 2.0.4 applies\n"
        "no turbulent rotor excitation). moorlife is nonlinear in time (Morison drag on the relative velocity,\n"
        "thrust of the relative wind, Newman slow drift, lumped-mass lines with seabed contact and friction), one\n"
        "random realisation per state. RAFT anchors cost; it is not a reference for accuracy."
    )


def tension(r: dict, key: str, i: int) -> tuple[float, float]:
    """Fairlead tension mean and std of line ``i``, kN."""
    if key.startswith("raft"):
        res = r[key][1][0]
        return res["mean"][i] / 1e3, res["std"][i] / 1e3
    out = r[key][1]
    return float(out["tension_mean"][0, i]) / 1e3, float(out["tension_std"][0, i]) / 1e3


if __name__ == "__main__":
    sys.exit(main())
