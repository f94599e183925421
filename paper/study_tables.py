"""What the study tables of paper/ share (restraint_outcomes.py, harm_outcomes.py): the Wilson 95 %
interval of a count and the study's damage state "fallen"."""
import math

Z95 = 1.959963984540054


def wilson(k, n, z=Z95):
    """The Wilson score interval of k successes in n runs (0 to 1 when there are no runs)."""
    if n == 0:
        return (0.0, 1.0)
    p = k / n
    d = 1 + z * z / n
    c = p + z * z / (2 * n)
    h = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return (max(0.0, (c - h) / d), min(1.0, (c + h) / d))


def fallen(body):
    """Off its feet at some time: tipped past 60 deg or came down more than 5 cm (has_fallen,
    scene/run_summary.hpp), a body of a run record."""
    return body["max_tilt_deg"] > 60 or body["lift_m"] < -0.05
