"""Translation between the FMI 2.0 scalar names of the reference cases (`u[2]`) and
the FMI 3.0 arrays of the same FMUs (`u`, element 2): start values, input signals and
results."""

import re

import numpy as np

ELEMENT = re.compile(r"^(.*)\[(\d+)\]$")


def split(name):
    """("u", 1) for "u[2]" (0-based index), (name, None) for a scalar; der(x[i]) is not
    used by the cases."""
    match = ELEMENT.match(name)
    return (match.group(1), int(match.group(2)) - 1) if match else (name, None)


def parse_start(variable):
    """The start values of an FMI 3.0 variable as a list of Python values."""
    words = str(variable.start).split()
    if variable.type == "Boolean":
        return [w.lower() in ("true", "1") for w in words]
    if variable.type == "Int32":
        return [int(w) for w in words]
    return [float(w) for w in words]


def start_values(scalars, description):
    """FMI 2.0 start values by scalar name -> FMI 3.0 start values by variable: the
    elements a case leaves out keep the FMU's start values."""
    variables = {v.name: v for v in description.modelVariables}
    out = {}
    for name, value in scalars.items():
        base, index = split(name)
        if index is None:
            out[base] = value
            continue
        out.setdefault(base, parse_start(variables[base]))[index] = value
    return out


def input_signals(signals, description):
    """A structured input array with scalar columns `f[1]`..`f[3]` -> one column `f`
    of shape (3,), elements the signal leaves out at their start values."""
    variables = {v.name: v for v in description.modelVariables}
    time_name = signals.dtype.names[0]
    columns = {}
    for name in signals.dtype.names[1:]:
        base, index = split(name)
        columns.setdefault(base, {})[index] = signals[name]
    dtype = [(time_name, np.float64)] + [
        (base, np.float64, (len(parse_start(variables[base])),)) for base in columns]
    out = np.zeros(len(signals), dtype=dtype)
    out[time_name] = signals[time_name]
    for base, elements in columns.items():
        values = np.tile(parse_start(variables[base]), (len(signals), 1))
        for index, column in elements.items():
            values[:, index] = column
        out[base] = values
    return out


def output_names(scalars):
    """The FMI 3.0 variables to record for FMI 2.0 scalar names (order kept)."""
    return list(dict.fromkeys(split(name)[0] for name in scalars))


def column(result, name):
    """The time series of FMI 2.0 scalar `name` from an FMI 3.0 result."""
    base, index = split(name)
    values = result[base]
    return values if index is None else values[:, index]
