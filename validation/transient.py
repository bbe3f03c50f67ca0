"""Issue 23, target 2: does a 200 s transient from the mean equilibrium change any output statistic?

For each sea state and mooring system, the waves and wind are synthesised once on the grid of
today's record (600 s transient + 3,600 s kept) and the same kept window, t = 600-4,200 s of
that realisation, is simulated several ways (a paired comparison: only the start differs):

* ``rest600``: at rest at the trimmed origin, 600 s transient (the start before issue 23;
  this variant is ``simulate_batch`` itself with ``simulation.start: rest``);
* ``eq600``, ``eq200`` and ``eq100``: at rest at the record's mean equilibrium
  (:func:`moorlife.simulate.equilibrium_start`), started 600, 200 or 100 s before the window;
* ``ref``: the mean equilibrium 1,800 s before the window, the converged reference (the
  synthesis is periodic with its FFT period, so the earlier forcing is the same realisation:
  :func:`window_forcing`);
* ``rest200``: at rest at the origin, 200 s before the window (the control: a shorter
  transient without the equilibrium start).

The seed-to-seed scatter is ``rest600`` with a second seed (another realisation of the same
states). Every statistic of ``simulate_batch`` is compared: per statistic (and line), the paired
differences ``d = variant - rest600`` (and ``variant - ref``) over all states (log ratios for the
damages) against the one-seed standard deviation ``sigma = RMS(rest600(seed) - rest600(seed2)) /
sqrt(2)``.

The test (both must hold for every statistic except the GEV-fit correlations, diagnostics):

1. no bias beyond the seed scatter: ``|mean(d)| <= 0.1 sigma``; the t value
   ``mean(d) / SE(d)`` is reported beside it;
2. the per-state change is small against the seed scatter: ``RMS(d) <= 0.25 sigma`` (it would add
   at most 3 % to the scatter in quadrature).

Usage (all variants: 7.1 simulated hours per state and system, 12-13 CPU-s on this host with
dynamic lines; results as Markdown on stdout, per system as soon as it is done, the raw
statistics in ``--out``)::

    nice -n 5 .venv/bin/python validation/transient.py --platform results/hydro/platform.nc \\
        --cases results/selection/cases.zarr --n-states 50 --systems MS1 MS5 --out transient.npz
    # a subset: --variants eq200 ref (rest600 and the second seed always run)
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

from moorlife import environment as env
from moorlife import names
from moorlife import simulate as sim
from moorlife.io import open_zarr, read_mooring_systems, read_yaml
from moorlife.io.platform import open_platform_nc, read_platform_config
from moorlife.settings import SimulationSettings, StatisticsSettings

ROOT = Path(__file__).resolve().parents[1]
VARIANTS = {
    "rest600": ("rest", 600.0),
    "eq600": ("equilibrium", 600.0),
    "eq200": ("equilibrium", 200.0),
    "eq100": ("equilibrium", 100.0),
    "ref": ("equilibrium", 1800.0),
    "steady200": ("steady", 200.0),
    "steady100": ("steady", 100.0),
    "steady300": ("steady", 300.0),
    "eq300": ("equilibrium", 300.0),
    "eq400": ("equilibrium", 400.0),
}
CONTROL = {"rest200": ("rest", 200.0)}
BIAS_LIMIT, RMS_LIMIT = 0.1, 0.25


def row_of(ms: str) -> dict:
    table = read_mooring_systems(ROOT / "config/mooring_systems.tsv")
    r = table.loc[ms]
    return {**{k: (v.item() if hasattr(v, "item") else v) for k, v in r.items()}, "mooring_system": ms}


def periodic_forcing(model, sea, ids, ms, seed, settings) -> sim.Forcing:
    """One whole period (``n_fft`` samples) of the forcing of today's record grid (600 s + duration).

    The synthesis is periodic with the FFT period, so the forcing of any earlier start that
    ends in the same kept window is this one, repeated (:func:`window_forcing`). Its first
    ``n_steps + 1`` samples are bit for bit those of the record itself.
    """
    from moorlife.simulate.batch import period_grid

    period = period_grid(env.record_grid(settings.duration, 600.0, settings.dt))
    return sim.batch_forcing(
        sea, case_ids=ids, mooring_system=ms, seed=seed, model=model, settings=settings, grid=period
    )


def window_forcing(periodic: sim.Forcing, lead: float, duration: float) -> sim.Forcing:
    """The forcing of a record that starts ``lead`` s before the kept window (t = 600 s of today's record)."""
    g = periodic.grid
    n_fft, ke = g.n_fft, periodic.kin_every
    if n_fft % ke:
        raise ValueError("the FFT period must be a whole number of kinematics samples")
    shift = int(round((600.0 - lead) / g.dt))  # first sample, on the periodic time axis
    if shift % ke:
        raise ValueError("the lead must be a whole number of kinematics samples")
    n_steps = int(round((lead + duration) / g.dt))

    def take(a: np.ndarray, period: int, first: int, count: int) -> np.ndarray:
        idx = (first + np.arange(count)) % period
        return np.ascontiguousarray(np.take(a[:, :period], idx, axis=1))

    return sim.Forcing(
        grid=env.RecordGrid(dt=g.dt, n_steps=n_steps, n_fft=n_fft, d_omega=g.d_omega),
        force=take(periodic.force, n_fft, shift, n_steps + 1),
        wind=take(periodic.wind, n_fft, shift, n_steps + 1),
        wind_dir=periodic.wind_dir,
        kin_every=ke,
        kinematics=take(periodic.kinematics, n_fft // ke, shift // ke, n_steps // ke + 2),
    )


def run_variants(model, sea, ids, ms, seed, cfg, variants) -> dict[str, dict[str, np.ndarray]]:
    """Statistics of one batch for every variant, all over the same window of one realisation."""
    sim_cfg = dict(cfg["simulation"])
    settings = SimulationSettings.from_config({**sim_cfg, "transient": 600.0}, source="simulation")
    stats = StatisticsSettings.from_config(cfg.get("statistics"), source="statistics")
    periodic = periodic_forcing(model, sea, ids, ms, seed, settings)
    out = {}
    for name, (start, lead) in variants.items():
        f = window_forcing(periodic, lead, settings.duration)
        if name == "rest600":  # today's code path, end to end; the same forcing bit for bit
            out[name] = sim.simulate_batch(
                sea,
                case_ids=ids,
                mooring_system=ms,
                seed=seed,
                model_inputs=model,
                sim_cfg={**sim_cfg, "transient": 600.0, "start": "rest"},
                fatigue_cfg=cfg.get("fatigue"),
                stats_cfg=cfg.get("statistics"),
            )
            ref = sim.batch_forcing(sea, case_ids=ids, mooring_system=ms, seed=seed, model=model, settings=settings)
            for field in ("force", "wind", "kinematics"):
                if not np.array_equal(getattr(ref, field), getattr(f, field)):
                    raise AssertionError(f"window_forcing differs from the record's forcing in {field}")
            continue
        if start == "steady":  # the linear periodic steady state of the whole period, at the start's step
            first = int(round((600.0 - lead) / settings.dt))
            st = sim.steady_start(model, periodic, periodic.grid.n_fft, first=first)
        else:
            st = sim.equilibrium_start(model, f) if start == "equilibrium" else None
        rec = sim.integrate(model, f, transient=lead, start=st)
        out[name] = sim.summarise(
            rec,
            line_info=model.line_info,
            fatigue_cfg=cfg.get("fatigue"),
            statistics=stats,
            mpm_duration=settings.mpm_duration,
        )
    return out


def statistics_of(result: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Flatten ``name`` or ``name[line]`` -> (n,) arrays."""
    flat = {}
    for name, v in result.items():
        if v.ndim == 1:
            flat[name] = v
        else:
            for i, line in enumerate(names.LINES):
                flat[f"{name}[{line}]"] = v[:, i]
    return flat


def compare(
    res: dict[str, dict[str, np.ndarray]], seed2: dict[str, np.ndarray], variant: str, against: str = "rest600"
) -> list[dict]:
    """Per statistic: bias, t value, RMS of the paired differences, seed sigma, the two ratios."""
    base, other = statistics_of(res[against]), statistics_of(res[variant])
    s2 = statistics_of(seed2)
    rows = []
    for key in base:
        a, b, c = base[key], other[key], s2[key]
        log = key.startswith("damage_")
        if log:
            d, s = np.log(b / a), np.log(a / c)
        else:
            d, s = b - a, a - c
        n = d.size
        sigma = math.sqrt(np.mean(s**2) / 2.0)
        mean, rms = float(d.mean()), float(np.sqrt(np.mean(d**2)))
        se = float(d.std(ddof=1) / math.sqrt(n)) if n > 1 else float("nan")
        rows.append(
            dict(
                stat=key,
                log=log,
                mean=mean,
                t=mean / se if se > 0 else 0.0,
                rms=rms,
                sigma=sigma,
                bias_ratio=abs(mean) / sigma if sigma > 0 else 0.0,
                rms_ratio=rms / sigma if sigma > 0 else 0.0,
                diagnostic=key.startswith("gev_corr_"),
            )
        )
    return rows


def passes(r: dict) -> bool:
    """The test of the module docstring for one statistic."""
    return r["bias_ratio"] <= BIAS_LIMIT and r["rms_ratio"] <= RMS_LIMIT


def markdown(rows: list[dict], title: str) -> str:
    lines = [
        f"#### {title}",
        "",
        "| statistic | mean d | t | RMS d | seed sigma | abs(mean)/sigma | RMS/sigma | pass |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        verdict = "diag." if r["diagnostic"] else ("yes" if passes(r) else "**no**")
        unit = " (ln)" if r["log"] else ""
        lines.append(
            f"| {r['stat']}{unit} | {r['mean']:.3g} | {r['t']:.2f} | {r['rms']:.3g} | {r['sigma']:.3g} "
            f"| {r['bias_ratio']:.3f} | {r['rms_ratio']:.3f} | {verdict} |"
        )
    return "\n".join(lines)


def summary(res: dict[str, dict[str, np.ndarray]], seed2: dict[str, np.ndarray], pairs: list) -> str:
    """One line per comparison: statistics failing, the largest ratios and where."""
    out = [
        "| comparison | states | failing | largest RMS/sigma | largest abs(mean)/sigma | damage: largest RMS/sigma |",
        "|---|---|---|---|---|---|",
    ]
    for v, against in pairs:
        rows = [r for r in compare(res, seed2, v, against) if not r["diagnostic"]]
        bad = [r for r in rows if not passes(r)]
        rm = max(rows, key=lambda r: r["rms_ratio"])
        bm = max(rows, key=lambda r: r["bias_ratio"])
        dm = max((r for r in rows if r["log"]), key=lambda r: r["rms_ratio"], default=None)
        n = next(iter(res[v].values())).shape[0]
        dam = f"{dm['rms_ratio']:.3f} ({dm['stat']})" if dm else "-"
        out.append(
            f"| {v} vs {against} | {n} | {len(bad)} of {len(rows)} | {rm['rms_ratio']:.3f} ({rm['stat']}) "
            f"| {bm['bias_ratio']:.3f} ({bm['stat']}) | {dam} |"
        )
    return "\n".join(out)


def comparisons(variants) -> list[tuple[str, str]]:
    """(variant, against) pairs: every variant against rest600, and against ref when it ran."""
    pairs = [(v, "rest600") for v in variants if v not in ("rest600", "ref")]
    return pairs + ([(v, "ref") for v in variants if v != "ref"] if "ref" in variants else [])


def reanalyse(path: str) -> str:
    """The report of the raw statistics saved by ``--out``."""
    z = np.load(path)
    out = []
    for ms in sorted({k.split("/")[0] for k in z.files}):
        res: dict[str, dict[str, np.ndarray]] = {}
        for k in z.files:
            m, v, stat = k.split("/")
            if m == ms:
                res.setdefault(v, {})[stat] = z[k]
        s2 = res.pop("rest600_seed2")
        pairs = comparisons(list(res))
        for v, against in pairs:
            out += [markdown(compare(res, s2, v, against), f"{ms}: {v} against {against}"), ""]
        out += [f"#### {ms}: summary", "", summary(res, s2, pairs), ""]
    return "\n".join(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--platform", required=True, help="results/hydro/platform.nc")
    ap.add_argument("--cases", required=True, help="results/selection/cases.zarr")
    ap.add_argument("--config", default=str(ROOT / "config/config.yaml"))
    ap.add_argument("--n-states", type=int, default=50, help="the first N cases (the MDA order: a spread)")
    ap.add_argument("--first", type=int, default=0, help="skip the first cases")
    ap.add_argument("--systems", nargs="+", default=["MS1", "MS5"])
    ap.add_argument("--seed2", type=int, default=None, help="second seed (default: config seed + 1)")
    ap.add_argument("--batch", type=int, default=5)
    ap.add_argument("--control", action="store_true", help="also the rest200 control")
    ap.add_argument("--variants", nargs="+", default=None, help="a subset of the variants (rest600 always)")
    ap.add_argument("--duration", type=float, default=None, help="kept duration in s (default: the config's)")
    ap.add_argument("--out", default=None, help="raw statistics (.npz)")
    ap.add_argument("--from-npz", default=None, help="only re-analyse the raw statistics of an earlier --out")
    args = ap.parse_args()
    if args.from_npz:
        print(reanalyse(args.from_npz))
        return

    cfg = read_yaml(args.config)
    if args.duration is not None:
        cfg["simulation"] = {**cfg["simulation"], "duration": float(args.duration)}
    seed = int(cfg["seed"])
    seed2 = seed + 1 if args.seed2 is None else int(args.seed2)
    cs = open_zarr(args.cases)
    sel = slice(args.first, min(args.first + args.n_states, cs.sizes["case"]))
    ids = np.asarray(cs["case"].values[sel])
    n = ids.size
    sea_all = {k: np.asarray(cs[k].values[sel], dtype=float) for k in names.METOCEAN_VARS}
    pcfg = read_platform_config(ROOT / "config/platform.yaml")
    platform_ds = open_platform_nc(args.platform)
    variants = {**VARIANTS, **(CONTROL if args.control else {})}
    if args.variants:
        variants = {k: v for k, v in variants.items() if k == "rest600" or k in args.variants}
    raw: dict[str, np.ndarray] = {}
    report = []
    print(
        f"states: {n} cases of {args.cases} (hs {sea_all['hs'].min():.2f}-{sea_all['hs'].max():.2f} m, "
        f"wind {sea_all['wind_speed'].min():.1f}-{sea_all['wind_speed'].max():.1f} m/s); seeds {seed}, {seed2}"
    )
    for ms in args.systems:
        t0 = time.process_time()
        model = sim.prepare_model(platform_ds, pcfg, row_of(ms), cfg.get("mooring"), cfg["simulation"])
        res: dict[str, dict[str, list]] = {v: {} for v in variants}
        other: dict[str, list] = {}
        for b0 in range(0, n, args.batch):
            sl = slice(b0, min(n, b0 + args.batch))
            sea = {k: v[sl] for k, v in sea_all.items()}
            out = run_variants(model, sea, ids[sl], ms, seed, cfg, variants)
            for v, stats in out.items():
                for k, x in stats.items():
                    res[v].setdefault(k, []).append(x)
            alt = run_variants(model, sea, ids[sl], ms, seed2, cfg, {"rest600": VARIANTS["rest600"]})["rest600"]
            for k, x in alt.items():
                other.setdefault(k, []).append(x)
            print(f"  {ms}: {sl.stop}/{n} states, {time.process_time() - t0:.0f} CPU-s", flush=True)
            if args.out:  # the raw statistics so far (--from-npz reads a partial run)
                part = {f"{ms}/{v}/{k}": np.concatenate(x) for v, st in res.items() for k, x in st.items()}
                part.update({f"{ms}/rest600_seed2/{k}": np.concatenate(x) for k, x in other.items()})
                np.savez(args.out, **raw, **part)
        cat = {v: {k: np.concatenate(x) for k, x in st.items()} for v, st in res.items()}
        s2 = {k: np.concatenate(x) for k, x in other.items()}
        for v, st in cat.items():
            for k, x in st.items():
                raw[f"{ms}/{v}/{k}"] = x
        for k, x in s2.items():
            raw[f"{ms}/rest600_seed2/{k}"] = x
        pairs = comparisons(list(variants))
        for v, against in pairs:
            rows = compare(cat, s2, v, against)
            bad = [r["stat"] for r in rows if not r["diagnostic"] and not passes(r)]
            report.append(markdown(rows, f"{ms}: {v} against {against} ({n} states)"))
            report.append("")
            report.append(f"{ms} {v} against {against}: {'PASS' if not bad else 'FAIL: ' + ', '.join(bad)}")
            report.append("")
        report.append(f"#### {ms}: summary")
        report.append("")
        report.append(summary(cat, s2, pairs))
        report.append("")
        print(f"  {ms}: {time.process_time() - t0:.0f} CPU-s in all", flush=True)
        print("\n".join(report), flush=True)  # each system as soon as it is done
        report = []
        if args.out:
            np.savez(args.out, **raw)


if __name__ == "__main__":
    main()
