# Stage 'truth' (opt-in, outside rule all): simulate every hour of the window truth.window
# (every truth.stride-th) for one mooring system with the simulate stage as it is (use rule), a second seed
# on truth.n_second_seed of them, and compare lifecycle.zarr and the 35 bins with that truth. The
# comparison refits the system's reconstruction (FIT_INPUTS) for the records' term of its window.
#   snakemake --cores 2 results/MS2/truth_comparison.zarr
# The truth keys are checked against the hindcast period when the DAG is built, before any job
# (truth_checked_hindcast in common.smk).


rule truth_hours:
    input:
        truth_checked_hindcast,
    output:
        directory("results/truth/hours.zarr"),
    log:
        "logs/truth/hours.log",
    conda:
        "../../envs/moorlife.yaml"
    params:
        window=config["truth"]["window"],
        stride=config["truth"]["stride"],
    script:
        "../scripts/truth_hours.py"


rule truth_hours_seed2:
    input:
        "results/truth/hours.zarr",
    output:
        directory("results/truth/hours_seed2.zarr"),
    log:
        "logs/truth/hours_seed2.log",
    conda:
        "../../envs/moorlife.yaml"
    params:
        n=config["truth"]["n_second_seed"],
        storm=config["truth"]["second_seed_storm"],
    script:
        "../scripts/truth_hours_seed2.py"


use rule simulate_cases as truth_simulate with:
    input:
        cases="results/truth/hours.zarr",
        platform="results/hydro/platform.nc",
        platform_cfg=config["platform"],
    output:
        store=directory("results/{ms}/truth.zarr"),
    log:
        "logs/{ms}/truth_simulate.log",
    params:
        dim="case",
        stream="truth",


use rule simulate_cases as truth_simulate_seed2 with:
    input:
        cases="results/truth/hours_seed2.zarr",
        platform="results/hydro/platform.nc",
        platform_cfg=config["platform"],
    output:
        store=directory("results/{ms}/truth_seed2.zarr"),
    log:
        "logs/{ms}/truth_simulate_seed2.log",
    params:
        dim="case",
        stream="truth_seed2",


rule truth_compare:
    input:
        **FIT_INPUTS,
        truth="results/{ms}/truth.zarr",
        seed2="results/{ms}/truth_seed2.zarr",
        lifecycle="results/{ms}/lifecycle.zarr",
        states="results/selection/discrete.zarr",
        discrete="results/{ms}/discrete.zarr",
    output:
        store=directory("results/{ms}/truth_comparison.zarr"),
        csv="results/{ms}/truth_comparison.csv",
        scatter=report(
            "results/figures/truth_scatter_{ms}.png",
            caption="../report/truth_scatter.rst",
            category="Truth",
            subcategory="{ms}",
        ),
        cumulative=report(
            "results/figures/truth_damage_{ms}.png",
            caption="../report/truth_damage.rst",
            category="Truth",
            subcategory="{ms}",
        ),
    log:
        "logs/{ms}/truth_compare.log",
    conda:
        "../../envs/moorlife.yaml"
    resources:
        mem_mb=2000,
    params:
        outputs=config["lifecycle"]["rbf"]["outputs"],
        second_seed_storm=config["truth"]["second_seed_storm"],
        # the lifecycle rule's fit, refitted for the records' term of the window's sums
        lifecycle=result_settings(config, "lifecycle", keys=("rbf",)),
    script:
        "../scripts/truth_compare.py"
