"""One-line TypeErrors for arguments of the wrong type (issue 30, fuzz/fuzz_python.py).

pybind11 refuses an argument it cannot convert with a TypeError of many lines (every overload's
signature, then "Invoked with: ..." and the whole value). Every function of heavytop._core and
the Body constructor are wrapped here, once, at import, so that the error says in one line
which argument is wrong and what it must be: "stability(): spin must be float, not str". The
conversion itself is pybind11's; only the message changes."""
import functools
import operator
import re

from . import _core

_SIGNATURE = re.compile(r"^\s*(?:\w+)?\((.*)\)\s*->")


def _parameters(doc):
    """[(name, annotation, has_default, keyword_only)] from pybind11's first docstring line."""
    first = (doc or "").lstrip().splitlines()[0] if doc else ""
    if first.startswith("__init__"):
        first = first[len("__init__"):]
    match = _SIGNATURE.match(first[first.find("("):] if "(" in first else "")
    if not match:
        return []
    out, depth, part, parts = [], 0, "", []
    for ch in match.group(1):  # split at the commas outside brackets
        if ch in "[(":
            depth += 1
        elif ch in "])":
            depth -= 1
        if ch == "," and depth == 0:
            parts.append(part)
            part = ""
        else:
            part += ch
    parts.append(part)
    keyword_only = False
    for p in (p.strip() for p in parts):
        if p == "*":
            keyword_only = True
            continue
        if ":" not in p:
            continue
        name, rest = p.split(":", 1)
        annotation, _, default = rest.partition("=")
        out.append((name.strip(), annotation.strip(), bool(default.strip()), keyword_only))
    return out


def _fits(value, annotation):
    """Whether pybind11 could convert value to the annotated C++ type (a close approximation)."""
    if annotation.startswith("Optional[") and annotation.endswith("]"):
        return value is None or _fits(value, annotation[len("Optional["):-1])
    if annotation == "float":
        try:
            float(value)
            return True
        except Exception:  # noqa: BLE001 - any failure of the conversion: it does not fit
            return False
    if annotation == "int":
        try:
            return -(2 ** 63) <= operator.index(value) < 2 ** 64
        except Exception:  # noqa: BLE001
            return False
    if annotation == "bool":
        return isinstance(value, bool) or type(value).__name__ == "bool_"
    if annotation == "str":
        return isinstance(value, str)
    if annotation == "dict":
        return isinstance(value, dict)
    if annotation.startswith("List["):
        return hasattr(value, "__iter__") and not isinstance(value, (str, bytes, dict))
    if annotation.endswith("Body"):
        return isinstance(value, _core.Body)
    if annotation.endswith("Table"):
        return isinstance(value, _core.Table)
    return True


def _one_line(name, doc, args, kwargs):
    parameters = _parameters(doc)
    positional = [p for p in parameters if not p[3]]
    if len(args) > len(positional):
        return f"{name}(): takes {len(positional)} positional arguments, {len(args)} given"
    given = dict(zip((p[0] for p in positional), args))
    for key in kwargs:
        if key in given:
            return f"{name}(): {key} given twice"
        if key not in (p[0] for p in parameters):
            return f"{name}(): no argument {key!r}"
    given.update(kwargs)
    for pname, annotation, has_default, _ in parameters:
        if pname not in given:
            if not has_default:
                return f"{name}(): {pname} is missing"
            continue
        if not _fits(given[pname], annotation):
            shown = repr(given[pname]) if isinstance(given[pname], (int, float)) else type(given[pname]).__name__
            return f"{name}(): {pname} must be {annotation}, not {shown[:40]}"
    return f"{name}(): the arguments do not fit ({', '.join(f'{p[0]}: {p[1]}' for p in parameters)})"


def _wrap(name, function, doc):
    @functools.wraps(function)
    def call(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except TypeError as error:
            if "incompatible function arguments" not in str(error) and \
               "incompatible constructor arguments" not in str(error):
                raise
            raise TypeError(_one_line(name, doc, args, kwargs)) from None
    return call


for _name in dir(_core):
    _function = getattr(_core, _name)
    if type(_function).__name__ == "builtin_function_or_method":
        setattr(_core, _name, _wrap(_name, _function, _function.__doc__))
_core.Body.__init__ = _wrap("Body", _core.Body.__init__, _core.Body.__init__.__doc__)
_core.Table.__init__ = _wrap("Table", _core.Table.__init__, _core.Table.__init__.__doc__)
