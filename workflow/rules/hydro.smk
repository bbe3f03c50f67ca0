# Stage 'hydro': platform hydrodynamic coefficients -> results/hydro/platform.nc.
# params hold exactly what changes the result (geometry, environment, mass properties and
# linear mooring stiffness behind the drift motions, grid, headings, mesh): platform.yaml is
# read here, at parse time, so editing e.g. the Ct table does not rerun the BEM.
# Fine mesh (2 m panels, 3-fold symmetry, 50 frequencies x 24 headings): about 25 min on
# 2 cores; the coarse setting (hydro.mesh.resolution: coarse, config/quick.yaml) about 1 min.


rule hydro:
    input:
        _hydro_inputs,
    output:
        store="results/hydro/platform.nc",
    log:
        "logs/hydro/platform.log",
    conda:
        "../../envs/moorlife.yaml"
    threads: 2
    resources:
        mem_mb=2000,
    params:
        bem=bem_settings(config["hydro"], STUDY.platform),
    script:
        "../scripts/hydro.py"
