"""SLURM route 2: one Dask cluster from dask-jobqueue, shared by every simulate rule.

Run this on the login node; with ``--detach`` it returns once the workers are up, printing the
scheduler address, and leaves the cluster running in the background:

    export DASK_SCHEDULER_ADDRESS=$(python workflow/profiles/slurm/dask_jobqueue_example.py \\
        --jobs 8 --cores 32 --detach)
    snakemake --cores 4
    kill $(cat dask-cluster.pid)          # scancels the worker jobs

Nothing is published before the workers have joined: stale address and PID files are removed
first, the job script is checked with ``sbatch --test-only`` (a bad partition or account
fails here, with sbatch's message), and if fewer than ``--min-workers`` workers join within
``--timeout`` seconds the cluster is closed and the command exits 1. Without ``--detach`` it
stays in the foreground (Ctrl-C or SIGTERM closes the cluster) and writes the address to
``--address-file`` once the workers are up.

moorlife.parallel joins the scheduler named by DASK_SCHEDULER_ADDRESS instead of starting a
LocalCluster; the address is not a rule parameter, so changing it reruns nothing. The workers
must be able to ``import moorlife``: by default they run this script's Python interpreter, so
install the package (``pip install -c constraints.txt -e ".[cluster]"``) in an environment that
the compute nodes see, or name one with ``--venv``. sbatch exports the submitting environment.
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--jobs", type=int, default=8, help="SLURM jobs (each one worker node)")
    ap.add_argument("--cores", type=int, default=32, help="cores per job = single-threaded worker processes per job")
    ap.add_argument("--memory", default="96GB", help="memory per job")
    ap.add_argument("--walltime", default="04:00:00")
    ap.add_argument("--queue", default=None, help="SLURM partition (default: the cluster's default partition)")
    ap.add_argument("--account", default=None, help="SLURM account (default: none given)")
    ap.add_argument(
        "--interface",
        default=None,
        help="network interface of the scheduler and workers, e.g. ib0 or eth0 "
        "(default: the address the hostname resolves to)",
    )
    ap.add_argument(
        "--venv",
        default=None,
        help=f"virtualenv activated in each job (default: run this interpreter, {sys.executable})",
    )
    ap.add_argument(
        "--min-workers", type=int, default=None, help="workers to wait for before publishing (default: jobs x cores)"
    )
    ap.add_argument(
        "--timeout",
        type=float,
        default=600.0,
        help="seconds to wait for the workers; then close the cluster and exit 1",
    )
    ap.add_argument("--address-file", type=Path, default=Path("dask-scheduler-address.txt"))
    ap.add_argument("--pid-file", type=Path, default=Path("dask-cluster.pid"))
    ap.add_argument("--log-file", type=Path, default=Path("dask-cluster.log"), help="log of the detached cluster")
    ap.add_argument(
        "--detach",
        action="store_true",
        help="print the address once the workers are up and return; the cluster "
        "keeps running in the background until SIGTERM (kill $(cat PID-FILE))",
    )
    return ap.parse_args(argv)


def _publish(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` atomically, so a reader never sees a partial address."""
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    tmp.write_text(text)
    os.replace(tmp, path)


def _check_job_script(script: str) -> None:
    """Let sbatch validate the job script (partition, account, limits) without queueing it."""
    with tempfile.NamedTemporaryFile("w", suffix=".sh", delete=False) as f:
        f.write(script)
    try:
        res = subprocess.run(["sbatch", "--test-only", f.name], capture_output=True, text=True)
    finally:
        os.unlink(f.name)
    if res.returncode != 0:
        raise SystemExit(f"sbatch rejects the worker job script: {res.stderr.strip()}\n{script}")


def serve(args: argparse.Namespace, ready_fd: int | None = None) -> int:
    """Start the cluster, wait for its workers, publish the address, then serve until stopped."""
    from dask_jobqueue import SLURMCluster  # pip install -c constraints.txt -e ".[cluster]"
    from distributed import Client

    def _stop(signum, frame):  # SIGTERM: close the cluster (scancel its jobs) like Ctrl-C
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, _stop)
    prologue = ["export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1 NUMBA_NUM_THREADS=1"]
    kwargs = {}
    if args.venv:
        prologue.insert(0, f"source {Path(args.venv).resolve()}/bin/activate")
        kwargs["python"] = "python"
    cluster = SLURMCluster(
        queue=args.queue,
        account=args.account,
        cores=args.cores,
        processes=args.cores,  # one single-threaded worker per core, as the LocalCluster
        memory=args.memory,
        walltime=args.walltime,
        interface=args.interface,
        job_script_prologue=prologue,
        **kwargs,
    )
    client = None
    try:
        _check_job_script(cluster.job_script())
        cluster.scale(jobs=args.jobs)
        client = Client(cluster)
        n = args.min_workers or args.jobs * args.cores
        try:
            client.wait_for_workers(n, timeout=args.timeout)
        except TimeoutError:
            raise SystemExit(
                f"only {len(client.scheduler_info()['workers'])} of {n} workers joined within "
                f"{args.timeout:g} s; squeue shows the jobs (pending? failed?)"
            ) from None
        address = cluster.scheduler_address
        args.pid_file.write_text(f"{os.getpid()}\n")
        _publish(args.address_file, address + "\n")
        jobs = " ".join(str(getattr(j, "job_id", "?")) for j in cluster.workers.values())
        print(
            f"scheduler at {address}; {n} workers up (SLURM jobs {jobs}); "
            f"dashboard {client.dashboard_link}; SIGTERM or Ctrl-C to stop",
            flush=True,
        )
        if ready_fd is not None:
            os.write(ready_fd, (address + "\n").encode())
            os.close(ready_fd)
        while True:
            time.sleep(60)
    except KeyboardInterrupt:
        return 0
    finally:
        for p in (args.address_file, args.pid_file):
            p.unlink(missing_ok=True)
        if client is not None:
            client.close()
        cluster.close()


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    # a stale address from an earlier run must never be read as this run's
    for p in (args.address_file, args.pid_file):
        p.unlink(missing_ok=True)
    if not args.detach:
        return serve(args)
    r, w = os.pipe()
    pid = os.fork()
    if pid == 0:  # the cluster: own session, output to the log file, not to the caller's $(...)
        os.close(r)
        os.setsid()
        fd = os.open(args.log_file, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        os.dup2(fd, 1)
        os.dup2(fd, 2)
        os.close(fd)
        null = os.open(os.devnull, os.O_RDONLY)
        os.dup2(null, 0)
        try:
            code = serve(args, ready_fd=w)
        except SystemExit as exc:
            print(exc, file=sys.stderr, flush=True)
            code = 1
        os._exit(code if isinstance(code, int) else 1)
    os.close(w)
    with os.fdopen(r) as ready:
        address = ready.read().strip()  # EOF without an address: the cluster failed
    if not address:
        _, status = os.waitpid(pid, 0)
        sys.stderr.write(args.log_file.read_text() if args.log_file.exists() else "")
        print(
            f"dask-jobqueue cluster failed (exit {os.waitstatus_to_exitcode(status)}); log: {args.log_file}",
            file=sys.stderr,
        )
        return 1
    print(address)
    return 0


if __name__ == "__main__":
    sys.exit(main())
