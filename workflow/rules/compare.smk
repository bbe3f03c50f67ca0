# Stage 'compare': life cycle vs the discrete scatter matrix (paper section 4.1, Table 7), the
# comparison across mooring systems (Fig. 20) with the recommendation, and the sensitivities of
# paper section 4 (random seeds Fig. 21, corrosion Fig. 22, mean-stress factors Table 8).

SENS = config["lifecycle"]["sensitivity"]
SENS_MS = SENS["mooring_system"]
# The seed realisations feed the fatigue-life band when the sensitivity system is studied.
SEEDS = ["results/sensitivity/seeds.zarr"] if SENS_MS in MS_IDS else []


rule compare:
    input:
        lifecycle=expand("results/{ms}/lifecycle.zarr", ms=MS_IDS),
        discrete=expand("results/{ms}/discrete.zarr", ms=MS_IDS),
        bins="results/selection/discrete.zarr",
        mooring=config["mooring_systems"],
        seeds=SEEDS,
    output:
        summary=report(
            "results/comparison/summary.csv",
            caption="../report/summary.rst",
            category="Comparison",
        ),
        recommendation="results/comparison/recommendation.yaml",
    params:
        systems=MS_IDS,
        lifecycle=config["lifecycle"],
        fatigue=config["fatigue"],
    conda:
        "../../envs/moorlife.yaml"
    log:
        "logs/comparison/compare.log",
    script:
        "../scripts/compare.py"


rule compare_figures:
    input:
        summary="results/comparison/summary.csv",
        recommendation="results/comparison/recommendation.yaml",
        lifecycle=expand("results/{ms}/lifecycle.zarr", ms=MS_IDS),
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
        recommendation=report(
            "results/figures/recommendation.png",
            caption="../report/recommendation.rst",
            category="Comparison",
        ),
    params:
        systems=MS_IDS,
    conda:
        "../../envs/moorlife.yaml"
    log:
        "logs/comparison/compare_figures.log",
    script:
        "../scripts/compare_figures.py"


rule sensitivity_cases:
    output:
        directory("results/sensitivity/seed_cases.zarr"),
    params:
        sea_state=SENS["sea_state"],
        n_seeds=SENS["n_seeds"],
        case_offset=SENS["case_offset"],
    conda:
        "../../envs/moorlife.yaml"
    log:
        "logs/sensitivity/seed_cases.log",
    script:
        "../scripts/sensitivity_cases.py"


rule sensitivity_seeds:
    input:
        cases="results/sensitivity/seed_cases.zarr",
        platform="results/hydro/platform.nc",
        platform_cfg=config["platform"],
    output:
        directory("results/sensitivity/seeds.zarr"),
    params:
        dim="case",
        ms=SENS_MS,
        row=lambda wc: mooring_row(SENS_MS),
        seed=config["seed"],
        simulation=config["simulation"],
        mooring=config.get("mooring", {}),
        fatigue=config["fatigue"],
        statistics=config.get("statistics", {}),
    threads: all_cores()
    conda:
        "../../envs/moorlife.yaml"
    log:
        "logs/sensitivity/seeds.log",
    script:
        "../scripts/simulate.py"


rule sensitivity:
    input:
        seeds="results/sensitivity/seeds.zarr",
        lifecycle=f"results/{SENS_MS}/lifecycle.zarr",
        lifecycles=expand("results/{ms}/lifecycle.zarr", ms=MS_IDS),
        mooring=config["mooring_systems"],
    output:
        seeds_csv="results/sensitivity/seed_lives.csv",
        corrosion_csv="results/sensitivity/corrosion.csv",
        mean_stress_csv=report(
            "results/sensitivity/mean_stress.csv",
            caption="../report/mean_stress.rst",
            category="Sensitivity",
        ),
        seeds_fig=report(
            "results/figures/seed_spread.png",
            caption="../report/seed_spread.rst",
            category="Sensitivity",
        ),
        corrosion_fig=report(
            "results/figures/corrosion_evolution.png",
            caption="../report/corrosion_evolution.rst",
            category="Sensitivity",
        ),
        mean_stress_fig=report(
            "results/figures/mean_stress_factors.png",
            caption="../report/mean_stress.rst",
            category="Sensitivity",
        ),
    params:
        systems=MS_IDS,
        ms=SENS_MS,
        line=SENS["corrosion_line"],
        fatigue=config["fatigue"],
    conda:
        "../../envs/moorlife.yaml"
    log:
        "logs/sensitivity/sensitivity.log",
    script:
        "../scripts/sensitivity.py"
