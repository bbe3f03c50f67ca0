"""The seed noise of a truth window's storm hours, and what it leaves to the reconstruction (issue 22).

    python validation/storm_noise.py --results results --systems MS1 MS2 --hs 5.0 \\
        --variant paper= --variant gp_m52=validation/overlays/gp_matern52.yaml > storm.md

The truth target's noise floor (``truth_seed2.zarr``) is one more record of a subset of the
window's hours: evenly spaced (``truth.second_seed_storm: 0``), or, by default since 473affb,
the hours of largest Hs plus evenly spaced others. A year's damage variance sits in a few storm
hours, which an evenly spaced subset rarely holds, so its ``sqrt(r)`` is the ceiling of a calm
population, and one record per storm hour is a noisy estimate of a storm's variance. This
script measures the storm directly: every truth hour with ``Hs >= --hs`` is simulated three more times
by the simulate stage (random streams ``truth_seed2`` .. ``truth_seed4``, case id = the hour's
position in the hindcast, as the truth target does; into ``--work/{ms}/``, reused when present).
With the truth, four records per storm hour.

- The window's noise variance, stratified: the storm hours' own variance of the four records
  (ddof 1), plus the calm hours at the mean of the second seed's calm hours
  (``(x1 - x2)^2 / 2``; with a storm stratum, each weighted by the window hours it stands for,
  ``moorlife.truth.strata_weights``). The ceiling of the per-hour r is
  ``sqrt(1 - noise / var(truth))``.
- Each variant (fitted as ``validation/reconstruction.py`` does) on the same hours: per-hour r,
  and its range when the storm hours of the truth are replaced by each of the other records
  (the per-hour r's own seed scatter), and against the truth whose storm hours are the mean of
  their four records (a quarter of their seed variance);
  the storm's share of the squared error; that error over the storm's summed noise variance
  (1 is a perfect reconstruction, whose error is the truth record's own noise); the storm's
  reconstructed damage over the mean of the four records.

The hours of the second seed that fall in the storm set are simulated again with
``truth_seed2``: they must give the bits of ``truth_seed2.zarr`` (checked, printed). The ceiling
rows also give the window sum's seed sd from the same stratified variance, beside the truth
target's own ceiling (``sqrt(r)`` of an evenly spaced store, the weighted one of a stratified store).

With ``--second-seed-storm K``, the truth target's noise floor of both designs, evenly spaced and
with a storm stratum of K hours (the same number of hours as ``truth_seed2.zarr``), is printed:
the one the store holds is read, the other is simulated into ``--work``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import reconstruction as rec  # noqa: E402

STREAMS = ("truth_seed2", "truth_seed3", "truth_seed4")


def seed2_design(ms: str, results: Path, stores: dict, storm: int) -> int:
    """The storm stratum ``truth_seed2.zarr`` was drawn with: 0 (evenly spaced) or ``storm``
    (``truth.second_seed_storm`` of the config, the default since 473affb).

    :func:`measure` weights the calm hours' seed variance by the window hours each second-seed
    hour stands for, and :func:`target_floor` simulates the design the store does not hold: both
    need to know which design it is. Stops, naming the store, when it is neither.
    """
    from moorlife import truth as kernels

    idx, hs = stores["truth"]["hindcast_index"].values, stores["truth"]["hs"].values
    s2 = stores["seed2"]["hindcast_index"].values
    for design in dict.fromkeys((0, int(storm))):
        if design < s2.size and np.array_equal(
            idx[kernels.second_seed_subset(idx.size, s2.size, hs=hs, storm=design)], s2
        ):
            return design
    raise SystemExit(
        f"{results}/{ms}/truth_seed2.zarr: its {s2.size} hours are neither the evenly spaced subset nor the one with "
        f"truth.second_seed_storm = {storm} (config/config.yaml): rebuild it (snakemake -R truth_hours_seed2 ...)"
    )


def records(cfg: dict, ms: str, results: Path, work: Path, stores: dict, hs_min: float) -> tuple[np.ndarray, list]:
    """The window positions of the storm hours and their three extra records (simulated when absent)."""
    from moorlife.io import write_zarr

    truth, seed2 = stores["truth"], stores["seed2"]
    idx = truth["hindcast_index"].values
    storm = np.flatnonzero(truth["hs"].values >= hs_min)
    cases = work / "cases.zarr"
    if cases.exists():  # a run before: its hours, whichever second seed chose the extra ones
        held = rec._open(cases)["hindcast_index"].values
        pick = np.searchsorted(idx, held)
        if not (np.array_equal(idx[np.clip(pick, 0, idx.size - 1)], held) and np.isin(storm, pick).all()):
            raise SystemExit(
                f"{cases}: not the storm hours (Hs >= {hs_min} m) of {ms}'s truth window: pass another --work"
            )
    else:
        # the second seed's hours inside the storm set, plus a few others: the bit check of the streams
        extra = np.searchsorted(idx, seed2["hindcast_index"].values[::20])
        pick = np.union1d(storm, extra)
        work.mkdir(parents=True, exist_ok=True)
        hours = rec._open(results / "truth" / "hours.zarr")  # the window's sea states, in the truth's order
        if not np.array_equal(hours["hindcast_index"].values, idx):
            raise SystemExit(f"{results}/truth/hours.zarr is not the window of {ms}'s truth.zarr")
        write_zarr(hours.isel(case=pick), cases)
    out = []
    for s in STREAMS:
        store = work / f"{s}.zarr"
        if not store.exists():
            rec.simulate_cases(cfg, ms, results, cases, store, stream=s, threads=2, log=work / f"{s}.log")
        out.append(rec._open(store))
    s2i = seed2["hindcast_index"].values
    both = np.intersect1d(idx[pick], s2i)
    same = np.array_equal(
        out[0]["damage_sn"].values[np.searchsorted(idx[pick], both)],
        seed2["damage_sn"].values[np.searchsorted(s2i, both)],
    )
    print(
        f"{ms}: {storm.size} storm hours (Hs >= {hs_min} m); {both.size} hours of truth_seed2 simulated again: "
        f"{'bit-identical' if same else 'DIFFERENT'}",
        file=sys.stderr,
    )
    if not same:
        raise SystemExit(f"{ms}: the extra records do not reproduce truth_seed2.zarr: not the truth target's streams")
    return pick, out


def measure(
    ms: str, stores: dict, pick: np.ndarray, extra: list, variants: dict, hs_min: float, design: int = 0
) -> list[str]:
    """The markdown rows of one system (S-N damage per line); ``design`` from :func:`seed2_design`."""
    from moorlife import lifecycle
    from moorlife import truth as kernels
    from moorlife.stages import thrust_for

    truth, seed2 = stores["truth"], stores["seed2"]
    idx = truth["hindcast_index"].values
    hs = truth["hs"].values
    x = truth["damage_sn"].transpose("case", "line").values
    lines = truth["line"].values.astype(object).astype(str)
    in_storm = hs[pick] >= hs_min
    spos = pick[in_storm]
    rec4 = np.stack([x[spos]] + [e["damage_sn"].transpose("case", "line").values[in_storm] for e in extra])
    nv_storm = rec4.var(axis=0, ddof=1)  # (storm hours, line)
    p2 = np.searchsorted(idx, seed2["hindcast_index"].values)
    calm = hs[p2] < hs_min
    x2 = seed2["damage_sn"].transpose("case", "line").values
    n, n_storm = x.shape[0], spos.size
    # the window's calm hours: each second-seed hour weighted by the window hours it stands for
    # (all alike for the evenly spaced subset); the truth target's own ceiling beside it
    w = kernels.strata_weights(n, p2, hs=hs, storm=design)
    nv_calm = np.average((0.5 * (x[p2] - x2) ** 2)[calm], axis=0, weights=w[calm])
    subset = kernels.noise_floor(x[p2], x2, n_window=n, window=x, weights=w if design else None)["r_ceiling"]
    noise = (nv_storm.sum(axis=0) + (n - n_storm) * nv_calm) / n
    ceiling = np.sqrt(np.clip(1.0 - noise / x.var(axis=0), 0.0, 1.0))
    sum_sd = 100.0 * np.sqrt(noise * n) / x.sum(axis=0)  # the window sum's seed sd, % (stratified)
    label = "subset" if design == 0 else f"the target's, storm {design}"
    rows = []
    for j, ln in enumerate(lines):
        share = nv_storm[:, j].sum() / (noise[j] * n)
        rows.append(
            f"| {ms} | {ln} | ceiling | {subset[j]:.4f} ({label}) / **{ceiling[j]:.4f}** (stratified) | "
            f"| storm noise {100 * share:.0f} % of the window's; the sum's seed sd {sum_sd[j]:.2f} % | | |"
        )
    for name, overlays in variants.items():
        cfg = rec.study(overlays)
        settings = lifecycle.rbf_settings(cfg["lifecycle"]["rbf"])
        lc = lifecycle.reconstruct_lifecycle(
            stores["hindcast"],
            stores["cases"],
            stores["sims"],
            settings=settings,
            fatigue_cfg=cfg["fatigue"],
            compare_transforms=False,
            thrust=thrust_for(settings, rec.ROOT / cfg["platform"], cfg["simulation"]["wind"]),
        )
        p = lc["damage_sn"].isel(time=idx).transpose("time", "line").values
        for j, ln in enumerate(lines):
            e2 = (p[:, j] - x[:, j]) ** 2
            storm_sse = e2[spos].sum()
            r_k = []  # the per-hour r against the window with the storm hours of record k
            for k in range(rec4.shape[0]):
                xk = x[:, j].copy()
                xk[spos] = rec4[k, :, j]
                r_k.append(np.corrcoef(p[:, j], xk)[0, 1])
            xm = x[:, j].copy()
            xm[spos] = rec4[:, :, j].mean(axis=0)  # the storm hours' seed noise divided by four
            rows.append(
                f"| {ms} | {ln} | {name} | {r_k[0]:.4f} ({min(r_k):.4f}-{max(r_k):.4f}) | "
                f"{np.corrcoef(p[:, j], xm)[0, 1]:.4f} | "
                f"{100 * storm_sse / e2.sum():.0f} % | {storm_sse / nv_storm[:, j].sum():.2f} | "
                f"{p[spos, j].sum() / rec4[:, :, j].mean(axis=0).sum():.3f} |"
            )
    return rows


def target_floor(cfg: dict, ms: str, results: Path, work: Path, stores: dict, storm: int, design: int) -> str:
    """The truth target's noise floor of the S-N damage, evenly spaced and with a storm stratum of
    ``storm`` hours (``truth.second_seed_storm``): ceiling of the per-hour r and the window sum's
    seed sd, per line. ``truth_seed2.zarr`` holds the design ``design`` (:func:`seed2_design`); the
    other is simulated into ``work`` (reused when present)."""
    from moorlife import truth as kernels
    from moorlife.io import write_zarr

    truth, seed2 = stores["truth"], stores["seed2"]
    idx, hs = truth["hindcast_index"].values, truth["hs"].values
    n, k = idx.size, seed2.sizes["case"]
    x = truth["damage_sn"].transpose("case", "line").values
    floors = {}
    for d, name in ((0, "even"), (storm, "stratified")):
        pick = kernels.second_seed_subset(n, k, hs=hs, storm=d)
        if d == design:
            rec2 = seed2
        else:
            cases, store = work / f"{name}_cases.zarr", work / f"{name}_seed2.zarr"
            if not cases.exists():
                write_zarr(rec._open(results / "truth" / "hours.zarr").isel(case=pick), cases)
            if not store.exists():
                rec.simulate_cases(
                    cfg, ms, results, cases, store, stream="truth_seed2", threads=2, log=work / f"{name}.log"
                )
            rec2 = rec._open(store)
        weights = kernels.strata_weights(n, pick, hs=hs, storm=d) if d else None
        y = rec2["damage_sn"].transpose("case", "line").values
        floors[name] = kernels.noise_floor(x[pick], y, n_window=n, window=x, weights=weights)
    even, strat = floors["even"], floors["stratified"]

    def f(v, d):
        return " / ".join(f"{u:.{d}f}" for u in v)

    return (
        f"| {ms} | {f(even['r_ceiling'], 3)} | {f(strat['r_ceiling'], 3)} | "
        f"{f(even['sum_std_pct'], 2)} | {f(strat['sum_std_pct'], 2)} |"
    )


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--results", type=Path, default=rec.ROOT / "results")
    ap.add_argument("--systems", nargs="+", default=["MS1", "MS2"])
    ap.add_argument("--hs", type=float, default=5.0, help="storm hours: Hs >= this (m)")
    ap.add_argument("--variant", action="append", default=[], help="NAME=OVERLAY[,OVERLAY...] (empty: config.yaml)")
    ap.add_argument("--work", type=Path, default=rec.ROOT / "results" / "storm_noise")
    ap.add_argument(
        "--second-seed-storm",
        type=int,
        default=0,
        help="also the truth target's noise floor with this storm stratum (truth.second_seed_storm)",
    )
    a = ap.parse_args(argv)
    variants = {v.split("=", 1)[0]: [o for o in v.split("=", 1)[1].split(",") if o] for v in a.variant}
    base = rec.study([])
    out = [
        f"Storm hours: Hs >= {a.hs} m, four records each. Columns: per-hour r of the S-N damage against the truth "
        "(in brackets its range over the four records of the storm hours), and against the truth with the storm hours "
        "at the mean of their four records; the storm's share of "
        "the squared error; that error over the storm's summed seed variance (1: a perfect reconstruction); the "
        "storm's reconstructed damage over the four records' mean. Ceiling rows: the truth target's ceiling "
        "(sqrt(r) of an evenly spaced second seed, the weighted one of a stratified one), and the stratified "
        "ceiling of the four records.",
        "",
        "| system | line | variant | per-hour r | r, storm hours at their 4-record mean "
        "| storm share of squared error | storm error / storm noise | storm sum / 4-record mean |",
        "|---|---|---|---|---|---|---|---|",
    ]
    target = [
        "",
        f"The truth target's noise floor of the S-N damage (M1 / M2 / M3): 'even' is truth_seed2.zarr, "
        f"'stratified' truth.second_seed_storm = {a.second_seed_storm} of the same number of hours.",
        "",
        "| system | ceiling, even | ceiling, stratified | sum's seed sd %, even | sum's seed sd %, stratified |",
        "|---|---|---|---|---|",
    ]
    for ms in a.systems:
        stores = rec.load(a.results, ms)
        if stores is None or stores.get("truth") is None or stores.get("seed2") is None:
            print(f"{ms}: no truth.zarr / truth_seed2.zarr under {a.results}: skipped", file=sys.stderr)
            continue
        design = seed2_design(ms, a.results, stores, base["truth"]["second_seed_storm"])
        pick, extra = records(base, ms, a.results, a.work / ms, stores, a.hs)
        out += measure(ms, stores, pick, extra, variants, a.hs, design)
        if a.second_seed_storm:
            if design not in (0, a.second_seed_storm):
                raise SystemExit(
                    f"--second-seed-storm {a.second_seed_storm}: {ms}'s truth_seed2.zarr has a stratum of {design}"
                )
            target.append(target_floor(base, ms, a.results, a.work / ms, stores, a.second_seed_storm, design))
        print(f"{ms}: done", file=sys.stderr, flush=True)
    print("\n".join(out + (target if a.second_seed_storm else [])))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
