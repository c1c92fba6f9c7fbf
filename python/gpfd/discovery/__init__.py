"""Discovery and its results: evolve, fitness, assess and the results directories (runs), the
evaluations and learning runs of an environment stepped in Python on an executor (evaluator, with
the work shipped once to the workers: _jobs), what a features text is read against (features),
the progress display (progress) and the signed-rank test of gpfd's verdicts (stats).

Layer 4 of the package (scripts/check-python-imports).
"""
