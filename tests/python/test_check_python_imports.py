"""scripts/check-python-imports on copies of the package: the package as it is passes; a planted
cycle, an import of a higher layer (of a higher subpackage, of a higher layer within a subpackage,
of a public path from a subpackage; at module level, in a function, under TYPE_CHECKING, of the
package's own names, relative) and a module in no layer fail, each named with its file and line."""

import shutil
import subprocess
import sys

import pytest


def copy_package(repo, root):
    """python/gpfd/**/*.py of the repository under root."""
    source = repo / "python" / "gpfd"
    target = root / "python" / "gpfd"
    for path in source.rglob("*.py"):
        copy = target / path.relative_to(source)
        copy.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(path, copy)
    return target


def check(repo, root):
    done = subprocess.run(
        [sys.executable, str(repo / "scripts" / "check-python-imports"), str(root)],
        capture_output=True,
        text=True,
    )
    return done.returncode, done.stdout.splitlines()


def plant(package, module, text):
    """Appends `text` to the file of `module` ("adapters.sources"); returns the line it starts
    on."""
    path = package / f"{module.replace('.', '/')}.py"
    before = path.read_text()
    path.write_text(before + text)
    return before.count("\n") + 1


def planted_failure(repo, root, module, text):
    """The check's lines on a copy of the package with `text` planted in `module`; it must fail."""
    plant(copy_package(repo, root), module, text)
    rc, out = check(repo, root)
    assert rc == 1
    return out


def names(out, file, *words):
    """Whether a line of `out` is about `file` and holds every one of `words`."""
    return any(line.startswith(file + ":") and all(w in line for w in words) for line in out)


def test_the_package_is_layered_without_cycles(repo, tmp_path):
    copy_package(repo, tmp_path)
    assert check(repo, tmp_path) == (0, [])


def test_a_planted_cycle_within_a_layer_fails(repo, tmp_path):
    # registry and render share an inner layer of environments: only the cycle breaks the rules.
    package = copy_package(repo, tmp_path)
    plant(
        package,
        "environments.render",
        "\n\ndef late():\n    from gpfd.environments import registry\n",
    )
    line = plant(package, "environments.registry", "\nfrom gpfd.environments.render import MODES\n")
    assert line > 1
    rc, out = check(repo, tmp_path)
    assert rc == 1
    assert out == [
        "python/gpfd: import cycle: environments.registry -> environments.render -> "
        "environments.registry"
    ]


@pytest.mark.parametrize(
    "text",
    [
        "\nfrom gpfd.adapters import user_env\n",  # At module level.
        "\n\ndef hidden():\n    import gpfd.adapters.user_env\n",  # In a function: counted.
        "\nfrom typing import TYPE_CHECKING\n\nif TYPE_CHECKING:\n"
        "    from gpfd.adapters.user_env import Adapter\n",  # For types only: counted too.
    ],
)
def test_an_import_of_a_higher_subpackage_fails_with_its_line_and_the_cycle(repo, tmp_path, text):
    package = copy_package(repo, tmp_path)
    start = plant(package, "environments.gpfd_env", text)
    rc, out = check(repo, tmp_path)
    assert rc == 1
    layer = [line for line in out if "imports gpfd.adapters.user_env" in line]
    assert len(layer) == 1
    path, line, rest = layer[0].split(":", 2)
    assert path == "python/gpfd/environments/gpfd_env.py"
    assert start <= int(line) <= start + len(text.splitlines())
    assert (
        "environments.gpfd_env (layer 2.1) may import only lower layers and its own, "
        "adapters.user_env is in layer 3.3" in rest
    )
    # user_env imports sources, which imports gpfd_env: a cycle too.
    cycle = "environments.gpfd_env -> adapters.user_env -> adapters.sources"
    assert any(line.startswith("python/gpfd: import cycle: ") and cycle in line for line in out)


def test_an_import_of_a_higher_layer_within_a_subpackage_fails(repo, tmp_path):
    text = "\n\ndef late():\n    from gpfd.adapters import user_env\n"
    out = planted_failure(repo, tmp_path, "adapters.sources", text)
    rule = "adapters.sources (layer 3.1) may import only lower layers and its own, "
    assert names(out, "python/gpfd/adapters/sources.py", rule + "adapters.user_env is in layer 3.3")


def test_a_subpackage_importing_a_public_path_fails(repo, tmp_path):
    # gpfd.envs, a path users have, is above every subpackage: the code imports the code.
    text = "\nfrom gpfd.envs import GpfdEnv\n"
    out = planted_failure(repo, tmp_path, "environments.gpfd_vector", text)
    assert names(out, "python/gpfd/environments/gpfd_vector.py", "imports gpfd.envs")


def test_a_name_of_the_package_itself_is_an_import_of_its_top(repo, tmp_path):
    # from gpfd import EnvError runs gpfd/__init__.py, which imports everything.
    out = planted_failure(repo, tmp_path, "adapters.sources", "\nfrom gpfd import EnvError\n")
    assert names(out, "python/gpfd/adapters/sources.py", "imports gpfd.__init__")
    assert any("import cycle: __init__ -> " in line for line in out)


def test_relative_imports_count(repo, tmp_path):
    text = "\nfrom .. import user_env\nfrom ..discovery.runs import evolve\nfrom . import render\n"
    out = planted_failure(repo, tmp_path, "environments.registry", text)
    wrong = [line for line in out if line.startswith("python/gpfd/environments/registry.py:")]
    assert len(wrong) == 2  # render shares registry's layer.
    assert "imports gpfd.user_env" in wrong[0] and "imports gpfd.discovery.runs" in wrong[1]


def test_a_module_in_no_layer_fails(repo, tmp_path):
    package = copy_package(repo, tmp_path)
    (package / "stray.py").write_text("from gpfd import errors\n")
    (package / "adapters" / "stray.py").write_text("from gpfd import errors\n")
    assert check(repo, tmp_path) == (
        1,
        [
            "python/gpfd/adapters/stray.py: in no layer: add it to scripts/check-python-imports, "
            "SUBPACKAGES['adapters']",
            "python/gpfd/stray.py: in no layer: add it to scripts/check-python-imports, LAYERS",
        ],
    )


def test_a_layer_naming_no_module_fails(repo, tmp_path):
    package = copy_package(repo, tmp_path)
    (package / "agents" / "sb3.py").unlink()
    (package / "sb3.py").unlink()
    rc, out = check(repo, tmp_path)
    assert rc == 1
    assert "scripts/check-python-imports, LAYERS: agents.sb3 is not a module of python/gpfd" in out


def test_a_tree_without_the_package_is_a_usage_error(repo, tmp_path):
    assert check(repo, tmp_path)[0] == 2
