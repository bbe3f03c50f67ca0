"""Benchmark: moorlife.rbf against scipy's RBFInterpolator and bluemath-tk's RBF, same run.

Run:  .venv/bin/python benchmarks/bench_rbf.py                 (paper scale)
      .venv/bin/python benchmarks/bench_rbf.py --hours 50000   (quicker)
      .venv/bin/python benchmarks/bench_rbf.py --skip-bluemath
      .venv/bin/python benchmarks/bench_rbf.py --choice-only   (section 5 only)
      .venv/bin/python benchmarks/bench_rbf.py --choice-only --noise   (seed-like noise added)

Data: the synthetic BiMEP-like hindcast of moorlife.metocean (31 years = 271,728 hours, seed
20190601), 1,000 training states by moorlife.selection.mda (from the largest Hs) and 225
validation states (seeded uniform sample of the rest). The 16 outputs of a simulated sea
state (names.SIM_SCALAR_VARS + SIM_LINE_VARS x 3 lines) are replaced by smooth synthetic
response surfaces of the right character (offsets and tensions rising with Hs and thrust,
thrust peaking at rated wind 11.4 m/s, damage spanning decades and peaking for Tp 13-21 s and
west-north-west seas), so that the timing and the transform comparison are meaningful.

1. Ours at paper scale with the lifecycle defaults (Rippa's closed-form LOO jointly over the
   q0 grid and the smoothing candidates of ``lifecycle.RBFSettings``, shared shapes) and
   fixed shapes (paper: 0.1 damage, 0.175 others), then predict every hour x 16 outputs.
2. scipy.interpolate.RBFInterpolator (kernel "gaussian", epsilon = 1/0.175, degree 1) on the
   same normalised coordinates (scipy has no circular metric: directions enter as deg/180
   without folding), 16 outputs, one shape; ours at the same single shape for the ratio.
3. bluemath-tk RBF (Gaussian, its own sigma search, directions as u/v, row_chunks for the
   prediction) on --bluemath-outputs outputs; its time is also scaled to 16 outputs.
4. Validation on the 225 states: r and RMSE per output; damage interpolated linearly vs as
   log10 (the lifecycle default is chosen from this and from the real simulations); and the
   error of the life damage (sum over every hour) against the true sum of the surfaces.
5. The choice of ``lifecycle.rbf.choose``: ``lifecycle.fit_outputs`` + ``predict_outputs`` with
   the default settings (``global``), ``global`` in the ``wind_trend`` space, and with
   ``per_output`` (spaces paper and thrust, with
   the NREL 5 MW thrust curve of ``config/platform.yaml``; transforms linear and log10, or the
   damage kept log10), with each back-transform correction, and the Gaussian process
   (``method: gp``, :mod:`moorlife.gp`) in the same run: cost, its ratio to the default,
   choices, validation r and the error of the life damage against the true sum; then per output
   the leave-one-out RMSE in the output's units and the validation r, RBF against GP.
   ``--noise`` multiplies every simulated value (training and validation) by seeded lognormal
   noise of mean 1, CV 25 % on the damage and 3 % on the other outputs (the seed noise of a
   one-hour record; a line's two damage curves share a draw, as they share the record); the true
   sums stay those of the noise-free surfaces.
"""

from __future__ import annotations

import argparse
import logging
import os
import time

import numpy as np

from moorlife import names, rbf
from moorlife.lifecycle import RBFSettings
from moorlife.selection import mda, scaling_from, select_validation

SEED = 20190601
MASK = np.array([v in names.DIRECTION_VARS for v in names.METOCEAN_VARS])
LINE_HEADING = {"M1": 30.0, "M2": 270.0, "M3": 150.0}  # nautical bearing of each line from the platform


def hindcast_points() -> np.ndarray:
    """(271728, 5) synthetic hindcast points in names.METOCEAN_VARS order."""
    from moorlife import metocean

    t = metocean.hourly_time("1985-01-01T00:00", "2015-12-31T23:00")
    d = metocean.generate_synthetic(t, metocean.SyntheticParams.from_config({}), SEED, 90.0, 0.14)
    return np.column_stack([d[v] for v in names.METOCEAN_VARS])


