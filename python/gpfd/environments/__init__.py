"""gpfd's own environments in Gymnasium: the C++ environments (gpfd_env, gpfd_vector), the twins
of Gymnasium's tasks (twins, twin_vector), the tasks with a known answer (planted, planted_check),
their drawing (render), and which names are gpfd's own or registered from Python (registry).

Layer 2 of the package (scripts/check-python-imports).
"""
