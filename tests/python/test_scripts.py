"""scripts/ holds what a user or maintainer runs, and nothing else (issue 54): every script there
says what it is for with -h / --help (and exits 0 without doing anything else), and every one is
named by a document, a test or CI, where its purpose is told."""

import re
import shutil
import subprocess
import sys

import pytest

from conftest import REPO

SCRIPTS = sorted(p for p in (REPO / "scripts").iterdir() if p.is_file())
# Where a script must be named: the documents, the tests and CI (this file aside).
NAMING = [REPO / "README.md", REPO / "CONTRIBUTING.md", *sorted((REPO / "docs").rglob("*.md"))]
NAMING += [p for p in (REPO / ".ci").rglob("*") if p.is_file()]
NAMING += [p for p in (REPO / "tests").rglob("*") if p.suffix in (".py", ".cpp", ".hpp", ".txt")]


def command(script):
    """How the script is run: Python scripts by this interpreter (the package's venv)."""
    first = script.read_text().splitlines()[0]
    return [sys.executable if "python" in first else "bash", str(script)]


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
@pytest.mark.parametrize("flag", ["-h", "--help"])
def test_a_script_says_what_it_is_for(script, flag):
    done = subprocess.run(
        [*command(script), flag], cwd=REPO, capture_output=True, text=True, timeout=60
    )
    assert done.returncode == 0, done.stderr
    assert len(done.stdout.split()) >= 8, done.stdout  # a sentence of purpose, not a bare usage


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_a_script_is_named_where_its_purpose_is_told(script):
    here = REPO / "tests/python/test_scripts.py"
    pattern = re.compile(rf"scripts/{re.escape(script.name)}(?![\w-])")
    assert any(pattern.search(p.read_text(errors="replace")) for p in NAMING if p != here)


@pytest.mark.skipif(shutil.which("clang-format") is None, reason="needs clang-format")
def test_the_ziggurat_tables_are_the_generator_s_output():
    generated = subprocess.run(
        [sys.executable, str(REPO / "scripts/gen-ziggurat-tables")],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    header = REPO / "include/gpfd/util/ziggurat_tables.hpp"
    formatted = subprocess.run(
        ["clang-format", f"--assume-filename={header}"],
        input=generated,
        cwd=REPO,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    assert formatted == header.read_text()
