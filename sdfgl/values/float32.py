"""The range of the shader's numbers: every constant and uniform is a float32."""
from __future__ import annotations

import numpy as np

FLOAT32_MAX = float(np.finfo(np.float32).max)
"""The largest magnitude a shader constant or uniform holds (3.4e38); past it a value is infinity there."""
