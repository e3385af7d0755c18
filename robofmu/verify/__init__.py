"""``cosim verify FMU [CASE]``: runs an FMU (FMI 2.0 or 3.0, Model Exchange or
Co-Simulation) through FMPy and checks every reference column against its tolerance;
``cosim verify FMU``: every experiment the FMU carries (FMI-LS-REF);
``cosim verify TREE``: every case of an FMI cross-check tree.

Modules: errors (the user-error types), table (CSV and .opt readers), casefile (the
case file), case (the case: folder, case file and options), events (repeated times:
both sides of a jump), tolerance (the rules), names (FMI 3.0 arrays), simulate (the
FMPy run), compare (the verdicts, an early end), report/junit/plot (the outputs), runner
(one case, files to verdicts), tree (a cross-check tree), own (the experiments an FMU
carries, FMI-LS-REF), page (the results page of a tree), files (all-or-nothing writes),
cli (the command line). See docs/verify.md."""
