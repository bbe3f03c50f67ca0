# Stage 'lifecycle': rebuild every output of the simulated sea states for every hindcast hour
# with Gaussian RBF interpolation, validate it on the states kept aside, and sum the hourly
# damage over the hindcast (paper sections 3.4-3.5, methodology step 6). One job per system;
# the training states are the MDA states of cases.zarr and the system's adaptive rounds, with
# the mean of the seed replicates' records where there are any.


rule lifecycle:
    input:
        **FIT_INPUTS,
        hindcast="results/metocean/hindcast.zarr",
    output:
        store=directory("results/{ms}/lifecycle.zarr"),
    log:
        "logs/{ms}/lifecycle.log",
    conda:
        "../../envs/moorlife.yaml"
    threads: 2
    resources:
        mem_mb=2000,
    params:
        # what the fit reads: the band, the recommendation and the sensitivities rerun their own rules
        lifecycle=result_settings(config, "lifecycle", keys=("rbf", "adaptive")),
        fatigue=config["fatigue"],
    script:
        "../scripts/lifecycle.py"


rule lifecycle_figures:
    input:
        lifecycle="results/{ms}/lifecycle.zarr",
    output:
        validation=report(
            "results/figures/validation_{ms}.png",
            caption="../report/validation.rst",
            category="Life cycle",
            subcategory="{ms}",
        ),
        loo_map=report(
            "results/figures/loo_error_{ms}.png",
            caption="../report/loo_error.rst",
            category="Life cycle",
            subcategory="{ms}",
        ),
        damage_metocean=report(
            "results/figures/damage_metocean_{ms}.png",
            caption="../report/damage_metocean.rst",
            category="Life cycle",
            subcategory="{ms}",
        ),
    log:
        "logs/{ms}/lifecycle_figures.log",
    conda:
        "../../envs/moorlife.yaml"
    script:
        "../scripts/lifecycle_figures.py"
