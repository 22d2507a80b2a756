"""How long a PAB typically takes, for the operator's time-left figures (pure).

``typical`` is config/supervisory.yaml's ``typical_s``: each PAB's rough
duration (s); a Drive adds its distance over its speed. An estimate for the
operator, not a bound: the guards' timeouts are the bounds.
"""


def typical_s(pab, distance_mm, speed_mm_s, typical):
    """Typical duration (s) of PAB ``pab`` (its name, e.g. 'DRIVE') asked to go
    ``distance_mm`` at ``speed_mm_s`` (0 or None: no drive time known)."""
    total = float(typical.get(pab, 0.0))
    if pab == 'DRIVE' and speed_mm_s:
        total += abs(distance_mm) / speed_mm_s
    return total
