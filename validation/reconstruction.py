"""Paper-scale measurement of the reconstruction (issue 22): settings side by side, same simulations.

    python validation/reconstruction.py --results results --systems MS1 MS2 MS3 MS4 MS5 MS6 \\
        --variant paper= --variant new=validation/overlays/new_default.yaml > tables.md

Each ``--variant NAME=OVERLAY[,OVERLAY...]`` is ``config/config.yaml`` plus those overlays (empty:
the config as it is), validated as Snakemake validates it. For every system with a
``simulations.zarr`` under ``--results``, every variant is fitted on the same simulations of the
study, in this process, and measured:

- on the 225 validation states: r per output (``lifecycle.validation_metrics``);
- on the truth window, where ``results/{ms}/truth.zarr`` exists: per-hour r of every output, the
  window's damage per line and curve against the truth's (``moorlife.truth.compare_window``, the
  arithmetic of the ``truth_compare`` rule), and the bias test below;
- the design check of the life cycle: DFF x design-life damage of every line (S-N);
- the CPU time of the fit and the prediction of every hour.

Adaptive variants (``lifecycle.adaptive.rounds > 0``) are made at equal cost from the study's own
simulations: the first ``n_train - rounds x per_round`` MDA states (maximum dissimilarity is
greedy, so they are exactly the states an MDA of that size picks, with the same case ids and
phases), then the rounds, picked by ``moorlife.selection.rounds.pick_round`` and simulated by the
simulate stage itself into ``--work/{ms}/{variant}/`` (resumable; reused when present). The
validation states are the study's, so every variant is measured on the same 225 realisations.

With ``--choose NAME=A,B``, NAME is also reported: per output, the figures of variant A or B,
whichever has the smaller leave-one-out RMS (in the output's units) on the training states; the
validation states and the truth never steer it (:func:`choose`).

With ``--validation-seeds K`` (K >= 2), the 225 validation states are simulated K - 1 more times
(random streams ``validation_seed2`` .. ``validation_seedK``, into ``--work/{ms}/validation_seeds/``,
resumable) and every variant is also measured against the mean of the K records. The noise
ceiling of the validation r is reported beside it: ``sqrt(r1)`` for one record, with ``r1`` the
mean correlation of two records, and ``sqrt(K r1 / (1 + (K - 1) r1))`` for their mean (the
correlation of a perfect reconstruction with them). A variant below the ceiling by more than
the noise is limited by interpolation, not by the seed.

The bias test: for each line and curve, ``z = (reconstruction - truth) / sd``, with ``sd`` the seed
scatter of the truth's window sum (``seed_sum_std_pct``, from the second-seed hours). ``|z| <= 2``
is "within the seed noise". Systematic bias shows as z of one sign on every line. Beside it, the
comparison's ``bias_z``, against both noises of the difference: the truth's and the seed scatter of
the reconstructed sum from its training records (``records_sum_std_pct``; the variant refitted
on the window's hours, :func:`moorlife.stages.truth.window_records`), printed as ``z truth / z both``.
The life band on the window carries the records' term too, as the truth comparison's does.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

ROOT = Path(__file__).resolve().parents[1]
DAMAGE = ("damage_sn", "damage_tn")


def study(overlays: list[str]) -> dict[str, Any]:
    """config.yaml + overlays, validated and filled as the Snakefile does."""
    from moorlife.io import read_yaml
    from moorlife.stages.check import check_study, read_configs

    cfg = read_configs(str(ROOT / "config" / "config.yaml"), overlays)
    return check_study(cfg, read_yaml(ROOT / "workflow" / "schemas" / "config.schema.yaml"), "config").config


def _open(path: Path) -> xr.Dataset | None:
    from moorlife.io import open_zarr

    return open_zarr(path) if path.exists() else None


def adaptive_training(
    cfg: dict[str, Any], ms: str, results: Path, work: Path, cases: xr.Dataset, sims: xr.Dataset, hindcast: xr.Dataset
) -> tuple[xr.Dataset, xr.Dataset]:
    """The MDA prefix of the study plus the adaptive rounds of ``cfg`` (simulated into ``work``)."""
    from moorlife import lifecycle
    from moorlife.selection import rounds as rounds_mod
    from moorlife.stages import thrust_for

    ad = cfg["lifecycle"]["adaptive"]
    n_mda = rounds_mod.mda_budget(cfg["selection"]["n_train"], ad["rounds"], ad["per_round"])
    role = cases["role"].values.astype(object).astype(str)
    keep = (role == "validate") | ((role == "train") & (np.arange(role.size) < n_mda))
    if int(((role == "train") & keep).sum()) != n_mda:
        raise ValueError(f"{ms}: the study has {int((role == 'train').sum())} MDA states, fewer than {n_mda}")
    cs = cases.isel(case=np.flatnonzero(keep))
    sm = sims.sel(case=cs["case"].values)
    settings = lifecycle.rbf_settings(cfg["lifecycle"]["rbf"])
    thrust = thrust_for(settings, ROOT / cfg["platform"], cfg["simulation"]["wind"])
    picks, rsims = [], []
    for r in range(1, ad["rounds"] + 1):
        pdir = work / "picks"
        ppath, spath = pdir / f"picks_{r}.zarr", pdir / f"simulations_{r}.zarr"
        if not ppath.exists():
            from moorlife.io import write_zarr

            ds = rounds_mod.pick_round(
                hindcast,
                rounds_mod.with_rounds(cs, picks),
                rounds_mod.with_rounds(sm, rsims),
                settings=settings,
                n=int(ad["per_round"]),
                number=r,
                thrust=thrust,
            )
            pdir.mkdir(parents=True, exist_ok=True)
            write_zarr(ds, ppath)
        if not spath.exists():
            simulate_cases(
                cfg,
                ms,
                results,
                ppath,
                spath,
                stream=rounds_mod.ROUND_STREAM,
                threads=2,
                log=work / f"simulate_{r}.log",
            )
        picks.append(_open(ppath))
        rsims.append(_open(spath))
    return rounds_mod.with_rounds(cs, picks), rounds_mod.with_rounds(sm, rsims)


def simulate_cases(
    cfg: dict[str, Any], ms: str, results: Path, cases: Path, store: Path, *, stream: str, threads: int, log: Path
) -> None:
    """The simulate stage on the sea states of ``cases`` with the study's settings (``cfg``),
    the platform of ``results`` and the random ``stream``, into ``store``."""
    from moorlife.stages import result_settings
    from moorlife.stages import simulate as sim_stage
    from moorlife.stages.check import check_study

    row = check_study(cfg, _schema()).mooring.loc[ms]
    sim_stage.run(
        cases=cases,
        platform=results / "hydro" / "platform.nc",
        platform_cfg=ROOT / cfg["platform"],
        store=store,
        dim="case",
        ms=ms,
        row={k: (v.item() if hasattr(v, "item") else v) for k, v in row.items()},
        seed=cfg["seed"],
        simulation=result_settings(cfg, "simulation"),
        mooring=cfg.get("mooring", {}),
        fatigue=cfg["fatigue"],
        statistics=cfg.get("statistics", {}),
        stream=stream,
        threads=threads,
        log=log,
    )


def validation_records(
    cfg: dict[str, Any], ms: str, results: Path, work: Path, cases: xr.Dataset, k: int
) -> list[xr.Dataset]:
    """Records 2 .. ``k`` of the validation states of ``cases`` (random streams
    ``validation_seed{j}``), simulated by the simulate stage into ``work`` (reused when present)."""
    from moorlife.io import write_zarr

    role = cases["role"].values.astype(object).astype(str)
    vpath = work / "cases.zarr"
    if not vpath.exists():
        work.mkdir(parents=True, exist_ok=True)
        write_zarr(cases.isel(case=np.flatnonzero(role == "validate")), vpath)
    out = []
    for j in range(2, k + 1):
        store = work / f"seed{j}.zarr"
        if not store.exists():
            simulate_cases(
                cfg, ms, results, vpath, store, stream=f"validation_seed{j}", threads=2, log=work / f"seed{j}.log"
            )
        out.append(_open(store))
    return out


def seed_ceiling(records: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The noise ceilings of a validation r, per output, from ``records`` (k >= 2, states, outputs):
    ``sqrt(r1)`` against one record and ``sqrt(k r1 / (1 + (k - 1) r1))`` against their mean, with
    ``r1`` the mean correlation of two records of the same states."""
    from moorlife import truth

    k = records.shape[0]
    pairs = [(a, b) for a in range(k) for b in range(a + 1, k)]
    r1 = np.mean([truth.noise_floor(records[a], records[b])["r"] for a, b in pairs], axis=0)
    return np.sqrt(r1), np.sqrt(k * r1 / (1.0 + (k - 1) * r1))


