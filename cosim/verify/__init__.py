"""``cosim verify FMU [CASE]``: runs an FMU (FMI 2.0 or 3.0, Model Exchange or
Co-Simulation) through FMPy and checks every reference column against its tolerance.

Modules: errors (the user-error types), table (CSV and .opt readers), casefile (the
case file), case (the case: folder, case file and options), tolerance (the rules),
names (FMI 3.0 arrays), simulate (the FMPy run), compare (the verdicts),
report/junit/plot (the outputs), files (all-or-nothing writes), cli (the command
line). See docs/verify.md."""