def responses(x: np.ndarray) -> tuple[np.ndarray, list[str]]:
    """Synthetic outputs (n, 16) of sea states x (n, 5) and their names."""
    w, beta, hs, tp, alpha = x.T
    thrust = np.where(w < 11.4, (w / 11.4) ** 2, np.where(w < 25.0, (11.4 / w) ** 0.8, 0.1))
    g = np.exp(-(((tp - 16.0) / 5.0) ** 2)) + 0.25
    cols, labels = [], []
    offset = 3.0 * thrust + 0.8 * hs
    for name, f in (("surge_mpm", np.cos), ("sway_mpm", np.sin)):
        cols.append(np.abs(offset * f(np.deg2rad(beta - 270.0))) + 0.5 * hs)
        labels.append(name)
    cols.append(0.3 * hs * g + 0.05)
    labels.append("heave_mpm")
    for k in ("accel_mpm", "accel_p90", "accel_p95", "accel_p99"):
        s = {"accel_mpm": 1.0, "accel_p90": 0.45, "accel_p95": 0.55, "accel_p99": 0.7}[k]
        cols.append(s * (0.4 * hs / np.maximum(tp, 3.0) ** 0.5 + 0.1 * thrust))
        labels.append(k)
    for line, head in LINE_HEADING.items():
        cw = np.cos(np.deg2rad(alpha - head))  # waves coming from the line's side load it
        cb = np.cos(np.deg2rad(beta - head))
        tension = 1.1e6 + 2.0e5 * hs * (1 + 0.6 * cw) + 3.5e5 * thrust * (1 + 0.8 * cb)
        dmg = 1e-7 * ((hs / 2.0) ** 3 * g * (1.2 + cw) ** 2 + 0.5 * thrust**2 * (1.2 + cb) ** 2) + 1e-10
        cols += [tension, dmg, 0.6 * dmg]
        labels += [f"tension_mpm_{line}", f"damage_sn_{line}", f"damage_tn_{line}"]
    return np.column_stack(cols), labels


#: Coefficient of variation of the seed-like noise of ``--noise``: damage, other outputs.
NOISE_CV = (0.25, 0.03)


def add_noise(y: np.ndarray, labels: list[str], seed: int) -> np.ndarray:
    """``y`` times lognormal noise of mean 1 (CV ``NOISE_CV``), seeded.

    A line's S-N and T-N damage come from one tension record, so they share its draw (as in the
    simulations, where they are a constant factor apart when both slopes are equal)."""
    cv = np.array([NOISE_CV[0] if lab.startswith("damage") else NOISE_CV[1] for lab in labels])
    s2 = np.log1p(cv**2)
    e = np.random.default_rng(seed).standard_normal(y.shape)
    for k, lab in enumerate(labels):
        if lab.startswith("damage_tn_"):
            e[:, k] = e[:, labels.index("damage_sn_" + lab.removeprefix("damage_tn_"))]
    return y * np.exp(np.sqrt(s2) * e - s2 / 2)


