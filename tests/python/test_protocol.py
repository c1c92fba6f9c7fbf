"""gpfd.adapters.protocol: every name the C++ sources look up on an adapter is a member of its
protocol, the adapters have every member, and every module-level function C++ calls exists."""

import re

import gymnasium as gym
import numpy as np
import pytest

import gpfd
from gpfd.adapters import protocol, sources, user_env, vector_adapter

# The C++ file that drives each adapter, and the protocol it follows.
DRIVERS = {
    "python_environment.cpp": protocol.AdapterProtocol,
    "vector_hub.cpp": protocol.VectorAdapterProtocol,
}


def members(cls: type) -> set[str]:
    return {name for name in vars(cls) if not name.startswith("_")} - {"mro"}


def looked_up(repo, file: str) -> set[str]:
    """The names the file reads off its adapter: adapter_.attr("NAME")."""
    text = (repo / "python" / "src" / file).read_text()
    return set(re.findall(r'adapter_?\s*\.attr\("(\w+)"\)', text))


@pytest.mark.parametrize("file, cls", DRIVERS.items())
def test_what_cpp_looks_up_is_in_the_protocol(repo, file, cls):
    names = looked_up(repo, file)
    assert len(names) >= 8, f"{file}: the adapter's lookups were not found"
    missing = names - members(cls)
    assert not missing, f"{file} looks up {sorted(missing)}, not in {cls.__name__}"


def test_the_module_functions_cpp_calls_exist(repo):
    calls = set()
    for path in (repo / "python" / "src").glob("*.cpp"):
        calls |= set(re.findall(r'import_\("(gpfd[\w.]*)"\)\s*\.attr\("(\w+)"\)', path.read_text()))
    assert ("gpfd.adapters.user_env", "make_adapter") in calls
    for module, name in calls:
        assert callable(getattr(__import__(module, fromlist=[name]), name)), (module, name)


def test_the_adapter_has_every_member():
    for env, kind in (("CartPole-v1", "discrete"), ("Pendulum-v1", "continuous")):
        adapter = user_env.Adapter(env, gym.make(env))
        assert isinstance(adapter, protocol.AdapterProtocol)
        assert adapter.action_kind == kind


def test_the_vector_adapter_has_every_member_after_a_reset():
    source = gpfd.VectorFactory(lambda n: gym.make_vec("CartPole-v1", n))
    user_env.register("python:protocol-test", source)
    adapter = vector_adapter.make_vector_adapter("python:protocol-test", 4, 2, [], [])
    try:
        obs = adapter.reset([1, 2])
        assert isinstance(adapter, protocol.VectorAdapterProtocol)
        assert obs.shape == (2, 4) and obs.dtype == np.float64
        assert callable(adapter.step_function) and adapter.native_engine is None
    finally:
        adapter.close()


def test_gpfds_own_environments_name_their_engine():
    env = gym.make("gpfd/CartPole-v0")
    envs = gym.make_vec("gpfd/CartPole-v0", num_envs=3)
    assert isinstance(env.unwrapped.native_engine, gpfd._core.EnvBatch)  # type: ignore[attr-defined]
    assert isinstance(envs.native_engine, gpfd._core.EnvBatch)  # type: ignore[attr-defined]
    user_env.register("gpfd/CartPole-v0", sources.GymnasiumSource("gpfd/CartPole-v0"))
    adapter = user_env.make_adapter("gpfd/CartPole-v0")
    native = sources.native_single("gpfd/CartPole-v0", adapter)
    assert native is not None and isinstance(native[0], gpfd._core.EnvBatch)
