# Stage 'sensitivity': the sensitivities of paper section 4, random seeds (Fig. 21), corrosion
# (Fig. 22) and mean-stress factors (Table 8), on the system lifecycle.sensitivity.mooring_system.
# Python side: moorlife.stages.sensitivity (sensitivity_seeds runs moorlife.stages.simulate).


rule sensitivity_cases:
    output:
        store=directory("results/sensitivity/seed_cases.zarr"),
    log:
        "logs/sensitivity/seed_cases.log",
    conda:
        "../../envs/moorlife.yaml"
    params:
        sea_state=SENS["sea_state"],
        n_seeds=SENS["n_seeds"],
        case_offset=SENS["case_offset"],
    script:
        "../scripts/sensitivity_cases.py"


# The seed realisations: the simulate stage on the seed cases of the sensitivity system.
use rule simulate_cases as sensitivity_seeds with:
    input:
        cases="results/sensitivity/seed_cases.zarr",
        platform="results/hydro/platform.nc",
        platform_cfg=config["platform"],
    output:
        store=directory("results/sensitivity/seeds.zarr"),
    log:
        "logs/sensitivity/seeds.log",
    params:
        ms=SENS_MS,
        row=lambda wc: mooring_row(SENS_MS),


rule sensitivity:
    input:
        seeds="results/sensitivity/seeds.zarr",
        lifecycle=f"results/{SENS_MS}/lifecycle.zarr",
        lifecycles=expand("results/{ms}/lifecycle.zarr", ms=MS_IDS),
        mooring_systems=config["mooring_systems"],
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
    log:
        "logs/sensitivity/sensitivity.log",
    conda:
        "../../envs/moorlife.yaml"
    params:
        systems=MS_IDS,
        ms=SENS_MS,
        line=SENS["corrosion_line"],
        fatigue=config["fatigue"],
    script:
        "../scripts/sensitivity.py"
