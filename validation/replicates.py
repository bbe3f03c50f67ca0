"""Seed replicates of the training states that hold the damage (issue 22, the storm peak).

    python validation/replicates.py --results results --system MS6 --top 20 --seeds 5 \\
        --overlay validation/overlays/rest600.yaml > tables.md
    python validation/replicates.py ... --cv-estimates   # can one record rank the seed CV?

The truth year of MS6 is overestimated by 8-18 % (``validation/truth.md``), by the hours of
its largest storm, all reconstructed from one training record (the MDA's first state, the
hindcast's largest Hs). This harness asks how much of that is the seed noise of the few
training records that govern the damage, and whether averaging seed replicates of them, at
the same cost, removes it:

1. fit the paper's reconstruction on the study's training states, predict every hindcast
   hour, and give each training state the damage of the hours whose nearest training state it
   is (its *damage mass*, per line, as a share of the line's life-cycle damage); rank the states
   by their largest share over the lines;
2. simulate ``--seeds`` replicates of the ``--top`` states (the simulate stage itself, random
   streams ``replicate1`` .. ``replicateK``: phases independent of every other simulation),
   into ``--work`` (reused when present);
3. print the seed scatter of the damage at those states (the CV of one record, over the
   1 + K records; the study's record over their mean), and every ``--grid`` variant against
   the validation states and the truth window (:func:`validation.reconstruction.measure`, the
   harness of ``validation/reconstruction.md``). A variant ``N_MDA:TOP:SEEDS`` fits the first
   ``N_MDA`` MDA states (maximum dissimilarity is greedy: exactly an MDA of that size) with the
   outputs of its ``TOP`` states by damage mass (or of one state, ``caseID``) replaced by the
   mean of their study record and ``SEEDS`` replicates: ``N_MDA + TOP x SEEDS`` simulations.
   ``1000:0:0`` is the paper's method; ``960:20:2`` costs the same. ``N:pilotT.M:SEEDS`` gives the
   top ``T`` one pilot replicate and averages ``SEEDS`` into the ``M`` of them with the largest
   damage share x seed CV (:func:`pilot_picks`): ``N + T + M (SEEDS - 1)`` simulations
   (``960:pilot20.5:5`` costs 1,000). ``lifeT`` and ``yearsT`` rank the ``T`` states by their
   share of the records' seed variance in the life-cycle sum, or in each calendar year's sum
   (:func:`damage_mass`, from the carried shares of ``moorlife.lifecycle.records``).

    python validation/replicates.py --results results --system MS6 --top 20 --seeds 2 \
        --grid 1000:0:0,960:20:2,960:life20:2,960:years20:2

``--overlay`` sets the simulation settings of the replicates; they must be the study's (the
year of ``validation/truth.md`` ran from rest with a 600 s transient).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

sys.path.insert(0, str(Path(__file__).resolve().parent))
import reconstruction as harness  # noqa: E402

from moorlife import lifecycle  # noqa: E402
from moorlife.io import open_zarr, write_zarr  # noqa: E402
from moorlife.selection import replicates as rep  # noqa: E402

DIM = "case"


def damage_mass(
    cfg: dict[str, Any], cases: xr.Dataset, sims: xr.Dataset, hindcast: xr.Dataset, rank: str = "damage"
) -> pd.DataFrame:
    """Every training state's share, largest first, by the package's ranking
    ``lifecycle.replicates.rank`` (:func:`moorlife.selection.replicates.pick_replicates`): of each
    line's life-cycle damage in its cell (``damage``, with the cell's ``hours``), or of the records'
    seed variance in the life-cycle sum or the years' sums (``life``, ``years``)."""
    from moorlife.stages import thrust_for

    settings = lifecycle.rbf_settings(cfg["lifecycle"]["rbf"])
    n_train = int((cases["role"].values.astype(object).astype(str) == "train").sum())
    ds = rep.pick_replicates(
        hindcast,
        cases,
        sims,
        settings=settings,
        n=n_train,
        seeds=1,
        thrust=thrust_for(settings, harness.ROOT / cfg["platform"], cfg["simulation"]["wind"]),
        rank=rank,
    )
    out = ds["damage_share" if rank == "damage" else "records_variance_share"].to_pandas()
    out.index = ds[DIM].values
    out["largest"] = out.max(axis=1)
    if rank == "damage":
        out["hours"] = ds["cell_hours"].values
    return out


