"""Stage glue: one module per workflow stage, each with the functions its rules' scripts call.

A stage module reads its inputs through :mod:`moorlife.io`, calls the pure kernels and writes
its outputs; the scripts in ``workflow/scripts/`` are adapters of 20 lines or fewer over it.
"""
