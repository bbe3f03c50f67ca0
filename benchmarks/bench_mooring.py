"""Benchmark: mooring line models, moorlife vs MoorDyn (dynamic) and MoorPy (quasi-static).

Same line (a row of config/mooring_systems.tsv, default MS2), same OC4 layout, 20 segments,
same prescribed fairlead motion (surge 5 m at 100 s + 1 m at 10 s, smooth 20 s ramp), called
the way the coupled simulator calls a mooring model: one ``step`` per platform time step
from a Python loop. Cost is CPU seconds (``time.process_time``, best of ``--repeat``) per
simulated hour of one sea state (three lines); accuracy is the mean, standard deviation and
range of each fairlead tension after 100 s against MoorDyn at its OC4 deck step (1 ms).

Run:  .venv/bin/python benchmarks/bench_mooring.py [--ms MS2] [--duration 600] [--repeat 3]
"""

from __future__ import annotations

import argparse
import contextlib
import os
import tempfile
import time
from pathlib import Path

import numpy as np

from moorlife.io import read_mooring_systems
from moorlife.mooring import fairlead_positions, lines, make_mooring


def surge(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    w1, w2 = 2 * np.pi / 100.0, 2 * np.pi / 10.0
    x = 5 * np.sin(w1 * t) + np.sin(w2 * t)
    v = 5 * w1 * np.cos(w1 * t) + w2 * np.cos(w2 * t)
    tt = np.minimum(t, 20.0)
    ramp = 0.5 * (1.0 - np.cos(np.pi * tt / 20.0))
    dramp = np.where(t < 20.0, 0.5 * np.pi / 20.0 * np.sin(np.pi * tt / 20.0), 0.0)
    return x * ramp, v * ramp + x * dramp


@contextlib.contextmanager
def quiet():
    """Silence C-level stdout (MoorDyn prints every step)."""
    fd = os.dup(1)
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
        try:
            yield
        finally:
            os.dup2(fd, 1)
            os.close(fd)


def moordyn_deck(path: Path, props, layout, settings, dtm: float) -> Path:
    rows = [
        "--------------------- MoorDyn Input File ---------------------",
        "moorlife benchmark deck",
        "----------------------- LINE TYPES ---------------------------",
        "Name Diam MassDen EA BA/-zeta EI Cd Ca CdAx CaAx",
        "(-) (m) (kg/m) (N) (N-s/-) () (-) (-) (-) (-)",
        f"main {props.equivalent_diameter} {props.mass} {props.EA} -{settings.internal_damping_ratio} 0 "
        f"{settings.cd_normal} {settings.ca_normal} {settings.cd_axial} {settings.ca_axial}",
        "---------------------- POINTS --------------------------------",
        "Node Type X Y Z M V CdA CA",
        "(-) (-) (m) (m) (m) (kg) (m^3) (m^2) (-)",
    ]
    rows += [f"{k + 1} Fixed {a[0]:.9f} {a[1]:.9f} {a[2]:.9f} 0 0 0 0" for k, a in enumerate(layout.anchors)]
    rows += [f"{k + 4} Coupled {f[0]:.9f} {f[1]:.9f} {f[2]:.9f} 0 0 0 0" for k, f in enumerate(layout.fairleads_body)]
    rows += [
        "---------------------- LINES ---------------------------------",
        "Line LineType AttachA AttachB UnstrLen NumSegs Outputs",
        "(-) (-) (-) (-) (m) (-) (-)",
    ]
    rows += [f"{k + 1} main {k + 1} {k + 4} {layout.length} {settings.n_segments} -" for k in range(3)]
    fric_damp = props.wet_weight * layout.length / settings.n_segments / settings.friction_slip_velocity
    rows += [
        "---------------------- OPTIONS -------------------------------",
        f"{dtm} dtM",
        f"{settings.seabed_stiffness} kbot",
        f"{settings.seabed_damping} cbot",
        f"{layout.depth} WtrDpth",
        f"{settings.water_density} rho",
        f"{settings.gravity} g",
        "1.0 dtIC",
        "60.0 TmaxIC",
        "4.0 CdScaleIC",
        "0.001 threshIC",
        f"{settings.friction_coefficient} FrictionCoefficient",
        f"{fric_damp if settings.friction_coefficient > 0 else 200.0} FricDamp",
        "------------------------- need this line ----------------------",
        "",
    ]
    path.write_text("\n".join(rows))
    return path


def run_moordyn(deck: Path, layout, t: np.ndarray) -> tuple[np.ndarray, float]:
    import moordyn

    X, V = surge(t)
    out = np.full((t.size, 3), np.nan)
    with quiet():
        system = moordyn.Create(str(deck))
        moordyn.Init(system, list(layout.fairleads_body.ravel()), [0.0] * 9)
        c0 = time.process_time()
        for i in range(1, t.size):
            x = (layout.fairleads_body + [X[i], 0.0, 0.0]).ravel()
            f = moordyn.Step(system, list(x), list(np.tile([V[i], 0.0, 0.0], 3)), t[i - 1], t[i] - t[i - 1])
            out[i] = np.linalg.norm(np.asarray(f).reshape(3, 3), axis=1)
        cpu = time.process_time() - c0
        moordyn.Close(system)
    return out, cpu


def run_ours(props, layout, cfg, t: np.ndarray, batch: int = 1) -> tuple[np.ndarray, float, float]:
    X, V = surge(t)
    model = make_mooring(None, props, layout, cfg, batch=batch)
    c0 = time.process_time()
    state = model.init(fairlead_positions(layout, np.zeros((batch, 3))))
    c_init = time.process_time() - c0
    rf = np.repeat(layout.fairleads_body[None], batch, axis=0)
    base = rf.copy()
    vf = np.zeros_like(rf)
    out = np.empty((t.size, 3))
    out[0] = model.tension(state)[0]
    c0 = time.process_time()
    for i in range(1, t.size):
        rf[..., 0] = base[..., 0] + X[i]
        vf[..., 0] = V[i]
        model.step(state, rf, vf, t[i] - t[i - 1])
        out[i] = model.tension(state)[0]
    cpu = time.process_time() - c0
    return out, cpu, c_init


def profile_kernels(props, layout, repeat: int) -> None:
    """Microseconds per call of the numba kernels of one BDF2 step, on a moving MS line."""
    from numba import njit

    from moorlife.mooring import dynamic as dyn

    model = make_mooring("dynamic", props, layout, None, batch=1)
    state = model.init(fairlead_positions(layout, np.zeros((1, 3))))
    t = np.arange(0.0, 60.0 + 1e-9, 0.1)
    X, V = surge(t)
    vf = np.zeros((1, 3, 3))
    for i in range(1, t.size):
        vf[..., 0] = V[i]
        model.step(state, fairlead_positions(layout, [[X[i], 0.0, 0.0]]), vf, 0.1)
    r, v = state.r[0, 1].copy(), state.v[0, 1].copy()
    rp, vp = state.r_prev[0, 1].copy(), state.v_prev[0, 1].copy()
    p, buf, N = model.model.params, model._w, model.model.n_segments

    @njit
    def forces(n, r, v, p, buf, N, jac):
        w, _ = dyn._views(buf, N)
        for _ in range(n):
            dyn._node_forces(r, v, p, 0.05, jac, w[0])

    @njit
    def factor(n, r, v, p, buf, N):
        w, _ = dyn._views(buf, N)
        dyn._node_forces(r, v, p, 0.05, True, w[0])
        for _ in range(n):
            dyn._factor(w[0], w[2], w[3], w[4], w[5], N, 0.0333 * p[3], 0.0333**2, 0.0333)

    @njit
    def solve(n, r, v, p, buf, N):
        w, _ = dyn._views(buf, N)
        for _ in range(n):
            dyn._solve_blocks(w[2], w[3], w[6], w[10], N, w[13])

    @njit
    def step(n, r, v, p, buf, N, rp, vp):
        w, _ = dyn._views(buf, N)
        for _ in range(n):
            r2, v2, rp2, vp2 = r.copy(), v.copy(), rp.copy(), vp.copy()
            dyn._bdf2_step(r2, v2, rp2, vp2, r[N], v[N], 0.05, p, w)

    n = 100000
    print(f"\nKernels of one BDF2 step of one {N}-segment line (us per call, best of {repeat}):")
    base = (r, v, p, buf, N)
    for name, f, args in [
        ("node forces + matrix pieces", forces, (*base, True)),
        ("node forces only", forces, (*base, False)),
        ("block factorisation", factor, base),
        ("block solve", solve, base),
        ("whole BDF2 step (+4 state copies)", step, (*base, rp, vp)),
    ]:
        f(10, *args)
        best = np.inf
        for _ in range(repeat):
            c0 = time.process_time()
            f(n, *args)
            best = min(best, time.process_time() - c0)
        print(f"  {name:<36s} {1e6 * best / n:6.2f}")


def stats_line(name: str, T: np.ndarray, ref: np.ndarray, keep: np.ndarray) -> str:
    parts = []
    for k in range(3):
        a, b = T[keep, k], ref[keep, k]
        parts.append(
            f"M{k + 1} mean {100 * (a.mean() / b.mean() - 1):+5.2f}% std {100 * (a.std() / b.std() - 1):+5.2f}% "
            f"range {100 * (np.ptp(a) / np.ptp(b) - 1):+5.2f}%"
        )
    return f"  {name:<34s} " + " | ".join(parts)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ms", default="MS2")
    ap.add_argument("--duration", type=float, default=600.0, help="simulated seconds per run")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--batch", type=int, default=8)
    args = ap.parse_args()

    table = read_mooring_systems("config/mooring_systems.tsv")
    props = lines.line_properties(table.loc[args.ms])
    layout = lines.oc4_layout(None)
    settings = lines.mooring_settings(None)
    per_hour = 3600.0 / args.duration
    print(
        f"{args.ms}: {settings.n_segments} segments x 3 lines, {args.duration:.0f} s of prescribed surge "
        f"(5 m @ 100 s + 1 m @ 10 s), friction {settings.friction_coefficient}; CPU s per simulated hour "
        f"(best of {args.repeat})\n"
    )

    results: dict[str, tuple[float, np.ndarray]] = {}
    with tempfile.TemporaryDirectory() as tmp:
        for dtm in (0.001, 0.005):
            deck = moordyn_deck(Path(tmp) / f"md_{dtm}.dat", props, layout, settings, dtm)
            t = np.arange(0.0, args.duration + 1e-9, 0.05)
            best, T = np.inf, None
            for _ in range(args.repeat):
                T, cpu = run_moordyn(deck, layout, t)
                best = min(best, cpu)
            results[f"MoorDyn RK2 dtM={dtm} (dt 0.05)"] = (best * per_hour, T)
    ref_name = "MoorDyn RK2 dtM=0.001 (dt 0.05)"
    ref = results[ref_name][1]

    cases = [
        ("moorlife bdf2 h=0.05 (dt 0.05)", {}, 0.05, 1),
        ("moorlife bdf2 h=0.05 (dt 0.1)", {}, 0.1, 1),
        ("moorlife ros2 h=0.05 (dt 0.05)", {"integrator": "ros2"}, 0.05, 1),
        ("moorlife bdf2 h=0.1 (dt 0.1)", {"max_time_step": 0.1}, 0.1, 1),
        (f"moorlife bdf2 h=0.05 (dt 0.1) B={args.batch}", {}, 0.1, args.batch),
        ("moorlife quasi-static (dt 0.1)", {"model": "quasistatic"}, 0.1, 1),
    ]
    inits = {}
    for name, over, dt, batch in cases:
        cfg = {"mooring": over}
        t = np.arange(0.0, args.duration + 1e-9, dt)
        best, T = np.inf, None
        for _ in range(args.repeat):
            T, cpu, c_init = run_ours(props, layout, cfg, t, batch)
            best = min(best, cpu / batch)
        inits[name] = c_init / batch
        # compare on the common 0.1 s grid
        results[name] = (best * per_hour, T if dt == 0.05 else np.repeat(T, 2, axis=0)[: ref.shape[0]])

    md = results[ref_name][0]
    md_fast = results["MoorDyn RK2 dtM=0.005 (dt 0.05)"][0]
    print(f"  {'model':<34s} {'CPU s/h':>8s} {'vs MoorDyn 1 ms':>16s} {'vs MoorDyn 5 ms':>16s}")
    for name, (cost, _) in results.items():
        print(f"  {name:<34s} {cost:8.3f} {md / cost:15.1f}x {md_fast / cost:15.1f}x")
    print(
        f"\n  initialisation (static Newton + relaxation, per sea state): "
        f"{inits['moorlife bdf2 h=0.05 (dt 0.1)']:.3f} CPU s"
    )
    print("\nAccuracy vs MoorDyn dtM=0.001, t >= 100 s (fairlead tension, force at the coupled point):")
    t05 = np.arange(0.0, args.duration + 1e-9, 0.05)
    keep = t05 >= 100.0
    for name, (_, T) in results.items():
        if name == ref_name:
            continue
        if T.shape[0] != ref.shape[0]:
            continue
        if "dt 0.1" in name:  # held samples on the 0.05 grid: compare on the 0.1 s grid
            k2 = keep & (np.arange(t05.size) % 2 == 0)
            print(stats_line(name, T, ref, k2))
        else:
            print(stats_line(name, T, ref, keep))
    profile_kernels(props, layout, args.repeat)


if __name__ == "__main__":
    main()