def _schema() -> dict[str, Any]:
    from moorlife.io import read_yaml

    return read_yaml(ROOT / "workflow" / "schemas" / "config.schema.yaml")


def measure(cfg: dict[str, Any], ms: str, results: Path, work: Path, stores: dict[str, xr.Dataset]) -> dict[str, Any]:
    """Fit one variant for one system; its validation, truth and cost figures."""
    from moorlife import lifecycle, truth
    from moorlife.stages import thrust_for

    settings = lifecycle.rbf_settings(cfg["lifecycle"]["rbf"])
    cases, sims = stores["cases"], stores["sims"]
    if cfg["lifecycle"]["adaptive"]["rounds"]:
        cases, sims = adaptive_training(cfg, ms, results, work, cases, sims, stores["hindcast"])
    thrust = thrust_for(settings, ROOT / cfg["platform"], cfg["simulation"]["wind"])
    t0 = time.process_time()
    fitted = lifecycle.fit_reconstruction(cases, sims, settings=settings, thrust=thrust)
    lc = lifecycle.reconstruct_lifecycle(
        stores["hindcast"],
        cases,
        sims,
        settings=settings,
        fatigue_cfg=cfg["fatigue"],
        compare_transforms=False,
        thrust=thrust,
        fitted=fitted,
    )
    cpu = time.process_time() - t0
    records = None
    if stores.get("truth") is not None and stores.get("seed2") is not None:  # the window's records' term
        from moorlife.stages.truth import window_records

        records = window_records(fitted, lc, stores["truth"]["hindcast_index"].values, source=f"{ms} ({work})")
    out: dict[str, Any] = {"cpu": cpu, "n_train": int(lc.attrs["n_train"])}
    out["validation_r"] = pd.Series(lc["validation_r"].values, index=lc["output"].values.astype(object).astype(str))
    out["loo"] = pd.Series(lc["loo_rmse_units"].values, index=out["validation_r"].index)  # training states only
    sn = lc["utilisation"].sel(curve="sn")  # DFF x design-life damage per line: the design check
    out["utilisation"] = pd.Series(sn.values, index=sn["line"].values.astype(object).astype(str))
    out["choice"] = pd.DataFrame(
        {k: lc[k].values for k in ("input_space", "transform", "retransform_factor", "shape_parameter", "smoothing")},
        index=out["validation_r"].index,
    )
    if stores.get("truth") is not None:
        cmp = truth.compare_window(
            stores["truth"],
            lc,
            stores["discrete_states"],
            stores["discrete_sims"],
            outputs=list(settings.outputs),
            seed2=stores.get("seed2"),
            second_seed_storm=cfg["truth"]["second_seed_storm"],
            records=records,
        )
        out["truth_r"] = pd.Series(cmp["r"].values, index=cmp["output"].values.astype(object).astype(str))
        for k in ("noise_r", "ceiling_r"):  # from the second seed (truth_seed2.zarr), when it exists
            nan = np.full(cmp["r"].shape, np.nan)
            out[k] = pd.Series(cmp[k].values if k in cmp else nan, index=out["truth_r"].index)
        dmg = cmp[[k for k in truth.WINDOW_DAMAGE_VARS if k in cmp]].to_dataframe()
        if "seed_sum_std_pct" not in dmg:  # no second seed: no seed scatter, no z
            dmg["seed_sum_std_pct"] = np.nan
        dmg["z"] = dmg["reconstruction_error_pct"] / dmg["seed_sum_std_pct"]
        if "bias_z" not in dmg:
            dmg["bias_z"] = np.nan
        # band_sigma_pct and coverage_needed: the life band on the window, as the comparison
        # writes them (moorlife.truth; validation/band_calibration.py reads the same columns)
        out["window"] = dmg
        out["n_hours"] = int(cmp.attrs["n_hours"])
    if stores.get("validation_records"):
        out.update(against_records(lc, stores["validation_records"], settings.outputs))
    return out


