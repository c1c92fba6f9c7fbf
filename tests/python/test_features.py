"""gpfd.FeatureSet: reading, printing, exporting, and values bit-identical to gpfd's own."""

import pickle
import subprocess
import textwrap
from typing import Any

import numpy as np
import pytest

import gpfd

# Every operator of the control set, with inputs that reach the protected cases (division by
# ~0, sqrt of negatives, overflow to +-DBL_MAX, large sin/cos arguments).
CONTROL = textwrap.dedent(
    """\
    # gpfd features 1
    # env: acrobot
    # variables: th1, th2, dth1, dth2
    # format: infix
    sin(th1) * dth2
    th2 / (dth1 - dth1)
    sqrt(th1 - 3) + cos(dth2 * 1e6)
    (dth1 * 1e300) * (dth2 * 1e300)
    th1 / 0.5 - sin(cos(th2))
    """
)


def states(n, dim=4, seed=0):
    rng = np.random.default_rng(seed)
    x = rng.normal(scale=3.0, size=(n, dim))
    x[::7] *= 1e5  # Large arguments for sin and cos.
    return x


def cli_text(cli, *args):
    return subprocess.run([cli, *map(str, args)], check=True, capture_output=True, text=True).stdout


@pytest.fixture()
def control_file(tmp_path):
    path = tmp_path / "control.features"
    path.write_text(CONTROL)
    return path


def test_load_reads_the_file_and_its_metadata(control_file):
    fs = gpfd.FeatureSet.load(str(control_file))
    assert fs.env == "acrobot"
    assert fs.variables == ["th1", "th2", "dth1", "dth2"]
    assert len(fs) == fs.n_features == 5
    assert fs.input_dim == 4
    assert fs.name == "control"
    assert fs.native and fs.native_batch  # This machine has the JIT and AVX2.


def test_show_and_export_match_the_command_line(cli, control_file):
    fs = gpfd.FeatureSet.load(str(control_file))
    for fmt in ("infix", "sexpr"):
        assert fs.show(fmt) == cli_text(cli, "features", "show", control_file, "--format", fmt)
    for fmt in ("c", "python", "latex", "sexpr"):
        assert fs.export(fmt) == cli_text(cli, "features", "export", control_file, "--format", fmt)
    assert fs.show(simplify=True) == cli_text(cli, "features", "show", control_file, "--simplify")


def test_values_are_bit_identical_to_the_command_lines_numpy_export(cli, control_file):
    namespace: dict[str, Any] = {}
    exec(cli_text(cli, "features", "export", control_file, "--format", "python"), namespace)
    fs = gpfd.FeatureSet.load(str(control_file))
    x = states(1000)
    expected = namespace["features"](x)
    got = fs(x)
    assert got.dtype == np.float64 and got.shape == (1000, 5)
    assert np.array_equal(got.view(np.uint64), expected.view(np.uint64))


def test_values_are_bit_identical_to_the_command_lines_c_export(cli, control_file, tmp_path):
    cc = "gcc"
    source = tmp_path / "features.c"
    source.write_text(
        cli_text(cli, "features", "export", control_file, "--format", "c")
        + textwrap.dedent(
            """
            #include <stdio.h>
            int main(void) {
              double s[4], f[5];
              while (fread(s, sizeof s, 1, stdin) == 1) {
                gpfd_features(s, f);
                fwrite(f, sizeof f, 1, stdout);
              }
              return 0;
            }
            """
        )
    )
    binary = tmp_path / "features"
    subprocess.run(
        [cc, "-O2", "-fno-builtin", "-ffp-contract=off", str(source), "-o", str(binary), "-lm"],
        check=True,
    )
    x = states(1000, seed=1)
    out = subprocess.run([str(binary)], input=x.tobytes(), capture_output=True, check=True).stdout
    expected = np.frombuffer(out, dtype=np.float64).reshape(1000, 5)
    fs = gpfd.FeatureSet.load(str(control_file))
    assert np.array_equal(fs(x).view(np.uint64), expected.view(np.uint64))


def test_one_state_and_every_batch_size_agree_bit_for_bit(control_file):
    fs = gpfd.FeatureSet.load(str(control_file))
    x = states(4096, seed=2)
    batch = fs(x)
    for n in (1, 2, 3, 5, 15, 16, 17, 4095):  # Below and above the GIL threshold; AVX2 tails.
        assert np.array_equal(fs(x[:n]).view(np.uint64), batch[:n].view(np.uint64))
    rows = np.stack([fs(row) for row in x[:64]])
    assert np.array_equal(rows.view(np.uint64), batch[:64].view(np.uint64))


def test_layouts_and_dtypes_that_convert(control_file):
    fs = gpfd.FeatureSet.load(str(control_file))
    x = states(40, seed=3)
    reference = fs(x)
    assert np.array_equal(fs(np.asfortranarray(x)), reference)
    assert np.array_equal(fs(x[::2]), reference[::2])  # Strided rows.
    assert np.array_equal(fs(x.tolist()), reference)
    x32 = x.astype(np.float32)
    assert np.array_equal(fs(x32), fs(x32.astype(np.float64)))
    assert np.array_equal(fs(np.arange(8).reshape(2, 4)), fs(np.arange(8.0).reshape(2, 4)))
    read_only = x.copy()
    read_only.flags.writeable = False
    assert np.array_equal(fs(read_only), reference)
    assert fs(np.empty((0, 4))).shape == (0, 5)


