"""scripts/check-python-imports on copies of the package: the package as it is passes; a planted
cycle, an import of a higher layer (at module level, in a function, under TYPE_CHECKING, of the
package's own names) and a module in no layer fail, each named with its file and line."""

import shutil
import subprocess
import sys

import pytest


def copy_package(repo, root):
    """python/gpfd/*.py of the repository under root."""
    target = root / "python" / "gpfd"
    target.mkdir(parents=True)
    for path in (repo / "python" / "gpfd").glob("*.py"):
        shutil.copy(path, target / path.name)
    return target


def check(repo, root):
    done = subprocess.run(
        [sys.executable, str(repo / "scripts" / "check-python-imports"), str(root)],
        capture_output=True,
        text=True,
    )
    return done.returncode, done.stdout.splitlines()


def plant(package, module, text):
    """Appends `text` to the module's file; returns the line it starts on."""
    path = package / f"{module}.py"
    before = path.read_text()
    path.write_text(before + text)
    return before.count("\n") + 1


def test_the_package_is_layered_without_cycles(repo, tmp_path):
    copy_package(repo, tmp_path)
    assert check(repo, tmp_path) == (0, [])


def test_a_planted_cycle_within_a_layer_fails(repo, tmp_path):
    # errors and registry share a layer: only the cycle breaks the rules.
    package = copy_package(repo, tmp_path)
    plant(package, "errors", "\n\ndef late():\n    from gpfd import registry\n")
    line = plant(package, "registry", "\nfrom gpfd.errors import EnvError\n")
    assert line > 1
    rc, out = check(repo, tmp_path)
    assert rc == 1
    assert out == ["python/gpfd: import cycle: errors -> registry -> errors"]


@pytest.mark.parametrize(
    "text",
    [
        "\nfrom gpfd import user_env\n",  # At module level.
        "\n\ndef hidden():\n    import gpfd.user_env\n",  # In a function: counted all the same.
        "\nfrom typing import TYPE_CHECKING\n\nif TYPE_CHECKING:\n"
        "    from gpfd.user_env import Adapter\n",  # For types only: counted too.
    ],
)
def test_an_import_of_a_higher_layer_fails_with_its_line_and_the_cycle(repo, tmp_path, text):
    package = copy_package(repo, tmp_path)
    start = plant(package, "envs", text)
    rc, out = check(repo, tmp_path)
    assert rc == 1
    layer = [line for line in out if "imports gpfd.user_env" in line]
    assert len(layer) == 1
    path, line, rest = layer[0].split(":", 2)
    assert path == "python/gpfd/envs.py" and start <= int(line) <= start + len(text.splitlines())
    assert "envs (layer 2) may import only layers 0-2, user_env is in layer 5" in rest
    # user_env imports vector_source, which imports envs: a cycle too.
    assert any(line.startswith("python/gpfd: import cycle: envs -> user_env") for line in out)


def test_a_name_of_the_package_itself_is_an_import_of_its_top(repo, tmp_path):
    # from gpfd import EnvError runs gpfd/__init__.py, which imports everything.
    package = copy_package(repo, tmp_path)
    plant(package, "vector_source", "\nfrom gpfd import EnvError\n")
    rc, out = check(repo, tmp_path)
    assert rc == 1
    assert any("vector_source.py:" in line and "imports gpfd.__init__" in line for line in out)
    assert any("import cycle: __init__ -> " in line for line in out)


def test_relative_imports_count(repo, tmp_path):
    package = copy_package(repo, tmp_path)
    plant(package, "registry", "\nfrom . import user_env\nfrom .discovery import evolve\n")
    rc, out = check(repo, tmp_path)
    assert rc == 1
    assert sum("python/gpfd/registry.py:" in line for line in out) == 2


def test_a_module_in_no_layer_fails(repo, tmp_path):
    package = copy_package(repo, tmp_path)
    (package / "stray.py").write_text("from gpfd import errors\n")
    assert check(repo, tmp_path) == (
        1,
        ["python/gpfd/stray.py: in no layer: add it to scripts/check-python-imports, LAYERS"],
    )


def test_a_tree_without_the_package_is_a_usage_error(repo, tmp_path):
    assert check(repo, tmp_path)[0] == 2
