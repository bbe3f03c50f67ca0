# Stage 'metocean': the hourly hindcast (paper section 2, Fig. 3). The default is the seeded
# BiMEP-like synthetic hindcast; `hindcast.source: file` loads an ERA5/NORA3/mapped file instead.


rule metocean:
    input:
        _hindcast_file,
    output:
        store=directory("results/metocean/hindcast.zarr"),
    log:
        "logs/metocean/hindcast.log",
    conda:
        "../../envs/moorlife.yaml"
    params:
        hindcast=config["hindcast"],
        seed=config["seed"],
    script:
        "../scripts/metocean.py"


rule metocean_figures:
    input:
        hindcast="results/metocean/hindcast.zarr",
    output:
        wind_rose=report("results/figures/wind_rose.png", category="Metocean", caption="../report/wind_rose.rst"),
        wave_rose=report("results/figures/wave_rose.png", category="Metocean", caption="../report/wave_rose.rst"),
        hs_tp=report("results/figures/hs_tp_scatter.png", category="Metocean", caption="../report/hs_tp_scatter.rst"),
    log:
        "logs/metocean/figures.log",
    conda:
        "../../envs/moorlife.yaml"
    script:
        "../scripts/metocean_figures.py"
