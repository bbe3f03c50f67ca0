"""Rule `hydro`: BEM (Capytaine) or WAMIT import -> results/hydro/platform.nc."""
from moorlife.hydro import bem_from_settings
from moorlife.io import log_to
from moorlife.io.platform import write_platform_nc
from moorlife.io.wamit import read_wamit_dataset


def main(smk):
    p, env = smk.params.bem, smk.params.bem["environment"]
    with log_to(smk.log[0]):
        if p["source"] == "wamit":
            ds = read_wamit_dataset(p["wamit_prefix"], rho=env["rho_water"], g=env["gravity"], water_depth=env["water_depth"])
        else:
            ds = bem_from_settings(p, n_jobs=smk.threads)
        write_platform_nc(ds, smk.output[0])


if __name__ == "__main__":
    main(snakemake)  # noqa: F821
