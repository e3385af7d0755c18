"""Fixed-step co-simulation master for FMI 2.0 co-simulation FMUs (FMPy low-level API).

Scenarios are data files (TOML or JSON) that name the FMUs, their parameters, the
connections and the step; see ``scenario.py`` for the schema and docs/user-guide.md for
the reference. The command line is ``cosim COMMAND`` (robofmu/cli.py).
"""
