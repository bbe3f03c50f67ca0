"""Verification of the coupled simulator on the OC4 DeepCwind model (issue 7, point 4).

1. Decay tests: surge, heave and pitch natural periods with the OC4 (MS2) catenary lines,
   against the OC4 Phase II code comparison (Robertson et al. 2014): 107.5 s, 17.3 s, 26.8 s,
   with the radiation memory and without it (constant A_inf, the convention of those figures);
   then (1c) on the OC4 line itself, against the initial offset and its direction.
2. Small-amplitude regular waves: time-domain amplitude and phase against the frequency-domain
   RAO computed from the same BEM coefficients (A(w), B(w), X(w)), linear OC4 mooring.
3. Steady 11.4 m/s wind, no waves: mean offset and tensions against the static balance of
   thrust and catenary restoring, quasi-static and dynamic lines.
4. MS1-MS6 under the paper's sensitivity sea state (Hs 3.35 m, Tp 9.21 s, alpha 316.09 deg,
   W 12.10 m/s, beta 328.09 deg): offsets must fall and tensions rise from MS1 to MS6.

Usage (writes the tables to stdout as Markdown)::

    .venv/bin/python validation/simulate_verification.py --platform results/hydro/platform.nc
    .venv/bin/python validation/simulate_verification.py --wamit path/to/marin_semi   # WAMIT files
    .venv/bin/python validation/simulate_verification.py --sections 1 --platform other.nc  # decays only
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import time
from pathlib import Path

import numpy as np

from moorlife import environment as env
from moorlife import hydro
from moorlife import simulate as sim
from moorlife.io import read_mooring_systems
from moorlife.io.platform import open_platform_nc, read_platform_config

ROOT = Path(__file__).resolve().parents[1]
OC4_PERIODS = {"surge": 107.5, "heave": 17.3, "pitch": 26.8}  # s, Robertson et al. 2014 (platform.yaml)
DOF = {"surge": 0, "heave": 2, "pitch": 4}


def rows() -> dict[str, dict]:
    table = read_mooring_systems(ROOT / "config/mooring_systems.tsv")
    return {
        ms: {**{k: (v.item() if hasattr(v, "item") else v) for k, v in r.items()}, "mooring_system": ms}
        for ms, r in table.iterrows()
    }


def quiet(model: sim.ModelInputs, grid: env.RecordGrid, wind: float = 0.0, wind_dir: float = 270.0) -> sim.Forcing:
    n1 = grid.n_steps + 1
    th = math.radians(270.0 - wind_dir)
    return sim.Forcing(
        grid=grid,
        force=np.zeros((1, n1, 6)),
        wind=np.full((1, n1), wind),
        wind_dir=np.array([[math.cos(th), math.sin(th)]]),
        kin_every=1,
        kinematics=np.zeros((1, grid.n_steps + 2, 3, model.strip_pos.shape[0]), np.float32),
    )


def period(x: np.ndarray, dt: float, cycles: int = 3) -> float:
    """Mean period of the first ``cycles`` oscillations from upward zero crossings about the mean."""
    y = x - x[len(x) // 2 :].mean()
    up = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))
    tz = up + (-y[up]) / (y[up + 1] - y[up])  # linear interpolation of the crossings
    return float(np.diff(tz[: cycles + 1]).mean() * dt)


def free_decay(
    model: sim.ModelInputs, dof: int, x0: float, duration: float, locked: tuple[int, ...] = ()
) -> tuple[np.ndarray, float]:
    """The DOF's record of a free decay from ``x0`` at rest in calm water, and its time step."""
    grid = env.record_grid(duration, 0.0, 0.1)
    q0 = np.zeros((1, 6))
    q0[0, dof] = x0
    rec = sim.integrate(model, quiet(model, grid), transient=0.0, q0=q0, locked=locked)
    return rec.motion[0, dof], grid.dt


