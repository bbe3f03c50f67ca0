"""The training records' seed noise in a reconstructed damage sum, and the bias test with it (issue 22).

    OMP_NUM_THREADS=1 python validation/record_noise.py --results results --systems MS4 MS6 --life \\
        --variant paper= --variant frozen=validation/overlays/gp_matern52_wind_frozen.yaml > noise.md

A reconstruction is trained on one record (one seed) per training state, and is linear in those
records: the RBF's and the GP's ``log10`` prediction at an hour ``h`` is ``f_h = sum_i A_hi y_i``
(the GP about its constant mean), with ``y_i`` the ``log10`` damage of training state ``i``. A
relative seed error ``e_i`` of record ``i`` moves ``y_i`` by ``e_i / ln 10`` and the window's sum
``S = sum_h D_h`` by ``sum_i G_i e_i``, with ``G = A^T D`` (``D_h`` the reconstructed hourly damage):
``G_i`` is the part of the sum that record ``i`` carries (:func:`moorlife.rbf.training_weights`,
:func:`moorlife.gp.training_weights`). With each record's seed error of relative
sd ``c`` (the truth's own model, ``var(x) = c^2 x^2``, ``c`` measured on the window's second-seed
hours by :func:`moorlife.truth.noise_floor`), the reconstructed sum has a seed scatter
of relative sd ``c |G| / S``, beside the truth sum's ``c |x| / sum x``. The truth's hours are
independent; the reconstruction's are not: every storm hour near one training state carries that
one record's error.

Printed per system, variant and line (S-N damage; T-N is the same up to a constant):

- the window sum's error against the truth, %;
- ``sd truth``: the truth sum's seed scatter (the harness's ``seed_sum_std_pct``);
- ``sd records``: the reconstructed sum's, ``100 c |G| / S``;
- ``z`` against the truth's scatter alone (the harness's bias test) and against both,
  ``error / hypot(sd truth, sd records)``: the bias test of two noisy sums;
- the coverage factor the life band needs to hold the truth (``|error| / sd``): with the band's
  sd on the window today, ``hypot(sd truth, validation term)`` (the largest ``|validation sum
  error|`` over the curve's lines, :func:`moorlife.lifecycle.validation_sum_term`), and with the
  records' term added in quadrature;
- the training states carrying the most of the sum, ``G_i / S``, with their case ids;
- with ``--life``, the same records' term for the sum over every hindcast hour (the life cycle),
  with the window's ``c``, beside the term of independent hours that the life band's seed part
  takes today (:func:`moorlife.lifecycle.sum_seed_cv`).

The linear map is checked against the package's own prediction on the first hours (printed as
``check``, the largest difference in ``log10``). The RBF's shape and the GP's hyperparameters
are held at their fitted values: the map is the one of the fitted model. Models in the paper's
space only (``lifecycle.rbf.space: paper``, the GP's ``gp.thrust: false``).

Section 25 of ``validation/reconstruction.md`` has the figures.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import reconstruction as rec  # noqa: E402  (the harness's config and store loaders)

LINE_OUTPUT = "damage_sn"


def carried(model, method: str, points: np.ndarray, weights: np.ndarray, j: int, train: np.ndarray) -> np.ndarray:
    """``G = A^T weights`` of output ``j`` of one fitted model (the package's ``training_weights``)."""
    from moorlife import gp, rbf

    if method == "gp":
        return gp.training_weights(model, points, weights, outputs=[j])[:, 0]
    return rbf.training_weights(model, points, weights, outputs=[j], train_points=train)[:, 0]


def window_noise(truth_ds, seed2, line: str, storm: int) -> tuple[float, float]:
    """The relative seed sd ``c`` of one hour's damage on the window and the truth sum's seed sd %,
    from :func:`moorlife.truth.noise_floor` as the truth stage calls it."""
    from moorlife.truth import noise_floor, strata_weights

    idx = truth_ds["hindcast_index"].values
    pos = np.searchsorted(idx, seed2["hindcast_index"].values)
    w = strata_weights(idx.size, pos, hs=truth_ds["hs"].values, storm=storm) if storm else None
    x = truth_ds[LINE_OUTPUT].sel(line=line).values[:, None]
    nf = noise_floor(x[pos], seed2[LINE_OUTPUT].sel(line=line).values[:, None], n_window=idx.size, window=x, weights=w)
    return float(nf["hour_cv"][0]), float(nf["sum_std_pct"][0])


def measure(cfg, st, life: bool = False) -> list[dict]:
    """Every line of one system and variant: the sums, the two scatters and the carrying states."""
    from moorlife import lifecycle
    from moorlife.lifecycle.fit import _floored, fit_outputs, predict_outputs
    from moorlife.lifecycle.spaces import space_points
    from moorlife.stages import thrust_for

    settings = lifecycle.rbf_settings(cfg["lifecycle"]["rbf"])
    cases, sims, truth_ds, seed2 = st["cases"], st["sims"], st["truth"], st["seed2"]
    role = cases["role"].values.astype(object).astype(str)
    train = role == "train"
    cols = lifecycle.output_columns(sims, "case", settings.outputs)
    y = lifecycle.stack_outputs(sims, "case", cols)
    x = lifecycle._points(cases, "case")
    lo, span = lifecycle._selection_scaling(cases)
    thrust = thrust_for(settings, rec.ROOT / cfg["platform"], cfg["simulation"]["wind"])
    model = fit_outputs(x[train], y[train], cols, settings, lo=lo, span=span, thrust=thrust)
    hours = lifecycle._points(st["hindcast"].isel(time=truth_ds["hindcast_index"].values), "time")
    pred = predict_outputs(model, hours)
    valid = role == "validate"
    # the band's reconstruction term, as lifecycle.validation_sum_term: the largest |validation
    # sum error| over the lines of the curve
    pv = predict_outputs(model, x[valid])
    dmg = [i for i, c in enumerate(cols) if c[0] == LINE_OUTPUT]
    val = 100 * max(abs(pv[:, i].sum() / y[valid][:, i].sum() - 1) for i in dmg)
    every = lifecycle._points(st["hindcast"], "time") if life else None
    pred_all = predict_outputs(model, every) if life else None
    lines = truth_ds["line"].values.astype(object).astype(str)
    for line in lines:  # every line's model in the paper's space, before any adjoint
        k = next(i for i, c in enumerate(model.columns) if cols.index((LINE_OUTPUT, line)) in c)
        if model.spaces[k] != "paper":
            raise SystemExit(
                f"{LINE_OUTPUT}/{line} is fitted in the {model.spaces[k]!r} space; record_noise.py takes 'paper' only"
            )
    xh, xt = space_points("paper", hours, model.thrust), space_points("paper", x[train], model.thrust)
    xa = space_points("paper", every, model.thrust) if life else None
    ids = cases["case"].values[train]
    rows = []
    for line in lines:
        col = cols.index((LINE_OUTPUT, line))
        k = next(i for i, c in enumerate(model.columns) if col in c)
        sub = model.models[k]
        j = int(np.flatnonzero(model.columns[k] == col)[0])
        p = pred[:, col]
        yt = np.log10(_floored(y[train][:, col].copy(), cols[col]))
        f3 = np.log10(p[:3] / sub.log_factor[j])
        g = carried(sub, model.method, xh, p, j, xt)
        rows3 = np.stack([carried(sub, model.method, xh[h : h + 1], np.ones(1), j, xt) for h in range(3)])
        mean = sub.mean[j] if model.method == "gp" else 0.0
        check = np.abs(mean + rows3 @ (yt - mean) - f3)
        c, sd_t = window_noise(truth_ds, seed2, line, int(cfg["truth"]["second_seed_storm"]))
        s = p.sum()
        err, sd_r = 100 * (s / truth_ds[LINE_OUTPUT].sel(line=line).values.sum() - 1), 100 * c * np.linalg.norm(g) / s
        top = np.argsort(-np.abs(g))[:3]
        row = dict(
            line=line,
            c=c,
            err=err,
            sd_t=sd_t,
            sd_r=sd_r,
            z=err / sd_t,
            z2=err / np.hypot(sd_t, sd_r),
            val=val,
            k=abs(err) / np.hypot(sd_t, val),
            k2=abs(err) / np.sqrt(sd_t**2 + sd_r**2 + val**2),
            top=[(int(ids[i]), g[i] / s) for i in top],
            check=float(check.max()),
        )
        if life:  # the whole hindcast's sum: its records' term with the window's c
            pa = pred_all[:, col]
            ga = carried(sub, model.method, xa, pa, j, xt)
            ta = np.argsort(-np.abs(ga))[:3]
            row["life"] = (
                100 * c * np.linalg.norm(ga) / pa.sum(),
                [(int(ids[i]), ga[i] / pa.sum()) for i in ta],
                100 * c * np.linalg.norm(pa) / pa.sum(),
            )
        rows.append(row)
    return rows


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--results", type=Path, default=rec.ROOT / "results")
    p.add_argument("--systems", nargs="+", default=["MS1", "MS2", "MS3", "MS4", "MS5", "MS6"])
    p.add_argument("--variant", action="append", default=[], help="NAME=OVERLAY[,OVERLAY...] (empty: config.yaml)")
    p.add_argument("--life", action="store_true", help="also the records' term of the whole hindcast's sum")
    a = p.parse_args(argv)
    variants = {}
    for spec in a.variant or ["paper="]:
        name, _, files = spec.partition("=")
        variants[name] = rec.study([f for f in files.split(",") if f])
    life: list[str] = []
    print(
        "| system | variant | line | c | error % | sd truth % | sd records % | z (truth) | z (both) | band k needed: today / with records | carried by (case: share) | check |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for ms in a.systems:
        st = rec.load(a.results, ms)
        if st is None or st["truth"] is None or st["seed2"] is None:
            print(f"{ms}: no simulations, truth.zarr or truth_seed2.zarr under {a.results}, skipped", file=sys.stderr)
            continue
        for name, cfg in variants.items():
            for r in measure(cfg, st, a.life):
                carriers = ", ".join(f"{i}: {sh:.2f}" for i, sh in r["top"])
                print(
                    f"| {ms} | {name} | {r['line']} | {r['c']:.3f} | {r['err']:+.1f} | {r['sd_t']:.2f} | {r['sd_r']:.2f} "
                    f"| {r['z']:+.1f} | {r['z2']:+.1f} | {r['k']:.2f} / {r['k2']:.2f} | {carriers} | {r['check']:.0e} |",
                    flush=True,
                )
                if "life" in r:
                    sd, top, hours_term = r["life"]
                    life.append(
                        f"| {ms} | {name} | {r['line']} | {sd:.2f} | {hours_term:.3f} | "
                        + ", ".join(f"{i}: {sh:.3f}" for i, sh in top)
                        + " |"
                    )
    if life:
        print(
            "\n| system | variant | line | life-cycle sum: sd records % | sd of independent hours % | carried by (case: share) |"
        )
        print("|---|---|---|---|---|---|")
        print("\n".join(life))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