def simulate_replicates(cfg: dict[str, Any], ms: str, results: Path, work: Path, ids: np.ndarray, seeds: int) -> list:
    """``seeds`` stores of the cases ``ids``, random streams ``replicate1`` .. (reused when present)."""

    work.mkdir(parents=True, exist_ok=True)
    cases_path = work / "cases.zarr"
    sub = open_zarr(results / "selection" / "cases.zarr").sel({DIM: np.sort(ids)})
    if cases_path.exists():
        have = open_zarr(cases_path)[DIM].values
        if not np.array_equal(have, sub[DIM].values):
            raise ValueError(f"{cases_path}: holds other cases than --top asks; use another --work")
    else:
        write_zarr(sub, cases_path)
    out = []
    for j in range(1, seeds + 1):
        store = work / f"replicate{j}.zarr"
        if not store.exists():
            harness.simulate_cases(
                cfg,
                ms,
                results,
                cases_path,
                store,
                stream=rep.replicate_stream(j),
                threads=1,
                log=work / f"replicate{j}.log",
            )
        out.append(open_zarr(store))
    return out


def averaged(sims: xr.Dataset, reps: list[xr.Dataset], ids: np.ndarray) -> xr.Dataset:
    """``sims`` with the outputs of ``ids`` the mean of their records (the package's own mean)."""
    return rep.average_replicates(sims, [r.sel({DIM: np.asarray(ids)}) for r in reps])


def seed_scatter(sims: xr.Dataset, reps: list[xr.Dataset], ids: np.ndarray) -> pd.DataFrame:
    """Per state and line: the study's record over the mean of all records, and the records' CV."""
    rows = []
    for line in sims["line"].values.astype(object).astype(str):
        recs = np.stack(
            [sims["damage_sn"].sel({DIM: ids, "line": line}).values]
            + [r["damage_sn"].sel({DIM: ids, "line": line}).values for r in reps]
        )
        mean = recs.mean(axis=0)
        for i, c in enumerate(ids):
            rows.append(
                {
                    "case": int(c),
                    "line": line,
                    "study_over_mean": recs[0, i] / mean[i],
                    "cv_one_record": recs[:, i].std(ddof=1) / mean[i],
                }
            )
    return pd.DataFrame(rows)


def cv_estimates(
    cfg: dict[str, Any], ms: str, results: Path, cases: xr.Dataset, sims: xr.Dataset, scatter: pd.DataFrame
) -> str:
    """Can one record rank the states by their seed CV? Estimates from a new record of each state.

    The CV of the hour's damage from the spread of its ``k`` sub-windows' damage
    (``std / mean / sqrt(k)``, as if they were independent), and two proxies of the study's
    record (tension std / mean; Hs), each against the CV of ``1 + K`` records (``scatter``):
    Spearman's rank correlation per line and pooled, and the ratio of the medians.
    """
    from scipy.stats import spearmanr

    from moorlife import fatigue, simulate
    from moorlife.io.platform import open_platform_nc, read_platform_config
    from moorlife.stages import result_settings
    from moorlife.stages.check import check_study

    ids = np.sort(scatter["case"].unique())
    seed_cv = scatter.pivot(index="case", columns="line", values="cv_one_record").loc[ids]
    lines = list(seed_cv.columns)
    sim = {**result_settings(cfg, "simulation"), "keep_timeseries": True}
    row = check_study(cfg, harness._schema()).mooring.loc[ms]
    model = simulate.prepare_model(
        open_platform_nc(results / "hydro" / "platform.nc"),
        read_platform_config(harness.ROOT / cfg["platform"]),
        {**{k: (v.item() if hasattr(v, "item") else v) for k, v in row.items()}, "mooring_system": ms},
        cfg.get("mooring", {}),
        sim,
    )
    c = cases.sel({DIM: ids})
    ten = []
    for a in range(0, ids.size, 8):  # batches of 8: a record's time series is large
        sl = slice(a, a + 8)
        sea = {k: c[k].values[sl] for k in ("wind_speed", "wind_dir", "hs", "tp", "wave_dir")}
        out = simulate.simulate_batch(
            sea,
            case_ids=ids[sl],
            mooring_system=ms,
            seed=int(cfg["seed"]),
            stream="cvpilot",
            model_inputs=model,
            sim_cfg=sim,
            fatigue_cfg=cfg["fatigue"],
            stats_cfg=cfg.get("statistics", {}),
        )
        ten.append(out["ts_tension"].astype(float))
    ten = np.concatenate(ten)  # (state, line, nt)
    kw = fatigue.fatigue_settings(cfg["fatigue"], source="config").damage_kwargs()
    li = model.line_info
    est = {}
    for k in (4, 6, 12):
        w = ten.shape[-1] // k
        sub = np.stack(
            [
                fatigue.hourly_damage(
                    ten[..., i * w : (i + 1) * w],
                    w * float(sim["dt"]),
                    link_diameter=li["link_diameter"],
                    mbs=li["mbs"],
                    chain=li["chain"],
                    **kw,
                )[0]
                for i in range(k)
            ]
        )
        est[f"{k} sub-windows"] = sub.std(axis=0, ddof=1) / sub.mean(axis=0) / np.sqrt(k)
    rec = sims.sel({DIM: ids, "line": lines})  # the proxies of the study's record
    est["tension std / mean"] = (rec["tension_std"] / rec["tension_mean"]).values
    est["Hs"] = np.repeat(c["hs"].values[:, None], len(lines), axis=1)
    rows = []
    for name, e in est.items():
        r = [spearmanr(e[:, j], seed_cv.values[:, j])[0] for j in range(len(lines))]
        ratio = np.median(e / seed_cv.values, axis=0) if "sub-windows" in name else [np.nan] * len(lines)
        rows.append(
            {
                "estimate": name,
                **{f"rank r {ln}": round(x, 2) for ln, x in zip(lines, r)},
                "rank r pooled": round(spearmanr(e.ravel(), seed_cv.values.ravel())[0], 2),
                **{f"median est/CV {ln}": round(x, 2) for ln, x in zip(lines, ratio)},
            }
        )
    return pd.DataFrame(rows).set_index("estimate").to_markdown()