def decay(model: sim.ModelInputs, no_drag: sim.ModelInputs) -> list[str]:
    out = [
        "| DOF | initial | uncoupled estimate (s) | coupled eigen, linear OC4 stiffness (s) | decay, MS2 catenary, no drag (s) "
        "| decay, MS2 catenary + drag (s) | OC4 (s) | error (catenary + drag) | one DOF, others held: decay (s) | error |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    lin_model = dataclasses.replace(model, mooring_kind="linear")
    lin = sim.linear_natural_periods(lin_model)
    k = lin_model.stiffness + lin_model.mooring_stiffness
    unc = [
        2
        * math.pi
        * math.sqrt(
            (
                lin_model.mass[d, d]
                - sim.radiation_impedance(lin_model, [2 * math.pi / lin[d]])[0, d, d].imag / (2 * math.pi / lin[d])
            )
            / k[d, d]
        )
        for d in range(6)
    ]
    init = {"surge": (0, 8.0, "8 m"), "heave": (2, 1.5, "1.5 m"), "pitch": (4, math.radians(2.0), "2 deg")}
    for name, (d, x0, label) in init.items():
        res = [
            period(*free_decay(m, d, x0, 8 * OC4_PERIODS[name], held))
            for m, held in ((no_drag, ()), (model, ()), (model, tuple(i for i in range(6) if i != d)))
        ]
        err, err1 = res[1] / OC4_PERIODS[name] - 1, res[2] / OC4_PERIODS[name] - 1
        out.append(
            f"| {name} | {label} | {unc[d]:.2f} | {lin[d]:.2f} | {res[0]:.2f} | {res[1]:.2f} | {OC4_PERIODS[name]} "
            f"| {100 * err:+.1f} % | {res[2]:.2f} | {100 * err1:+.1f} % |"
        )
    return out + [""] + decay_oc4_convention(model, init)


def decay_oc4_convention(model: sim.ModelInputs, init: dict) -> list[str]:
    """The same decays in the convention of the OC4 figures: constant A_inf, no radiation memory."""
    out = [
        "Without the radiation memory (constant added mass A_inf, the convention of the OC4 figures):",
        "",
        "| DOF | initial | coupled eigen, A_inf, linear OC4 stiffness (s) | one DOF: eigen (s) | one DOF: decay, "
        "MS2 catenary + drag (s) | OC4 (s) | error (one-DOF decay) | all DOFs free: decay (s) | error |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    flat = sim.without_radiation_memory(model)
    lin_model = dataclasses.replace(flat, mooring_kind="linear")
    coupled = sim.linear_natural_periods(lin_model)
    for name, (d, x0, label) in init.items():
        held = tuple(i for i in range(6) if i != d)
        one = sim.linear_natural_periods(lin_model, locked=held)[d]
        t1, tall = (period(*free_decay(flat, d, x0, 8 * OC4_PERIODS[name], h)) for h in (held, ()))
        ref = OC4_PERIODS[name]
        out.append(
            f"| {name} | {label} | {coupled[d]:.2f} | {one:.2f} | {t1:.2f} | {ref} | {100 * (t1 / ref - 1):+.1f} % "
            f"| {tall:.2f} | {100 * (tall / ref - 1):+.1f} % |"
        )
    return out


def oc4_line(row: dict) -> dict:
    """The OC4 line itself (r-test MoorDyn deck: 113.35 kg/m, D 0.0766 m, EA 7.536e8 N) on the MS2 row."""
    return {**row, "mooring_system": "OC4", "mass_kg_per_m": 113.35, "equivalent_diameter_m": 0.0766, "EA_N": 7.536e8}


def decay_amplitudes(model: sim.ModelInputs) -> list[str]:
    """Decay periods against the initial offset and direction (first cycle, mean of three)."""
    out = [
        "| DOF | initial | first cycle (s) | mean of 3 cycles (s) | OC4 (s) | error (3 cycles) |",
        "|---|---|---|---|---|---|",
    ]
    cases = [
        ("surge", 0, 2.0, "+2 m"),
        ("surge", 0, 8.0, "+8 m"),
        ("surge", 0, 22.0, "+22 m"),
        ("surge", 0, -22.0, "-22 m"),
        ("sway", 1, 22.0, "+22 m"),
        ("pitch", 4, math.radians(2.0), "2 deg"),
        ("pitch", 4, math.radians(8.0), "8 deg"),
    ]
    for name, d, x0, label in cases:
        ref = OC4_PERIODS.get(name, 113.6)  # sway: 0.0088 Hz in the code comparison
        x, dt = free_decay(model, d, x0, 8 * ref)
        p1, p3 = period(x, dt, 1), period(x, dt, 3)
        out.append(f"| {name} | {label} | {p1:.2f} | {p3:.2f} | {ref} | {100 * (p3 / ref - 1):+.1f} % |")
    return out


def regular_waves(model: sim.ModelInputs, pm: hydro.PlatformModel) -> list[str]:
    lin = dataclasses.replace(
        model,
        mooring_kind="linear",
        strip_cdn=model.strip_cdn * 0,
        strip_cda=model.strip_cda * 0,
        static_load=np.zeros(6),
    )
    out = [
        "| omega (rad/s) | DOF | TD amplitude per m | FD RAO (BEM A, B) | error | phase TD - FD (rad) |",
        "|---|---|---|---|---|---|",
    ]
    a = 0.1  # m: small amplitude
    theta = 0.0
    worst = 0.0
    for w_target in (0.3, 0.5, 0.7, 0.9, 1.2):
        grid = env.record_grid(400.0, 600.0, 0.1)
        k = int(round(w_target / grid.d_omega))
        w = k * grid.d_omega
        waves = env.WaveComponents(
            index=np.array([k]), omega=np.array([w]), amplitude=np.array([[a + 0j]]), theta=np.array([theta])
        )
        f = sim.build_forcing(
            lin, grid, waves, np.zeros((1, grid.n_steps + 1)), np.array([270.0]), kin_every=1, second_order=False
        )
        a_inf = lin.mass - np.asarray(pm.mass)
        am = np.stack(
            [np.interp([w], pm.omega, pm.added_mass[:, i, j])[0] for i in range(6) for j in range(6)]
        ).reshape(6, 6)
        bm = np.stack([np.interp([w], pm.omega, pm.damping[:, i, j])[0] for i in range(6) for j in range(6)]).reshape(
            6, 6
        )
        rao = sim.frequency_response(lin, [w], theta, added_mass=(am - a_inf)[None], radiation_damping=bm[None])[0]
        # start on the harmonic solution so that the lightly damped slow modes are not excited
        q0 = (rao * a).real[None, :]
        v0 = (-1j * w * rao * a).real[None, :]
        rec = sim.integrate(lin, f, transient=600.0, q0=q0, v0=v0)
        nt = rec.motion.shape[-1]
        t = (np.arange(nt) + grid.n_steps - nt) * grid.dt
        basis = np.stack([np.cos(w * t), np.sin(w * t)], axis=1)
        for name, d in DOF.items():
            x = rec.motion[0, d] - rec.motion[0, d].mean()
            coef, *_ = np.linalg.lstsq(basis, x, rcond=None)
            amp = math.hypot(*coef) / a
            ref = abs(rao[d])
            if ref < 1e-4 * (1 if d < 3 else 0.01):
                continue
            err = amp / ref - 1
            worst = max(worst, abs(err))
            dph = (math.atan2(coef[1], coef[0]) - np.angle(rao[d]) + math.pi) % (2 * math.pi) - math.pi
            unit = "m/m" if d < 3 else "deg/m"
            scale = 1.0 if d < 3 else 180.0 / math.pi
            out.append(
                f"| {w:.3f} | {name} | {amp * scale:.4f} {unit} | {ref * scale:.4f} {unit} | {100 * err:+.2f} % | {dph:+.3f} |"
            )
    out.append(f"\nLargest amplitude error: {100 * worst:.2f} %")
    return out


def steady_wind(models: dict[str, sim.ModelInputs]) -> list[str]:
    out = [
        "| lines | surge mean (m) | static (m) | pitch mean (deg) | static (deg) | M2 tension mean (kN) | static (kN) | M1 (kN) | static (kN) |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for kind, m in models.items():
        thrust = float(np.interp(11.4, m.thrust_speed, m.thrust_force))
        load = np.array([thrust, 0, 0, 0, thrust * m.hub[2], 0])
        q_st, t_st = sim.static_equilibrium(m, load)
        grid = env.record_grid(600.0, 600.0, 0.1)
        # start at the static position: only the line and memory start-up transients remain
        rec = sim.integrate(m, quiet(m, grid, wind=11.4, wind_dir=270.0), transient=600.0, q0=[q_st])
        mean = rec.motion[0].mean(axis=-1)
        ten = rec.tension[0].mean(axis=-1)
        out.append(
            f"| {kind} | {mean[0]:.3f} | {q_st[0]:.3f} | {math.degrees(mean[4]):.3f} | {math.degrees(q_st[4]):.3f} | "
            f"{ten[1] / 1e3:.1f} | {t_st[1] / 1e3:.1f} | {ten[0] / 1e3:.1f} | {t_st[0] / 1e3:.1f} |"
        )
    out.append(f"\nThrust at 11.4 m/s: {thrust / 1e3:.1f} kN at the hub ({m.hub[2]:.0f} m).")
    return out


def systems(platform: sim.ModelInputs, kind: str, duration: float) -> list[str]:
    case = {
        "hs": np.array([3.35]),
        "tp": np.array([9.21]),
        "wave_dir": np.array([316.09]),
        "wind_speed": np.array([12.10]),
        "wind_dir": np.array([328.09]),
    }
    out = [
        f"{kind} lines, {duration:.0f} s after a 600 s transient, seed 20190601, case 0.\n",
        "| MS | mean offset (m) | max offset (m) | surge MPM (m) | M2 tension mean (kN) | M2 tension MPM (kN) | M1 MPM (kN) | M2 damage S-N /h | M2 damage T-N /h | CPU s |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    res = {}
    for ms, row in rows().items():
        m = sim.attach_mooring(platform, row, {"model": kind})
        t0 = time.process_time()
        r = sim.simulate_batch(
            case,
            case_ids=np.array([0]),
            mooring_system="verification",
            seed=20190601,
            model_inputs=m,
            sim_cfg={"duration": duration, "transient": 600.0},
            fatigue_cfg={},
            stats_cfg={"block": 60.0},
        )
        cpu = time.process_time() - t0
        off = math.hypot(r["surge_mean"][0], r["sway_mean"][0])
        res[ms] = (off, r["tension_mean"][0, 1])
        out.append(
            f"| {ms} | {off:.2f} | {r['offset_max'][0]:.2f} | {r['surge_mpm'][0]:.2f} | {r['tension_mean'][0, 1] / 1e3:.0f} | "
            f"{r['tension_mpm'][0, 1] / 1e3:.0f} | {r['tension_mpm'][0, 0] / 1e3:.0f} | {r['damage_sn'][0, 1]:.3e} | "
            f"{r['damage_tn'][0, 1]:.3e} | {cpu:.1f} |"
        )
    offs = [v[0] for v in res.values()]
    tens = [v[1] for v in res.values()]
    ok = all(a > b for a, b in zip(offs, offs[1:])) and all(a < b for a, b in zip(tens, tens[1:]))
    out.append(f"\nOffsets fall and tensions rise monotonically from MS1 to MS6: **{ok}**")
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    src = ap.add_mutually_exclusive_group()
    src.add_argument("--platform", default=str(ROOT / "results/hydro/platform.nc"))
    src.add_argument("--wamit", help="WAMIT prefix (.1 .3 .hst [.12d]) instead of platform.nc")
    ap.add_argument("--duration", type=float, default=3600.0, help="record of the MS1-MS6 runs, s")
    ap.add_argument("--systems-model", default="dynamic", choices=["quasistatic", "dynamic"])
    ap.add_argument("--sections", default="1,1c,2,3,4", help="comma-separated sections to run (default: all)")
    args = ap.parse_args()
    run = set(args.sections.split(","))
    platform_cfg = read_platform_config(ROOT / "config/platform.yaml")
    if args.wamit:
        from moorlife.io.wamit import read_wamit_dataset

        ds, source = read_wamit_dataset(args.wamit), f"WAMIT {Path(args.wamit).name}"
    else:
        ds, source = open_platform_nc(args.platform), str(Path(args.platform).name)
    pm = hydro.load_platform_model(ds, platform_cfg)
    platform = sim.platform_from(pm, platform_cfg, {})
    ms2 = rows()["MS2"]
    qs = sim.attach_mooring(platform, ms2, {"model": "quasistatic"})
    dyn = sim.attach_mooring(platform, ms2, {"model": "dynamic"})
    no_drag = dataclasses.replace(qs, strip_cdn=qs.strip_cdn * 0, strip_cda=qs.strip_cda * 0)
    print(f"# Simulator verification ({source}, radiation by kernel convolution, dt 0.1 s)\n")
    sections = {
        "1": ("Decay tests (MS2 = OC4 line, quasi-static catenary)", lambda: decay(qs, no_drag)),
        "1c": (
            "Decays on the OC4 line (113.35 kg/m), quasi-static catenary with drag: offset and direction",
            lambda: decay_amplitudes(sim.attach_mooring(platform, oc4_line(ms2), {"model": "quasistatic"})),
        ),
        "2": (
            "Regular waves, 0.1 m amplitude, from the west (heading 0), linear OC4 mooring, no drag",
            lambda: regular_waves(qs, pm),
        ),
        "3": (
            "Steady wind 11.4 m/s from the west, no waves (MS2)",
            lambda: steady_wind({"quasistatic": qs, "dynamic": dyn}),
        ),
        "4": ("MS1-MS6, paper sensitivity sea state", lambda: systems(platform, args.systems_model, args.duration)),
    }
    unknown = run - set(sections)
    if unknown:
        ap.error(f"--sections: unknown {sorted(unknown)}, expected some of {list(sections)}")
    for key, (title, table) in sections.items():
        if key in run:
            print(f"## {key}. {title}\n")
            print("\n".join(table()) + "\n")


if __name__ == "__main__":
    main()
