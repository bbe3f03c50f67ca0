"""The Gaussian process (``lifecycle.rbf.method: gp``) against the RBF on a study's stored simulations.

Usage::

    .venv/bin/python validation/reconstruction_gp.py RESULTS CONFIG MS2 [MS1 ...] [--gp-variants] [--truth STORE]

Reads (never writes) ``RESULTS/metocean/hindcast.zarr``, ``RESULTS/selection/cases.zarr`` and
``RESULTS/{ms}/simulations.zarr``, builds the training and validation matrices exactly as
:func:`moorlife.lifecycle.reconstruct_lifecycle` does, and fits, with the ``lifecycle.rbf``
settings of ``CONFIG`` (the run's config.yaml):

* the RBF as configured (``choose: global``, the paper's method and the default),
* the RBF with ``choose: per_output``, and with ``damage_transforms: [log10]``,
* the GP with the schema defaults of ``lifecycle.rbf.gp`` (and its variants with ``--gp-variants``).

For each: fit and predict CPU time (every hindcast hour, single thread when run with
``NUMBA_NUM_THREADS=1 OMP_NUM_THREADS=1``), and per output the leave-one-out RMSE in the output's
own units on the training states (closed form: Rippa's for the RBF, Rasmussen & Williams eq. 5.12
for the GP) and the validation r on the validation states; then the life-cycle damage sum of each
damage output relative to the default's. The validation states never enter a fit.

``--truth STORE`` (one system only) also compares with a truth store of every hour of a window
(``RESULTS/{ms}/truth.zarr``, case id = hindcast index; a store still being written may be
given: its hours not yet simulated are NaN and left out): per output the per-hour r, and per
damage output the window's sum over the truth's.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from moorlife import lifecycle as lc
from moorlife import names
from moorlife.io import open_zarr, read_yaml

ROOT = Path(__file__).resolve().parents[1]


def variants(rbf_cfg: dict, extra: bool) -> dict[str, dict]:
    """The settings compared: the configured RBF first (the reference of every ratio)."""
    out = {
        "rbf global (default)": rbf_cfg,
        "rbf per_output": {**rbf_cfg, "choose": "per_output"},
        "rbf per_output, damage log10": {**rbf_cfg, "choose": "per_output", "damage_transforms": ["log10"]},
        "gp": {**rbf_cfg, "method": "gp"},
    }
    if extra:
        out["gp, retransform none"] = {**rbf_cfg, "method": "gp", "gp": {"retransform": "none"}}
        out["gp, thrust"] = {**rbf_cfg, "method": "gp", "gp": {"thrust": True}}
        out["gp, subsample 300"] = {**rbf_cfg, "method": "gp", "gp": {"subsample": 300}}
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("results")
    ap.add_argument("config")
    ap.add_argument("systems", nargs="+")
    ap.add_argument("--gp-variants", action="store_true")
    ap.add_argument("--truth", help="a truth store of the (one) system, for per-hour r and window sums")
    ap.add_argument("--only", nargs="+", help="fit only these variants (the first stays the reference)")
    args = ap.parse_args()
    if args.truth and len(args.systems) != 1:
        ap.error("--truth takes one system")
    cfg = read_yaml(args.config)
    rbf_cfg = dict((cfg.get("lifecycle") or {}).get("rbf") or {})
    curve = lc.thrust_curve(read_yaml(ROOT / "config/platform.yaml"))
    hind = open_zarr(f"{args.results}/metocean/hindcast.zarr")
    hp = lc._points(hind, names.TIME)
    cases0 = open_zarr(f"{args.results}/selection/cases.zarr")
    for ms in args.systems:
        sims = open_zarr(f"{args.results}/{ms}/simulations.zarr")
        dim = names.CASE
        common = np.intersect1d(cases0[dim].values, sims[dim].values)
        cases, sims = cases0.sel({dim: common}), sims.sel({dim: common})
        role = np.array([str(v) for v in cases["role"].values])
        tr, va = role == "train", role == "validate"
        st0 = lc.RBFSettings.from_config(rbf_cfg)
        cols = lc.output_columns(sims, dim, st0.outputs)
        labels = [lc._label(c) for c in cols]
        y = lc.stack_outputs(sims, dim, cols)
        x = lc._points(cases, dim)
        lo, span = lc._selection_scaling(cases)
        is_dmg = np.array([c[0].startswith("damage") for c in cols])
        print(
            f"\n== {ms}: {int(tr.sum())} training + {int(va.sum())} validation states, {len(cols)} outputs, "
            f"{hp.shape[0]} hours",
            flush=True,
        )
        table, sums, base, truth_rows = {}, {}, None, {}
        if args.truth:
            import xarray as xr

            ts = xr.open_zarr(args.truth, consolidated=False)
            yt = lc.stack_outputs(ts, dim, cols)
            done = np.isfinite(yt).all(axis=1)
            yt, xt = yt[done], hp[ts[dim].values[done]]
            print(f"truth: {int(done.sum())} of {done.size} hours of {args.truth}", flush=True)
        todo = variants(rbf_cfg, args.gp_variants)
        if args.only:
            todo = {k: v for i, (k, v) in enumerate(todo.items()) if i == 0 or k in args.only}
        for name, c in todo.items():
            st = lc.RBFSettings.from_config(c)
            c0 = time.process_time()
            model = lc.fit_outputs(x[tr], y[tr], cols, st, lo=lo, span=span, thrust=curve)
            c1 = time.process_time()
            pred = lc.predict_outputs(model, hp, chunk_rows=st.chunk_rows)
            c2 = time.process_time()
            r = lc.validation_metrics(lc.predict_outputs(model, x[va]), y[va])["r"]
            table[name] = (model.loo_rmse_units, r)
            sums[name] = np.clip(pred[:, is_dmg], 0, None).sum(axis=0)
            if args.truth:
                pt = lc.predict_outputs(model, xt)
                truth_rows[name] = (
                    lc.validation_metrics(pt, yt)["r"],
                    np.clip(pt[:, is_dmg], 0, None).sum(axis=0) / yt[:, is_dmg].sum(axis=0),
                )
            base = c2 - c0 if base is None else base
            print(
                f"{name:<30} fit {c1 - c0:6.2f} + predict {c2 - c1:6.2f} = {c2 - c0:6.2f} CPU-s "
                f"({(c2 - c0) / base:.2f}x); validation r min {r.min():.4f}",
                flush=True,
            )
        keys = list(table)
        ref = keys[0]
        print(f"\n{ms}: leave-one-out RMSE in the output's units, ratio to {ref!r} (< 1: better)")
        print(f"{'output':<18}{'default':>12}" + "".join(f"{k[:20]:>22}" for k in keys[1:]))
        for j, lab in enumerate(labels):
            d = table[ref][0][j]
            print(f"{lab:<18}{d:>12.4g}" + "".join(f"{table[k][0][j] / d:>22.3f}" for k in keys[1:]))
        print(f"\n{ms}: validation r on the {int(va.sum())} states")
        print(f"{'output':<18}" + "".join(f"{k[:20]:>22}" for k in keys))
        for j, lab in enumerate(labels):
            print(f"{lab:<18}" + "".join(f"{table[k][1][j]:>22.4f}" for k in keys))
        print(f"{'min':<18}" + "".join(f"{table[k][1].min():>22.4f}" for k in keys))
        print(f"\n{ms}: life-cycle damage sum over every hour, ratio to {ref!r}")
        for j, lab in enumerate(np.asarray(labels)[is_dmg]):
            print(f"{lab:<18}" + "".join(f"{sums[k][j] / sums[ref][j]:>22.4f}" for k in keys))
        if truth_rows:
            print(f"\n{ms}: truth window, per-hour r")
            print(f"{'output':<18}" + "".join(f"{k[:20]:>22}" for k in keys))
            for j, lab in enumerate(labels):
                print(f"{lab:<18}" + "".join(f"{truth_rows[k][0][j]:>22.4f}" for k in keys))
            print(f"\n{ms}: truth window, damage sum over the truth's")
            for j, lab in enumerate(np.asarray(labels)[is_dmg]):
                print(f"{lab:<18}" + "".join(f"{truth_rows[k][1][j]:>22.4f}" for k in keys))


if __name__ == "__main__":
    main()
