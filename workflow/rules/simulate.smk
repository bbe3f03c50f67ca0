# Stage 'simulate': coupled time-domain simulation of every selected sea state and of every bin
# of the conventional scatter matrix, per mooring system (paper section 3.3). Batches of sea
# states are fanned out with Dask (moorlife.stages.fanout.map_cases); a killed run resumes.
# simulation.batch_size is scheduling only: it is not a param (the adapter reads it from the
# config), so changing it reruns nothing and keeps a partial store.


rule simulate_cases:
    input:
        cases="results/selection/cases.zarr",
        platform="results/hydro/platform.nc",
        platform_cfg=config["platform"],
    output:
        store=directory("results/{ms}/simulations.zarr"),
    log:
        "logs/{ms}/simulate_cases.log",
    conda:
        "../../envs/moorlife.yaml"
    threads: all_cores()
    params:
        dim="case",
        ms=lambda wc: wc.ms,
        row=lambda wc: mooring_row(wc.ms),
        seed=config["seed"],
        simulation=result_settings(config, "simulation"),
        mooring=config.get("mooring", {}),
        fatigue=config["fatigue"],
        statistics=config.get("statistics", {}),
    script:
        "../scripts/simulate.py"


use rule simulate_cases as simulate_discrete with:
    input:
        cases="results/selection/discrete.zarr",
        platform="results/hydro/platform.nc",
        platform_cfg=config["platform"],
    output:
        store=directory("results/{ms}/discrete.zarr"),
    log:
        "logs/{ms}/simulate_discrete.log",
    params:
        dim="bin",