def against_records(lc: xr.Dataset, records: list[xr.Dataset], outputs: Any) -> dict[str, pd.Series]:
    """The validation r of ``lc`` against the mean of its own validation record and ``records``,
    and the noise ceilings (:func:`seed_ceiling`)."""
    from moorlife import lifecycle, names

    labels = lc["output"].values.astype(object).astype(str)
    ids = lc["validate"].values
    stack = [lc["validation_simulated"].values]
    for rec in records:
        cols = lifecycle.output_columns(rec, names.CASE, outputs)
        y = lifecycle.stack_outputs(rec.sel({names.CASE: ids}), names.CASE, cols)
        column = {lifecycle._label(c): i for i, c in enumerate(cols)}
        stack.append(y[:, [column[o] for o in labels]])
    y = np.stack(stack)
    c1, ck = seed_ceiling(y)
    r = lifecycle.validation_metrics(lc["validation_predicted"].values, y.mean(axis=0))["r"]
    return {
        "records_r": pd.Series(r, index=labels),
        "ceiling_one": pd.Series(c1, index=labels),
        "ceiling_mean": pd.Series(ck, index=labels),
        "n_records": len(stack),
    }


def choose(a: dict[str, Any], b: dict[str, Any]) -> dict[str, Any]:
    """Per output, the figures of ``a`` or ``b``, whichever has the smaller leave-one-out RMS in
    units on the training states (ties: ``a``). The validation states and the truth steer
    nothing; the cost is both fits'. A line's window damage and design check follow the choice
    of its damage output (``damage_sn/M1`` for the S-N damage of M1)."""
    pick_b = b["loo"] < a["loo"]

    def per_output(key: str) -> pd.Series:
        return a[key].where(~pick_b.reindex(a[key].index), b[key])

    out: dict[str, Any] = {"cpu": a["cpu"] + b["cpu"], "n_train": a["n_train"], "loo": per_output("loo")}
    out["validation_r"] = per_output("validation_r")
    out["choice"] = pd.DataFrame({"variant": np.where(pick_b, "b", "a")}, index=a["loo"].index)
    out["utilisation"] = pd.Series(
        {ln: (b if pick_b[f"damage_sn/{ln}"] else a)["utilisation"][ln] for ln in a["utilisation"].index}
    )
    for key in ("truth_r", "noise_r", "ceiling_r", "records_r", "ceiling_one", "ceiling_mean"):
        if key in a:
            out[key] = per_output(key)
    for key in ("n_hours", "n_records"):
        if key in a:
            out[key] = a[key]
    if "window" in a:
        rows = [(b if pick_b[f"damage_{c}/{ln}"] else a)["window"].loc[[(c, ln)]] for c, ln in a["window"].index]
        out["window"] = pd.concat(rows)
    return out


