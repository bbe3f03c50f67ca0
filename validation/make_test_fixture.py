"""Regenerate tests/data/platform_coarse.nc: the package's own coarse-mesh Capytaine run.

The hydro settings of config/config.yaml + config/quick.yaml (coarse mesh, 40 frequencies,
headings every 30 deg) on config/platform.yaml. A committed fixture lets the simulator's and
the hydro tests load a real platform model without running a BEM (about 2 min on 2 cores).

    .venv/bin/python validation/make_test_fixture.py
"""

from pathlib import Path

from moorlife.hydro import bem_from_settings, bem_settings
from moorlife.io import read_study_config, read_yaml
from moorlife.io.platform import write_platform_nc

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    cfg = read_study_config(
        ROOT / "config/config.yaml", (ROOT / "config/quick.yaml",), schema=ROOT / "workflow/schemas/config.schema.yaml"
    )
    settings = bem_settings(cfg["hydro"], read_yaml(ROOT / "config/platform.yaml"))
    ds = bem_from_settings(settings, n_jobs=1)
    out = write_platform_nc(ds, ROOT / "tests/data/platform_coarse.nc")
    print(f"{out}: {out.stat().st_size / 1e3:.0f} kB, {ds.attrs['panels']} panels")


if __name__ == "__main__":
    main()
