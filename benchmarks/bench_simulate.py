"""CPU seconds per simulated hour of the coupled simulator, against MoorDyn's mooring alone.

Runs, in one process on the same machine:

* ``moorlife.simulate.simulate_batch`` (waves + NPD wind + drag + thrust + mooring + statistics
  and fatigue) with quasi-static and with dynamic (lumped-mass, 20 segments) lines, for one sea
  state and for a batch of 8;
* MoorDyn 2 (the peer, C++ via its Python wrapper) for the same three MS2 lines (20 segments,
  its OC4 r-test step dtM = 1 ms) under a prescribed fairlead motion (5 m surge at 100 s plus
  1 m at 10 s): the cost of the mooring alone, without any platform.

The platform is the BEM model of ``--wamit PREFIX`` or ``results/hydro/platform.nc`` when it
exists, else an OC4-sized synthetic stand-in with the same number of Morison strips. Usage::

    .venv/bin/python benchmarks/bench_simulate.py [--record 600] [--moordyn-seconds 60] [--repeat 3] [--wamit PREFIX]
    .venv/bin/python benchmarks/bench_simulate.py --starts [--repeat 3] [--wamit PREFIX]   # issue 23, target 2
"""

from __future__ import annotations

import argparse
import math
import os
import tempfile
import time
from pathlib import Path

import numpy as np

from moorlife import simulate as sim
from moorlife.io import read_mooring_systems
from moorlife.io.platform import read_platform_config
from moorlife.simulate import integration

ROOT = Path(__file__).resolve().parents[1]


def synthetic_platform(platform_cfg: dict) -> sim.ModelInputs:
    """OC4-sized stand-in: diagonal mass/stiffness, 6x4 radiation states, smooth excitation."""
    om = np.linspace(0.05, 2.5, 100)
    hd = np.deg2rad(np.arange(-180.0, 180.0, 10.0))
    amp = 2.0e6 * np.exp(-(((om - 0.6) / 0.5) ** 2))
    exc = np.zeros((om.size, hd.size, 6), dtype=complex)
    exc[:, :, 0] = amp[:, None] * np.cos(hd)
    exc[:, :, 1] = amp[:, None] * np.sin(hd)
    exc[:, :, 2] = 1.5 * amp[:, None]
    exc[:, :, 4] = 10.0 * amp[:, None] * np.cos(hd)
    drift = np.zeros((om.size, hd.size, 6))
    drift[:, :, 0] = 2.0e4 * om[:, None] ** 2 * np.cos(hd)
    nr = 24
    ra = np.diag(-np.linspace(0.3, 2.0, nr))
    rb = np.zeros((nr, 6))
    rc = np.zeros((6, nr))
    for r in range(nr):
        rb[r, r % 6] = 1e5
        rc[r % 6, r] = 1.0
    strips = sim._strips_from_members(platform_cfg["members"], 4.0, 1025.0)
    v = np.arange(-40.0, 80.0, 0.02)
    return sim.build_model(
        mass=np.diag([2.0e7, 2.0e7, 2.8e7, 1.4e10, 1.4e10, 1.8e10]),
        stiffness=np.diag([0, 0, 3.8e6, 1e9, 1e9, 0.0]),
        rad_a=ra,
        rad_b=rb,
        rad_c=rc,
        omega=om,
        headings=hd,
        excitation=exc,
        drift=drift,
        strip_pos=strips[0],
        strip_axis=strips[1],
        strip_cdn=strips[2],
        strip_cda=strips[3],
        hub=np.array([0.0, 0.0, 90.0]),
        thrust_speed=v,
        thrust_force=0.5 * 1.225 * math.pi * 63**2 * 0.8 * v * np.abs(v) * (np.abs(v) < 25),
    )


def platform_model(platform_cfg: dict, row: dict, kind: str, wamit: str | None = None) -> tuple[sim.ModelInputs, str]:
    nc = ROOT / "results/hydro/platform.nc"
    if wamit:
        from moorlife import hydro
        from moorlife.io.wamit import read_wamit_dataset

        pm = hydro.load_platform_model(read_wamit_dataset(wamit), platform_cfg)
        return sim.attach_mooring(
            sim.platform_from(pm, platform_cfg, {}), row, {"model": kind}
        ), f"WAMIT {Path(wamit).name}"
    try:
        from moorlife.io.platform import open_platform_nc

        if nc.exists():
            m = sim.prepare_model(open_platform_nc(nc), platform_cfg, row, {"model": kind}, {})
            return m, f"BEM model {nc.relative_to(ROOT)}"
    except ImportError:
        pass
    return sim.attach_mooring(synthetic_platform(platform_cfg), row, {"model": kind}), "synthetic OC4-sized stand-in"


