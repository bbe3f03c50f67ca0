# Stage 'compare': life cycle vs the discrete scatter matrix (paper section 4.1, Table 7) and the
# comparison across mooring systems (Fig. 20) with the recommendation. Python side:
# moorlife.stages.compare. The sensitivities of paper section 4 are in sensitivity.smk.


rule compare:
    input:
        lifecycles=expand("results/{ms}/lifecycle.zarr", ms=MS_IDS),
        discretes=expand("results/{ms}/discrete.zarr", ms=MS_IDS),
        bins="results/selection/discrete.zarr",
        mooring_systems=config["mooring_systems"],
        seeds=SEEDS,
    output:
        summary=report(
            "results/comparison/summary.csv",
            caption="../report/summary.rst",
            category="Comparison",
        ),
        recommendation="results/comparison/recommendation.yaml",
    log:
        "logs/comparison/compare.log",
    conda:
        "../../envs/moorlife.yaml"
    params:
        systems=MS_IDS,
        lifecycle=result_settings(config, "lifecycle", keys=("recommendation", "uncertainty")),
        fatigue=config["fatigue"],
    script:
        "../scripts/compare.py"


rule compare_figures:
    input:
        summary="results/comparison/summary.csv",
        recommendation="results/comparison/recommendation.yaml",
        lifecycles=expand("results/{ms}/lifecycle.zarr", ms=MS_IDS),
    output:
        damage_mass=report(
            "results/figures/damage_vs_mass.png",
            caption="../report/damage_vs_mass.rst",
            category="Comparison",
        ),
        difference=report(
            "results/figures/lifecycle_vs_discrete.png",
            caption="../report/lifecycle_vs_discrete.rst",
            category="Comparison",
        ),
        offsets=report(
            "results/figures/offsets_tensions.png",
            caption="../report/offsets_tensions.rst",
            category="Comparison",
        ),
        recommendation_fig=report(
            "results/figures/recommendation.png",
            caption="../report/recommendation.rst",
            category="Comparison",
        ),
    log:
        "logs/comparison/compare_figures.log",
    conda:
        "../../envs/moorlife.yaml"
    params:
        systems=MS_IDS,
    script:
        "../scripts/compare_figures.py"