def store_paths(results: Path, ms: str) -> dict[str, Path]:
    """Every store a system's measurement reads, by its key in :func:`load`'s dict."""
    return {
        "hindcast": results / "metocean" / "hindcast.zarr",
        "cases": results / "selection" / "cases.zarr",
        "sims": results / ms / "simulations.zarr",
        "truth": results / ms / "truth.zarr",
        "seed2": results / ms / "truth_seed2.zarr",
        "discrete_states": results / "selection" / "discrete.zarr",
        "discrete_sims": results / ms / "discrete.zarr",
    }


def load(results: Path, ms: str) -> dict[str, xr.Dataset] | None:
    paths = store_paths(results, ms)
    sims = _open(paths["sims"])
    if sims is None:
        return None
    return {key: sims if key == "sims" else _open(path) for key, path in paths.items()}


def check_truth_inputs(results: Path, ms: str, stores: dict[str, xr.Dataset]) -> None:
    """With a truth, the 35 bins' stores that its comparison (``truth.compare_window``) needs, named if missing.

    Called for every system before the first fit: a missing store otherwise fails after the fits.
    The second seed stays optional, as in :func:`measure`.
    """
    if stores["truth"] is None:
        return
    paths = store_paths(results, ms)
    missing = [str(paths[key]) for key in ("discrete_states", "discrete_sims") if stores[key] is None]
    if missing:
        raise SystemExit(f"{paths['truth']} exists but its comparison needs {', '.join(missing)}")


def _damage_labels(index: pd.Index) -> list[str]:
    return [o for o in index if o.startswith(DAMAGE)]


