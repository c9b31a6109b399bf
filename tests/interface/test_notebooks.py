"""Every notebook in notebooks/ executes without error.

Each notebook ends with ``assert`` cells on its key numbers (closed forms, bisections on the stability verdict,
convergence rates), so executing it is the test. The notebooks run in a fresh kernel, headless
(``MPLBACKEND=Agg``), in memory: nothing is written back to the repository. The kernel gets one BLAS thread:
OpenBLAS's threaded kernels stall when the machine's few cores are busy with other work (a 100-fold slowdown of
small dense operations was seen on two cores), and these notebooks gain nothing from threads.
"""

import time
from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

NOTEBOOK_DIR = Path(__file__).resolve().parents[2] / "notebooks"
NOTEBOOKS = sorted(NOTEBOOK_DIR.glob("*.ipynb"))
EXPECTED = {
    "double_pendulum",
    "pendulum_chains",
    "damping_and_follower_loads",
    "rotating_systems",
    "robot_arm",
    "constrained_mechanisms",
    "periodic_motions",
}
#: Seconds allowed per cell; all the notebooks together take about a minute.
CELL_TIMEOUT = 300


def test_every_expected_notebook_is_there():
    assert EXPECTED <= {path.stem for path in NOTEBOOKS}


def test_notebooks_are_stored_with_outputs():
    """Readers see the plots without running anything: every code cell was executed, figures are embedded."""
    for path in NOTEBOOKS:
        nb = nbformat.read(path, as_version=4)
        nbformat.validate(nb)
        code = [cell for cell in nb.cells if cell.cell_type == "code"]
        assert all(cell.execution_count is not None for cell in code), f"{path.name} has unexecuted cells"
        assert not any(out.output_type == "error" for cell in code for out in cell.outputs), path.name
        assert any("image/png" in out.get("data", {}) for cell in code for out in cell.outputs), path.name


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda path: path.stem)
def test_notebook_executes(path, tmp_path, monkeypatch):
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "1")
    monkeypatch.setenv("OMP_NUM_THREADS", "1")
    # keep IPython's profile and the kernel's connection file out of the home directory
    monkeypatch.setenv("IPYTHONDIR", str(tmp_path / "ipython"))
    monkeypatch.setenv("JUPYTER_RUNTIME_DIR", str(tmp_path / "runtime"))
    nb = nbformat.read(path, as_version=4)
    client = NotebookClient(
        nb,
        timeout=CELL_TIMEOUT,
        kernel_name="python3",
        resources={"metadata": {"path": str(NOTEBOOK_DIR)}},
    )
    start = time.perf_counter()
    client.execute()  # raises CellExecutionError, with the failing cell and traceback, on any error
    elapsed = time.perf_counter() - start
    errors = [out for cell in nb.cells if cell.cell_type == "code" for out in cell.outputs if out.output_type == "error"]
    assert not errors
    print(f"{path.name}: {elapsed:.1f} s")
