# Stage 'hydro': platform hydrodynamic coefficients -> results/hydro/platform.nc.
# params hold exactly what changes the result (geometry, environment, mass properties and
# linear mooring stiffness behind the drift motions, grid, headings, mesh, the deep-water
# threshold, the Capytaine version): platform.yaml is read here, at parse time, so editing
# e.g. the Ct table does not rerun the BEM.
# Fine mesh (1.2 m panels, 3-fold symmetry, 50 frequencies x 24 headings): about 30 min on
# 2 cores with every frequency in finite depth; 6-8 min measured in make run with the defaults
# (hydro.deep_water_kh: 10 and the mirror symmetry; validation/hydro.md, sections 4 and 7); the
# coarse setting (hydro.mesh.resolution: coarse, config/quick.yaml) about 1 min.
#
# Between-workflow cache (validation/hydro.md, section 6): with
#   export SNAKEMAKE_OUTPUT_CACHE=/path/to/a/shared/cache
#   snakemake --cores 2 --cache
# a study whose hydro params (and WAMIT files, if any) equal those of an earlier run copies
# platform.nc from the cache instead of solving. 'cache: True', not "omit-software": with
# --software-deployment-method conda the key then includes envs/moorlife.yaml. The key is the
# adapter script, the params and the input files: not the moorlife package's code, so clear the
# cache entry after a change to moorlife.hydro that changes the coefficients.


rule hydro:
    input:
        _hydro_inputs,
    output:
        store="results/hydro/platform.nc",
    log:
        "logs/hydro/platform.log",
    cache: True
    conda:
        "../../envs/moorlife.yaml"
    threads: 2
    resources:
        mem_mb=2000,
    params:
        bem=bem_settings(config["hydro"], STUDY.platform),
    script:
        "../scripts/hydro.py"
