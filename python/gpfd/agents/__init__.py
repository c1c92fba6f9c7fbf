"""What an agent is given: the features as its observation (wrappers), gpfd's environments as
Stable-Baselines3's VecEnv (sb3).

Layer 5 of the package (scripts/check-python-imports).
"""