def report(res: dict[tuple[str, str], dict[str, Any]], variants: list[str]) -> str:
    """The markdown tables."""
    lines = ["### Validation r on the 225 states (min over outputs; the damage of each line)", ""]
    sample = next(iter(res.values()))["validation_r"].index
    dl = _damage_labels(sample)
    lines += ["| system | variant | training states | min r (output) | " + " | ".join(dl) + " | fit + predict CPU-s |"]
    lines += ["|---" * (5 + len(dl)) + "|"]
    for (ms, v), m in res.items():
        r = m["validation_r"]
        lines.append(
            f"| {ms} | {v} | {m['n_train']} | {r.min():.3f} ({r.idxmin()}) | "
            + " | ".join(f"{r[o]:.3f}" for o in dl)
            + f" | {m['cpu']:.1f} |"
        )
    lines += ["", "### Life cycle: DFF x design-life damage per line (S-N), the design check", ""]
    lines_ = list(next(iter(res.values()))["utilisation"].index)
    lines += ["| system | variant | " + " | ".join(lines_) + " |", "|---" * (2 + len(lines_)) + "|"]
    for (ms, v), m in res.items():
        lines.append(f"| {ms} | {v} | " + " | ".join(f"{m['utilisation'][ln]:.3f}" for ln in lines_) + " |")
    with_records = {k: m for k, m in res.items() if "records_r" in m}
    if with_records:
        n = next(iter(with_records.values()))["n_records"]
        title = f"Validation r against the mean of {n} records of each state"
        lines += ["", f"### {title} (the ceilings: a perfect reconstruction against one record / against the mean)", ""]
        shown = dl + ["accel_mpm"]
        lines += [
            "| system | variant | min r (output) | " + " | ".join(shown) + " |",
            "|---" * (3 + len(shown)) + "|",
        ]

        def row(ms: str, label: str, r: pd.Series) -> str:
            return (
                f"| {ms} | {label} | {r.min():.3f} ({r.idxmin()}) | " + " | ".join(f"{r[o]:.3f}" for o in shown) + " |"
            )

        for (ms, v), m in with_records.items():
            lines.append(row(ms, v, m["records_r"]))
            if v == variants[0]:
                lines.append(row(ms, "ceiling, one record", m["ceiling_one"]))
                lines.append(row(ms, f"ceiling, mean of {n}", m["ceiling_mean"]))
    with_truth = {k: m for k, m in res.items() if "truth_r" in m}
    if with_truth:
        lines += ["", "### Per-hour r on the truth window (noise floor: r of two seeds)", ""]
        lines += [
            "| system | variant | hours | min r (output) | " + " | ".join(dl) + " |",
            "|---" * (4 + len(dl)) + "|",
        ]
        for (ms, v), m in with_truth.items():
            r = m["truth_r"]
            lines.append(
                f"| {ms} | {v} | {m['n_hours']} | {r.min():.3f} ({r.idxmin()}) | "
                + " | ".join(f"{r[o]:.3f}" for o in dl)
                + " |"
            )
            if v == variants[0]:
                nr = m["noise_r"]
                lines.append(f"| {ms} | r of two seeds | | | " + " | ".join(f"{nr[o]:.3f}" for o in dl) + " |")
                ceil = m["ceiling_r"]
                lines.append(f"| {ms} | ceiling, sqrt | | | " + " | ".join(f"{ceil[o]:.3f}" for o in dl) + " |")
        lines += [
            "",
            "### Window damage: reconstruction error % against the truth (z truth / z both: error / seed sd "
            "of the truth's sum, and / hypot of it and the training records' sd of the reconstructed sum)",
            "",
        ]
        keys = list(next(iter(with_truth.values()))["window"].index)
        head = [f"{c.upper()} {ln}" for c, ln in keys]
        lines += ["| system | variant | " + " | ".join(head) + " |", "|---" * (2 + len(head)) + "|"]
        for (ms, v), m in with_truth.items():
            w = m["window"]
            lines.append(
                f"| {ms} | {v} | "
                + " | ".join(
                    f"{w.loc[k, 'reconstruction_error_pct']:+.1f} (z {w.loc[k, 'z']:+.1f} / {w.loc[k, 'bias_z']:+.1f})"
                    for k in keys
                )
                + " |"
            )
            if "records_sum_std_pct" in w:
                lines.append(
                    f"| {ms} | {v}: records' sd % | "
                    + " | ".join(f"{w.loc[k, 'records_sum_std_pct']:.2f}" for k in keys)
                    + " |"
                )
            if v == variants[0]:
                lines.append(
                    f"| {ms} | bins | " + " | ".join(f"{w.loc[k, 'bins_error_pct']:+.1f}" for k in keys) + " |"
                )
                lines.append(
                    f"| {ms} | seed sd of the sum % | "
                    + " | ".join(f"{w.loc[k, 'seed_sum_std_pct']:.2f}" for k in keys)
                    + " |"
                )
        lines += ["", "### Life band against the truth: band sigma % (coverage factor k needed to hold the truth)", ""]
        lines += ["| system | variant | " + " | ".join(head) + " |", "|---" * (2 + len(head)) + "|"]
        for (ms, v), m in with_truth.items():
            w = m["window"]
            lines.append(
                f"| {ms} | {v} | "
                + " | ".join(f"{w.loc[k, 'band_sigma_pct']:.1f} (k {w.loc[k, 'coverage_needed']:.2f})" for k in keys)
                + " |"
            )
    return "\n".join(lines)


