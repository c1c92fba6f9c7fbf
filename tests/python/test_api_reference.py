"""The API reference (docs/api, Sphinx's autodoc; scripts/docs builds it into build/docs/): every
name of gpfd.__all__ and every gpfd.MODULE.NAME that the prose pages name is in it, and the prose
pages' links into it lead somewhere. The sources are read as text (no Sphinx needed); the built
pages are checked where scripts/docs runs this file after building them (GPFD_API_HTML)."""

from __future__ import annotations

import os
import re
import zlib
from pathlib import Path

import pytest

import gpfd

ROOT = Path(__file__).resolve().parents[2]
SOURCES = ROOT / "docs" / "api"
PROSE = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]

# Internals that the prose names to say how things work, not for users to call.
INTERNAL = {"gpfd.evaluator.Evaluator", "gpfd.vector_source.VectorAdapter"}

_DIRECTIVE = re.compile(r"^(\s*)\.\. (auto\w+|py:\w+|currentmodule)::\s*(\S+)\s*$")
_MEMBERS = re.compile(r"^\s+:members:\s*(.*)$")
# gpfd.MODULE.NAME in prose: a public submodule (no leading underscore) and one of its names.
_NAMED = re.compile(r"\bgpfd\.([a-z][a-z0-9_]*)\.([A-Za-z][A-Za-z0-9_]*)\b")
# A link into the built reference: (build/docs/PAGE.html#ANCHOR), from any page's folder.
_LINK = re.compile(r"\]\((?:\.\./)*build/docs/([\w-]+\.html)(?:#([\w.-]+))?\)")


def documented() -> set[str]:
    """The full name of everything the sources document: each directive's object, and the
    members its ``:members:`` option names."""
    names: set[str] = set()
    for page in sorted(SOURCES.glob("*.rst")):
        module = ""
        last = ""
        for line in page.read_text().splitlines():
            directive = _DIRECTIVE.match(line)
            if directive:
                kind, target = directive.group(2), directive.group(3)
                if kind == "currentmodule":
                    module = target
                    continue
                if not target.startswith("gpfd") and directive.group(1):
                    target = f"{last}.{target}"  # a method inside its class's directive
                elif not target.startswith("gpfd"):
                    target = f"{module}.{target}"
                names.add(target)
                if not directive.group(1):
                    last = target
                continue
            members = _MEMBERS.match(line)
            if members and last:
                names.update(f"{last}.{m.strip()}" for m in members.group(1).split(",") if m)
    return names


def named_in_prose() -> set[str]:
    return {
        f"gpfd.{module}.{name}"
        for page in PROSE
        for module, name in _NAMED.findall(page.read_text())
        if (ROOT / "python" / "gpfd" / f"{module}.py").is_file()
    } - INTERNAL


def links() -> list[tuple[str, str, str]]:
    """(prose page, built page, anchor or "") of each link into the reference."""
    return [
        (page.name, target, anchor)
        for page in PROSE
        for target, anchor in _LINK.findall(page.read_text())
    ]


def test_every_name_of_all_is_documented():
    missing = sorted(f"gpfd.{name}" for name in gpfd.__all__ if f"gpfd.{name}" not in documented())
    assert not missing, f"not in docs/api/*.rst: {missing}"


def test_every_name_the_prose_names_is_documented():
    named = named_in_prose()
    assert "gpfd.workers.WorkerPool" in named  # the search finds what the guide names
    missing = sorted(named - documented())
    assert not missing, f"named in the prose pages, not in docs/api/*.rst: {missing}"


def test_the_prose_links_into_the_reference():
    found = links()
    pages = {page for page, _, _ in found}
    assert {"python.md", "README.md"} <= pages, pages
    known = documented()
    for page, target, anchor in found:
        assert (SOURCES / target.replace(".html", ".rst")).is_file(), (page, target)
        name = anchor.removeprefix("module-")
        assert not anchor or name in known, (page, target, anchor)


def _inventory(built: Path) -> set[str]:
    """The Python objects of Sphinx's objects.inv: four lines of header, then zlib's stream of
    lines "name domain:role priority uri display"."""
    data = (built / "objects.inv").read_bytes()
    body = data.split(b"\n", 4)[4]
    lines = zlib.decompress(body).decode().splitlines()
    return {line.split(" ", 1)[0] for line in lines if " py:" in line}


@pytest.mark.skipif(
    not os.environ.get("GPFD_API_HTML"),
    reason="checks the built reference: scripts/docs builds it and runs this with GPFD_API_HTML",
)
def test_the_built_reference_holds_every_name_and_anchor():
    built = Path(os.environ["GPFD_API_HTML"])
    objects = _inventory(built)
    wanted = {f"gpfd.{name}" for name in gpfd.__all__} | named_in_prose() | documented()
    missing = sorted(wanted - objects)
    assert not missing, f"not in {built}/objects.inv: {missing}"
    for page, target, anchor in links():
        html = (built / target).read_text()
        assert not anchor or f'id="{anchor}"' in html, (page, target, anchor)
