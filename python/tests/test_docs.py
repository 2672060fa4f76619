"""The docstrings say units and frames; help(heavytop.simulate) reads like `heavytop simulate --help`."""
import pydoc

import heavytop
from conftest import run_cli


def test_simulate_help_reads_like_the_clis():
    text = pydoc.render_doc(heavytop.simulate, renderer=pydoc.plaintext)
    cli_help = run_cli("simulate", "--help").stdout
    # Every option of the command, with its unit, under its Python name.
    for cli_text, python_name in [("rad/s, spin w0 about the body axis", "spin"),
                                  ("rad, initial theta (tilt towards xi)", "theta0"),
                                  ("rad, initial phi (tilt about xi)", "phi0"),
                                  ("s, end of the simulated interval (> 0)", "t_end"),
                                  ("nonlinear: relative tolerance per step", "rtol")]:
        assert cli_text in cli_help
        assert cli_text in text or cli_text.replace(" (> 0)", "") in text, cli_text
        assert python_name in text
    for word in ("rad/s", "kg m^2", "t_i = i t_end / (samples - 1)", "float64", "--samples", "lagrange-exact"):
        assert word in text, word


def test_every_function_documents_units():
    for f in (heavytop.stability, heavytop.simulate, heavytop.compare, heavytop.sweep, heavytop.derive,
              heavytop.Body):
        assert "rad" in f.__doc__ or "kg m^2" in f.__doc__ or "omega0" in f.__doc__, f.__name__
    module = heavytop.__doc__
    for word in ("SI", "zeta vertical and up", "phi   = -asin(k_eta)", "theta = atan2(k_xi, k_zeta)"):
        assert word in module, word
    assert "kg m^2" in heavytop.Body.A.__doc__ and "N m" in heavytop.Body.mgR.__doc__


# A unit as the docstrings write them (SI; rpm for spins given in rpm).
UNIT = r"(rad/s|\brad\b|kg m\^2|\bkg\b|m/s\^2|N m\b|\brpm\b|\bJ\b|SI units|\(s\)|\bs, |\(m\)|\bm, )"


def public_functions():
    import inspect
    return {name: getattr(heavytop, name) for name in heavytop.__all__
            if inspect.isfunction(getattr(heavytop, name)) or inspect.isbuiltin(getattr(heavytop, name))}


def test_help_lists_every_function_on_one_line():
    import re
    functions = public_functions()
    assert {"stability", "simulate", "explore", "show", "report", "load", "fit_decay"} <= set(functions)
    listing = heavytop.__doc__.split("Functions, one a line")[1].split("\n\n", 2)[1]
    names = [re.match(r"    ([a-z_]+)\(", line).group(1) for line in listing.splitlines()]
    assert sorted(names) == sorted(functions), set(names) ^ set(functions)  # each once, none missing
    for line in listing.splitlines():
        assert len(line) <= 110 and re.search(r"\[[^\]]+\]$", line), line  # the command in brackets
    text = pydoc.render_doc(heavytop, renderer=pydoc.plaintext)
    for name in functions:
        assert f"    {name}(" in text, name


def test_every_public_function_documents_its_units():
    import re
    for name, function in public_functions().items():
        doc = function.__doc__ or ""
        assert len(doc.strip().splitlines()) >= 2 or name in ("rpm",), name
        assert re.search(UNIT, doc), f"{name}: no unit in its docstring"



def _accepted_arguments(function):
    """The argument names pybind11 accepts, from the signature it writes as the docstring's first
    line: "__init__(self: heavytop._core.Body, A: float, ..., *, transverse_damping: float = 0.0, ...)"."""
    import re
    signature = function.__doc__.splitlines()[0]
    return [name for name in re.findall(r"([A-Za-z_][A-Za-z0-9_]*): ", signature) if name != "self"]


def test_body_docstring_names_every_keyword_it_accepts():
    accepted = _accepted_arguments(heavytop.Body.__init__)
    assert accepted[:6] == ["A", "B", "C", "mass", "length", "gravity"]
    keywords = accepted[6:]
    assert {"transverse_damping", "axial_damping", "friction", "driven", "tip_radius"} <= set(keywords)
    heavytop.Body(1e-4, 1e-4, 1e-4, 0.1, 0.01, **{name: False if name == "driven" else 0.0 for name in keywords})
    # The class's own docstring (what Body? and the class line of help() show first): its signature
    # line names every argument, keyword by keyword, with its default.
    doc = heavytop.Body.__doc__
    for name in keywords:
        assert f"{name}=" in doc, f"Body.__doc__ does not name the keyword {name}"
    for name in accepted[:5]:
        assert name in doc, name
    # help(heavytop.Body) describes each, with its unit, in __init__'s text.
    text = pydoc.render_doc(heavytop.Body, renderer=pydoc.plaintext)
    init = heavytop.Body.__init__.__doc__.split("\n", 1)[1]
    for name in accepted:
        assert name in text, name
        assert any(line.lstrip().startswith(name) or f", {name}" in line.split(":")[0] for line in init.splitlines()), \
            f"Body.__init__ does not describe {name}"
