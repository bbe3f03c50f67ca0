# The report's opening page: the answer (recommendation, life-cycle table, comparison with the
# scatter matrix) as reStructuredText drawn from the run's outputs. The global description
# workflow/report/workflow.rst includes it (Snakefile `report:`): Snakemake renders that
# description with the config only, so the numbers are written here.


rule report_overview:
    input:
        summary="results/comparison/summary.csv",
        recommendation="results/comparison/recommendation.yaml",
    output:
        "results/report/overview.rst",
    log:
        "logs/report/overview.log",
    conda:
        "../../envs/moorlife.yaml"
    script:
        "../scripts/report_overview.py"
