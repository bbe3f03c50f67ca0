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
include: "workflow/rules/lifecycle.smk"
include: "workflow/rules/compare.smk"
include: "workflow/rules/truth.smk"


# Light gather rules run on the submit host under a cluster executor.
localrules:
    all,
    metocean_figures,
    selection_figures,
    lifecycle_figures,
    compare,
    compare_figures,
    sensitivity_cases,
    sensitivity,


rule all:
    input:
        final_targets(),
    default_target: True
