# Stage 'hydro': platform hydrodynamic coefficients -> results/hydro/platform.nc.
# params hold exactly what changes the result (geometry, environment, mass properties and
# linear mooring stiffness behind the drift motions, grid, headings, mesh): platform.yaml is
# read here, at parse time, so editing e.g. the Ct table does not rerun the BEM.
from moorlife.hydro import bem_settings
from moorlife.io import read_yaml


def _hydro_inputs(wildcards):
    if config["hydro"]["source"] != "wamit":
        return []
    prefix = config["hydro"]["wamit_prefix"]
    if not prefix:
        raise ValueError("config hydro.wamit_prefix is required when hydro.source is 'wamit'")
    exts = [".1", ".3", ".hst"] + ([".12d"] if os.path.exists(prefix + ".12d") else [])
    return [prefix + e for e in exts]


rule hydro:
    input:
        _hydro_inputs,
    output:
        "results/hydro/platform.nc",
    params:
        bem=bem_settings(config["hydro"], read_yaml(config["platform"])),
    threads: 2
    log:
        "logs/hydro/platform.log",
    script:
        "../scripts/hydro.py"
