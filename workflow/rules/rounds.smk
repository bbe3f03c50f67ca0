# Stage 'rounds': adaptive selection per mooring system (lifecycle.adaptive.rounds > 0). Round r
# fits the RBF on the MDA states and the rounds before r, picks lifecycle.adaptive.per_round
# hindcast hours where the reconstruction is least sure (never a simulated or validation
# state), and simulates them with the simulate stage as it is (use rule), under their own case
# ids and random stream. The rounds are numbered at parse time: no checkpoint; each round is
# its own pair of stores, and a killed round resumes like any simulation.


wildcard_constraints:
    r="[1-9][0-9]*",


rule adaptive_picks:
    input:
        hindcast="results/metocean/hindcast.zarr",
        cases="results/selection/cases.zarr",
        simulations="results/{ms}/simulations.zarr",
        rounds=earlier_rounds("picks"),
        round_simulations=earlier_rounds("simulations"),
        platform_cfg=config["platform"],
    output:
        store=directory("results/{ms}/rounds/picks_{r}.zarr"),
    log:
        "logs/{ms}/rounds/picks_{r}.log",
    conda:
        "../../envs/moorlife.yaml"
    resources:
        mem_mb=2000,
    params:
        # lifecycle.rbf without its memory-only key: the fit of the round (a change reruns it)
        rbf=result_settings(config, "lifecycle")["rbf"],
        per_round=ADAPTIVE["per_round"],
        number=lambda wc: int(wc.r),
    script:
        "../scripts/adaptive_picks.py"


use rule simulate_cases as simulate_round with:
    input:
        cases="results/{ms}/rounds/picks_{r}.zarr",
        platform="results/hydro/platform.nc",
        platform_cfg=config["platform"],
    output:
        store=directory("results/{ms}/rounds/simulations_{r}.zarr"),
    log:
        "logs/{ms}/rounds/simulate_{r}.log",
    params:
        dim="case",
        stream="adaptive",  # moorlife.selection.rounds.ROUND_STREAM