#: The rankings of a grid's ``TOP``: a bare count ranks by damage mass (the package's), a
#: prefix by the records' variance (:func:`damage_mass`).
RANKINGS = ("life", "years")


def ranking(top: str) -> tuple[str, int] | None:
    """``("", 20)`` for ``20``, ``("life", 20)`` for ``life20``; None for another ``TOP``."""
    for r in ("", *RANKINGS):
        rest = top[len(r) :]
        if top.startswith(r) and rest.isdigit():
            return r, int(rest)
    return None


def parse_grid(spec: str) -> list[tuple[int, str, int]]:
    """``N_MDA:TOP:SEEDS,...``; ``TOP`` is a count of states by damage mass, the same with a
    ranking by the records' variance (``life20``, ``years20``: :func:`damage_mass`), ``caseID``
    (one state) or ``pilotT.M`` (:func:`pilot_picks`)."""
    out = []
    for item in spec.split(","):
        n, top, k = item.split(":")
        pilot = top.startswith("pilot") and len(top[5:].split(".")) == 2 and top[5:].replace(".", "").isdigit()
        if not (ranking(top) or (top.startswith("case") and top[4:].isdigit()) or pilot):
            raise ValueError(f"--grid: {item!r}: TOP must be a number, lifeN, yearsN, caseID or pilotT.M")
        out.append((int(n), top, int(k)))
    return out


