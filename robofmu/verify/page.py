"""The results page (``cosim verify TREE --html FILE``, and the release's compatibility
folder, scripts/compatibility.py, which adds its other importers' verdicts): one static,
self-contained HTML file (no script, style or font from elsewhere) with the matrix FMU
(its FMI version, exporting tool and platform) x importer (each cell the verdict of each
interface; a refusal with its reason), then per case its verdict, the numbers of every
signal (max |error|, its time, the tolerance, samples outside), its plots and links to
every file of its case and results folder, all as paths relative to the page. A small
inline script marks the body ``data-images-broken`` with the number of images that did
not load (what the CI's browser check reads)."""

from __future__ import annotations

import html
import json
import os
from dataclasses import dataclass, field
from pathlib import Path


@dataclass
class Entry:
    """One verified case: where it ran and what came of it."""

    fmu: str  # the FMU's name, e.g. Pss3Plant.fmu
    fmi_version: str
    interface: str  # cs or me
    platform: str
    importer: str  # e.g. "cosim 0.1.0 (FMPy 0.3.32)"
    case: str
    status: str  # passed, failed, rejected (its files do not fit), refused (by the importer)
    summary: str
    folder: Path  # its results folder (its verify.json and plots, where it has them)
    files: list[Path] = field(default_factory=list)
    tool: str = ""  # the exporting tool and its version, e.g. "robofmu 0.1.0"
    how: str = ""  # how it was judged, for an importer without verify.json


def _link(path: Path, page: Path) -> str:
    return html.escape(Path(os.path.relpath(path, page.parent)).as_posix(), quote=True)


def _signals(report: dict, page: Path, folder: Path) -> str:
    rows = []
    for s in report.get("signals", []):
        error = s.get("max_error")
        shown = "n/a" if error is None else f"{error:.3g} at t = {s.get('max_error_time'):g} s"
        plot = s.get("plot")
        link = (f'<a href="{_link(folder / Path(plot).name, page)}">plot</a>' if plot else "")
        verdict = "PASS" if s.get("passed") else "FAIL"
        rows.append(f"<tr class=\"{verdict.lower()}\"><td>{html.escape(s['signal'])}</td>"
                    f"<td>{verdict}</td><td>{html.escape(shown)}</td>"
                    f"<td>{html.escape(str(s.get('tolerance')))}</td>"
                    f"<td>{s.get('samples_outside')} of {s.get('samples')}</td><td>{link}</td>"
                    "</tr>")
    if not rows:
        return ""
    return ("<table><tr><th>signal</th><th>verdict</th><th>max |error|</th><th>tolerance"
            "</th><th>samples outside</th><th></th></tr>" + "".join(rows) + "</table>")


def page(title: str, entries: list[Entry], path: Path, note: str = "") -> bytes:
    """The page of `entries`, to be written at `path` (links are relative to it); `note`
    a paragraph under the matrix (e.g. which importer runs which case)."""
    rows = sorted({(e.fmi_version, e.fmu, e.tool, e.platform) for e in entries})
    columns = list(dict.fromkeys(e.importer for e in entries))  # in the order given
    head = "".join(f"<th>{html.escape(importer)}</th>" for importer in columns)
    matrix = []
    for version, fmu, tool, plat in rows:
        cells = []
        for importer in columns:
            here = [e for e in entries if (e.fmi_version, e.fmu, e.tool, e.platform,
                                           e.importer) == (version, fmu, tool, plat, importer)]
            cells.append("<td>" + "<br>".join(
                f'<a class="{e.status}" href="#{_anchor(e)}">{e.interface} {e.status}</a>'
                + (f" ({html.escape(_reason(e.summary))})" if e.status == "refused" else "")
                for e in sorted(here, key=lambda e: (e.interface, e.case))) + "</td>")
        exporter = f", {html.escape(tool)}" if tool else ""
        matrix.append(f"<tr><th>{html.escape(fmu)} (FMI {version}{exporter}), "
                      f"{html.escape(plat)}</th>{''.join(cells)}</tr>")
    sections = []
    for e in entries:
        report_path = e.folder / "verify.json"
        report = json.loads(report_path.read_text()) if report_path.is_file() else {}
        images = "".join(
            f'<img src="{_link(e.folder / Path(s["plot"]).name, path)}" alt="{html.escape(s["signal"])}">'
            for s in report.get("signals", []) if s.get("plot"))
        links = " ".join(f'<a href="{_link(f, path)}">{html.escape(f.name)}</a>'
                         for f in e.files)
        experiment = report.get("experiment", {})
        settings = (f"{experiment.get('start')} to {experiment.get('stop')} s, step "
                    f"{experiment.get('step')} s, relative tolerance "
                    f"{experiment.get('relative_tolerance')}" if experiment else "not run")
        how = (html.escape(e.how) if e.how and not report
               else f"Case {html.escape(e.case)}; experiment {html.escape(settings)}.")
        sections.append(
            f'<section id="{_anchor(e)}"><h3 class="{e.status}">{html.escape(e.fmu)} FMI '
            f"{html.escape(e.fmi_version)}{f' ({html.escape(e.tool)})' if e.tool else ''} "
            f"{e.interface}, {html.escape(e.platform)}, "
            f"{html.escape(e.importer)}: {e.status}</h3><p>{html.escape(e.summary)}</p>"
            f"<p>{how}</p>"
            f"{_signals(report, path, e.folder)}{images}<p>Files: {links}</p></section>")
    counts = {s: sum(e.status == s for e in entries)
              for s in ("passed", "failed", "rejected", "refused")}
    refused = f", {counts['refused']} refused by the importer" if counts["refused"] else ""
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{html.escape(title)}</title>
<style>
body {{ font-family: sans-serif; margin: 1.5em; }}
table {{ border-collapse: collapse; margin: 0.5em 0; }}
td, th {{ border: 1px solid #999; padding: 0.2em 0.5em; text-align: left; }}
.passed, .pass {{ color: #176117; }} .failed, .fail, .rejected {{ color: #a01010; }}
.refused {{ color: #8a5a00; }}
img {{ max-width: 45%; margin: 0.3em; border: 1px solid #ccc; }}
</style></head>
<body data-images-broken="unknown">
<h1>{html.escape(title)}</h1>
<p>{counts['passed']} passed, {counts['failed']} failed, {counts['rejected']} rejected{refused}
of {len(entries)} cases. Each cell links to the case below: its numbers, plots and files.</p>
<table><tr><th>FMU (FMI version, exporting tool), platform</th>{head}</tr>{''.join(matrix)}</table>
{f"<p>{html.escape(note)}</p>" if note else ""}
{''.join(sections)}
<script>
window.addEventListener("load", function () {{
  var broken = 0;
  for (var i = 0; i < document.images.length; i++) {{
    if (!document.images[i].complete || document.images[i].naturalWidth === 0) broken++;
  }}
  document.body.setAttribute("data-images-broken", String(broken));
}});
</script>
</body></html>
""".encode()


def _reason(summary: str) -> str:
    """The reason of a refusal: what its summary says in the parentheses after
    "refused"."""
    return summary.partition("refused (")[2].rpartition(")")[0] or summary


def _anchor(e: Entry) -> str:
    text = f"{e.fmi_version}-{e.interface}-{e.platform}-{e.importer}-{e.fmu}-{e.case}"
    return "".join(c if c.isalnum() else "-" for c in text)
