"""Experiment: the rotor thrust T(W) as a sixth RBF coordinate (beyond the paper's 5-D space).

Usage::

    .venv/bin/python validation/rbf_thrust_coordinate.py RESULTS MS1 [MS5 ...]

For each system, fits the lifecycle RBF (default settings) on the stored training states in the
paper's 5-D space and in 6-D spaces that add ``T(W)`` (the NREL 5 MW thrust of the hub wind,
``config/platform.yaml``) scaled to a range of 1 (``6d_T``) or 0.5 (``6d_T0.5``), and prints the
validation r on the 225 states. Motivation: the damage of the lines away from the waves peaks
in a narrow band of wind speed just above rated (11.4-12.5 m/s), narrower than any useful shape
parameter in W; in T(W) that band is the maximum of one coordinate.
"""
import sys, warnings, numpy as np, xarray as xr, time
warnings.filterwarnings("ignore")
from moorlife import lifecycle as lc, rbf, names, turbine
from moorlife.io import read_yaml
R = sys.argv[1]
pcfg = read_yaml("config/platform.yaml")["turbine"]
ws, ct = turbine.ct_table(pcfg)
cases0 = xr.open_zarr(f"{R}/selection/cases.zarr", consolidated=False).load()
st = lc.RBFSettings()
grid = rbf.shape_grid(st.grid_min, st.grid_max, st.grid_n)
for ms in sys.argv[2:]:
    sims = xr.open_zarr(f"{R}/{ms}/simulations.zarr", consolidated=False).load()
    dim = names.CASE; common = np.intersect1d(cases0[dim].values, sims[dim].values)
    cases, sims = cases0.sel({dim: common}), sims.sel({dim: common})
    role = np.array([str(v) for v in cases["role"].values]); tr, va = role == "train", role == "validate"
    cols = lc.output_columns(sims, dim, st.outputs); y = lc.stack_outputs(sims, dim, cols)
    x = lc._points(cases, dim); lo, span = lc._selection_scaling(cases)
    labels = [lc._label(c) for c in cols]; isd = np.array([c[0].startswith("damage") for c in cols])
    mask = np.array([v.endswith("dir") for v in names.METOCEAN_VARS])
    T = turbine.thrust(x[:, 0], ws, ct); tmax = turbine.thrust(np.linspace(0, 30, 3001), ws, ct).max()
    res = {}
    for name, w in [("5d", None), ("6d_T", 1.0), ("6d_T0.5", 0.5)]:
        if w is None:
            X, m_, l_, s_ = x, mask, lo, span
        else:
            X = np.column_stack([x, T]); m_ = np.r_[mask, False]; l_ = np.r_[lo, 0.0]; s_ = np.r_[span, tmax / w]
        t = time.time()
        m = rbf.fit_rbf(X[tr], y[tr], is_direction=m_, log_output=isd, shapes=grid, smoothing=st.smoothing, lo=l_, span=s_)
        res[name] = lc.validation_metrics(rbf.predict_rbf(m, X[va]), y[va])["r"]
        print(ms, name, "%.0f s" % (time.time() - t), flush=True)
    for j, lab in enumerate(labels):
        if "_tn" in lab: continue
        print("  ", lab.ljust(16), *["%.4f" % res[k][j] for k in res])
    print("   min", *["%.4f" % res[k].min() for k in res], "mean", *["%.4f" % res[k].mean() for k in res])
