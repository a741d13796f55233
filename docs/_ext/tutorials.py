"""Runs the tutorials while the site is built, so that every output and
figure on the tutorial pages comes from this build of the project.

Each docs/tutorials/NAME.py runs with docs/_generated/NAME/ as its working
directory (where it writes its figures and files) and its standard output is
saved as docs/_generated/NAME/output.txt, which the page includes. A tutorial
that fails (exit code not 0, e.g. an assertion on its results) fails the
build with its error output. Before them, Doxygen writes the XML of the C++
headers that Breathe reads (conf.py's eqhb_api_headers)."""
import os
import pathlib
import shutil
import subprocess
import sys
import time

from sphinx.errors import ExtensionError
from sphinx.util import logging

logger = logging.getLogger(__name__)

TUTORIALS = ["own_structure", "two_node_contact", "sweep_stability", "backends", "damper_study", "lap_joint_levels"]


def run_tutorials(app):
    docs = pathlib.Path(app.srcdir)
    build = pathlib.Path(app.config.eqhb_build_dir)
    if not (build / "python" / "eqhb").is_dir() or not (build / "eqhb").exists():
        raise ExtensionError(f"no built project in {build} (build/eqhb, build/python/eqhb): build it first "
                             "(./run.sh docs does) or set EQHB_BUILD_DIR")
    env = dict(os.environ, EQHB_BUILD_DIR=str(build), EQHB_ROOT=str(docs.parent),
               PYTHONPATH=os.pathsep.join([str(build / "python"), str(docs / "tutorials")]))
    # Debian's interpreter has numpy, scipy and matplotlib; another on PATH may not.
    python = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
    for name in TUTORIALS:
        out = docs / "_generated" / name
        shutil.rmtree(out, ignore_errors=True)
        out.mkdir(parents=True)
        began = time.perf_counter()
        run = subprocess.run([python, str(docs / "tutorials" / f"{name}.py")], cwd=out, env=env,
                             capture_output=True, text=True)
        seconds = time.perf_counter() - began
        if run.returncode != 0:
            raise ExtensionError(f"tutorial {name}.py failed (exit {run.returncode}):\n{run.stderr[-4000:]}")
        # Paths of this machine out of the page.
        text = run.stdout.replace(str(build) + "/", "build/").replace(str(docs.parent) + "/", "")
        (out / "output.txt").write_text(text)
        logger.info(f"tutorial {name}: {seconds:.1f} s")


def run_doxygen(app):
    headers = app.config.eqhb_api_headers
    if not headers:
        return
    root = pathlib.Path(app.srcdir).parent
    out = pathlib.Path(app.outdir).parent / "doxygen"
    out.mkdir(parents=True, exist_ok=True)
    settings = "\n".join([
        "PROJECT_NAME = eqhb", f"OUTPUT_DIRECTORY = {out}", "GENERATE_XML = YES", "GENERATE_HTML = NO",
        "GENERATE_LATEX = NO", "QUIET = YES", "WARN_IF_UNDOCUMENTED = NO", "EXTRACT_ALL = YES",
        "JAVADOC_AUTOBRIEF = YES", "ENABLE_PREPROCESSING = YES", "MACRO_EXPANSION = NO",
        f"STRIP_FROM_PATH = {root}", "INPUT = " + " ".join(str(root / h) for h in headers),
    ])
    run = subprocess.run(["doxygen", "-"], input=settings, capture_output=True, text=True)
    if run.returncode != 0:
        raise ExtensionError(f"doxygen failed:\n{run.stderr[-4000:]}")
    app.config.breathe_projects = {"eqhb": str(out / "xml")}


def setup(app):
    app.add_config_value("eqhb_build_dir", "", "env")
    app.add_config_value("eqhb_api_headers", [], "env")
    app.connect("builder-inited", run_doxygen)
    app.connect("builder-inited", run_tutorials)
    return {"version": "1", "parallel_read_safe": True}
