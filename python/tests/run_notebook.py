"""Executes a notebook (jupyter nbconvert --execute, python3 kernel) into OUTPUT_FOLDER and saves
each figure it shows as OUTPUT_FOLDER/<name>-<cell>-<k>.png. Exits non-zero if any cell raises
(nbconvert stops there), or if the notebook's copy in the repository holds outputs.

    run_notebook.py NOTEBOOK OUTPUT_FOLDER        (ctest python_notebook)
"""
import base64
import os
import subprocess
import sys

import nbformat


def main() -> int:
    notebook, folder = sys.argv[1], sys.argv[2]
    os.makedirs(folder, exist_ok=True)
    name = os.path.splitext(os.path.basename(notebook))[0]
    source = nbformat.read(notebook, as_version=4)
    dirty = [i for i, c in enumerate(source.cells) if c.cell_type == "code" and (c.outputs or c.execution_count)]
    if dirty:
        print(f"{notebook}: cells {dirty} hold outputs; strip them (jupyter nbconvert --clear-output --inplace)")
        return 1
    executed = os.path.join(folder, f"{name}.ipynb")
    for stale in os.listdir(folder):  # the figures of an earlier run
        if stale.startswith(f"{name}-") and stale.endswith(".png"):
            os.remove(os.path.join(folder, stale))
    # The kernel starts in the notebook's folder, so its relative paths are the repository's.
    run = subprocess.run([sys.executable, "-m", "nbconvert", "--execute", "--to", "notebook",
                          "--ExecutePreprocessor.timeout=600", "--ExecutePreprocessor.kernel_name=python3",
                          "--output-dir", folder, "--output", f"{name}.ipynb", notebook],
                         env=dict(os.environ, PYDEVD_DISABLE_FILE_VALIDATION="1"))
    if run.returncode != 0:
        return run.returncode
    result = nbformat.read(executed, as_version=4)
    figures = 0
    for i, cell in enumerate(result.cells):
        for output in cell.get("outputs", []):
            if output.get("output_type") == "error":
                print(f"cell {i} raised {output.get('ename')}: {output.get('evalue')}")
                return 1
            png = output.get("data", {}).get("image/png")
            if png:
                figures += 1
                with open(os.path.join(folder, f"{name}-{i:02d}-{figures}.png"), "wb") as f:
                    f.write(base64.b64decode(png))
    print(f"{executed}: {len(result.cells)} cells, {figures} figures saved in {folder}")
    return 0 if figures else 1


if __name__ == "__main__":
    sys.exit(main())
