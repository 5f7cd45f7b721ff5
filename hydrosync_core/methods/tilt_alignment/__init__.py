"""Tilt-pole alignment: initial heading of a MEMS IMU on an RTK pole, and the pole tip.

Li et al., *initial alignment of an inertial-navigation RTK pole by gradient descent*
(multi-vector attitude determination with batch, stochastic and mini-batch gradient
descent, vector screening by per-pair headings, tilt compensation), plus HydroSync's
additions: the SVD (Wahba) and closed-form heading-only solutions side by side, and a
joint batch least-squares over the whole swing (initial attitude, tip, gyro and
accelerometer biases from accelerometers, gyros and GNSS together, with σ).

Modules: ``params`` (the parameter schema), ``geometry`` (rotations, attitude
propagation, Mahony levelling), ``align`` (observation vectors, screening, the seed's
solvers, tilt compensation), ``joint`` (the batch least-squares), ``pipeline`` (data →
every method), ``simulate`` (swings for tests, demo and Monte Carlo), ``io`` (the
``imu.csv``/``gnss.csv``/``pole.json`` files), ``montecarlo``, ``project_run``, ``demo``,
``report_section``, ``cli``. Importing the package is cheap: nothing below is imported
until used.

Frames: body x forward, y right, z down along the pole towards the tip (``formats.md``);
navigation frame NED inside (ENU at the file edges); attitude ``C = Rz(heading)·Ry(pitch)·
Rx(roll)`` body→NED; pole vector ``l_b = [0, 0, l]``; tip = antenna + C·l_b (NED).
"""

#: Version of the analysis (stored with its results; ``PluginSpec.version``).
VERSION = "1.0.0"