def time_ours(model: sim.ModelInputs, batch: int, record: float, repeat: int = 1) -> float:
    """CPU s per simulated hour per sea state, the best of ``repeat`` timings."""
    cases = {
        "wind_speed": np.linspace(10.0, 14.0, batch),
        "wind_dir": np.full(batch, 328.09),
        "hs": np.linspace(3.0, 3.7, batch),
        "tp": np.full(batch, 9.21),
        "wave_dir": np.full(batch, 316.09),
    }
    cfg = {"duration": record, "transient": 0.0, "dt": 0.1}
    return _best_cpu(model, cases, cfg, repeat) * 3600.0 / record / batch


def _best_cpu(model: sim.ModelInputs, cases: dict, cfg: dict, repeat: int) -> float:
    """The best of ``repeat`` CPU timings of ``simulate_batch`` on ``cases`` (after a JIT warm-up)."""
    kw = dict(mooring_system="MS2", seed=1, model_inputs=model, fatigue_cfg={}, stats_cfg={"block": 20.0})
    warm = {k: v[:1] for k, v in cases.items()}
    sim.simulate_batch(warm, case_ids=np.arange(1), sim_cfg={**cfg, "duration": 120.0}, **kw)
    batch = len(cases["hs"])
    best = math.inf
    for _ in range(repeat):
        t0 = time.process_time()
        sim.simulate_batch(cases, case_ids=np.arange(batch), sim_cfg=cfg, **kw)
        best = min(best, time.process_time() - t0)
    return best


def time_starts(model: sim.ModelInputs, batch: int, repeat: int = 1) -> dict[str, float]:
    """CPU s per sea state of ``simulate_batch`` (forcing, start, 3,600 s kept, statistics) for the
    starts of issue 23's target 2: at rest with 600 s of transient (the default), at the mean
    equilibrium with 600 s, at the linear periodic steady state with 200 s and 100 s."""
    cases = {
        "wind_speed": np.linspace(6.0, 20.0, batch),
        "wind_dir": np.full(batch, 328.09),
        "hs": np.linspace(1.5, 5.0, batch),
        "tp": np.linspace(7.0, 12.0, batch),
        "wave_dir": np.full(batch, 316.09),
    }
    starts = {"rest 600 s": ("rest", 600.0), "equilibrium 600 s": ("equilibrium", 600.0)}
    starts |= {"steady 200 s": ("steady", 200.0), "steady 100 s": ("steady", 100.0)}
    out = {}
    for name, (start, transient) in starts.items():
        cfg = {"duration": 3600.0, "transient": transient, "dt": 0.1, "start": start}
        out[name] = _best_cpu(model, cases, cfg, repeat) / batch
    return out


MOORDYN_DECK = """--------------------- MoorDyn Input File ------------------------------------
moorlife benchmark: OC4 layout, {name} chain
----------------------- LINE TYPES ------------------------------------------
Name     Diam      MassDen      EA    BA/-zeta  EI    Cd   Ca   CdAx  CaAx
(-)       (m)      (kg/m)       (N)   (N-s/-)    ()   (-)  (-)   (-)  (-)
main     {d:.4f}    {m:.3f}     {ea:.4e}  -1.0      0    2.0  0.8   0.4  0.25
---------------------- POINTS --------------------------------
Node Type       X        Y        Z          M      V    FX   FY   FZ  CdA   CA
(-)  (-)       (m)      (m)      (m)       (kg)   (m^3) (kN) (kN) (kN) (m^2) (-)
1      Fixed   418.8    725.383  -200.0     0      0      0    0    0    0     0
2      Fixed  -837.6      0.0    -200.0     0      0      0    0    0    0     0
3      Fixed   418.8   -725.383  -200.0     0      0      0    0    0    0     0
4      Coupled   20.434   35.393   -14.0     0      0      0    0    0    0     0
5      Coupled  -40.868    0.0     -14.0     0      0      0    0    0    0     0
6      Coupled   20.434  -35.393   -14.0     0      0      0    0    0    0     0
---------------------- LINES --------------------------------------
Line   LineType    AttachA    AttachB  UnstrLen  NumSegs   Outputs
(-)       (-)       (-)       (-)         (m)      (-)         (-)
1         main      1         4       835.5      20              -
2         main      2         5       835.5      20              -
3         main      3         6       835.5      20              -
---------------------- OPTIONS ---------------------------------------
0.001    dtM       - time step to use in mooring integration (s)
3.0e6    kbot      - bottom stiffness (Pa/m)
3.0e5    cbot      - bottom damping (Pa-s/m)
200      WtrDpth   - water depth (m)
1025     WtrDnsty  - water density (kg/m^3)
60.0     TmaxIC    - max time for ic gen (s)
4.0      CdScaleIC - factor by which to scale drag coefficients during dynamic relaxation (-)
0.01     threshIC  - threshold for IC convergence (-)
------------------------ OUTPUTS --------------------------------------------
END
------------------------- need this line --------------------------------------
"""


