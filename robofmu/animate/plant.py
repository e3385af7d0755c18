"""The plant's geometry parameters, read from the Pss3Plant FMU (FMI 2.0 or 3.0)."""

from __future__ import annotations

import math
from pathlib import Path

from fmpy import read_model_description

from .errors import AnimateError
from .geometry import PARAMETERS


def plant_parameters(fmu: Path, overrides: dict[str, float] | None = None) -> dict[str, float]:
    """The start values of the geometry parameters in `fmu`'s modelDescription.xml,
    replaced by `overrides` (name -> value, SI) where given."""
    if not fmu.is_file():
        raise AnimateError(str(fmu), "plant FMU", "no such file; build it with "
                           "scripts/build-fmus.sh or pass --fmu")
    try:
        description = read_model_description(str(fmu), validate=False)
    except Exception as e:  # not a zip, no modelDescription.xml, bad XML: all user input
        raise AnimateError(str(fmu), "plant FMU", f"cannot be read as an FMU ({e}); "
                           "pass the Pss3Plant FMU with --fmu") from None
    starts = {v.name: v.start for v in description.modelVariables}
    params = {}
    for name in PARAMETERS:
        if name not in starts or starts[name] is None:
            raise AnimateError(str(fmu), name, "no such parameter; pass the Pss3Plant "
                               "FMU with --fmu")
        params[name] = float(starts[name])
    for name, value in (overrides or {}).items():
        if name in params:
            params[name] = float(value)
    _check(params, str(fmu))
    return params


def _check(params: dict[str, float], where: str) -> None:
    bad = [n for n, v in params.items() if not math.isfinite(v)]
    if bad:
        raise AnimateError(where, bad[0], "not a finite number; give a finite value")
    for name in ("lp", "ld", "lb", "a"):
        if params[name] <= 0.0:
            raise AnimateError(where, name, f"{params[name]} m is not a length; give a "
                               "positive value")
    if params["strokeMin"] >= params["strokeMax"]:
        raise AnimateError(where, "strokeMin", f"{params['strokeMin']} m is not below "
                           f"strokeMax ({params['strokeMax']} m); give strokeMin < strokeMax")
