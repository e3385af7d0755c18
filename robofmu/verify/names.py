"""Scalar names (``u[2]``, as in the cross-check CSVs and FMI 2.0) on the variables of
an FMU: FMI 2.0 variables by name; FMI 3.0 arrays (``u``, element 2) by element, the
elements taken from each array's ``<Dimension>`` (``robofmu.fmi3.scalar_names``)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..fmi3 import scalar_names

_TYPES = {"Boolean": bool, "Int32": int, "Int64": int, "Integer": int}


def _size(variable) -> int:
    shape = getattr(variable, "shape", None)
    return int(np.prod(shape)) if shape else 1


def _starts(variable) -> list:
    """The start values of an FMI 3.0 array as Python values."""
    convert = _TYPES.get(variable.type, float)
    words = str(variable.start).split()
    if convert is bool:
        return [w.lower() in ("true", "1") for w in words]
    return [convert(w) for w in words]


class Names:
    """Where each scalar name lives in an FMU: (variable, element index or None)."""

    def __init__(self, model_description):
        self.variables = {v.name: v for v in model_description.modelVariables}
        self.scalars = scalar_names(model_description.modelVariables)

    def locate(self, name: str):
        """(variable, index) of `name`, or None when the FMU has no such scalar."""
        return self.scalars.get(name)

    def start_values(self, scalars: dict[str, object]) -> dict[str, object]:
        """Scalar start values -> FMPy's start_values: whole arrays, the elements left
        out at the FMU's start values."""
        out: dict[str, Any] = {}  # a scalar, or a whole array (list)
        for name, value in scalars.items():
            variable, index = self.locate(name)
            if index is None:
                out[variable.name] = value
            else:
                out.setdefault(variable.name, _starts(variable))[index] = value
        return out

    def input_signals(self, time: np.ndarray, columns: dict[str, np.ndarray]) -> np.ndarray:
        """Scalar input columns -> FMPy's structured input array (arrays as columns of
        their shape, the elements left out at their start values)."""
        grouped: dict[str, dict] = {}
        for name, values in columns.items():
            variable, index = self.locate(name)
            grouped.setdefault(variable.name, {})[index] = values
        dtype: list[tuple] = [("time", np.float64)]
        for base, elements in grouped.items():
            size = _size(self.variables[base])
            dtype.append((base, np.float64, (size,)) if None not in elements else (base, np.float64))
        out = np.zeros(len(time), dtype=dtype)
        out["time"] = time
        for base, elements in grouped.items():
            if None in elements:
                out[base] = elements[None]
                continue
            variable = self.variables[base]
            # Every element given: no start value is read (a container FMU of
            # fmu-manipulation-toolbox 2.0 declares none that FMPy reads).
            every = set(elements) == set(range(_size(variable)))
            starts = np.zeros(_size(variable)) if every else _starts(variable)
            values = np.tile(np.asarray(starts, float), (len(time), 1))
            for index, column in elements.items():
                values[:, index] = column
            out[base] = values
        return out

    def unit(self, name: str) -> str | None:
        """The unit of scalar `name` (its own or its type's), None when it has none."""
        found = self.locate(name)
        if found is None:
            return None
        variable = found[0]
        declared = getattr(variable, "declaredType", None)
        return variable.unit or (declared.unit if declared is not None else None)

    def outputs(self, scalars: list[str]) -> list[str]:
        """The variables to record for `scalars` (order kept, each once)."""
        return list(dict.fromkeys(self.locate(name)[0].name for name in scalars))

    def column(self, result: np.ndarray, name: str) -> np.ndarray:
        """The time series of scalar `name` in an FMPy result."""
        variable, index = self.locate(name)
        values = result[variable.name]
        return np.asarray(values if index is None else values[:, index], dtype=np.float64)
