"""Sphinx's configuration of gpfd's API reference: autodoc reads the docstrings of the installed
package (the compiled gpfd._core included), napoleon their Google-style sections. scripts/docs
builds it into build/docs/ with warnings as errors."""

from __future__ import annotations

import importlib.util
import inspect
import re
import sys
import types
from typing import Any

# gpfd.sb3 without its extra (which brings PyTorch): its base class, SB3's VecEnv, as a plain
# stand-in, so that autodoc reads GpfdVecEnv's own signature (autodoc_mock_imports' mock hides it).
if importlib.util.find_spec("stable_baselines3") is None:
    _vec_env = types.ModuleType("stable_baselines3.common.vec_env")
    _vec_env.VecEnv = type("VecEnv", (), {"__module__": _vec_env.__name__})
    sys.modules["stable_baselines3"] = types.ModuleType("stable_baselines3")
    sys.modules["stable_baselines3.common"] = types.ModuleType("stable_baselines3.common")
    sys.modules[_vec_env.__name__] = _vec_env

from sphinx.pycode import ModuleAnalyzer  # noqa: E402

import gpfd  # noqa: E402

project = "gpfd"
author = "gpfd's authors"
version = release = gpfd.__version__
extensions = ["sphinx.ext.autodoc", "sphinx.ext.napoleon"]
html_theme = "alabaster"  # Sphinx's own theme: nothing beyond PyPI's sphinx
html_title = f"gpfd {release}: Python API reference"
default_role = "literal"  # `x` in a docstring is code, as gpfd's docstrings mean it
napoleon_google_docstring = True
napoleon_numpy_docstring = False
autoclass_content = "both"  # the class docstring, then its __init__'s
autodoc_member_order = "bysource"
autodoc_typehints = "description"  # every parameter with its type, documented or not
autodoc_typehints_description_target = "all"
autodoc_inherit_docstrings = False  # Gymnasium's and SB3's docstrings are theirs to render

# gpfd's docstrings describe parameters as paragraphs "name: text" (several names: "a, b: text")
# up to a blank line. As ":param name: text" fields, autodoc puts each beside its type.
_PARAGRAPH = re.compile(r"^(\w+(?:, \w+)*): (.*)$")


# Napoleon reads an attribute's or property's docstring "A: b" as type A, description b; gpfd's
# are prose ("run.json: seed, version, ..."), kept as written.
_attribute_docs: dict[str, list[str]] = {}


# An import path users have (gpfd/planted_check.py) re-exports the module where the code is, which
# it names `_code` (gpfd.environments.planted_check): a constant's "#:" comment is there.
def _code_comment(name: str) -> list[str]:
    """The comment of the constant `name` (gpfd.planted_check.THRESHOLD) where its code is."""
    module, _, attribute = name.rpartition(".")
    code = getattr(sys.modules.get(module), "_code", None)
    if code is None:
        return []
    comments = ModuleAnalyzer.for_module(code.__name__).find_attr_docs()
    return list(comments.get(("", attribute), []))


def _parameter_fields(
    app: Any, what: str, name: str, obj: Any, options: Any, lines: list[str]
) -> None:
    if what in ("data", "attribute", "property"):
        if obj is not None and obj.__doc__ == type(obj).__doc__:
            lines.clear()  # a constant's docstring is its type's (int's, str's): the page says more
        if what == "data" and not lines:
            lines += _code_comment(name)
        # A property bound with nanobind: its type from its getter's signature, "def (self) -> T".
        signature = getattr(getattr(obj, "fget", None), "__nb_signature__", None)
        if signature:
            lines += ["", f":type: {signature[0][0].rsplit(' -> ', 1)[1]}"]
        _attribute_docs[name] = list(lines)
        return
    if what not in ("function", "method", "class"):
        return
    try:
        parameters = set(inspect.signature(obj).parameters)
    except (TypeError, ValueError):
        return
    out: list[str] = []
    in_field = False
    for line in lines:
        match = _PARAGRAPH.match(line)
        names = match.group(1).split(", ") if match else []
        if match and all(n in parameters for n in names):
            if out and out[-1]:
                out.append("")  # a field list starts a block of its own
            out += [f":param {n}: {match.group(2)}" for n in names]  # continued: the last one
            in_field = True
        elif in_field and line:
            out.append("   " + line.lstrip())  # the paragraph goes on
        else:
            in_field = False
            out.append(line)
    lines[:] = out


def _attribute_prose(
    app: Any, what: str, name: str, obj: Any, options: Any, lines: list[str]
) -> None:
    if name in _attribute_docs:
        lines[:] = _attribute_docs.pop(name)


def _no_self(
    app: Any,
    what: str,
    name: str,
    obj: Any,
    options: Any,
    signature: str | None,
    return_annotation: str | None,
) -> tuple[str | None, str | None] | None:
    """nanobind's signatures (its docstrings' first lines) name ``self``; Python's, as autodoc
    shows them, do not."""
    if signature and signature.startswith("(self"):
        return re.sub(r"^\(self(, )?", "(", signature), return_annotation
    return None


def setup(app: Any) -> None:
    app.connect("autodoc-process-signature", _no_self)
    app.connect("autodoc-process-docstring", _parameter_fields, priority=400)  # before napoleon
    app.connect("autodoc-process-docstring", _attribute_prose, priority=600)  # after it
