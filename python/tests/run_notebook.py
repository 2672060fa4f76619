"""Executes a notebook (jupyter nbconvert --execute, python3 kernel) into OUTPUT_FOLDER and saves
each figure it shows as OUTPUT_FOLDER/<name>-<cell>-<k>.png. Exits non-zero if any cell raises
(nbconvert stops there), or if the notebook's copy in the repository holds outputs.

The notebook runs as a user's copy would: copied alone into a temporary folder (so that it
must find its data through the package, heavytop.example_file, not beside itself), with a
temporary folder of its own as TMPDIR, which must hold no heavytop-report-* folder (show()'s)
once the kernel has exited.

    run_notebook.py NOTEBOOK OUTPUT_FOLDER        (ctest python_notebook)
"""
import base64
import os
import shutil
import subprocess
import sys
import tempfile

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
    # The kernel starts in the notebook's folder: a copy's, away from the repository.
    with tempfile.TemporaryDirectory(prefix="heavytop-notebook-") as work:
        copy = os.path.join(work, "copy", os.path.basename(notebook))
        private_tmp = os.path.join(work, "tmp")
        os.makedirs(os.path.dirname(copy))
        os.makedirs(private_tmp)
        shutil.copyfile(notebook, copy)
        run = subprocess.run([sys.executable, "-m", "nbconvert", "--execute", "--to", "notebook",
                              "--ExecutePreprocessor.timeout=600", "--ExecutePreprocessor.kernel_name=python3",
                              "--output-dir", os.path.abspath(folder), "--output", f"{name}.ipynb", copy],
                             env=dict(os.environ, PYDEVD_DISABLE_FILE_VALIDATION="1", TMPDIR=private_tmp))
        if run.returncode != 0:
            return run.returncode
        left = sorted(f for f in os.listdir(private_tmp) if f.startswith("heavytop-report-"))
        if left:
            print(f"{notebook}: the kernel left {left} in its TMPDIR (show()'s report folders)")
            return 1
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
