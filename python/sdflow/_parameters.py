"""Keyword arguments → the scenario reader of the command line.

A run's parameters have one reader, ``read_run_parameters`` (toolbox/sdflow/run/parameters.h),
which ``sdflow run SCENARIO.toml`` and ``run.toml`` go through. Keyword arguments are written as
such a TOML file and read by it, so that their names, defaults, ranges and error messages are
exactly the scenario keys' (``beta``, ``curvature``, ``t_end``, ``adaptive={...}``,
``retriangulation={...}``, ...). Sections are dicts; ``retriangulation=True``/``False`` is short
for ``retriangulation={"enabled": ...}``. ``None`` leaves a key at its default.

Layers are read in order, each overriding the keys it has: the defaults of the parameter schema
(the command line's; re-triangulation on), a scenario file, then the keyword arguments.
"""

import json
import math
import numbers
import os
import re
import tempfile

import numpy as np

from . import _sdflow

#: Keys holding paths: made absolute, since the reader resolves relative paths against the
#: folder of the file it reads (here a temporary file).
_PATH_KEYS = {"input", "out", "schedule"}

def _toml_value(key, value):
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        v = float(value)
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(value, (str, os.PathLike)):
        text = os.fspath(value)
        if key in _PATH_KEYS:
            text = os.path.abspath(text)
        return json.dumps(text, ensure_ascii=False)
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(key, v) for v in value) + "]"
    raise TypeError(f"keyword argument {key}: a {type(value).__name__} cannot be a parameter value "
                    "(numbers, booleans, strings, paths, lists and, for sections, dicts)")


def to_toml(parameters):
    """The TOML text of `parameters` and, for each of its lines, the keyword it comes from."""
    lines, origin = [], []
    sections = {}
    for key, value in parameters.items():
        if value is None:
            continue
        if key in ("retriangulation",) and isinstance(value, (bool, np.bool_)):
            value = {"enabled": bool(value)}
        if isinstance(value, dict):
            sections[key] = value
            continue
        lines.append(f"{key} = {_toml_value(key, value)}")
        origin.append(key)
    for section, table in sections.items():
        lines.append(f"[{section}]")
        origin.append(section)
        for key, value in table.items():
            if value is None:
                continue
            if isinstance(value, dict):
                raise TypeError(f"keyword argument {section}: {key} cannot be a table")
            lines.append(f"{key} = {_toml_value(key, value)}")
            origin.append(f"{section}.{key}")
    return "\n".join(lines) + "\n", origin


def read(parameters, scenario=None):
    """RunParameters from the schema's defaults, then the `scenario` file, then `parameters`
    (keyword arguments).

    Raises sdflow.InvalidParameter with the reader's message; for a keyword argument the
    location ``file:line:`` is replaced by ``keyword argument NAME:``.
    """
    with tempfile.TemporaryDirectory(prefix="sdflow-parameters-") as folder:
        text, origin = to_toml(parameters or {})
        path = os.path.join(folder, "kwargs.toml")
        with open(path, "w", encoding="utf-8") as out:
            out.write(text)
        files = [] if scenario is None else [os.fspath(scenario)]
        files.append(path)
        try:
            return _sdflow.read_parameters(files)
        except _sdflow.Error as e:
            match = re.match(re.escape(path) + r":(\d+): (.*)", str(e), re.S)
            if match:
                line = int(match.group(1))
                where = origin[line - 1] if 0 < line <= len(origin) else "?"
                raise type(e)(f"keyword argument {where}: {match.group(2)}") from None
            raise