def test_out_receives_the_features(control_file):
    fs = gpfd.FeatureSet.load(str(control_file))
    x = states(32, seed=4)
    out = np.empty((32, 5))
    assert fs(x, out=out) is out
    assert np.array_equal(out, fs(x))
    with pytest.raises(
        ValueError, match=r"out must be a writable C-contiguous float64 array of shape \(32, 5\)"
    ):
        fs(x, out=np.empty((32, 4)))
    with pytest.raises(ValueError, match="out must be"):
        fs(x, out=np.empty((32, 5), dtype=np.float32))


@pytest.mark.parametrize(
    "shape",
    [(3,), (5,), (2, 3), (2, 2, 4), ()],
)
def test_wrong_shapes_are_refused(control_file, shape):
    fs = gpfd.FeatureSet.load(str(control_file))
    with pytest.raises(
        ValueError,
        match=r"expected observations of shape \(4,\) or \(N, 4\) over th1, th2, dth1, dth2",
    ):
        fs(np.zeros(shape))


@pytest.mark.parametrize(
    "obs",
    [
        np.zeros(4, dtype=np.complex128),
        np.array(["a", "b", "c", "d"]),
        np.zeros(4, dtype=bool),
        np.array([object()] * 4),
        "abcd",
    ],
)
def test_wrong_dtypes_are_refused(control_file, obs):
    fs = gpfd.FeatureSet.load(str(control_file))
    with pytest.raises(TypeError, match="observations must be real numbers"):
        fs(obs)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
@pytest.mark.parametrize("n", [1, 100])
def test_non_finite_observations_are_refused(control_file, bad, n):
    fs = gpfd.FeatureSet.load(str(control_file))
    x = states(n)
    x[n - 1, 2] = bad
    with pytest.raises(ValueError, match=rf"observation {n - 1} holds {bad} in column 2 \(dth1\)"):
        fs(x if n > 1 else x[0])


def test_parse_uses_the_environments_variables(tmp_path):
    fs = gpfd.FeatureSet.parse("th1 * dth2\nsin(th2)\n", env="acrobot")
    assert fs.variables == ["th1", "th2", "dth1", "dth2"] and fs.env == "acrobot"
    swimmer = gpfd.FeatureSet.parse("th5 + dGx\n", env="swimmer", segments=5)
    assert swimmer.input_dim == 12
    with pytest.raises(gpfd.InputError, match="th5"):
        gpfd.FeatureSet.parse("th5 + dGx\n", env="swimmer")  # Three segments: no th5.
    assert gpfd.FeatureSet.parse("x[0] + x[1]\n", variables=["a", "b"]).variables == ["a", "b"]
    with pytest.raises(gpfd.InputError, match=r"<string>:1"):
        gpfd.FeatureSet.parse("th1 +\n", env="acrobot")
    with pytest.raises(gpfd.InputError):
        gpfd.FeatureSet.parse(CONTROL, env="cartpole")  # The file is for acrobot.
    with pytest.raises(gpfd.InputError, match="cannot read"):
        gpfd.FeatureSet.load(str(tmp_path / "missing.features"))


def test_parse_takes_a_gymnasium_environment():
    import gymnasium as gym

    env = gym.make("gpfd/Swimmer-v0", segments=4)
    fs = gpfd.FeatureSet.parse("th4 * dth1\n", env=env)
    assert fs.env == "swimmer" and fs.input_dim == 10
    pendulum = gpfd.FeatureSet.parse("x0 * x2\n", env=gym.make("Pendulum-v1"))
    assert pendulum.variables == ["x0", "x1", "x2"] and pendulum.env == "Pendulum-v1"


def test_save_and_pickle_round_trip(control_file, tmp_path):
    fs = gpfd.FeatureSet.load(str(control_file))
    fs.save(str(tmp_path / "copy.features"))
    again = gpfd.FeatureSet.load(str(tmp_path / "copy.features"))
    x = states(20)
    assert np.array_equal(again(x), fs(x))
    unpickled = pickle.loads(pickle.dumps(fs))
    assert unpickled.name == "control" and np.array_equal(unpickled(x), fs(x))


def test_discovered_files_in_the_repository_evaluate_like_their_export(cli, repo):
    for path in sorted((repo / "tests/data/results/features").glob("*.features")):
        fs = gpfd.FeatureSet.load(str(path))
        namespace: dict[str, Any] = {}
        exec(cli_text(cli, "features", "export", path, "--format", "python"), namespace)
        x = states(257, dim=fs.input_dim, seed=5)
        expected = namespace["features"](x)
        assert np.array_equal(fs(x).view(np.uint64), expected.view(np.uint64)), path
