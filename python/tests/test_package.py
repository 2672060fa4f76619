"""The package: heavytop._core under heavytop/, py.typed, and stubs that match the module."""
import ast
import inspect
import os

import pytest

import heavytop
import heavytop._core


def test_the_extension_is_heavytop_core_inside_the_package():
    package = os.path.dirname(heavytop.__file__)
    assert os.path.dirname(heavytop._core.__file__) == package
    assert heavytop._core.__name__ == "heavytop._core"
    assert os.path.isfile(os.path.join(package, "py.typed"))
    assert heavytop.__version__ == heavytop._core.__version__ and heavytop.__version__.count(".") == 2
    assert heavytop.MODELS == ("first-order", "body-fixed", "linearized", "nonlinear", "lagrange-exact")


def test_every_public_name_is_exported():
    for name in heavytop.__all__:
        assert hasattr(heavytop, name), name
    for name in ("Body", "InvalidInput", "stability", "simulate", "compare", "sweep", "grid_values", "derive",
                 "derive_rotations", "derive_check", "example_toy_top", "example_motion"):
        assert name in heavytop.__all__, name
    assert issubclass(heavytop.InvalidInput, ValueError)


def stub_names(path):
    tree = ast.parse(open(path).read())
    names = {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names[node.name] = node
        elif isinstance(node, ast.AnnAssign):
            names[node.target.id] = node
    return names


def test_the_stub_declares_exactly_what_the_module_has():
    path = os.path.join(os.path.dirname(heavytop.__file__), "_core.pyi")
    stub = stub_names(path)
    module = {n for n in dir(heavytop._core) if not n.startswith("_") or n == "__version__"}
    assert set(stub) == module
    # The functions' parameters, by name and kind, as pybind11 bound them.
    for name, node in stub.items():
        if isinstance(node, ast.FunctionDef):
            doc = getattr(heavytop._core, name).__doc__.splitlines()[0]
            bound = [p.split(":")[0].strip() for p in doc[doc.index("(") + 1:doc.rindex(")")].split(",")]
            declared = [a.arg for a in node.args.args] + (["*"] if node.args.kwonlyargs else []) + \
                       [a.arg for a in node.args.kwonlyargs]
            assert [p for p in bound if p] == declared, name


def test_the_python_functions_are_annotated():
    for name in ("stability", "simulate", "compare", "sweep", "derive", "derive_rotations", "derive_check"):
        signature = inspect.signature(getattr(heavytop, name))
        assert signature.return_annotation is not inspect.Signature.empty, name
        for parameter in signature.parameters.values():
            assert parameter.annotation is not inspect.Parameter.empty, (name, parameter.name)


def test_the_examples_data_ships_with_the_package(tmp_path, monkeypatch):
    # Found from any folder (a copied notebook): the files of examples/ byte for byte.
    import glob
    root = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "examples")
    names = sorted(os.path.relpath(p, root).replace(os.sep, "/")
                   for pattern in ("*.toml", "*.csv", "meshes/*") for p in glob.glob(os.path.join(root, pattern)))
    assert {"toy-top.toml", "spin-decay.csv", "meshes/spinning-top.stl"} <= set(names)
    monkeypatch.chdir(tmp_path)
    for name in names:
        path = heavytop.example_file(name)
        assert os.path.isabs(path) and os.path.dirname(heavytop.__file__) in path, path
        with open(path, "rb") as mine, open(os.path.join(root, name), "rb") as theirs:
            assert mine.read() == theirs.read(), name
    assert heavytop.load(heavytop.example_file("toy-top.toml")).motion["spin"] == 200.0
    assert heavytop.load(heavytop.example_file("mesh-top.toml")).body.mass > 0  # its meshes/ beside it
    with pytest.raises(heavytop.InvalidInput, match=r"^name: no example 'top.toml'; the examples: asymmetric-plate"):
        heavytop.example_file("top.toml")
