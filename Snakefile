# moorlife: life-cycle fatigue of FOWT moorings (Barrera et al., Ocean Engineering 2019).
# Table of contents only: the rules live in workflow/rules/<stage>.smk.
from snakemake.utils import min_version

min_version("9.0")


configfile: "config/config.yaml"


include: "workflow/rules/common.smk"


wildcard_constraints:
    ms="|".join(MS_IDS),


include: "workflow/rules/metocean.smk"
include: "workflow/rules/selection.smk"
include: "workflow/rules/hydro.smk"
include: "workflow/rules/simulate.smk"
include: "workflow/rules/rounds.smk"
include: "workflow/rules/replicates.smk"
include: "workflow/rules/lifecycle.smk"
include: "workflow/rules/compare.smk"
include: "workflow/rules/report.smk"
include: "workflow/rules/sensitivity.smk"
include: "workflow/rules/truth.smk"


# The report opens on the answer: workflow/report/workflow.rst includes the overview that rule
# report_overview writes from the run's outputs (read when `snakemake --report` parses this).
REPORT_OVERVIEW = "results/report/overview.rst"
_report_rst = "workflow.rst" if os.path.exists(REPORT_OVERVIEW) else "workflow_pending.rst"


report: f"workflow/report/{_report_rst}"


# Light rules run on the submit host under a cluster executor (workflow/profiles/slurm):
# the hindcast, the selection and the scatter bins (seconds to a few minutes, one core), the
# figures, the comparison and the sensitivity gathers. hydro, simulate_* and lifecycle are jobs.
localrules:
    all,
    metocean,
    metocean_figures,
    selection,
    discrete,
    selection_figures,
    lifecycle_figures,
    compare,
    compare_figures,
    sensitivity_cases,
    sensitivity,
    report_overview,


rule all:
    default_target: True
    input:
        final_targets(),