def pilot_picks(sims: xr.Dataset, pilot: xr.Dataset, mass: pd.DataFrame, t: int, m: int) -> np.ndarray:
    """The ``m`` of the top ``t`` states by damage mass with the largest share x seed CV.

    Each of the ``t`` states has one pilot record (``pilot``) beside the study's: the CV of one
    record is estimated from the two, ``sqrt(2) |d1 - d2| / (d1 + d2)`` per line (S-N damage),
    and a state's score is its largest ``share x CV`` over the lines. The variant ``pilotT.M``
    with ``SEEDS`` costs ``t`` pilot records plus ``m (SEEDS - 1)``.
    """
    cand = mass.index.values[:t]
    lines = [c for c in mass.columns if c not in ("largest", "hours")]
    d1 = sims["damage_sn"].sel({DIM: cand, "line": lines}).values
    d2 = pilot["damage_sn"].sel({DIM: cand, "line": lines}).values
    cv = np.sqrt(2.0) * np.abs(d1 - d2) / (d1 + d2)
    score = (mass.loc[cand, lines].values * cv).max(axis=1)
    return cand[np.argsort(-score, kind="stable")[:m]]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--results", type=Path, default=harness.ROOT / "results")
    p.add_argument("--system", default="MS6")
    p.add_argument(
        "--top", type=int, default=20, help="states replicated (of each fit of the grid, and of 1,000 and 900 states)"
    )
    p.add_argument("--seeds", type=int, default=5)
    p.add_argument(
        "--grid",
        default="1000:0:0,1000:20:5,1000:case0:5,1000:10:5,1000:20:2,1000:20:1,900:0:0,900:20:5,950:0:0,960:20:2,980:20:1",
        help="variants N_MDA:TOP:SEEDS (first N_MDA MDA states; TOP states by damage mass of their fit, or caseID; "
        "their first SEEDS replicates averaged in)",
    )
    p.add_argument("--overlay", action="append", default=[], help="overlays of the study's simulation settings")
    p.add_argument("--work", type=Path, default=harness.ROOT / "results" / "validation_replicates")
    p.add_argument(
        "--cv-estimates", action="store_true", help="only the seed scatter and its estimates from one record (no grid)"
    )
    a = p.parse_args(argv)
    cfg = harness.study(a.overlay)
    ms = a.system
    stores = harness.load(a.results, ms)
    if stores is None:
        raise SystemExit(f"{ms}: no simulations under {a.results}")
    cases, sims = stores["cases"], stores["sims"]
    role = cases["role"].values.astype(object).astype(str)
    grid = parse_grid(a.grid)
    prefixes, carried = {}, {}
    for n in sorted({g[0] for g in grid} | {1000, 900}):
        keep = (role == "validate") | ((role == "train") & (np.arange(role.size) < n))
        cs = cases.isel({DIM: keep})
        sm = sims.sel({DIM: cs[DIM].values})
        prefixes[n] = (cs, sm, damage_mass(cfg, cs, sm, stores["hindcast"]))
    for n, top, _ in grid:  # the records' variance rankings the grid asks for, one per fit
        r = ranking(top)
        if r and r[0] and (n, r[0]) not in carried:
            cs, sm, _ = prefixes[n]
            carried[(n, r[0])] = damage_mass(cfg, cs, sm, stores["hindcast"], r[0])
    # the top states of every fit the grid makes (each MDA prefix ranks its own): every variant has its replicates
    ranked = [m for _, _, m in prefixes.values()] + list(carried.values())
    ids = np.unique(np.concatenate([m.index.values[: a.top] for m in ranked]))
    for (n, by), m in carried.items():
        where = {int(c): int(np.flatnonzero(prefixes[n][2].index.values == c)[0]) + 1 for c in m.index.values[: a.top]}
        print(
            f"{ms}, {n} states, the top {a.top} by the records' variance ({by}; rank by damage mass): "
            + ", ".join(f"{c} ({k})" for c, k in where.items()),
            file=sys.stderr,
        )
    mass = prefixes[1000][2]
    print(
        f"{ms}: the top {a.top} of 1,000 training states hold {100 * mass['largest'].iloc[: a.top].sum():.1f} % "
        f"(largest share summed); {ids.size} states simulated x {a.seeds} seeds",
        file=sys.stderr,
    )
    print(f"## {ms}: damage mass of the top training states (share of the line's life-cycle damage, %)\n")
    head = mass.iloc[: a.top]
    print((100 * head.drop(columns=["largest", "hours"])).round(2).assign(hours=head["hours"]).to_markdown())
    reps = simulate_replicates(cfg, ms, a.results, a.work / ms, ids, a.seeds)

    sc = seed_scatter(sims, reps, ids)
    table = sc.pivot(index="case", columns="line", values="cv_one_record").round(3)
    ratio = sc.pivot(index="case", columns="line", values="study_over_mean").round(2)
    c = cases.sel({DIM: table.index.values})
    table = table.join(ratio, rsuffix=" study/mean").assign(
        hs=c["hs"].values.round(2), wind_speed=c["wind_speed"].values.round(1), tp=c["tp"].values.round(1)
    )
    print(
        f"\n## Seed scatter of the damage (S-N) at the replicated states: CV of one record over {a.seeds + 1} "
        "records, and the study's record over their mean\n"
    )
    print(table.sort_values(table.columns[1], ascending=False).to_markdown())
    if a.cv_estimates:
        print("\n## Estimates of the seed CV from one new record of each state (stream cvpilot)\n")
        print(cv_estimates(cfg, ms, a.results, cases, sims, sc))
        return 0

    res, names_ = {}, []
    for n, top, k in grid:
        cs, sm, m = prefixes[n]
        if top.startswith("pilot"):  # the pilot record of the top t, then the m of largest share x CV
            t, mm = (int(x) for x in top[5:].split("."))
            if t > a.top:
                raise SystemExit(f"--grid {n}:{top}:{k}: the pilot needs --top >= {t}")
            chosen = pilot_picks(sm, reps[0], m, t, mm)
            rest = np.setdiff1d(m.index.values[:t], chosen)
            sm = averaged(averaged(sm, reps[:1], rest), reps[:k], chosen)
            name = f"{n} MDA + pilot {t} + {mm} x {k - 1} seeds (cases {', '.join(map(str, chosen))})"
        else:
            r = ranking(top)
            if r and r[0]:
                m = carried[(n, r[0])]
            chosen = np.array([int(top[4:])]) if top.startswith("case") else m.index.values[: r[1]]
            missing = np.setdiff1d(chosen, reps[0][DIM].values) if k else np.array([], dtype=int)
            if missing.size:
                raise SystemExit(f"--grid {n}:{top}:{k}: cases {missing.tolist()} have no replicates (raise --top)")
            name = f"{n} MDA" + (f" + {top} x {k} seeds" if k else "")
            sm = averaged(sm, reps[:k], chosen) if k else sm
        names_.append(name)
        res[(ms, name)] = harness.measure(cfg, ms, a.results, a.work / ms / "fit", {**stores, "cases": cs, "sims": sm})
        print(f"{name}: done", file=sys.stderr)
    print()
    print(harness.report(res, names_))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
