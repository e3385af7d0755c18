"""The demo's comparison of the controllers: every demo scenario run again with the
computed-torque controller in place of the PID (same motion, plant and bandwidth
gains.omega; robofmu.controllers), with a perfect model and with the model's leg mass
20 % low and high, printed beside the PID's tracking error and peak force."""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np

from . import bundle
from .fmu_check import describe
from .master import Master
from .report import format_table, metrics, sig
from .scenario import fmu_file, parse_document, read_document

MISMATCH = (0.8, 1.2)  # factors on the model's leg mass


def computed_torque_document(data: dict, model: dict | None = None) -> dict:
    """The hand-written PID scenario `data` with the ComputedTorque FMU (beside the PID
    FMU) as its controller, at the same bandwidth, with `model` as its [model] table."""
    d = copy.deepcopy(data)
    fmus = d["fmus"]
    pid = str(fmus["pid"])
    ct = (pid[:len(pid) - len(Path(pid).name)] + "ComputedTorque" if bundle.is_name(pid)
          else str(Path(pid).with_name("ComputedTorque.fmu")))
    d["fmus"] = {"planner": fmus["planner"], "ct": ct, "plant": fmus["plant"]}
    d["controller"] = "computed-torque"
    d["gains"] = {"omega": d["gains"]["omega"]}
    d["name"] = f"{d['name']}_ct"
    if model:
        d["model"] = model
    return d


def _run(data: dict, base_dir: Path) -> dict:
    result = Master(parse_document(data, base_dir)).run()
    return {"time": np.array(result.time),
            **{k: np.array(v) for k, v in result.columns.items()}}


def comparison_rows(paths: list[Path], pid_results: dict) -> list[list[str]]:
    """Per scenario file: the PID row (from `pid_results`, by scenario name) and the
    computed-torque row with the RMS errors of the mismatched models."""
    rows = []
    for path in paths:
        data = read_document(path)
        pid = metrics(pid_results[path.stem])
        ct_doc = computed_torque_document(data)
        fmu = fmu_file("ct", ct_doc["fmus"]["ct"], path.parent)
        leg_mass = next(float(v.start) for v in describe(fmu, "fmus.ct").modelVariables
                        if v.name == "legMass")
        ct = metrics(_run(ct_doc, path.parent))
        off = [metrics(_run(computed_torque_document(data, {"legMass": f * leg_mass}),
                            path.parent)).rms_error_deg for f in MISMATCH]
        rows.append([path.stem, "PID", sig(pid.rms_error_deg), sig(pid.max_error_deg),
                     sig(pid.peak_force_n), "model-free"])
        rows.append([path.stem, "computed torque", sig(ct.rms_error_deg),
                     sig(ct.max_error_deg), sig(ct.peak_force_n),
                     " / ".join(sig(x) for x in off)])
    return rows


def print_comparison(paths: list[Path], pid_results: dict) -> None:
    header = ["scenario", "controller", "RMS error (deg)", "max error (deg)",
              "peak |f| (N)", "RMS error, model leg mass x0.8 / x1.2 (deg)"]
    print("PID vs computed torque at equal bandwidth (triple pole at -omega), thesis bar "
          "0.05 deg:")
    print(format_table(header, comparison_rows(paths, pid_results)))