def time_moordyn(row: dict, seconds: float, dt: float = 0.1) -> float:
    """MoorDyn CPU s per simulated hour for the three lines under prescribed fairlead motion."""
    import moordyn

    deck = MOORDYN_DECK.format(
        name=row["mooring_system"], d=row["equivalent_diameter_m"], m=row["mass_kg_per_m"], ea=row["EA_N"]
    )
    fair = np.array([[20.434, 35.393, -14.0], [-40.868, 0.0, -14.0], [20.434, -35.393, -14.0]])
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "lines.dat")
        Path(path).write_text(deck)
        cwd = os.getcwd()
        os.chdir(tmp)  # MoorDyn writes its outputs beside the deck
        saved = os.dup(1)
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, 1)  # MoorDyn's C++ progress printing goes to stdout
        try:
            system = moordyn.Create(path)
            moordyn.SetVerbosity(system, moordyn.LEVEL_ERR)
            moordyn.Init(system, fair.ravel().tolist(), [0.0] * 9)
            n = int(round(seconds / dt))
            t0 = time.process_time()
            for k in range(n):
                t = k * dt
                sx = 5.0 * math.sin(2 * math.pi * t / 100.0) + 1.0 * math.sin(2 * math.pi * t / 10.0)
                vx = 5.0 * 2 * math.pi / 100.0 * math.cos(
                    2 * math.pi * t / 100.0
                ) + 1.0 * 2 * math.pi / 10.0 * math.cos(2 * math.pi * t / 10.0)
                x = (fair + np.array([sx, 0.0, 0.0])).ravel().tolist()
                moordyn.Step(system, x, [vx, 0.0, 0.0] * 3, t, dt)
            cpu = time.process_time() - t0
            moordyn.Close(system)
        finally:
            os.dup2(saved, 1)
            os.close(devnull)
            os.close(saved)
            os.chdir(cwd)
    return cpu * 3600.0 / seconds


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--record", type=float, default=600.0, help="simulated seconds per timing (scaled to 1 h)")
    ap.add_argument("--moordyn-seconds", type=float, default=60.0, help="simulated seconds of MoorDyn")
    ap.add_argument("--batch", type=int, default=8)
    ap.add_argument("--repeat", type=int, default=3, help="timings of ours per figure; the best is printed")
    ap.add_argument("--wamit", default=None, help="WAMIT prefix for the platform (else results/hydro/platform.nc)")
    ap.add_argument("--starts", action="store_true", help="only the cost per sea state of each start (target 2)")
    args = ap.parse_args()
    platform_cfg = read_platform_config(ROOT / "config/platform.yaml")
    table = read_mooring_systems(ROOT / "config/mooring_systems.tsv")
    row = {k: (v.item() if hasattr(v, "item") else v) for k, v in table.loc["MS2"].items()}
    row["mooring_system"] = "MS2"
    print(
        f"record {args.record:.0f} s per timing, best of {args.repeat}, dt 0.1 s, MS2 lines, "
        "CPU s per simulated hour per sea state"
    )
    if args.starts:
        model, source = platform_model(platform_cfg, row, "dynamic", args.wamit)
        cost = time_starts(model, args.batch, args.repeat)
        print(f"CPU s per sea state, batch {args.batch}, 3,600 s kept, dynamic lines ({source}):")
        for name, c in cost.items():
            print(f"  {name:<18s} {c:6.3f}   ratio to rest 600 s: {c / cost['rest 600 s']:.3f}")
        return
    ours = {}
    for kind in ("quasistatic", "dynamic"):
        model, source = platform_model(platform_cfg, row, kind, args.wamit)
        for b in (1, args.batch):
            ours[kind, b] = time_ours(model, b, args.record, args.repeat)
            print(f"moorlife {kind:<12s} batch {b:2d}: {ours[kind, b]:7.3f} CPU-s/h   ({source})")
    # the lines of a batch stepped together (mooring.lanes, the default) against the one-line
    # reference step, in the same process on the same states (the same bits: tests/test_mooring_lanes.py)
    integration.LANES = False
    ref = time_ours(model, args.batch, args.record, args.repeat)
    integration.LANES = True
    print(
        f"moorlife dynamic, one line at a time (reference step), batch {args.batch:2d}: {ref:7.3f} CPU-s/h; "
        f"lanes / reference {ours['dynamic', args.batch] / ref:.3f}"
    )
    md = time_moordyn(row, args.moordyn_seconds)
    print(f"MoorDyn 2 mooring alone (3 lines x 20 segments, dtM 1 ms): {md:7.2f} CPU-s/h")
    for b in (1, args.batch):
        print(f"ratio MoorDyn mooring-alone / moorlife coupled dynamic, batch {b}: {md / ours['dynamic', b]:6.1f}x")


if __name__ == "__main__":
    main()
