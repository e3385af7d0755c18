"""Executes a notebook with nbclient (run by scripts/test-wheel.sh in the venv where only
the wheel, its extras and nbclient/ipykernel are installed) and checks its outputs:
every code cell ran, in order, without an error output (the notebook's own asserts check
its numbers), and every cell that shows a figure (plt.show()) produced an image/png.

    python run_notebook.py NOTEBOOK     prints each cell's text output and a summary
"""

from __future__ import annotations

import sys
import time

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError


def main(path: str) -> None:
    notebook = nbformat.read(path, as_version=4)
    started = time.perf_counter()
    try:
        NotebookClient(notebook, timeout=120, kernel_name="python3").execute()
    except CellExecutionError as e:
        raise SystemExit(f"run_notebook: {path}: a cell failed:\n{e}") from None
    code = [c for c in notebook.cells if c.cell_type == "code"]
    assert code, f"{path}: no code cell"
    images = 0
    for number, cell in enumerate(code, 1):
        assert cell.execution_count == number, (number, cell.execution_count, cell.source[:60])
        kinds = [o.output_type for o in cell.outputs]
        assert "error" not in kinds, (number, cell.outputs)
        for output in cell.outputs:
            if output.output_type == "stream":
                assert output.name == "stdout", (number, output.text)  # no warning either
                print(output.text, end="")
        pngs = [o for o in cell.outputs if "image/png" in o.get("data", {})]
        if "plt.show()" in cell.source:
            assert pngs, f"{path}: code cell {number} shows a figure but has no image/png"
            assert all(len(o.data["image/png"]) > 1000 for o in pngs), number
        images += len(pngs)
    assert images >= 2, images
    print(f"run_notebook: {path}: {len(code)} code cells ran without error, {images} figures "
          f"(image/png), {time.perf_counter() - started:.1f} s")


if __name__ == "__main__":
    main(sys.argv[1])
