# Stage 'replicates': seed replicates of the training states that hold the damage, per mooring
# system (lifecycle.replicates.states > 0). After the MDA states and every adaptive round, the
# fit ranks the training states (lifecycle.replicates.rank: the share of the life-cycle damage of
# the hours nearest to each, or of the records' seed variance in the sums); the top ones are simulated again, once per seed, by the simulate stage as
# it is (use rule), under their own case ids and the random streams replicate1 .. replicatek.
# The lifecycle stage fits the mean of their records.


wildcard_constraints:
    j="[1-9][0-9]*",


rule replicate_picks:
    input:
        hindcast="results/metocean/hindcast.zarr",
        cases="results/selection/cases.zarr",
        simulations="results/{ms}/simulations.zarr",
        rounds=expand("results/{{ms}}/rounds/picks_{r}.zarr", r=ROUNDS),
        round_simulations=expand("results/{{ms}}/rounds/simulations_{r}.zarr", r=ROUNDS),
        platform_cfg=config["platform"],
    output:
        store=directory("results/{ms}/replicates/picks.zarr"),
    log:
        "logs/{ms}/replicates/picks.log",
    conda:
        "../../envs/moorlife.yaml"
    resources:
        mem_mb=2000,
    params:
        # lifecycle.rbf without its memory-only key: the fit of the picks (a change reruns it)
        rbf=result_settings(config, "lifecycle")["rbf"],
        states=REPLICATES["states"],
        seeds=REPLICATES["seeds"],
        rank=REPLICATES["rank"],
    script:
        "../scripts/replicate_picks.py"


use rule simulate_cases as simulate_replicate with:
    input:
        cases="results/{ms}/replicates/picks.zarr",
        platform="results/hydro/platform.nc",
        platform_cfg=config["platform"],
    output:
        store=directory("results/{ms}/replicates/simulations_{j}.zarr"),
    log:
        "logs/{ms}/replicates/simulate_{j}.log",
    params:
        dim="case",
        stream=lambda wc: f"replicate{wc.j}",  # moorlife.selection.replicates.replicate_stream
