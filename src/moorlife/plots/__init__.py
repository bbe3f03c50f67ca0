"""The paper's figures, one function per figure; each returns a ``matplotlib.figure.Figure``.

Plotting functions never touch the disk and never use ``pyplot`` global state: the workflow
scripts save the returned figures to ``results/figures/*.png``.
"""
