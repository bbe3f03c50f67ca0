# Stage 'simulate': coupled time-domain simulation of every selected sea state and of every bin
# of the conventional scatter matrix, per mooring system (paper section 3.3). Batches of sea
# states are fanned out with Dask (moorlife.parallel.map_cases); a killed run resumes.


rule simulate_cases:
    input:
        cases="results/selection/cases.zarr",
        platform="results/hydro/platform.nc",
        platform_cfg=config["platform"],
    output:
        directory("results/{ms}/simulations.zarr"),
    params:
        dim="case",
        ms=lambda wc: wc.ms,
        row=lambda wc: mooring_row(wc.ms),
        seed=config["seed"],
        simulation=config["simulation"],
        mooring=config.get("mooring", {}),
        fatigue=config["fatigue"],
        statistics=config.get("statistics", {}),
    threads: all_cores()
    conda:
        "../../envs/moorlife.yaml"
    log:
        "logs/{ms}/simulate_cases.log",
    script:
        "../scripts/simulate.py"


rule simulate_discrete:
    input:
        cases="results/selection/discrete.zarr",
        platform="results/hydro/platform.nc",
        platform_cfg=config["platform"],
    output:
        directory("results/{ms}/discrete.zarr"),
    params:
        dim="bin",
        ms=lambda wc: wc.ms,
        row=lambda wc: mooring_row(wc.ms),
        seed=config["seed"],
        simulation=config["simulation"],
        mooring=config.get("mooring", {}),
        fatigue=config["fatigue"],
        statistics=config.get("statistics", {}),
    threads: all_cores()
    conda:
        "../../envs/moorlife.yaml"
    log:
        "logs/{ms}/simulate_discrete.log",
    script:
        "../scripts/simulate.py"
