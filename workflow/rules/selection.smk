# Stage 'selection': the sea states to simulate (maximum dissimilarity, paper section 3.2) and the
# conventional discrete scatter matrix the life-cycle method is compared against (section 4.1).


rule selection:
    input:
        hindcast="results/metocean/hindcast.zarr",
    output:
        store=directory("results/selection/cases.zarr"),
    log:
        "logs/selection/selection.log",
    conda:
        "../../envs/moorlife.yaml"
    resources:
        mem_mb=1000,
    params:
        n_train=N_MDA,  # selection.n_train less the rounds' and the replicates' states (common.smk)
        n_validate=config["selection"]["n_validate"],
        rule=config["selection"]["validation_rule"],
        seed=config["seed"],
    script:
        "../scripts/selection.py"


rule discrete:
    input:
        hindcast="results/metocean/hindcast.zarr",
    output:
        store=directory("results/selection/discrete.zarr"),
    log:
        "logs/selection/discrete.log",
    conda:
        "../../envs/moorlife.yaml"
    resources:
        mem_mb=500,
    params:
        hs_edges=config["selection"]["discrete"]["hs_edges"],
        wind_edges=config["selection"]["discrete"]["wind_edges"],
        tp_edges=config["selection"]["discrete"]["tp_edges"],
        sector=config["selection"]["discrete"]["direction_sector"],
    script:
        "../scripts/discrete.py"


rule selection_figures:
    input:
        hindcast="results/metocean/hindcast.zarr",
        cases="results/selection/cases.zarr",
        discrete="results/selection/discrete.zarr",
    output:
        cloud_fig=report(
            "results/figures/selection_cloud.png", caption="../report/selection_cloud.rst", category="Selection"
        ),
        discrete_fig=report(
            "results/figures/discrete_states.png", caption="../report/discrete_states.rst", category="Selection"
        ),
    log:
        "logs/selection/figures.log",
    conda:
        "../../envs/moorlife.yaml"
    resources:
        mem_mb=1000,
    script:
        "../scripts/selection_figures.py"