def split_argv(argv: list[str]) -> tuple[list[str], list[str]]:
    """A wrapper script's own arguments and this harness's, split at the first ``--`` (none: all its own)."""
    if "--" not in argv:
        return list(argv), []
    i = argv.index("--")
    return argv[:i], argv[i + 1 :]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--results", type=Path, default=ROOT / "results")
    p.add_argument("--systems", nargs="+", default=["MS1", "MS2", "MS3", "MS4", "MS5", "MS6"])
    p.add_argument("--variant", action="append", default=[], help="NAME=OVERLAY[,OVERLAY...] (empty: config.yaml)")
    p.add_argument("--work", type=Path, default=ROOT / "results" / "validation_rounds")
    p.add_argument("--choices", action="store_true", help="also print each variant's per-output choices")
    p.add_argument(
        "--choose",
        action="append",
        default=[],
        metavar="NAME=A,B",
        help="also a variant NAME: per output, variant A's or B's figures by the training states' leave-one-out",
    )
    p.add_argument(
        "--validation-seeds",
        type=int,
        default=1,
        metavar="K",
        help="also measure against the mean of K records of each validation state (K - 1 simulated)",
    )
    a = p.parse_args(argv)
    variants = {}
    for spec in a.variant or ["paper="]:
        name, _, files = spec.partition("=")
        variants[name] = study([f for f in files.split(",") if f])
    pairs = {}
    for spec in a.choose:  # checked before any fit
        name, _, pair = spec.partition("=")
        parts = pair.split(",")
        if len(parts) != 2 or not all(v in variants for v in parts) or not name or name in variants:
            p.error(
                f"--choose {spec!r}: expected NAME=A,B with A and B among the variants {list(variants)} and a new NAME"
            )
        pairs[name] = tuple(parts)
    res: dict[tuple[str, str], dict[str, Any]] = {}
    loaded = {ms: load(a.results, ms) for ms in a.systems}
    for ms, stores in loaded.items():  # every system's truth inputs checked before any fit
        if stores is not None:
            check_truth_inputs(a.results, ms, stores)
    for ms, stores in loaded.items():
        if stores is None:
            print(f"{ms}: no simulations under {a.results}, skipped", file=sys.stderr)
            continue
        if a.validation_seeds > 1:
            first = next(iter(variants.values()))
            stores["validation_records"] = validation_records(
                first, ms, a.results, a.work / ms / "validation_seeds", stores["cases"], a.validation_seeds
            )
        for name, cfg in variants.items():
            res[(ms, name)] = m = measure(cfg, ms, a.results, a.work / ms / name, stores)
            print(f"{ms} {name}: min validation r {m['validation_r'].min():.4f}, {m['cpu']:.1f} CPU-s", file=sys.stderr)
            if a.choices:
                print(f"{ms} {name} choices:\n{m['choice'].to_string()}", file=sys.stderr)
        for name, (va, vb) in pairs.items():
            res[(ms, name)] = m = choose(res[(ms, va)], res[(ms, vb)])
            picked = ", ".join(o for o, c in m["choice"]["variant"].items() if c == "b")
            print(f"{ms} {name}: min validation r {m['validation_r'].min():.4f}; {vb} for: {picked}", file=sys.stderr)
    if not res:
        print(f"no {', '.join(a.systems)}/simulations.zarr under {a.results}: nothing measured", file=sys.stderr)
        return 1
    print(report(res, list(variants) + list(pairs)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
