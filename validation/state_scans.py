"""One-variable scans through the worst validation states of one damage output (issue 22).

    OMP_NUM_THREADS=1 python validation/state_scans.py --results results --system MS1 --line M1 \\
        --work scans/MS1 --variant paper= --variant gp=validation/overlays/gp_matern52_sdT_choose.yaml

Each ``--variant NAME=OVERLAY[,OVERLAY...]`` is fitted on the study's training states as
``validation/reconstruction.py`` fits it (``lifecycle.fit_outputs``; the first variant ranks the
states). The script then:

1. lists the ``--worst`` validation states of ``damage_sn`` of ``--line`` by their squared error
   against their one record, with each variant's prediction and the state's share of the squared error;
2. scans through the ``--scans`` worst ones, one variable at a time, the others held at the state's
   values: the wind direction (the state's +/- 60 deg, step 5), the wind speed (9-20 m/s, step 0.5)
   and Hs (0.3-3 m);
3. simulates every scan point three times with the simulate stage (random streams
   ``validation_seed2`` .. ``validation_seed4``, case ids from 900000, into ``--work``, reused when
   present) and prints, per point, the three records, their mean and every variant's prediction.

The scans show the shape of the function the reconstruction interpolates where it errs most,
beside the seed scatter of one record.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import reconstruction as rec  # noqa: E402

VARS = ("wind_speed", "wind_dir", "hs", "tp", "wave_dir")
STREAMS = ("validation_seed2", "validation_seed3", "validation_seed4")
FIRST_ID = 900000


def fit(cfg: dict, stores: dict) -> tuple:
    """The variant's model on the training states, its output columns, all points and values, roles."""
    from moorlife import lifecycle
    from moorlife.stages import thrust_for

    cases, sims = stores["cases"], stores["sims"]
    settings = lifecycle.rbf_settings(cfg["lifecycle"]["rbf"])
    cols = lifecycle.output_columns(sims, "case", settings.outputs)
    x, y = lifecycle._points(cases, "case"), lifecycle.stack_outputs(sims, "case", cols)
    lo, span = lifecycle._selection_scaling(cases)
    role = cases["role"].values.astype(object).astype(str)
    tr = role == "train"
    thrust = thrust_for(settings, rec.ROOT / cfg["platform"], cfg["simulation"]["wind"])
    model = lifecycle.fit_outputs(x[tr], y[tr], cols, settings, lo=lo, span=span, thrust=thrust)
    return model, cols, x, y, role


def scan_points(base: np.ndarray) -> list[tuple[str, int, np.ndarray]]:
    """(variable, column, point) of the three scans through ``base`` (VARS order)."""
    grid = {
        "wind_dir": (1, base[1] + np.arange(-60.0, 60.1, 5.0)),
        "wind_speed": (0, np.arange(9.0, 20.01, 0.5)),
        "hs": (2, np.array([0.3, 0.6, 0.9, 1.2, 1.6, 2.0, 2.5, 3.0])),
    }
    out = []
    for name, (k, values) in grid.items():
        for v in values:
            p = base.copy()
            p[k] = v % 360.0 if k == 1 else v
            out.append((name, k, p))
    return out


def records(cfg: dict, ms: str, results: Path, work: Path, cases, template: int, pts: np.ndarray, line: str):
    """Three records of ``damage_sn`` of ``line`` at ``pts`` (simulated into ``work`` when absent)."""
    from moorlife.io import write_zarr

    path = work / "cases.zarr"
    if path.exists():
        from moorlife import lifecycle

        held = lifecycle._points(rec._open(path), "case")
        if held.shape != pts.shape or not np.allclose(held, pts, rtol=0, atol=1e-4):
            raise SystemExit(f"{path}: other scan points than this run's; pass another --work")
    else:
        work.mkdir(parents=True, exist_ok=True)
        ds = cases.isel(case=[template] * len(pts)).assign_coords(case=np.arange(FIRST_ID, FIRST_ID + len(pts)))
        for k, v in enumerate(VARS):
            ds[v] = ("case", pts[:, k].astype(ds[v].dtype))
        write_zarr(ds, path)
    out = []
    for s in STREAMS:
        store = work / f"{s}.zarr"
        if not store.exists():
            rec.simulate_cases(cfg, ms, results, path, store, stream=s, threads=2, log=work / f"{s}.log")
        out.append(rec._open(store)["damage_sn"].sel(line=line).values)
    return np.array(out)


def main(argv: list[str] | None = None) -> int:
    from moorlife import lifecycle

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--results", type=Path, default=rec.ROOT / "results")
    p.add_argument("--system", default="MS1")
    p.add_argument("--line", default="M1")
    p.add_argument("--work", type=Path, required=True)
    p.add_argument("--variant", action="append", default=[], help="NAME=OVERLAY[,OVERLAY...] (empty: config.yaml)")
    p.add_argument("--worst", type=int, default=12)
    p.add_argument("--scans", type=int, default=2)
    a = p.parse_args(argv)
    stores = rec.load(a.results, a.system)
    if stores is None:
        p.error(f"--results {a.results}: no {a.system}/simulations.zarr")
    cfgs = {}
    for spec in a.variant or ["paper="]:
        name, _, files = spec.partition("=")
        cfgs[name] = rec.study([f for f in files.split(",") if f])
    fits = {name: fit(cfg, stores) for name, cfg in cfgs.items()}
    first = next(iter(fits))
    _, cols, x, y, role = fits[first]
    j = cols.index(("damage_sn", a.line))
    val = np.flatnonzero(role == "validate")
    pred = {k: lifecycle.predict_outputs(f[0], x[val])[:, j] for k, f in fits.items()}
    err = (pred[first] - y[val, j]) ** 2
    order = np.argsort(err)[::-1]
    print(f"# {a.system} damage_sn[{a.line}]: the {a.worst} worst of {val.size} validation states ({first})\n")
    print("| " + " | ".join(VARS) + " | record | " + " | ".join(fits) + " | share |")
    print("|" + "---|" * (len(VARS) + len(fits) + 2))
    for i in order[: a.worst]:
        row = [f"{v:.2f}" for v in x[val[i]]] + [f"{y[val[i], j]:.3e}"] + [f"{pred[k][i]:.3e}" for k in fits]
        print("| " + " | ".join(row) + f" | {err[i] / err.sum():.3f} |")
    scans = [(rank, *s) for rank, i in enumerate(order[: a.scans]) for s in scan_points(x[val[i]])]
    pts = np.array([s[3] for s in scans])
    recs = records(cfgs[first], a.system, a.results, a.work, stores["cases"], int(val[order[0]]), pts, a.line)
    at = {k: lifecycle.predict_outputs(f[0], pts)[:, j] for k, f in fits.items()}
    last = None
    for n, (rank, name, k, pt) in enumerate(scans):
        if (rank, name) != last:
            state = ", ".join(f"{v} {pt[c]:.2f}" for c, v in enumerate(VARS) if c != k)
            print(f"\n## {name} through the worst state #{rank + 1} ({state})\n")
            print(f"| {name} | three records | mean | " + " | ".join(fits) + " |")
            print("|---|---|---|" + "---|" * len(fits))
            last = (rank, name)
        three = " ".join(f"{r:.3e}" for r in recs[:, n])
        print(
            f"| {pt[k]:.2f} | {three} | {recs[:, n].mean():.3e} | " + " | ".join(f"{at[v][n]:.3e}" for v in fits) + " |"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
