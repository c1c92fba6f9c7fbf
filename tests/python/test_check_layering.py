"""scripts/check-layering on small fake source trees: it follows the gpfd_module(...) lines of
CMakeLists.txt (transitively), and names each include that breaks them, and each include of a
header of apps/."""

import subprocess
import sys
import textwrap

import pytest

CMAKE = """\
gpfd_module(util DEPS fmt::fmt)
gpfd_module(expr DEPS gpfd::util)
gpfd_module(features)
gpfd_module(jit DEPS gpfd::expr gpfd::features)
if(GPFD_JIT_AVAILABLE)
  target_link_libraries(gpfd_jit PUBLIC asmjit::asmjit)
endif()
# gpfd_module(gp DEPS gpfd::jit) in a comment does not count
gpfd_module(gp DEPS gpfd::expr)
gpfd_module(run DEPS gpfd::gp gpfd::jit
                     TBB::tbb)
"""

# A tree that keeps the layering: every include is of the module itself or of a dependency,
# direct or transitive, relative or through include/.
CLEAN = {
    "include/gpfd/util/rng.hpp": "#include <fmt/format.h>\n#include <vector>\n",
    "include/gpfd/expr/genome.hpp": '#include "gpfd/util/rng.hpp"\n',
    "include/gpfd/features/feature_map.hpp": "#include <span>\n",
    "include/gpfd/jit/program.hpp": '#include "gpfd/expr/genome.hpp"\n#include <asmjit/x86.h>\n',
    "src/gp/evolution.cpp": '#include "gpfd/expr/genome.hpp"\n#include "gpfd/util/rng.hpp"\n',
    "src/run/task.cpp": '#include "gpfd/jit/program.hpp"\n#include "local.hpp"\n'
    '#include <tbb/parallel_for.h>\n#include "gpfd/version.hpp"\n',
    "src/run/local.hpp": '#include "gpfd/features/feature_map.hpp"\n',
    "apps/gpfd/config_loading.hpp": '#include "gpfd/run/task.hpp"\n',
    "apps/gpfd/main.cpp": '#include "config_loading.hpp"\n#include "gpfd/run/task.hpp"\n',
    "python/src/module.cpp": '#include "gpfd/run/task.hpp"\n#include <nanobind/nanobind.h>\n',
}


def make_tree(root, files, cmake=CMAKE):
    (root / "CMakeLists.txt").write_text(cmake)
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)


def check(repo, root):
    done = subprocess.run(
        [sys.executable, str(repo / "scripts" / "check-layering"), str(root)],
        capture_output=True,
        text=True,
    )
    return done.returncode, done.stdout.splitlines()


def test_a_tree_that_keeps_the_declared_layering_passes(repo, tmp_path):
    make_tree(tmp_path, CLEAN)
    assert check(repo, tmp_path) == (0, [])


@pytest.mark.parametrize(
    "name, text, expected",
    [
        # gp declares expr only: the jit include is one the build does not allow.
        (
            "src/gp/evolution.cpp",
            '#include "gpfd/util/rng.hpp"\n#include "gpfd/jit/program.hpp"\n',
            'src/gp/evolution.cpp:2: #include "gpfd/jit/program.hpp": uses jit; '
            "gp may use only the modules expr, util (CMakeLists.txt, gpfd_module(gp ...))",
        ),
        # The same through a relative path.
        (
            "src/gp/evolution.cpp",
            '\n#include "../run/local.hpp"\n',
            'src/gp/evolution.cpp:2: #include "../run/local.hpp": uses run; gp may use only the '
            "modules expr, util (CMakeLists.txt, gpfd_module(gp ...))",
        ),
        # A public header that reaches up the layers.
        (
            "include/gpfd/util/rng.hpp",
            '#include "gpfd/expr/genome.hpp"\n',
            'include/gpfd/util/rng.hpp:1: #include "gpfd/expr/genome.hpp": uses expr; util may use '
            "no other module (CMakeLists.txt, gpfd_module(util ...))",
        ),
        # A library the module does not link.
        (
            "src/gp/evolution.cpp",
            "#include <asmjit/x86.h>\n",
            "src/gp/evolution.cpp:1: #include <asmjit/x86.h>: uses asmjit::asmjit; gp may use only "
            "the libraries fmt::fmt (CMakeLists.txt, gpfd_module(gp ...))",
        ),
        # The Python module including the tool's header through an include path into apps/.
        (
            "python/src/discovery.cpp",
            '#include "config_loading.hpp"\n',
            'python/src/discovery.cpp:1: #include "config_loading.hpp": reaches '
            "apps/gpfd/config_loading.hpp; nothing under include/, src/ or python/ may include a "
            "header of apps/ (the command-line tool's own code)",
        ),
        (
            "src/run/task.cpp",
            '#include "../../apps/gpfd/config_loading.hpp"\n',
            'src/run/task.cpp:1: #include "../../apps/gpfd/config_loading.hpp": reaches '
            "apps/gpfd/config_loading.hpp; nothing under include/, src/ or python/ may include a "
            "header of apps/ (the command-line tool's own code)",
        ),
        # A module the build does not declare.
        (
            "src/service/server.cpp",
            '#include "gpfd/run/task.hpp"\n',
            "src/service/server.cpp:1: module service has no gpfd_module(...) line in "
            "CMakeLists.txt",
        ),
    ],
)
def test_each_include_that_breaks_the_layering_is_named(repo, tmp_path, name, text, expected):
    make_tree(tmp_path, {**CLEAN, name: text})
    assert check(repo, tmp_path) == (1, [expected])


def test_a_module_added_later_follows_its_own_declaration(repo, tmp_path):
    cmake = CMAKE + "gpfd_module(service DEPS gpfd::run)\ngpfd_module(experiments DEPS gpfd::gp)\n"
    files = {
        **CLEAN,
        "src/service/server.cpp": '#include "gpfd/jit/program.hpp"\n',
        "src/experiments/sweep.cpp": '#include "gpfd/expr/genome.hpp"\n',
    }
    make_tree(tmp_path, files, cmake)
    assert check(repo, tmp_path) == (0, [])
    files["src/experiments/sweep.cpp"] = textwrap.dedent("""\
        #include "gpfd/expr/genome.hpp"
        #include "gpfd/service/server.hpp"
        """)
    make_tree(tmp_path, files, cmake)
    assert check(repo, tmp_path) == (
        1,
        [
            'src/experiments/sweep.cpp:2: #include "gpfd/service/server.hpp": uses service; '
            "experiments may use only the modules expr, gp, util (CMakeLists.txt, "
            "gpfd_module(experiments ...))"
        ],
    )


def test_a_tree_without_module_declarations_is_refused(repo, tmp_path):
    make_tree(tmp_path, CLEAN, cmake="project(other)\n")
    code, _ = check(repo, tmp_path)
    assert code == 2
