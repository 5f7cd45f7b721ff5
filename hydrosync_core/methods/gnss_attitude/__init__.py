"""Heading, pitch and roll from a GNSS antenna array (Liu et al.).

Liu et al., *attitude determination with a GNSS antenna array* (three-antenna direct
method, iterative least squares for four or more antennas, accuracy versus baseline
length), plus HydroSync's additions: the closed-form optimal weighted Wahba solution as a
cross-check and initial value, epoch screening, precision prediction and a simulator.

Modules: ``params`` (the parameter schema), ``solve`` (the three estimators),
``screening``, ``precision``, ``pipeline`` (positions → attitude), ``antennas``
(``antennas.json``), ``simulate``, ``project_run``, ``demo``, ``report_section``, ``cli``.
Importing the package is cheap: nothing below is imported until used.
"""

#: Version of the analysis (stored with its results; ``PluginSpec.version``).
VERSION = "1.0.0"
