# The documentation site: Sphinx with MyST pages, the Python API from the
# module's docstrings, the C++ API from the headers (Doxygen XML through
# Breathe), and tutorials that run while the site is built
# (_ext/tutorials.py). Build: ./run.sh docs, or
#   EQHB_BUILD_DIR=build sphinx-build -W --keep-going -b html docs build/docs/html
import os
import pathlib
import sys

here = pathlib.Path(__file__).resolve().parent
root = here.parent
build_dir = pathlib.Path(os.environ.get("EQHB_BUILD_DIR", root / "build")).resolve()
sys.path.insert(0, str(here / "_ext"))
sys.path.insert(0, str(build_dir / "python"))  # the module eqhb as built

project = "eqhb"
author = "the eqhb authors"
copyright = "the eqhb authors, BSD-3-Clause"
release = (root / "CMakeLists.txt").read_text().split("project(eqhb VERSION ")[1].split()[0]

extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.mathjax", "breathe", "tutorials"]
myst_enable_extensions = ["dollarmath", "amsmath", "deflist"]
myst_heading_anchors = 3
source_suffix = {".md": "markdown"}
exclude_patterns = ["_generated", "_build", "README.md"]
root_doc = "index"

html_theme = "alabaster"
html_theme_options = {"description": "equality-based harmonic balance for friction and contact",
                      "page_width": "1100px", "sidebar_width": "240px"}
html_static_path = []

autodoc_member_order = "bysource"
autodoc_mock_imports = []

eqhb_build_dir = str(build_dir)
# The C++ reference: the headers a program that builds and solves a model
# includes (the rest is documented in its headers; docs/guide/layout.md).
eqhb_api_headers = [
    "lib/eqhb/harmonic_balance/hb_model.h",
    "lib/eqhb/structures/linear_structure.h",
    "lib/eqhb/harmonic_balance/harmonic_set.h",
    "lib/eqhb/harmonic_balance/hb_systems.h",
    "lib/eqhb/harmonic_balance/hb_solution.h",
    "lib/eqhb/solvers/solver.h",
    "backends/eqhb/backends/registry.h",
    "lib/eqhb/app/scene_settings.h",
    "lib/eqhb/app/solve_options.h",
    "lib/eqhb/app/solution.h",
    "lib/eqhb/app/solve.h",
]
breathe_default_project = "eqhb"
