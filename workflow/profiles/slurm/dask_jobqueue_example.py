"""SLURM route 2: one Dask cluster from dask-jobqueue, shared by every simulate rule.

Run this on the login node (it keeps the scheduler alive), then in another shell:

    export DASK_SCHEDULER_ADDRESS=$(cat dask-scheduler-address.txt)
    snakemake --cores 4

moorlife.parallel joins the scheduler named by DASK_SCHEDULER_ADDRESS instead of starting a
LocalCluster; the address is not a rule parameter, so changing it reruns nothing. The workers
must be able to `import moorlife`: install the package (`pip install -e .`) in the environment
that `python` resolves to inside the SLURM jobs (the `job_script_prologue` below activates it).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path


def main() -> None:
    from dask_jobqueue import SLURMCluster  # pip install -e ".[cluster]"
    from distributed import Client

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--jobs", type=int, default=8, help="SLURM jobs (each one worker node)")
    ap.add_argument("--cores", type=int, default=32, help="cores per job = worker processes per job")
    ap.add_argument("--memory", default="96GB")
    ap.add_argument("--walltime", default="04:00:00")
    ap.add_argument("--queue", default="compute")
    ap.add_argument("--venv", default=str(Path(".venv").resolve()))
    args = ap.parse_args()
    cluster = SLURMCluster(
        queue=args.queue,
        cores=args.cores,
        processes=args.cores,  # one single-threaded worker per core, as the LocalCluster
        memory=args.memory,
        walltime=args.walltime,
        job_script_prologue=[
            f"source {args.venv}/bin/activate",
            "export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1 NUMBA_NUM_THREADS=1",
        ],
    )
    cluster.scale(jobs=args.jobs)
    client = Client(cluster)
    Path("dask-scheduler-address.txt").write_text(cluster.scheduler_address + "\n")
    print(f"scheduler at {cluster.scheduler_address}; dashboard {client.dashboard_link}; Ctrl-C to stop")
    try:
        while True:
            time.sleep(60)
    except KeyboardInterrupt:
        client.close()
        cluster.close()


if __name__ == "__main__":
    main()
