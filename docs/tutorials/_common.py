"""What every tutorial script shares: where the built project is, and
matplotlib without a display. The documentation build runs each script with
its own output folder as the working directory (docs/_ext/tutorials.py)."""
import os
import pathlib

ROOT = pathlib.Path(os.environ.get("EQHB_ROOT", pathlib.Path(__file__).resolve().parents[2]))
BUILD = pathlib.Path(os.environ.get("EQHB_BUILD_DIR", ROOT / "build"))
EQHB = str(BUILD / "eqhb")  # the command-line program


def pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.rcParams.update({"figure.dpi": 100, "savefig.bbox": "tight", "font.size": 10})
    return plt
