"""Environments stepped in Python, as C++ drives them: resolving and registering a user's
environment and its adapter (user_env), vector forms (sources) and the vector adapter
(vector_adapter), the idle vector environments kept per process (vector_cache), and what C++
looks up on the adapters (protocol).

Layer 3 of the package (scripts/check-python-imports).
"""