def metrics(pred: np.ndarray, true: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r = np.array([np.corrcoef(pred[:, k], true[:, k])[0, 1] for k in range(true.shape[1])])
    rmse = np.sqrt(np.mean((pred - true) ** 2, axis=0))
    return r, rmse


def timed(f, *a, **k):
    t0, c0 = time.perf_counter(), time.process_time()
    out = f(*a, **k)
    return out, time.perf_counter() - t0, time.process_time() - c0


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--hours", type=int, default=None, help="use only the first N hours")
    ap.add_argument("--skip-bluemath", action="store_true")
    ap.add_argument("--bluemath-outputs", type=int, default=1)
    ap.add_argument("--choice-only", action="store_true", help="run section 5 only (lifecycle.rbf.choose)")
    ap.add_argument("--noise", action="store_true", help="add seed-like lognormal noise to every simulated value")
    ap.add_argument("--gp-variants", action="store_true", help="section 5: also the GP's other settings")
    ap.add_argument(
        "--only", default="", help="section 5: only the variants whose name has this text (and the default)"
    )
    args = ap.parse_args()

    pts = hindcast_points()
    if args.hours:
        pts = pts[: args.hours]
    n = pts.shape[0]
    lo, span = scaling_from(pts, MASK)
    train = mda(pts, 1000, is_direction=MASK, start=int(np.argmax(pts[:, 2])), lo=lo, span=span)
    valid = select_validation(pts, 225, exclude=train, is_direction=MASK, rule="random", seed=SEED)
    y, labels = responses(pts[train])
    y_val, _ = responses(pts[valid])
    if args.noise:
        y, y_val = add_noise(y, labels, SEED + 1), add_noise(y_val, labels, SEED + 2)
    is_dmg = np.array([lab.startswith("damage") for lab in labels])
    print(f"hindcast {n} hours, {len(train)} training + {len(valid)} validation states, {len(labels)} outputs")
    print(f"threads: numba {os.environ.get('NUMBA_NUM_THREADS', 'default')}, load {os.getloadavg()[0]:.2f}")

    # warm up the numba kernels (compilation is cached, not part of the measurement)
    rbf.predict_rbf(rbf.fit_rbf(pts[train[:50]], y[:50, :2], is_direction=MASK, shape=0.2), pts[:100])
    if args.choice_only:
        choice_section(pts, train, valid, y, y_val, labels, lo, span, args.gp_variants, args.only)
        return

    # 1. ours at paper scale
    st = RBFSettings.from_config({})
    grid = rbf.shape_grid(st.grid_min, st.grid_max, st.grid_n)
    print(
        f"settings: q0 grid {st.grid_min}-{st.grid_max} x {st.grid_n}, smoothing {st.smoothing}, "
        f"share_tol {st.share_tol}"
    )
    model, t_fit, c_fit = timed(
        rbf.fit_rbf,
        pts[train],
        y,
        is_direction=MASK,
        shapes=grid,
        log_output=is_dmg,
        share_tol=st.share_tol,
        smoothing=st.smoothing,
        lo=lo,
        span=span,
    )
    pred, t_pred, c_pred = timed(rbf.predict_rbf, model, pts)
    print(
        f"\n[ours, Rippa] fit {t_fit:.2f} s (cpu {c_fit:.2f}), predict {n} x {len(labels)} "
        f"{t_pred:.2f} s (cpu {c_pred:.2f}), total {t_fit + t_pred:.2f} s; "
        f"{np.unique(model.shape).size} distinct shapes: {np.round(np.unique(model.shape), 4)}"
    )
    q_fixed = np.where(is_dmg, 0.1, 0.175)
    model_f, t_fit_f, _ = timed(
        rbf.fit_rbf, pts[train], y, is_direction=MASK, shape=q_fixed, log_output=is_dmg, lo=lo, span=span
    )
    _, t_pred_f, _ = timed(rbf.predict_rbf, model_f, pts)
    print(f"[ours, fixed 0.1/0.175] fit {t_fit_f:.2f} s, predict {t_pred_f:.2f} s, total {t_fit_f + t_pred_f:.2f} s")

    # 2. scipy, one shape, Euclidean on the same normalised coordinates
    from scipy.interpolate import RBFInterpolator

    z_tr = rbf.normalise(pts[train], model.space)
    z_all = rbf.normalise(pts, model.space)
    sp, t_sfit, _ = timed(RBFInterpolator, z_tr, y, kernel="gaussian", epsilon=1 / 0.175, degree=1)
    sp_pred, t_spred, _ = timed(sp, z_all)
    one, t_ofit, _ = timed(rbf.fit_rbf, pts[train], y, is_direction=MASK, shape=0.175, lo=lo, span=span)
    our_pred, t_opred, _ = timed(rbf.predict_rbf, one, pts)
    print(
        f"\n[scipy RBFInterpolator, 1 shape] fit {t_sfit:.2f} s, predict {t_spred:.2f} s, total {t_sfit + t_spred:.2f} s"
    )
    print(
        f"[ours, same single shape]        fit {t_ofit:.2f} s, predict {t_opred:.2f} s, total {t_ofit + t_opred:.2f} s"
    )
    print(
        f"ratio scipy / ours: {(t_sfit + t_spred) / (t_ofit + t_opred):.1f}x "
        f"(scipy's metric does not fold directions; the numbers differ only there)"
    )

    # 3. bluemath-tk
    if not args.skip_bluemath:
        import pandas as pd
        from bluemath_tk.interpolation.rbf import RBF

        logging.getLogger("RBF").setLevel(logging.WARNING)
        k = max(1, min(args.bluemath_outputs, len(labels)))
        cols = list(names.METOCEAN_VARS)
        sub = pd.DataFrame(pts[train], columns=cols)
        tgt = pd.DataFrame(y[:, :k], columns=labels[:k])
        bm = RBF(kernel="gaussian", sigma_min=0.001, sigma_max=0.5)
        bm.row_chunks = 4096
        _, t_bfit, _ = timed(
            bm.fit,
            subset_data=sub,
            target_data=tgt,
            subset_directional_variables=["wind_dir", "wave_dir"],
            num_workers=1,
        )
        _, t_bpred, _ = timed(bm.predict, pd.DataFrame(pts, columns=cols), num_workers=1)
        scale = len(labels) / k
        print(
            f"\n[bluemath-tk RBF, {k} output(s)] fit {t_bfit:.2f} s, predict {t_bpred:.2f} s; "
            f"scaled to {len(labels)} outputs: {(t_bfit + t_bpred) * scale:.1f} s"
        )
        print(f"ratio bluemath-tk / ours (Rippa, all outputs): {(t_bfit + t_bpred) * scale / (t_fit + t_pred):.1f}x")

    # 4. validation quality: log10 vs linear damage, Rippa vs fixed
    lin = rbf.fit_rbf(
        pts[train],
        y,
        is_direction=MASK,
        shapes=grid,
        log_output=False,
        share_tol=st.share_tol,
        smoothing=st.smoothing,
        lo=lo,
        span=span,
    )
    exact = rbf.fit_rbf(
        pts[train],
        y,
        is_direction=MASK,
        shapes=rbf.shape_grid(0.02, 1.0, 18),
        log_output=is_dmg,
        share_tol=0.02,
        lo=lo,
        span=span,
    )
    variants = {"rippa+log": model, "rippa+linear": lin, "fixed+log": model_f, "previous (exact)": exact}
    print("\nvalidation on 225 states: r (RMSE) per output")
    res = {k: metrics(rbf.predict_rbf(m, pts[valid]), y_val) for k, m in variants.items()}
    print(f"{'output':<18}" + "".join(f"{k:>28}" for k in variants))
    for j, lab in enumerate(labels):
        print(f"{lab:<18}" + "".join(f"{res[k][0][j]:>14.4f} ({res[k][1][j]:9.3g})" for k in variants))
    for k, (r, _) in res.items():
        print(f"{k}: min r over damage {r[is_dmg].min():.4f}, over all {r.min():.4f}")
    y_all, _ = responses(pts)
    life_err = 100 * (pred[:, is_dmg].sum(axis=0) / y_all[:, is_dmg].sum(axis=0) - 1)
    print(f"rippa+log: life damage over all {n} hours vs the true sum: {np.round(life_err, 2)} %")
    tot_true = y_val[:, is_dmg].sum(axis=0)
    for k, m in variants.items():
        p = rbf.predict_rbf(m, pts[valid])[:, is_dmg].sum(axis=0)
        print(f"{k}: validation damage sum error {np.round(100 * (p / tot_true - 1), 2)} %")


def choice_section(pts, train, valid, y, y_val, labels, lo, span, gp_variants=False, only="") -> None:
    """5. lifecycle.rbf.choose: global (the default) vs per_output vs the GP, cost and quality, same run."""
    from pathlib import Path

    from moorlife import lifecycle, stages
    from moorlife.io import read_study_config

    root = Path(__file__).resolve().parents[1]
    study = read_study_config(root / "config/config.yaml", (), schema=root / "workflow/schemas/config.schema.yaml")
    # (variable, line) as the lifecycle names them: tension_mpm_M1 -> (tension_mpm, M1)
    cols = [tuple(lab.rsplit("_", 1)) if lab[-2:-1] == "M" else (lab, None) for lab in labels]
    is_dmg = np.array([lab.startswith("damage") for lab in labels])
    y_all, _ = responses(pts)
    true_sum = y_all[:, is_dmg].sum(axis=0)
    variants = {
        "global (default)": {},
        "global + smearing": {"retransform": "smearing"},
        "global, wind_trend": {"space": "wind_trend"},
        "per_output": {"choose": "per_output"},
        "per_output, damage log10": {"choose": "per_output", "damage_transforms": ["log10"]},
        "  + smearing": {"choose": "per_output", "damage_transforms": ["log10"], "retransform": "smearing"},
        "  + ratio": {"choose": "per_output", "damage_transforms": ["log10"], "retransform": "ratio"},
        "gp (method: gp)": {"method": "gp"},
    }
    if gp_variants:
        variants.update(
            {
                "gp, retransform none": {"method": "gp", "gp": {"retransform": "none"}},
                "gp, isotropic": {"method": "gp", "gp": {"kernel": "isotropic"}},
                "gp, thrust": {"method": "gp", "gp": {"thrust": True}},
                "gp, subsample 300": {"method": "gp", "gp": {"subsample": 300}},
                "gp, share variable": {"method": "gp", "gp": {"share": "variable"}},
                "gp, share all": {"method": "gp", "gp": {"share": "all"}},
                "gp, matern52": {"method": "gp", "gp": {"covariance": "matern52"}},
                "gp, matern52, share var.": {"method": "gp", "gp": {"covariance": "matern52", "share": "variable"}},
                "gp, matern52, wind term": {"method": "gp", "gp": {"covariance": "matern52", "wind_term": "damage"}},
                "gp, matern52, wind, warm": {
                    "method": "gp",
                    "gp": {"covariance": "matern52", "wind_term": "damage", "wind_start": "warm"},
                },
                "gp, matern52, wind, frozen": {
                    "method": "gp",
                    "gp": {"covariance": "matern52", "wind_term": "damage", "wind_start": "frozen"},
                },
                # validation/overlays/gp_matern52_wind_all_frozen_sdT_stack_bagged.yaml
                "gp stack, bagged": {
                    "method": "gp",
                    "choose": "stack",
                    "stack": {"resamples": 500, "seed": 0},
                    "spaces": ["paper", "thrust"],
                    "thrust": {"statistic": "turbulent_sd"},
                    "gp": {"covariance": "matern52", "wind_term": "all", "wind_start": "frozen"},
                },
            }
        )
    variants = {k: v for i, (k, v) in enumerate(variants.items()) if i == 0 or only in k}
    table = {}
    base = None
    print("\n[5. lifecycle.rbf.choose] fit 1,000 + predict every hour x 16 outputs")
    for name, cfg in variants.items():
        st = lifecycle.RBFSettings.from_config(cfg)
        # the thrust coordinate as the lifecycle stage builds it (None where no space needs it)
        thrust = stages.thrust_for(st, root / "config/platform.yaml", study["simulation"]["wind"])
        model, t_fit, c_fit = timed(lifecycle.fit_outputs, pts[train], y, cols, st, lo=lo, span=span, thrust=thrust)
        pred, t_pred, c_pred = timed(lifecycle.predict_outputs, model, pts, chunk_rows=st.chunk_rows)
        total = c_fit + c_pred
        base = total if base is None else base
        r = metrics(lifecycle.predict_outputs(model, pts[valid]), y_val)[0]
        life = 100 * (pred[:, is_dmg].sum(axis=0) / true_sum - 1)
        table[name] = (model.loo_rmse_units, r)
        print(
            f"{name:<25} fit {t_fit:.2f} s (cpu {c_fit:.2f}), predict {t_pred:.2f} s (cpu {c_pred:.2f}), "
            f"total {total:.2f} CPU-s, {total / base:.2f}x the default; validation r min {r.min():.4f}, "
            f"damage {r[is_dmg].min():.4f}; life damage vs truth {np.round(life, 2)} %",
            flush=True,
        )
        if cfg.get("choose") == "per_output" and "retransform" not in cfg and "damage_transforms" not in cfg:
            for lab, sp, lg, q in zip(labels, model.input_space, model.log_output, model.shape):
                print(f"    {lab:<18} {sp:<6} {'log10' if lg else 'linear':<6} q0 {q:.4g}")
        if st.method == "gp":
            g = model.models[0]
            for lab, ls, sv, nv in zip(labels, g.length_scale, g.signal_var, g.noise_var):
                print(f"    {lab:<18} l {np.array2string(ls, precision=3)} s_f {np.sqrt(sv):.3g} s_n {np.sqrt(nv):.3g}")
    compare = [k for k in ("global (default)", "per_output, damage log10", "gp (method: gp)") if k in table]
    print("\nper output: leave-one-out RMSE in the output's units (training states) | validation r (225 states)")
    print(f"{'output':<18}" + "".join(f"{k[:22]:>24}" for k in compare) + "".join(f"{k[:22]:>24}" for k in compare))
    for j, lab in enumerate(labels):
        loo = "".join(f"{table[k][0][j]:>24.4g}" for k in compare)
        print(f"{lab:<18}" + loo + "".join(f"{table[k][1][j]:>24.4f}" for k in compare))
    for k in compare:
        ratio = table[k][0] / table["global (default)"][0]
        print(
            f"{k}: LOO RMSE / the default's, min {ratio.min():.3f} max {ratio.max():.3f}; r min {table[k][1].min():.4f}"
        )


if __name__ == "__main__":
    main()
