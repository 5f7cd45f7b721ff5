"""GNSS/INS smoother: loosely coupled 15/21-state EKF with motion constraints and RTS smoothing.

Wang et al., *high-precision GNSS/INS backward smoothing based on the extended Kalman
filter* (15-state error model, GNSS position update with lever arm, non-holonomic and
zero-velocity constraints, Rauch-Tung-Striebel fixed-interval smoother), plus HydroSync's
additions: optional gyro/accelerometer scale-factor states (21 states), the smoother on
the total state with memory-bounded node storage, alignment from the data, outage
simulation and error statistics against a reference trajectory.

Modules: ``params`` (the parameter schema), ``config`` (KF-GINS YAML), ``io`` (readers and
writers), ``kernel`` (compiled mechanisation, filter and smoother), ``filter``
(:func:`run_gins`), ``evaluate``, ``simulate``, ``project_run``, ``demo``,
``report_section``, ``cli``. Importing the package is cheap: nothing below is imported
until used.
"""

#: Version of the analysis (stored with its results; ``PluginSpec.version``).
VERSION = "1.0.0"
