"""rostui's tf.transformations gives Debian's numbers: every function, every Euler convention, random inputs.

Debian's python3-tf runs tests/tf_compare/transformations_vs_debian.py, which loads rostui's module from its
file and reports the largest difference per function; each must stay under 1e-9 (the issue's bound).
"""

from __future__ import annotations

import json
import subprocess

from conftest import REPO, SYSTEM_PYTHON, need_peer

SCRIPT = REPO / "tests" / "tf_compare" / "transformations_vs_debian.py"



def _debian_tf() -> bool:
    return subprocess.run([SYSTEM_PYTHON, "-c", "import tf.transformations"], capture_output=True).returncode == 0


def test_every_function_equals_debians_tf() -> None:
    need_peer(_debian_tf(), "Debian's tf (python3-tf)")
    out = subprocess.run([SYSTEM_PYTHON, str(SCRIPT), str(REPO), "300"], capture_output=True, text=True,
                         timeout=120)
    assert out.returncode == 0, out.stderr
    worst = json.loads(out.stdout)
    assert len(worst) >= 41, sorted(worst)
    assert {name: d for name, d in worst.items() if not d < 1e-9} == {}


def test_quaternions_are_x_y_z_w_and_angles_sxyz_by_default() -> None:
    import math

    import numpy as np

    from rostui.tools.tf import transformations as tft

    yaw_quarter = tft.quaternion_from_euler(0.0, 0.0, math.pi / 2)
    assert np.allclose(yaw_quarter, [0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)])
    assert np.allclose(tft.euler_from_quaternion(yaw_quarter), (0.0, 0.0, math.pi / 2))
    assert np.allclose(tft.quaternion_matrix(yaw_quarter)[:3, 0], [0.0, 1.0, 0.0])  # x turns into y
